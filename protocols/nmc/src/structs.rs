//! The manual's structs (digest 001 §3.6, §3.12, §3.13, §3.18) as the wire carries them: each
//! field in declaration order, with the kinds of `crate::payload` (`long` as i64, `float` as
//! f64, `char[N]` as N raw bytes); `reserved` members are not sent.

use crate::payload::{PayloadError, Reader, Writer};

/// A fixed `char[N]` field: N bytes on the wire.
pub(crate) fn put_chars<const N: usize>(w: &mut Writer, s: &[u8; N]) {
    w.bytes.extend_from_slice(s);
}

pub(crate) fn get_chars<const N: usize>(r: &mut Reader<'_>) -> Result<[u8; N], PayloadError> {
    let mut out = [0u8; N];
    for b in &mut out {
        *b = r.u8()?;
    }
    Ok(out)
}

/// `char[N]` holding `s`, NUL-padded (cut to N − 1 bytes so a NUL always ends it).
pub fn chars<const N: usize>(s: &str) -> [u8; N] {
    let mut out = [0u8; N];
    for (o, b) in out.iter_mut().zip(s.bytes().take(N.saturating_sub(1))) {
        *o = b;
    }
    out
}

/// `TPtpPara`: acc, dec (pulse/ms²), startVel, endVel (pulse/ms), smoothCoef [0,199] ms.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PtpPara {
    pub acc: f64,
    pub dec: f64,
    pub start_vel: f64,
    pub end_vel: f64,
    pub smooth_coef: i16,
}

impl PtpPara {
    pub fn write(&self, w: &mut Writer) {
        w.f64(self.acc)
            .f64(self.dec)
            .f64(self.start_vel)
            .f64(self.end_vel)
            .i16(self.smooth_coef);
    }
    pub fn read(r: &mut Reader<'_>) -> Result<PtpPara, PayloadError> {
        Ok(PtpPara {
            acc: r.f64()?,
            dec: r.f64()?,
            start_vel: r.f64()?,
            end_vel: r.f64()?,
            smooth_coef: r.i16()?,
        })
    }
}

/// `TJogPara`: acc, dec (pulse/ms²), smoothCoef (a double here, [0,199] ms).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct JogPara {
    pub acc: f64,
    pub dec: f64,
    pub smooth_coef: f64,
}

impl JogPara {
    pub fn write(&self, w: &mut Writer) {
        w.f64(self.acc).f64(self.dec).f64(self.smooth_coef);
    }
    pub fn read(r: &mut Reader<'_>) -> Result<JogPara, PayloadError> {
        Ok(JogPara {
            acc: r.f64()?,
            dec: r.f64()?,
            smooth_coef: r.f64()?,
        })
    }
}

/// `THomeSetting` (digest 001 §3.13), pulses and pulse/ms.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct HomeSetting {
    pub mode: i16,
    pub dir: i16,
    pub offset: i64,
    pub scan1st_vel: f64,
    pub scan2nd_vel: f64,
    pub acc: f64,
    pub re_scan_en: u8,
    pub home_edge: u8,
    pub lmt_edge: u8,
    pub z_edge: u8,
    pub ini_ret_pos: u64,
    pub ret_sw_offset: u64,
    pub safe_len: u64,
    pub use_pre_set_ptp_para: u8,
}

impl HomeSetting {
    pub fn write(&self, w: &mut Writer) {
        w.i16(self.mode)
            .i16(self.dir)
            .i64(self.offset)
            .f64(self.scan1st_vel)
            .f64(self.scan2nd_vel)
            .f64(self.acc)
            .u8(self.re_scan_en)
            .u8(self.home_edge)
            .u8(self.lmt_edge)
            .u8(self.z_edge)
            .u64(self.ini_ret_pos)
            .u64(self.ret_sw_offset)
            .u64(self.safe_len)
            .u8(self.use_pre_set_ptp_para);
    }
    pub fn read(r: &mut Reader<'_>) -> Result<HomeSetting, PayloadError> {
        Ok(HomeSetting {
            mode: r.i16()?,
            dir: r.i16()?,
            offset: r.i64()?,
            scan1st_vel: r.f64()?,
            scan2nd_vel: r.f64()?,
            acc: r.f64()?,
            re_scan_en: r.u8()?,
            home_edge: r.u8()?,
            lmt_edge: r.u8()?,
            z_edge: r.u8()?,
            ini_ret_pos: r.u64()?,
            ret_sw_offset: r.u64()?,
            safe_len: r.u64()?,
            use_pre_set_ptp_para: r.u8()?,
        })
    }
}

/// `TCardInfo` (digest 001 §3.18).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CardInfo {
    pub str_ver: [u8; 16],
    pub str_oem_ver: [u8; 16],
    /// Year, month, day, hour, minute, second (of the firmware build).
    pub time: [i16; 6],
    pub axis_num: i16,
    pub enc_num: i16,
    pub di_num: i16,
    pub do_num: i16,
    pub da_num: i16,
    pub ad_num: i16,
    pub shio_num: i16,
    pub ipv4: [u8; 4],
    pub id_str: [u8; 16],
    pub uid: [u64; 4],
}

impl CardInfo {
    pub fn write(&self, w: &mut Writer) {
        put_chars(w, &self.str_ver);
        put_chars(w, &self.str_oem_ver);
        for t in self.time {
            w.i16(t);
        }
        for n in [
            self.axis_num,
            self.enc_num,
            self.di_num,
            self.do_num,
            self.da_num,
            self.ad_num,
            self.shio_num,
        ] {
            w.i16(n);
        }
        put_chars(w, &self.ipv4);
        put_chars(w, &self.id_str);
        for u in self.uid {
            w.u64(u);
        }
    }
    pub fn read(r: &mut Reader<'_>) -> Result<CardInfo, PayloadError> {
        let str_ver = get_chars(r)?;
        let str_oem_ver = get_chars(r)?;
        let mut time = [0i16; 6];
        for t in &mut time {
            *t = r.i16()?;
        }
        let mut n = [0i16; 7];
        for v in &mut n {
            *v = r.i16()?;
        }
        let ipv4 = get_chars(r)?;
        let id_str = get_chars(r)?;
        let mut uid = [0u64; 4];
        for u in &mut uid {
            *u = r.u64()?;
        }
        let [axis_num, enc_num, di_num, do_num, da_num, ad_num, shio_num] = n;
        Ok(CardInfo {
            str_ver,
            str_oem_ver,
            time,
            axis_num,
            enc_num,
            di_num,
            do_num,
            da_num,
            ad_num,
            shio_num,
            ipv4,
            id_str,
            uid,
        })
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn structs_round_trip() {
        let p = PtpPara {
            acc: 0.5,
            dec: 0.25,
            start_vel: 1.0,
            end_vel: 0.0,
            smooth_coef: 10,
        };
        let h = HomeSetting {
            mode: 1,
            offset: -5,
            scan1st_vel: 5.0,
            acc: 0.5,
            safe_len: 1000,
            ..HomeSetting::default()
        };
        let c = CardInfo {
            str_ver: chars("mcemu 0.1.0"),
            id_str: chars("CARD1"),
            ipv4: [192, 168, 1, 110],
            axis_num: 4,
            uid: [1, 2, 3, u64::MAX],
            ..CardInfo::default()
        };
        let j = JogPara {
            acc: 1.0,
            dec: 2.0,
            smooth_coef: 3.0,
        };
        let mut w = Writer::new();
        p.write(&mut w);
        h.write(&mut w);
        c.write(&mut w);
        j.write(&mut w);
        let mut r = Reader::new(&w.bytes);
        assert_eq!(PtpPara::read(&mut r).unwrap(), p);
        assert_eq!(HomeSetting::read(&mut r).unwrap(), h);
        assert_eq!(CardInfo::read(&mut r).unwrap(), c);
        assert_eq!(JogPara::read(&mut r).unwrap(), j);
        r.finish().unwrap();
    }

    #[test]
    fn chars_always_end_in_nul() {
        let c: [u8; 4] = chars("ABCDEFG");
        assert_eq!(c, *b"ABC\0");
    }
}
