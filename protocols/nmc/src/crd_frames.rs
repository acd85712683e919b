//! The structs of the 0x17xx family (coordinate transforms, arc sections, move protection;
//! digest 001 §2.7, §2.20 C3§10.5, §3.7) as the wire carries them (`reserved` members are not
//! sent), and their C text.

use crate::payload::{PayloadError, Reader, Writer};

/// `MAX_ERR_TABLE_SECTION` (referenced, not defined by the manual): its comment names r0, r1
/// and err0–err2, so 2 radii and 3 errors (decisions.md).
pub const MAX_ERR_TABLE_SECTION: usize = 2;

/// `TArcSecSetting` (digest 001 §3.7): the arcs' smallest section, the arc validity error and
/// the radius → interpolation-error table (all radii 0: off).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArcSecSetting {
    pub min_section_len: f64,
    pub max_arc_diff: f64,
    pub r: [f64; MAX_ERR_TABLE_SECTION],
    pub err: [f64; MAX_ERR_TABLE_SECTION + 1],
}

impl Default for ArcSecSetting {
    /// minSectionLen 1 pulse (the stated default); the table off; maxArcDiff 0 (none stated).
    fn default() -> ArcSecSetting {
        ArcSecSetting {
            min_section_len: 1.0,
            max_arc_diff: 0.0,
            r: [0.0; MAX_ERR_TABLE_SECTION],
            err: [0.0; MAX_ERR_TABLE_SECTION + 1],
        }
    }
}

impl ArcSecSetting {
    pub fn write(&self, w: &mut Writer) {
        w.f64(self.min_section_len).f64(self.max_arc_diff);
        for v in self.r.iter().chain(&self.err) {
            w.f64(*v);
        }
    }

    pub fn read(r: &mut Reader<'_>) -> Result<ArcSecSetting, PayloadError> {
        let (min_section_len, max_arc_diff) = (r.f64()?, r.f64()?);
        let mut radii = [0.0; MAX_ERR_TABLE_SECTION];
        for v in &mut radii {
            *v = r.f64()?;
        }
        let mut err = [0.0; MAX_ERR_TABLE_SECTION + 1];
        for v in &mut err {
            *v = r.f64()?;
        }
        Ok(ArcSecSetting {
            min_section_len,
            max_arc_diff,
            r: radii,
            err,
        })
    }
}

/// `TmvProtectPara` / `TMvProtectPara` (digest 001 §3.7): which coordinate of which two
/// coordinate systems are guarded, and how.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MvProtectPara {
    pub crd_no: [i16; 2],
    pub crd_ax_no: [i16; 2],
    pub move_dir: [i16; 2],
    pub org_dis: i64,
    pub mv_protect_dis: i64,
    pub safe_wait_pos: i64,
    pub mv_to_safe_acc: f64,
    pub mv_to_safe_vel: f64,
    pub stop_crd_no: i16,
}

impl MvProtectPara {
    pub fn write(&self, w: &mut Writer) {
        for v in self
            .crd_no
            .iter()
            .chain(&self.crd_ax_no)
            .chain(&self.move_dir)
        {
            w.i16(*v);
        }
        w.i64(self.org_dis)
            .i64(self.mv_protect_dis)
            .i64(self.safe_wait_pos)
            .f64(self.mv_to_safe_acc)
            .f64(self.mv_to_safe_vel)
            .i16(self.stop_crd_no);
    }

    pub fn read(r: &mut Reader<'_>) -> Result<MvProtectPara, PayloadError> {
        let mut pairs = [[0i16; 2]; 3];
        for v in pairs.iter_mut().flatten() {
            *v = r.i16()?;
        }
        Ok(MvProtectPara {
            crd_no: pairs[0],
            crd_ax_no: pairs[1],
            move_dir: pairs[2],
            org_dis: r.i64()?,
            mv_protect_dis: r.i64()?,
            safe_wait_pos: r.i64()?,
            mv_to_safe_acc: r.f64()?,
            mv_to_safe_vel: r.f64()?,
            stop_crd_no: r.i16()?,
        })
    }
}

/// The C declarations of the 0x17xx family's structs (digest 001 §3.7; the manual writes the
/// protection struct both `TMvProtectPara` and `TmvProtectPara`: both names are declared).
pub const C_DECLARATIONS: &str = r#"/* Coordinate transforms, arc sections, move protection (digest 001 §2.7, §3.7). */
#define MAX_ERR_TABLE_SECTION 2
typedef struct {
    double minSectionLen;
    double maxArcDiff;
    double r[MAX_ERR_TABLE_SECTION];
    double err[MAX_ERR_TABLE_SECTION + 1];
} TArcSecSetting;
typedef struct {
    short crdNo[2];
    short crdAxNo[2];
    short moveDir[2];
    long orgDis;
    long mvProtectDis;
    long safeWaitPos;
    double mvToSafeAcc;
    double mvToSafeVel;
    short stopCrdNo;
    short reserved[3];
} TmvProtectPara;
typedef TmvProtectPara TMvProtectPara;

"#;

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn arc_sections_and_protection_round_trip() {
        let a = ArcSecSetting {
            min_section_len: 2.0,
            max_arc_diff: 3.0,
            r: [100.0, 1000.0],
            err: [0.5, 1.0, 2.0],
        };
        let p = MvProtectPara {
            crd_no: [0, 1],
            crd_ax_no: [0, 0],
            move_dir: [1, -1],
            org_dis: 100_000,
            mv_protect_dis: 5000,
            safe_wait_pos: -2000,
            mv_to_safe_acc: 1.5,
            mv_to_safe_vel: 20.0,
            stop_crd_no: 1,
        };
        let mut w = Writer::new();
        a.write(&mut w);
        p.write(&mut w);
        let mut r = Reader::new(&w.bytes);
        assert_eq!(ArcSecSetting::read(&mut r).unwrap(), a);
        assert_eq!(MvProtectPara::read(&mut r).unwrap(), p);
        r.finish().unwrap();
    }
}
