//! The coordinate-system structs (digest 001 §3.7) as the wire carries them (the kinds of
//! `crate::payload`; `reserved` and `port` members are not sent), and the C text the header
//! declares them with.

use crate::payload::{PayloadError, Reader, Writer};

/// Axes a coordinate system has at most ("目前坐标系最多支持 4 个轴", digest 001 §3.7).
pub const CRD_MAX_AXES: usize = 4;
/// Coordinates of `NMC_CrdLineXYZD8` (crd axes first, then the extra axes).
pub const D8_AXES: usize = 8;
/// `NMC_CrdLineXYZD8Pack` takes 1 to 18 units (TV53).
pub const D8_PACK_MAX: usize = 18;

/// `TCrdConfig`: the axis map; `ax[k]` is the axis of coordinate k (X, Y, Z, A), −1 unused.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CrdConfig {
    pub ax_cnts: i16,
    pub ax: [i16; CRD_MAX_AXES],
}

impl Default for CrdConfig {
    fn default() -> CrdConfig {
        CrdConfig {
            ax_cnts: 0,
            ax: [-1; CRD_MAX_AXES],
        }
    }
}

impl CrdConfig {
    pub fn write(&self, w: &mut Writer) {
        w.i16(self.ax_cnts);
        for a in self.ax {
            w.i16(a);
        }
    }
    pub fn read(r: &mut Reader<'_>) -> Result<CrdConfig, PayloadError> {
        let ax_cnts = r.i16()?;
        let mut ax = [0i16; CRD_MAX_AXES];
        for a in &mut ax {
            *a = r.i16()?;
        }
        Ok(CrdConfig { ax_cnts, ax })
    }
}

/// `TCrdPara`: origin (orgFlag 1: `offset` from machine zero), path limits (pulse/ms²,
/// pulse/ms).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CrdPara {
    pub org_flag: i16,
    pub offset: [i64; CRD_MAX_AXES],
    pub syn_acc_max: f64,
    pub syn_vel_max: f64,
}

impl Default for CrdPara {
    /// The manual states no defaults: mcemu's are the axes' (TSafePara 32767, TV07).
    fn default() -> CrdPara {
        CrdPara {
            org_flag: 1,
            offset: [0; CRD_MAX_AXES],
            syn_acc_max: 32767.0,
            syn_vel_max: 32767.0,
        }
    }
}

impl CrdPara {
    pub fn write(&self, w: &mut Writer) {
        w.i16(self.org_flag);
        for o in self.offset {
            w.i64(o);
        }
        w.f64(self.syn_acc_max).f64(self.syn_vel_max);
    }
    pub fn read(r: &mut Reader<'_>) -> Result<CrdPara, PayloadError> {
        let org_flag = r.i16()?;
        let mut offset = [0i64; CRD_MAX_AXES];
        for o in &mut offset {
            *o = r.i64()?;
        }
        Ok(CrdPara {
            org_flag,
            offset,
            syn_acc_max: r.f64()?,
            syn_vel_max: r.f64()?,
        })
    }
}

/// `TExtCrdPara` (digest 001 §3.7, defaults as stated there).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ExtCrdPara {
    pub start_vel: f64,
    pub t: f64,
    /// 0 = the path acceleration (the manual's "默认 accMax").
    pub smooth_dec: f64,
    /// 0 = the axes' E-stop deceleration (the manual's "默认无穷大").
    pub abrupt_dec: f64,
    pub look_ahead_switch: i16,
    pub event_time: i16,
}

impl Default for ExtCrdPara {
    fn default() -> ExtCrdPara {
        ExtCrdPara {
            start_vel: 0.0,
            t: 1.0,
            smooth_dec: 0.0,
            abrupt_dec: 0.0,
            look_ahead_switch: 1,
            event_time: 10,
        }
    }
}

impl ExtCrdPara {
    pub fn write(&self, w: &mut Writer) {
        w.f64(self.start_vel)
            .f64(self.t)
            .f64(self.smooth_dec)
            .f64(self.abrupt_dec)
            .i16(self.look_ahead_switch)
            .i16(self.event_time);
    }
    pub fn read(r: &mut Reader<'_>) -> Result<ExtCrdPara, PayloadError> {
        Ok(ExtCrdPara {
            start_vel: r.f64()?,
            t: r.f64()?,
            smooth_dec: r.f64()?,
            abrupt_dec: r.f64()?,
            look_ahead_switch: r.i16()?,
            event_time: r.i16()?,
        })
    }
}

/// `TCrdSafePara {estpDec, maxAcc, maxVel}` (used by the examples, not documented; doubles,
/// digest 001 §8 item 3).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CrdSafePara {
    pub estp_dec: f64,
    pub max_acc: f64,
    pub max_vel: f64,
}

impl Default for CrdSafePara {
    fn default() -> CrdSafePara {
        CrdSafePara {
            estp_dec: 32767.0,
            max_acc: 32767.0,
            max_vel: 32767.0,
        }
    }
}

impl CrdSafePara {
    pub fn write(&self, w: &mut Writer) {
        w.f64(self.estp_dec).f64(self.max_acc).f64(self.max_vel);
    }
    pub fn read(r: &mut Reader<'_>) -> Result<CrdSafePara, PayloadError> {
        Ok(CrdSafePara {
            estp_dec: r.f64()?,
            max_acc: r.f64()?,
            max_vel: r.f64()?,
        })
    }
}

/// `TCrdLineXYZD8Unit` (one `NMC_CrdLineXYZD8` call; `float`s travel as f64).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LineD8Unit {
    pub seg_no: i64,
    pub crd_ax_mask: i16,
    pub ext_ax_mask: i16,
    pub tg_pos: [i64; D8_AXES],
    pub vel: f64,
    pub end_vel: f64,
    pub acc: f64,
    pub lookahead_dis: i16,
}

impl LineD8Unit {
    pub fn write(&self, w: &mut Writer) {
        w.i64(self.seg_no)
            .i16(self.crd_ax_mask)
            .i16(self.ext_ax_mask);
        for p in self.tg_pos {
            w.i64(p);
        }
        w.f64(self.vel)
            .f64(self.end_vel)
            .f64(self.acc)
            .i16(self.lookahead_dis);
    }
    pub fn read(r: &mut Reader<'_>) -> Result<LineD8Unit, PayloadError> {
        let (seg_no, crd_ax_mask, ext_ax_mask) = (r.i64()?, r.i16()?, r.i16()?);
        let mut tg_pos = [0i64; D8_AXES];
        for p in &mut tg_pos {
            *p = r.i64()?;
        }
        Ok(LineD8Unit {
            seg_no,
            crd_ax_mask,
            ext_ax_mask,
            tg_pos,
            vel: r.f64()?,
            end_vel: r.f64()?,
            acc: r.f64()?,
            lookahead_dis: r.i16()?,
        })
    }
}

/// The C declarations of `mtn_lib20.h` for the coordinate system (digest 001 §3.7, §3.8,
/// §3.10; `CRD_BUFF_DELAY_SCALE_MS` = 0 inferred from the scale's definition).
pub const C_DECLARATIONS: &str = r#"/* Coordinate system (digest 001 §3.7, §3.8, §3.10). */
#define BIT_CORD_BUSY           0x00000001
#define BIT_CORD_MVERR          0x00000002
#define BIT_CORD_EMPTY          0x00000004
#define BIT_CORD_FULL           0x00000008
#define BIT_CORD_NODATASTOP     0x00000010
#define BIT_CORD_SDRAM_HWERR    0x00000020
#define BIT_CORD_POSREC         0x00000040
#define BIT_CORD_AUXAXIS_BUSY   0x00000080
#define BIT_CORD_AUXAXIS_ERR    0x00000100
#define BIT_CORD_AXIS_ERR       0x00000200
#define BIT_CORD_SDRAM_CALC_ERR 0x00000400
#define BIT_CORD_SCARA_CALC_ERR 0x00000800
#define CRD_BUFF_DO_MOTOR_ENABLE 1
#define CRD_BUFF_DO_MOTOR_CLEAR  2
#define CRD_BUFF_DO_GPDO1        3
#define CRD_BUFF_DO_GPDO2        4
#define CRD_BUFF_DO_EXTDO1       5
#define CRD_BUFF_DO_EXTDO2       6
#define CRD_BUFF_DO_EXTDO3       7
#define CRD_BUFF_DO_EXTDO4       8
#define CRD_BUFF_DO_EXTDO5       9
#define CRD_BUFF_DO_EXTDO6       10
#define CRD_BUFF_DELAY_SCALE_MS  0
#define CRD_BUFF_DELAY_SCALE_S   1

typedef struct { short axCnts; short reserved[3]; short pAxArray[4]; short port[4]; } TCrdConfig;
typedef struct {
    short orgFlag;
    short reserved[3];
    long offset[4];
    double synAccMax;
    double synVelMax;
} TCrdPara;
typedef struct {
    double startVel;
    double T;
    double smoothDec;
    double abruptDec;
    short lookAheadSwitch;
    short eventTime;
    short reserved[2];
} TExtCrdPara;
typedef struct { double estpDec; double maxAcc; double maxVel; } TCrdSafePara;
typedef struct {
    long segNo;
    short crdAxMask;
    short extAxMask;
    long tgPos[8];
    float vel;
    float endVel;
    float acc;
    short lookaheadDis;
    short reserved;
} TCrdLineXYZD8Unit;

"#;

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn crd_structs_round_trip() {
        let c = CrdConfig {
            ax_cnts: 3,
            ax: [0, 1, 2, -1],
        };
        let p = CrdPara {
            org_flag: 1,
            offset: [1, -2, 3, 4],
            syn_acc_max: 50.0,
            syn_vel_max: 800.0,
        };
        let e = ExtCrdPara {
            look_ahead_switch: 0,
            ..ExtCrdPara::default()
        };
        let s = CrdSafePara {
            estp_dec: 1000.0,
            max_acc: 50.0,
            max_vel: 800.0,
        };
        let u = LineD8Unit {
            seg_no: 7,
            crd_ax_mask: 7,
            ext_ax_mask: 0x38,
            tg_pos: [1, 2, 3, 4, 5, 6, 0, 0],
            vel: 10.0,
            end_vel: 0.0,
            acc: 1.0,
            lookahead_dis: 0,
        };
        let mut w = Writer::new();
        c.write(&mut w);
        p.write(&mut w);
        e.write(&mut w);
        s.write(&mut w);
        u.write(&mut w);
        let mut r = Reader::new(&w.bytes);
        assert_eq!(CrdConfig::read(&mut r).unwrap(), c);
        assert_eq!(CrdPara::read(&mut r).unwrap(), p);
        assert_eq!(ExtCrdPara::read(&mut r).unwrap(), e);
        assert_eq!(CrdSafePara::read(&mut r).unwrap(), s);
        assert_eq!(LineD8Unit::read(&mut r).unwrap(), u);
        r.finish().unwrap();
    }
}
