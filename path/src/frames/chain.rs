//! HIMC's frame chain MCS → OFFSET → WCSn → PCS (digest 004 §2.7, Table 8.1.2.1, examples
//! 5-1…5-3, TV 56–57).

use super::Transform;
use crate::checks::GeometryError;
use crate::Point;

/// Workpiece frames `CS_WCS1` … `CS_WCS15`.
pub const WCS_COUNT: usize = 15;

/// One link of the chain.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Frame {
    /// `CS_OFFSET`: the temporary zero.
    Offset,
    /// `CS_WCS1` … `CS_WCS15` (1-based, as HIMC numbers them).
    Wcs(u8),
    /// `CS_PCS`: the product (program) frame.
    Pcs,
}

/// Which links a move's coordinates go through: HIMC's `coord_sys` bits (`CS_MCS` is all
/// off; `CS_WCS1 | CS_PCS`; `CS_OFFSET | CS_WCS2 | CS_PCS`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FrameSelection {
    pub offset: bool,
    /// 1 to 15.
    pub wcs: Option<u8>,
    pub pcs: bool,
}

#[derive(Clone, Copy, Debug, PartialEq)]
struct Link {
    /// As set (`{X, Y, Z, A, B, C}`, A–C in degrees), returned unchanged (TV 57).
    pose: [f64; 6],
    transform: Transform,
}

impl Default for Link {
    fn default() -> Self {
        Link {
            pose: [0.0; 6],
            transform: Transform::identity(),
        }
    }
}

/// The frames of one group: every link starts as the identity ("no offset by default").
///
/// Inputs: [`FrameChain::set`] per link (HIMC `SetGrpCoordTrans`). Outputs:
/// [`FrameChain::pose`] (`GetGrpCoordTrans`), [`FrameChain::to_machine`] (the composite
/// transform for a selection), [`FrameChain::point_to_machine`] and
/// [`FrameChain::point_from_machine`].
///
/// Each link's pose is its frame's placement in its parent: a point `p` of the PCS is
/// `T_pcs·p` in the WCSn, `T_wcs·T_pcs·p` in OFFSET and `T_offset·T_wcs·T_pcs·p` in the MCS;
/// links not selected are skipped. With only the PCS set this is TV 56's
/// `MCS = R_z(C)·p + t`; the order of the other links is our reading of the chain's arrows
/// (the manual gives no numbers for it).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FrameChain {
    offset: Link,
    wcs: [Link; WCS_COUNT],
    pcs: Link,
}

fn wcs_index(n: u8) -> Result<usize, GeometryError> {
    match usize::from(n) {
        k @ 1..=WCS_COUNT => Ok(k - 1),
        _ => Err(GeometryError::Invalid(
            "a workpiece frame is CS_WCS1 to CS_WCS15",
        )),
    }
}

impl FrameChain {
    pub fn new() -> FrameChain {
        FrameChain::default()
    }

    fn link(&self, frame: Frame) -> Result<&Link, GeometryError> {
        Ok(match frame {
            Frame::Offset => &self.offset,
            Frame::Wcs(n) => &self.wcs[wcs_index(n)?],
            Frame::Pcs => &self.pcs,
        })
    }

    /// Sets a link from HIMC's `{X, Y, Z, A, B, C}` (A–C degrees, roll-pitch-yaw).
    pub fn set(&mut self, frame: Frame, pose: [f64; 6]) -> Result<(), GeometryError> {
        let transform = Transform::from_himc_pose(pose)?;
        let link = match frame {
            Frame::Offset => &mut self.offset,
            Frame::Wcs(n) => &mut self.wcs[wcs_index(n)?],
            Frame::Pcs => &mut self.pcs,
        };
        *link = Link { pose, transform };
        Ok(())
    }

    /// The pose a link was set to, exactly (TV 57).
    pub fn pose(&self, frame: Frame) -> Result<[f64; 6], GeometryError> {
        Ok(self.link(frame)?.pose)
    }

    /// One link's transform (frame → parent).
    pub fn transform(&self, frame: Frame) -> Result<Transform, GeometryError> {
        Ok(self.link(frame)?.transform)
    }

    /// The composite transform from the selection's innermost frame to the MCS:
    /// `T_offset ∘ T_wcs ∘ T_pcs` over the selected links.
    pub fn to_machine(&self, selection: FrameSelection) -> Result<Transform, GeometryError> {
        let mut t = Transform::identity();
        if selection.offset {
            t = self.offset.transform;
        }
        if let Some(n) = selection.wcs {
            t = t.compose(&self.wcs[wcs_index(n)?].transform);
        }
        if selection.pcs {
            t = t.compose(&self.pcs.transform);
        }
        Ok(t)
    }

    pub fn point_to_machine(
        &self,
        selection: FrameSelection,
        p: &Point,
    ) -> Result<Point, GeometryError> {
        Ok(self.to_machine(selection)?.apply(p))
    }

    pub fn point_from_machine(
        &self,
        selection: FrameSelection,
        p: &Point,
    ) -> Result<Point, GeometryError> {
        Ok(self.to_machine(selection)?.inverse().apply(p))
    }
}
