//! The laser and SHIO (high-speed gate) families' structs as the wire carries them (digest 001
//! §2.12, §3.20; rules of `crate::structs`: fields in declaration order, `long` as i64,
//! `reserved` members not sent) and their part of `mtn_lib20.h`.

use crate::payload::{PayloadError, Reader, Writer};

/// Points of one power-time array (`LASET_POINT`: the manual leaves it undefined; the vendor's
/// header has 40, and the manual's welding example's `count = 60` is over it: refused).
pub const LASET_POINT: usize = 40;
/// Power-time arrays (`LASER_GROUP`, "最大支持 12 组").
pub const LASER_GROUP: usize = 12;

/// `TTimeArrayPara` (digest 001 §3.20).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TimeArrayPara {
    /// 0: one waveform at once, 1: one per `gate_distance` of travel.
    pub pwm_enable: i16,
    /// The switch signal: 0 gate, 1 GPO (`output_ch`).
    pub output_type: i16,
    pub output_ch: i16,
    pub st_level_revs: i16,
    pub pwm_period: i64,
    pub pwm_width: i64,
    pub gate_distance: i64,
    pub min_frq_frq: i64,
    pub pos_src: i16,
    pub axis_mask: i16,
    pub min_frq_en: i16,
}

impl TimeArrayPara {
    pub fn write(&self, w: &mut Writer) {
        w.i16(self.pwm_enable)
            .i16(self.output_type)
            .i16(self.output_ch)
            .i16(self.st_level_revs)
            .i64(self.pwm_period)
            .i64(self.pwm_width)
            .i64(self.gate_distance)
            .i64(self.min_frq_frq)
            .i16(self.pos_src)
            .i16(self.axis_mask)
            .i16(self.min_frq_en);
    }
    pub fn read(r: &mut Reader<'_>) -> Result<TimeArrayPara, PayloadError> {
        Ok(TimeArrayPara {
            pwm_enable: r.i16()?,
            output_type: r.i16()?,
            output_ch: r.i16()?,
            st_level_revs: r.i16()?,
            pwm_period: r.i64()?,
            pwm_width: r.i64()?,
            gate_distance: r.i64()?,
            min_frq_frq: r.i64()?,
            pos_src: r.i16()?,
            axis_mask: r.i16()?,
            min_frq_en: r.i16()?,
        })
    }
}

/// `TLaserPower`: `count` points of (time in 100 µs, power). On the wire: count, then the
/// first `count` pairs (at most [`LASET_POINT`]; a larger count is sent as is and refused by
/// the server).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LaserPower {
    pub count: i16,
    pub points: Vec<(u16, i16)>,
}

impl LaserPower {
    pub fn write(&self, w: &mut Writer) {
        w.i16(self.count).u16(self.points.len() as u16);
        for (t, p) in &self.points {
            w.u16(*t).i16(*p);
        }
    }
    pub fn read(r: &mut Reader<'_>) -> Result<LaserPower, PayloadError> {
        let count = r.i16()?;
        let n = usize::from(r.u16()?);
        let mut points = Vec::with_capacity(n.min(LASET_POINT));
        for _ in 0..n {
            let p = (r.u16()?, r.i16()?);
            if points.len() < LASET_POINT {
                points.push(p);
            }
        }
        Ok(LaserPower { count, points })
    }
}

/// `TSHIOPara` (digest 001 §3.20; the manual's layout, `reserved4`/`reserved5` not sent).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ShioPara {
    pub is_array: i16,
    /// 1 gate on/off at once, 2 by travel, 3 by travel + trigger, 4 by travel + input.
    pub out_mode: i16,
    /// 0 encoder, 1 planned.
    pub pos_src: i16,
    pub axis_mask: i16,
    /// s.
    pub delay: f64,
    /// s, (0, 0.0009).
    pub gate_time: f64,
    /// pulse.
    pub gate_distance: i64,
    pub k: i64,
    pub start_dot: i64,
    pub low_frq_range: i64,
}

impl ShioPara {
    pub fn write(&self, w: &mut Writer) {
        w.i16(self.is_array)
            .i16(self.out_mode)
            .i16(self.pos_src)
            .i16(self.axis_mask)
            .f64(self.delay)
            .f64(self.gate_time)
            .i64(self.gate_distance)
            .i64(self.k)
            .i64(self.start_dot)
            .i64(self.low_frq_range);
    }
    pub fn read(r: &mut Reader<'_>) -> Result<ShioPara, PayloadError> {
        Ok(ShioPara {
            is_array: r.i16()?,
            out_mode: r.i16()?,
            pos_src: r.i16()?,
            axis_mask: r.i16()?,
            delay: r.f64()?,
            gate_time: r.f64()?,
            gate_distance: r.i64()?,
            k: r.i64()?,
            start_dot: r.i64()?,
            low_frq_range: r.i64()?,
        })
    }
}

/// Appended to `crate::header`'s preamble: the laser constants and structs (digest 001 §3.20,
/// verbatim names; `long` the platform's).
pub const LASER_PREAMBLE: &str = r#"/* Laser and SHIO (digest 001 §2.12, §3.20). */
#define LASER_DISABLE_MODE     (0)
#define BASIC_OUTPUT_MODE      (1)
#define TIME_ARRAY_OUTPUT_MODE (2)
#define SHIO_OUTPUT_MODE       (3)
#define LASER_NONE        (0)
#define LASER_DA          (1)
#define LASER_PWM_DUTY    (2)
#define LASER_PWM_FRQ     (3)
#define LASER_PWM_FRQ_EXT (4)
#define LASER_GROUP (12)
#define LASET_POINT (40)

typedef struct {
    short pwmEnable;
    short outputType;
    short outputCh;
    short stLevelRevs;
    long pwmPeriod;
    long pwmWidth;
    long gateDistance;
    long minFrqFrq;
    short posSrc;
    short axisMask;
    short minFrqEn;
    short reserved2;
} TTimeArrayPara;
typedef struct { unsigned short time[LASET_POINT]; short power[LASET_POINT]; short count; } TLaserPower;
typedef struct {
    short isArray;
    short outMode;
    short posSrc;
    short axisMask;
    double delay;
    double gateTime;
    long gateDistance;
    long k;
    long startDot;
    long lowFrqRange;
    long reserved4;
    long reserved5;
} TSHIOPara;

"#;

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn structs_round_trip() {
        let t = TimeArrayPara {
            pwm_enable: 1,
            gate_distance: 20,
            axis_mask: 3,
            pwm_period: 500_000,
            ..TimeArrayPara::default()
        };
        let p = LaserPower {
            count: 2,
            points: vec![(100, 5), (100, 0)],
        };
        let s = ShioPara {
            out_mode: 2,
            gate_time: 0.0008,
            gate_distance: 20,
            ..ShioPara::default()
        };
        let mut w = Writer::new();
        t.write(&mut w);
        p.write(&mut w);
        s.write(&mut w);
        let mut r = Reader::new(&w.bytes);
        assert_eq!(TimeArrayPara::read(&mut r).unwrap(), t);
        assert_eq!(LaserPower::read(&mut r).unwrap(), p);
        assert_eq!(ShioPara::read(&mut r).unwrap(), s);
        r.finish().unwrap();
    }
}
