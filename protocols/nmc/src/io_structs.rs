//! The structs of the I/O-by-type, extension-module and controller-service families (0x12xx,
//! digest 001 §3.12, §3.18, §3.19) as the wire carries them, in `crate::structs`' manner:
//! fields in declaration order, `char[N]` as N bytes, `long` as i64, `reserved` not sent.

use crate::payload::{PayloadError, Reader, Writer};
use crate::structs::{get_chars, put_chars};

/// `TmLibVersion` (NMC_GetMtLibVersion): the manual leaves it undefined (digest 001 §8 item 3);
/// mcemu's: a version string and its three numbers.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LibVersion {
    pub str_ver: [u8; 16],
    pub major: i16,
    pub minor: i16,
    pub patch: i16,
}

impl LibVersion {
    pub fn write(&self, w: &mut Writer) {
        put_chars(w, &self.str_ver);
        w.i16(self.major).i16(self.minor).i16(self.patch);
    }
    pub fn read(r: &mut Reader<'_>) -> Result<LibVersion, PayloadError> {
        Ok(LibVersion {
            str_ver: get_chars(r)?,
            major: r.i16()?,
            minor: r.i16()?,
            patch: r.i16()?,
        })
    }
}

/// `TDioMappingCfg` (NMC_SetDioMapping, digest 001 §3.12): six bytes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct DioMapping {
    pub enable: u8,
    pub pin_grp: u8,
    pub pin_index: u8,
    pub out_enable: u8,
    pub new_grp: u8,
    pub new_index: u8,
}

impl DioMapping {
    pub fn write(&self, w: &mut Writer) {
        for b in [
            self.enable,
            self.pin_grp,
            self.pin_index,
            self.out_enable,
            self.new_grp,
            self.new_index,
        ] {
            w.u8(b);
        }
    }
    pub fn read(r: &mut Reader<'_>) -> Result<DioMapping, PayloadError> {
        Ok(DioMapping {
            enable: r.u8()?,
            pin_grp: r.u8()?,
            pin_index: r.u8()?,
            out_enable: r.u8()?,
            new_grp: r.u8()?,
            new_index: r.u8()?,
        })
    }
}

/// `TNMCTime` (NMC_GetTime / SetTime, digest 001 §3.18): year ("ear" [sic]) … second.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct NmcTime(pub [i16; 6]);

impl NmcTime {
    pub fn write(&self, w: &mut Writer) {
        for v in self.0 {
            w.i16(v);
        }
    }
    pub fn read(r: &mut Reader<'_>) -> Result<NmcTime, PayloadError> {
        let mut t = [0i16; 6];
        for v in &mut t {
            *v = r.i16()?;
        }
        Ok(NmcTime(t))
    }
}

/// `TBackGroup2` (NMC_GetBackedVarGroup2): 2 crd segment numbers, 2 × 3 crd planned
/// positions, 12 axes' planned, axis and encoder positions; 56 `long`s in that order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BackGroup2(pub [i64; BACK_GROUP2_LONGS]);

/// The `long`s of `TBackGroup2`.
pub const BACK_GROUP2_LONGS: usize = 2 + 6 + 12 * 3;

impl Default for BackGroup2 {
    fn default() -> BackGroup2 {
        BackGroup2([0; BACK_GROUP2_LONGS])
    }
}

impl BackGroup2 {
    pub fn write(&self, w: &mut Writer) {
        for v in self.0 {
            w.i64(v);
        }
    }
    pub fn read(r: &mut Reader<'_>) -> Result<BackGroup2, PayloadError> {
        let mut b = BackGroup2::default();
        for v in &mut b.0 {
            *v = r.i64()?;
        }
        Ok(b)
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn structs_round_trip() {
        let v = LibVersion {
            str_ver: crate::structs::chars("mcemu 1"),
            major: 1,
            minor: 2,
            patch: 3,
        };
        let mut w = Writer::new();
        v.write(&mut w);
        let mut r = Reader::new(&w.bytes);
        assert_eq!(LibVersion::read(&mut r).unwrap(), v);
        r.finish().unwrap();
        let m = DioMapping {
            enable: 1,
            pin_grp: 0,
            pin_index: 3,
            out_enable: 1,
            new_grp: 1,
            new_index: 7,
        };
        let mut w = Writer::new();
        m.write(&mut w);
        assert_eq!(DioMapping::read(&mut Reader::new(&w.bytes)).unwrap(), m);
    }
}
