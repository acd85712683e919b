//! The coordinate-system structs of the 0x14xx family (digest 001 §3.4, §3.9): the look-ahead
//! parameters and the packed status, as the wire carries them (`float`s travel as f64,
//! `reserved` members are not sent), and their C text.

use crate::crd::CRD_MAX_AXES;
use crate::payload::{PayloadError, Reader, Writer};

/// `CRD_MAX_DIMENSION` (referenced, not defined by the manual): the coordinate system's 4
/// coordinates (decisions.md).
pub const CRD_MAX_DIMENSION: usize = CRD_MAX_AXES;

/// `TLookaheadPara` (digest 001 §3.9); `Default` is the manual's stated defaults (what
/// `NMC_CrdGetLookaheadPara(…, 1)` reads).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LookaheadPara {
    pub look_ahead_switch: i16,
    pub cent_acc_en: i16,
    pub cross_en: i16,
    pub event_time: i16,
    pub acc_max: f64,
    pub t: f64,
    pub slow_ang: f64,
    pub stop_ang: f64,
    pub cross_prop: f64,
    pub cent_acc: f64,
    pub dv_max: [f64; CRD_MAX_DIMENSION],
    pub da_max: [f64; CRD_MAX_DIMENSION],
    pub radius_coef: f64,
    pub radius_err: f64,
    pub radius_ang: f64,
    pub radius_ang_max: f64,
    pub radius_ang_min: f64,
    pub ax_prop_time_unit_prop: i16,
    pub pre_handle_en: i16,
    pub pre_handle_dis_ang_min: f64,
    pub pre_handle_dis_ang_max: f64,
    pub pre_handle_tol: f64,
    pub min_corner_vel: f64,
    pub ax_prop: [f64; CRD_MAX_DIMENSION],
}

impl Default for LookaheadPara {
    /// The stated defaults (§3.9, §3.7 TExtCrdPara); slowAng and stopAng 0 (none stated):
    /// no corner-angle rule; the unit-conversion ratios 1.
    fn default() -> LookaheadPara {
        LookaheadPara {
            look_ahead_switch: 1,
            cent_acc_en: 0,
            cross_en: 0,
            event_time: 10,
            acc_max: 1000.0,
            t: 1.0,
            slow_ang: 0.0,
            stop_ang: 0.0,
            cross_prop: 0.0,
            cent_acc: 0.0,
            dv_max: [0.0; CRD_MAX_DIMENSION],
            da_max: [0.0; CRD_MAX_DIMENSION],
            radius_coef: 1.0,
            radius_err: 200.0,
            radius_ang: 7.0,
            radius_ang_max: 7.0,
            radius_ang_min: 0.5,
            ax_prop_time_unit_prop: 0,
            pre_handle_en: 0,
            pre_handle_dis_ang_min: 0.1,
            pre_handle_dis_ang_max: 10.0,
            pre_handle_tol: 0.0,
            min_corner_vel: 0.0,
            ax_prop: [1.0; CRD_MAX_DIMENSION],
        }
    }
}

fn read_array(r: &mut Reader<'_>) -> Result<[f64; CRD_MAX_DIMENSION], PayloadError> {
    let mut a = [0.0; CRD_MAX_DIMENSION];
    for v in &mut a {
        *v = r.f64()?;
    }
    Ok(a)
}

impl LookaheadPara {
    pub fn write(&self, w: &mut Writer) {
        w.i16(self.look_ahead_switch)
            .i16(self.cent_acc_en)
            .i16(self.cross_en)
            .i16(self.event_time);
        for v in [
            self.acc_max,
            self.t,
            self.slow_ang,
            self.stop_ang,
            self.cross_prop,
            self.cent_acc,
        ] {
            w.f64(v);
        }
        for v in self.dv_max.iter().chain(&self.da_max) {
            w.f64(*v);
        }
        for v in [
            self.radius_coef,
            self.radius_err,
            self.radius_ang,
            self.radius_ang_max,
            self.radius_ang_min,
        ] {
            w.f64(v);
        }
        w.i16(self.ax_prop_time_unit_prop).i16(self.pre_handle_en);
        for v in [
            self.pre_handle_dis_ang_min,
            self.pre_handle_dis_ang_max,
            self.pre_handle_tol,
            self.min_corner_vel,
        ] {
            w.f64(v);
        }
        for v in self.ax_prop {
            w.f64(v);
        }
    }

    pub fn read(r: &mut Reader<'_>) -> Result<LookaheadPara, PayloadError> {
        Ok(LookaheadPara {
            look_ahead_switch: r.i16()?,
            cent_acc_en: r.i16()?,
            cross_en: r.i16()?,
            event_time: r.i16()?,
            acc_max: r.f64()?,
            t: r.f64()?,
            slow_ang: r.f64()?,
            stop_ang: r.f64()?,
            cross_prop: r.f64()?,
            cent_acc: r.f64()?,
            dv_max: read_array(r)?,
            da_max: read_array(r)?,
            radius_coef: r.f64()?,
            radius_err: r.f64()?,
            radius_ang: r.f64()?,
            radius_ang_max: r.f64()?,
            radius_ang_min: r.f64()?,
            ax_prop_time_unit_prop: r.i16()?,
            pre_handle_en: r.i16()?,
            pre_handle_dis_ang_min: r.f64()?,
            pre_handle_dis_ang_max: r.f64()?,
            pre_handle_tol: r.f64()?,
            min_corner_vel: r.f64()?,
            ax_prop: read_array(r)?,
        })
    }
}

/// `TPackedCrdSts4` (digest 001 §3.4): one coordinate system's status in one call.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PackedCrdSts4 {
    pub crd_sts: i16,
    pub ax_sts: [i16; CRD_MAX_AXES],
    pub prf_pos: [i64; CRD_MAX_AXES],
    pub axis_pos: [i64; CRD_MAX_AXES],
    pub enc_pos: [i64; CRD_MAX_AXES],
    pub user_seg: i64,
    pub prf_vel: f64,
    pub gp_di: i64,
    pub gp_do: i64,
    pub mot_di: [i16; CRD_MAX_AXES],
    pub crd_free_space: i64,
    pub crd_used_space: i64,
}

impl PackedCrdSts4 {
    pub fn write(&self, w: &mut Writer) {
        w.i16(self.crd_sts);
        for s in self.ax_sts {
            w.i16(s);
        }
        for p in self
            .prf_pos
            .iter()
            .chain(&self.axis_pos)
            .chain(&self.enc_pos)
        {
            w.i64(*p);
        }
        w.i64(self.user_seg)
            .f64(self.prf_vel)
            .i64(self.gp_di)
            .i64(self.gp_do);
        for m in self.mot_di {
            w.i16(m);
        }
        w.i64(self.crd_free_space).i64(self.crd_used_space);
    }

    pub fn read(r: &mut Reader<'_>) -> Result<PackedCrdSts4, PayloadError> {
        let crd_sts = r.i16()?;
        let mut ax_sts = [0i16; CRD_MAX_AXES];
        for s in &mut ax_sts {
            *s = r.i16()?;
        }
        let mut pos = [[0i64; CRD_MAX_AXES]; 3];
        for p in pos.iter_mut().flatten() {
            *p = r.i64()?;
        }
        let (user_seg, prf_vel, gp_di, gp_do) = (r.i64()?, r.f64()?, r.i64()?, r.i64()?);
        let mut mot_di = [0i16; CRD_MAX_AXES];
        for m in &mut mot_di {
            *m = r.i16()?;
        }
        Ok(PackedCrdSts4 {
            crd_sts,
            ax_sts,
            prf_pos: pos[0],
            axis_pos: pos[1],
            enc_pos: pos[2],
            user_seg,
            prf_vel,
            gp_di,
            gp_do,
            mot_di,
            crd_free_space: r.i64()?,
            crd_used_space: r.i64()?,
        })
    }
}

/// The C declarations of the 0x14xx family's structs (digest 001 §3.4, §3.9; `float[] axProp`
/// [sic, C#] as `float axProp[CRD_MAX_DIMENSION]`).
pub const C_DECLARATIONS: &str = r#"/* Coordinate system: look-ahead and packed status (digest 001 §3.4, §3.9). */
#define CRD_MAX_DIMENSION 4
#define CRD_WAIT_POS_LE 0
#define CRD_WAIT_POS_GE 1
typedef struct {
    short lookAheadSwitch;
    short centAccEn;
    short crossEn;
    short eventTime;
    double accMax;
    double T;
    double slowAng;
    double stopAng;
    double crossProp;
    double centAcc;
    double dvMax[CRD_MAX_DIMENSION];
    double daMax[CRD_MAX_DIMENSION];
    double radiusCoef;
    double radiusErr;
    double radiusAng;
    double radiusAngMax;
    double radiusAngMin;
    short axPropTimeUnitProp;
    short preHandleEn;
    short reserved;
    float preHandleDisAngMin;
    float preHandleDisAngMax;
    float preHandleTol;
    float minCornerVel;
    float axProp[CRD_MAX_DIMENSION];
} TLookaheadPara;
typedef struct {
    short crdSts;
    short axSts[4];
    long prfPos[4];
    long axisPos[4];
    long encPos[4];
    long userSeg;
    double prfVel;
    long gpDi;
    long gpDo;
    short motDi[4];
    short reserved;
    long crdFreeSpace;
    long crdUsedSpace;
} TPackedCrdSts4;

"#;

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn lookahead_and_pack_round_trip() {
        let l = LookaheadPara {
            look_ahead_switch: 0,
            slow_ang: 10.0,
            stop_ang: 170.0,
            da_max: [1.0, 2.0, 3.0, 4.0],
            ax_prop: [5.0, 6.0, 7.0, 8.0],
            ..LookaheadPara::default()
        };
        let p = PackedCrdSts4 {
            crd_sts: 5,
            ax_sts: [1, 2, 3, 4],
            prf_pos: [1, -2, 3, -4],
            axis_pos: [5, 6, 7, 8],
            enc_pos: [9, 10, 11, 12],
            user_seg: 7,
            prf_vel: 2.5,
            gp_di: 3,
            gp_do: 4,
            mot_di: [0, 1, 0, 1],
            crd_free_space: 1000,
            crd_used_space: 24,
        };
        let mut w = Writer::new();
        l.write(&mut w);
        p.write(&mut w);
        let mut r = Reader::new(&w.bytes);
        assert_eq!(LookaheadPara::read(&mut r).unwrap(), l);
        assert_eq!(PackedCrdSts4::read(&mut r).unwrap(), p);
        r.finish().unwrap();
    }
}
