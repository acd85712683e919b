//! What the synchronised-motion families keep that the engine does not (digest 001 §2.9–2.11,
//! §2.13–2.19): the settings a later call starts from (gear, capture sense, compare parameters
//! and points, gantry groups, the handwheel, the compensation tables as written), in the
//! manual's units, per device section and shared by its connections like `AxisSettings`.

use mcemu_nmc::sync_structs::{Comp2D, Comp2DTable, Comp2DimensParam, CompData, PtPara, PvtPara};

/// One axis's gear, PT/PVT, capture and compensation settings.
#[derive(Clone, Debug, PartialEq)]
pub struct AxisSync {
    /// MtGearSetDir: 0 both ways, < 0 negative only, > 0 positive only.
    pub gear_dir: i16,
    pub gear_master: i16,
    /// 1 planned, 2 feedback, 3 encoder.
    pub gear_master_type: i16,
    pub gear_master_even: i64,
    pub gear_slave_even: i64,
    pub gear_master_slope: i64,
    pub pt: PtPara,
    pub pvt: PvtPara,
    /// MtSetCaptSns: mode, ioSrc, level.
    pub capt_mode: i16,
    pub capt_io_src: i16,
    pub capt_level: i16,
    /// MtSetCaptRepeat: edges per arming (1 = single shot).
    pub capt_repeat: u16,
    /// MtSetLeadScrewCompPara as written: points, start, length, tables.
    pub lead_screw: Option<LeadScrew>,
    pub lead_screw_on: bool,
    /// MtSetBacklash: value, delta, dir.
    pub backlash: (i64, f64, i64),
}

impl Default for AxisSync {
    fn default() -> AxisSync {
        AxisSync {
            gear_dir: 0,
            gear_master: 0,
            gear_master_type: 1,
            gear_master_even: 1,
            gear_slave_even: 1,
            gear_master_slope: 0,
            pt: PtPara::default(),
            pvt: PvtPara::default(),
            capt_mode: 0,
            capt_io_src: 0,
            capt_level: 0,
            capt_repeat: 1,
            lead_screw: None,
            lead_screw_on: false,
            backlash: (0, 0.0, 0),
        }
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct LeadScrew {
    pub start: i64,
    pub length: i64,
    pub positive: Vec<i16>,
    pub negative: Vec<i16>,
}

/// One compare group (module 0 or 1).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CompareGroup {
    pub param: Comp2DimensParam,
    /// Points written since the last clear: (x, y), y 0 for a 1-D compare.
    pub points: Vec<[i64; 2]>,
}

/// A gantry group: its number, its master, its slaves with their error limits (pulses).
pub type GantryGroup = (i16, usize, Vec<(usize, i64)>);

/// The device-wide part.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SyncState {
    pub axes: Vec<AxisSync>,
    pub compare: [CompareGroup; 2],
    /// Advanced capture channel 0–3: the axis whose positions it latches.
    pub adv_capture_axis: [Option<usize>; 4],
    pub gantry: Vec<GantryGroup>,
    /// SetHandWheelInput (default 256, the first external encoder).
    pub handwheel_input: u16,
    /// The axis a handwheel drives now, with ratio, acc and vel as written.
    pub handwheel: Option<(usize, f64, f64, f64)>,
    /// Set2DCompensationTable (table 0) and Set2DCompensation.
    pub comp_table: Option<(Comp2DTable, Vec<CompData>)>,
    pub comp: Comp2D,
}

impl SyncState {
    /// The power-on state of a device of `axes` axes.
    pub fn new(axes: usize) -> SyncState {
        let mut compare = <[CompareGroup; 2]>::default();
        for g in &mut compare {
            g.param = Comp2DimensParam {
                dir1_no: 0,
                dir2_no: -1,
                gate_time: 1000,
                ..Comp2DimensParam::default()
            };
        }
        SyncState {
            axes: vec![AxisSync::default(); axes],
            compare,
            handwheel_input: 256,
            comp: Comp2D {
                axis_index: [0, 1, -1],
                ..Comp2D::default()
            },
            ..SyncState::default()
        }
    }
}
