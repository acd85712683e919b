//! The structs of the synchronised-motion families (digest 001 §3.15–§3.17: PT/PVT parameters,
//! advanced capture, 2-D compare, 2-D compensation) as the wire carries them, with the rules of
//! `crate::structs`: fields in declaration order, `long` as i64, `reserved` members not sent.

use crate::payload::{PayloadError, Reader, Writer};

/// `TPtPara`: smoothDec (the stop's deceleration, pulse/ms²), abruptDec (reserved).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PtPara {
    pub smooth_dec: f64,
    pub abrupt_dec: f64,
}

impl PtPara {
    pub fn write(&self, w: &mut Writer) {
        w.f64(self.smooth_dec).f64(self.abrupt_dec);
    }
    pub fn read(r: &mut Reader<'_>) -> Result<PtPara, PayloadError> {
        Ok(PtPara {
            smooth_dec: r.f64()?,
            abrupt_dec: r.f64()?,
        })
    }
}

/// `TPvtPara`: as `TPtPara`, plus dataMode (1 static, 0 refresh) and loopCount.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PvtPara {
    pub smooth_dec: f64,
    pub abrupt_dec: f64,
    pub data_mode: i64,
    pub loop_count: i64,
}

impl PvtPara {
    pub fn write(&self, w: &mut Writer) {
        w.f64(self.smooth_dec)
            .f64(self.abrupt_dec)
            .i64(self.data_mode)
            .i64(self.loop_count);
    }
    pub fn read(r: &mut Reader<'_>) -> Result<PvtPara, PayloadError> {
        Ok(PvtPara {
            smooth_dec: r.f64()?,
            abrupt_dec: r.f64()?,
            data_mode: r.i64()?,
            loop_count: r.i64()?,
        })
    }
}

/// `TAdvCaptureParam` (digest 001 §3.15).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct AdvCaptureParam {
    pub cap_pos_index: i16,
    pub trig_src: i16,
    pub trig_index: i16,
    /// 0.1 ms, [0, 255].
    pub filter: i16,
    pub trig_value: i64,
}

impl AdvCaptureParam {
    pub fn write(&self, w: &mut Writer) {
        w.i16(self.cap_pos_index)
            .i16(self.trig_src)
            .i16(self.trig_index)
            .i16(self.filter)
            .i64(self.trig_value);
    }
    pub fn read(r: &mut Reader<'_>) -> Result<AdvCaptureParam, PayloadError> {
        Ok(AdvCaptureParam {
            cap_pos_index: r.i16()?,
            trig_src: r.i16()?,
            trig_index: r.i16()?,
            filter: r.i16()?,
            trig_value: r.i64()?,
        })
    }
}

/// `TComp2DimensParamEx` (digest 001 §3.16).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Comp2DimensParam {
    pub output_chn: i16,
    /// 0 pulse, 1 level.
    pub output_type: i16,
    /// 0 GPO, 1 GATE (HSIO).
    pub chn_type: i16,
    pub dir1_no: i16,
    /// −1: 1-D compare.
    pub dir2_no: i16,
    /// 0 planned, 1 encoder.
    pub pos_src: i16,
    pub st_level: i16,
    pub err_zone: i16,
    pub direct_out_zone: i16,
    pub vibrate_range: i16,
    /// µs.
    pub gate_time: i64,
    /// µs.
    pub min_interval_time: i64,
}

impl Comp2DimensParam {
    pub fn write(&self, w: &mut Writer) {
        for v in [
            self.output_chn,
            self.output_type,
            self.chn_type,
            self.dir1_no,
            self.dir2_no,
            self.pos_src,
            self.st_level,
            self.err_zone,
            self.direct_out_zone,
            self.vibrate_range,
        ] {
            w.i16(v);
        }
        w.i64(self.gate_time).i64(self.min_interval_time);
    }
    pub fn read(r: &mut Reader<'_>) -> Result<Comp2DimensParam, PayloadError> {
        let mut s = [0i16; 10];
        for v in &mut s {
            *v = r.i16()?;
        }
        let [output_chn, output_type, chn_type, dir1_no, dir2_no, pos_src, st_level, err_zone, direct_out_zone, vibrate_range] =
            s;
        Ok(Comp2DimensParam {
            output_chn,
            output_type,
            chn_type,
            dir1_no,
            dir2_no,
            pos_src,
            st_level,
            err_zone,
            direct_out_zone,
            vibrate_range,
            gate_time: r.i64()?,
            min_interval_time: r.i64()?,
        })
    }
}

/// `TComp2DimensSts`: sts 0 idle / 1 busy, free space, points not yet output, outputs so far.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Comp2DimensSts {
    pub sts: i16,
    pub free_space: i64,
    pub used_space: i64,
    pub out_count: i64,
}

impl Comp2DimensSts {
    pub fn write(&self, w: &mut Writer) {
        w.i16(self.sts)
            .i64(self.free_space)
            .i64(self.used_space)
            .i64(self.out_count);
    }
    pub fn read(r: &mut Reader<'_>) -> Result<Comp2DimensSts, PayloadError> {
        Ok(Comp2DimensSts {
            sts: r.i16()?,
            free_space: r.i64()?,
            used_space: r.i64()?,
            out_count: r.i64()?,
        })
    }
}

/// `T2DCompensationTable`: points per direction, first point, spacing (pulse), angle (degrees).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Comp2DTable {
    pub count: [i16; 2],
    pub pos_begin: [i64; 2],
    pub step: [i64; 2],
    pub angle: f64,
}

impl Comp2DTable {
    pub fn write(&self, w: &mut Writer) {
        w.i16(self.count[0]).i16(self.count[1]);
        w.i64(self.pos_begin[0]).i64(self.pos_begin[1]);
        w.i64(self.step[0]).i64(self.step[1]).f64(self.angle);
    }
    pub fn read(r: &mut Reader<'_>) -> Result<Comp2DTable, PayloadError> {
        Ok(Comp2DTable {
            count: [r.i16()?, r.i16()?],
            pos_begin: [r.i64()?, r.i64()?],
            step: [r.i64()?, r.i64()?],
            angle: r.f64()?,
        })
    }
}

/// `TCompData`: the X, Y and Z corrections at one grid point (pulse).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CompData {
    pub x: i64,
    pub y: i64,
    pub z: i64,
}

impl CompData {
    pub fn write(&self, w: &mut Writer) {
        w.i64(self.x).i64(self.y).i64(self.z);
    }
    pub fn read(r: &mut Reader<'_>) -> Result<CompData, PayloadError> {
        Ok(CompData {
            x: r.i64()?,
            y: r.i64()?,
            z: r.i64()?,
        })
    }
}

/// `T2DCompensation`: on/off, the table, the X/Y reference sources (0 planned, 1 encoder) and
/// the corrected X, Y, Z axes (−1 none).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Comp2D {
    pub enable: i16,
    pub table_index: i16,
    pub axis_type: [i16; 2],
    pub axis_index: [i16; 3],
}

impl Comp2D {
    pub fn write(&self, w: &mut Writer) {
        w.i16(self.enable).i16(self.table_index);
        for v in self.axis_type.iter().chain(&self.axis_index) {
            w.i16(*v);
        }
    }
    pub fn read(r: &mut Reader<'_>) -> Result<Comp2D, PayloadError> {
        Ok(Comp2D {
            enable: r.i16()?,
            table_index: r.i16()?,
            axis_type: [r.i16()?, r.i16()?],
            axis_index: [r.i16()?, r.i16()?, r.i16()?],
        })
    }
}

/// An array argument: u16 count, then the elements (`crate::payload`).
pub fn write_array<T>(w: &mut Writer, items: &[T], mut put: impl FnMut(&mut Writer, &T)) {
    let n = items.len().min(usize::from(u16::MAX));
    w.u16(n as u16);
    for item in items.iter().take(n) {
        put(w, item);
    }
}

/// An array argument's elements.
pub fn read_array<T>(
    r: &mut Reader<'_>,
    mut get: impl FnMut(&mut Reader<'_>) -> Result<T, PayloadError>,
) -> Result<Vec<T>, PayloadError> {
    let n = usize::from(r.u16()?);
    // Each element is at least 1 byte: a count above what is left cannot be complete, and
    // capping the reservation keeps a hostile count from allocating.
    let mut out = Vec::with_capacity(n.min(r.remaining()));
    for _ in 0..n {
        out.push(get(r)?);
    }
    Ok(out)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn sync_structs_and_arrays_round_trip() {
        let p = Comp2DimensParam {
            dir2_no: -1,
            err_zone: 10,
            gate_time: 10,
            ..Default::default()
        };
        let t = Comp2DTable {
            count: [3, 4],
            step: [3000, 4000],
            ..Default::default()
        };
        let c = Comp2D {
            enable: 1,
            axis_index: [0, 1, -1],
            ..Default::default()
        };
        let a = AdvCaptureParam {
            filter: 100,
            trig_value: -1,
            ..Default::default()
        };
        let mut w = Writer::new();
        p.write(&mut w);
        t.write(&mut w);
        c.write(&mut w);
        a.write(&mut w);
        write_array(&mut w, &[1.5, -2.0], |w, v| {
            w.f64(*v);
        });
        let mut r = Reader::new(&w.bytes);
        assert_eq!(Comp2DimensParam::read(&mut r).unwrap(), p);
        assert_eq!(Comp2DTable::read(&mut r).unwrap(), t);
        assert_eq!(Comp2D::read(&mut r).unwrap(), c);
        assert_eq!(AdvCaptureParam::read(&mut r).unwrap(), a);
        assert_eq!(read_array(&mut r, |r| r.f64()).unwrap(), [1.5, -2.0]);
        r.finish().unwrap();
    }

    #[test]
    fn a_count_beyond_the_payload_is_short() {
        let mut w = Writer::new();
        w.u16(u16::MAX).i16(1);
        let mut r = Reader::new(&w.bytes);
        assert!(read_array(&mut r, |r| r.i16()).is_err());
    }
}
