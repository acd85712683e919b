//! The NMC coordinate systems' front-end state (digest 001 §2.7, §4.4): what the engine's
//! groups do not keep. A coordinate system n is the engine's group n; its parameters are the
//! manual's, in pulses; commands pushed before `NMC_CrdStartMtn` wait here (the manual's
//! "push first, then start"), commands pushed after it go to the engine at once.

use axes::command::Command;
use mcemu_nmc::crd::{CrdConfig, CrdPara, CrdSafePara, ExtCrdPara, CRD_MAX_AXES};
use mcemu_nmc::crd_lookahead::LookaheadPara;

/// Coordinate systems a device has (`NMC_CrdOpenEx` itemNo ∈ [0, 1], TV04).
pub const CRD_COUNT: usize = 2;

/// Entries a coordinate system's buffer holds: the engine queue's capacity (decisions.md).
pub const CRD_BUFFER: usize = 1024;

/// One coordinate system.
#[derive(Clone, Debug, Default)]
pub struct CrdState {
    /// `NMC_CrdConfig`'s map; `None` until configured (or after `NMC_CrdDelete`).
    pub config: Option<CrdConfig>,
    pub para: CrdPara,
    pub ext: ExtCrdPara,
    pub safe: CrdSafePara,
    /// Commands pushed and not yet handed to the engine (before `NMC_CrdStartMtn`).
    pub pending: Vec<Command>,
    /// `NMC_CrdStartMtn` ran since the last `NMC_CrdBufClr`: pushes go to the engine.
    pub started: bool,
    /// Where the last pushed motion ends, pulses in user coordinates: the start of the next
    /// one (a coordinate a segment does not name keeps this value).
    pub end: [i64; CRD_MAX_AXES],
    /// Where the extra axes of `NMC_CrdLineXYZD8` and buffered axis moves end, by axis.
    pub ext_end: Vec<(usize, i64)>,
    /// Commands pushed since the last `NMC_CrdBufClr` (`NMC_CrdGetBufAllCmdCnt`).
    pub pushed: u64,
    /// The feed override, (0, 10).
    pub override_factor: f64,
    /// `NMC_CrdBufSetPtpMovePara` by axis: velocity (pulse/ms), acceleration (pulse/ms²).
    pub axis_ptp: Vec<(usize, f64, f64)>,
    /// `NMC_CrdSetLookAheadCentriAcc`: the arcs' centripetal acceleration, pulse/ms² (0 off).
    pub centri_acc: f64,
    /// `NMC_CrdSetLookaheadPara`'s last parameters; `None` until it is called (the engine's
    /// corner rules stay off).
    pub lookahead: Option<LookaheadPara>,
    /// `NMC_CrdSetBufLengthFlag` 1: the path length of what is pushed is summed.
    pub length_flag: bool,
    /// The path length pushed since the last `NMC_CrdBufClr` (while `length_flag`), pulses.
    pub pushed_length: f64,
}

impl CrdState {
    pub fn fresh() -> CrdState {
        CrdState {
            override_factor: 1.0,
            ..CrdState::default()
        }
    }

    /// The member axes, in coordinate order.
    pub fn axes(&self) -> Vec<usize> {
        self.config.map_or(Vec::new(), |c| {
            c.ax.iter()
                .take(usize::try_from(c.ax_cnts).unwrap_or(0))
                .filter_map(|a| usize::try_from(*a).ok())
                .collect()
        })
    }

    /// The origin of user coordinates (orgFlag 1: `offset`, else machine zero; decisions.md).
    pub fn origin(&self) -> [i64; CRD_MAX_AXES] {
        if self.para.org_flag == 1 {
            self.para.offset
        } else {
            [0; CRD_MAX_AXES]
        }
    }
}
