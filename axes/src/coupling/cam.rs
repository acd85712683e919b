//! The cam: the slave follows a table of the master's position (PLCopen MC_CamIn; HMC_Cam and
//! HMC_SplineCam modes 0–7, digest 000 §4.3; NMC Follow, digest 001 §2.17/§4.7, TV 59).
//!
//! The table coordinate is x = (master − origin − master_offset) / master_scaling (+ the
//! table's first master position when the master is relative), the slave
//! slave_origin + slave_scaling · (Y(x) − Y(x at the start)) + slave_offset (relative slave)
//! or slave_scaling · Y(x) + slave_offset (absolute). A periodic cam's Y adds the table's slave
//! rise once per period, so each period starts the slave where the last ended (HMC cyclic cam).

use std::sync::Arc;

use super::table::CamTable;
use crate::command::{CamIn, Direction};
use crate::profile::MotionState;
use crate::status::CouplingPhase;

/// What starts a cam (HMC ucMode: immediate, fixed position, DI; NMC FollowSetEvent).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CamStart {
    Immediate,
    /// The master crosses this position (in this direction, or either).
    MasterPosition(f64, Option<Direction>),
    /// This digital input is on.
    Input(u16),
    /// This capture channel of the master latches (HMC event modes 2/6, digest 000 §4.3): the
    /// cam starts at the latched master position.
    Capture(u8),
}

/// What the cam asks of its slave this tick.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CamStep {
    /// Not started: leave the slave alone.
    Wait,
    Follow(MotionState),
    /// The last setpoint: the master left a single cam's table, or a periodic cam finished its
    /// loops. The slave stands there and is released.
    End(MotionState),
}

#[derive(Clone, Debug)]
pub struct Cam {
    pub table_id: u16,
    table: Arc<CamTable>,
    periodic: bool,
    loop_count: u32,
    master_absolute: bool,
    slave_absolute: bool,
    master_offset: f64,
    slave_offset: f64,
    /// 1 / master_scaling: table units per master unit.
    per_master_unit: f64,
    slave_scaling: f64,
    start: CamStart,
    phase: CouplingPhase,
    /// The master position where the cam started (relative master).
    master_origin: f64,
    /// The slave position where the cam started, less the table there (relative slave).
    slave_origin: f64,
    /// The period the master is in (0 = the first).
    cycle: i64,
    /// The table span the master is in (HMC_GetCamMasterPosIndex); where the next sample's
    /// search starts.
    span: usize,
    /// A capture start: the channel's latch count already seen (latches from before the
    /// cam do not start it), and the latched master position once a new latch came.
    capture_seen: Option<u32>,
    captured: Option<f64>,
    /// The table's first and last master coordinates and its slave rise, read once (a table
    /// in use is never replaced).
    x0: f64,
    x1: f64,
    rise: f64,
    /// Periodic: the period k of the last division and the master coordinates [lo, hi) well
    /// inside it, where floor((x − x0) / period) is k for certain: a tick there skips the
    /// division (the cam slave's per-tick cost, issue 12 performance) and gets the same k.
    period_cache: (f64, f64, f64),
}

impl Cam {
    /// A cam as `c` asks, on `table`, with the parameters already checked.
    pub fn new(c: &CamIn, table: Arc<CamTable>, start: CamStart) -> Cam {
        let (x0, x1) = table.master_range();
        let (y0, y1) = table.slave_range();
        Cam {
            x0,
            x1,
            rise: y1 - y0,
            period_cache: (0.0, f64::INFINITY, f64::NEG_INFINITY),
            table_id: c.table,
            table,
            periodic: c.periodic,
            loop_count: c.loop_count,
            master_absolute: c.master_absolute,
            slave_absolute: c.slave_absolute,
            master_offset: c.master_offset,
            slave_offset: c.slave_offset,
            per_master_unit: 1.0 / c.master_scaling,
            slave_scaling: c.slave_scaling,
            start,
            phase: CouplingPhase::Waiting,
            master_origin: 0.0,
            slave_origin: 0.0,
            cycle: 0,
            span: 0,
            capture_seen: None,
            captured: None,
        }
    }

    /// The digital input that starts the cam, if one does.
    pub fn start_input(&self) -> Option<u16> {
        match self.start {
            CamStart::Input(ch) => Some(ch),
            _ => None,
        }
    }

    pub fn span(&self) -> u32 {
        u32::try_from(self.span).unwrap_or(u32::MAX)
    }

    pub fn phase(&self) -> CouplingPhase {
        self.phase
    }

    pub fn cycle(&self) -> i64 {
        self.cycle
    }

    pub fn table(&self) -> &CamTable {
        &self.table
    }

    /// Whether the start condition holds this tick: the master went from `previous` to
    /// `master`, `input` is the start input's level. Returns the master position to start
    /// from: the crossed position itself, so the cam starts exactly there.
    fn started(&self, previous: f64, master: f64, input: bool) -> Option<f64> {
        match self.start {
            CamStart::Immediate => Some(master),
            CamStart::Input(_) => input.then_some(master),
            CamStart::Capture(_) => self.captured,
            CamStart::MasterPosition(at, direction) => {
                let up = previous < at && at <= master;
                let down = previous > at && at >= master;
                let crossed = match direction {
                    Some(Direction::Positive) => up,
                    Some(Direction::Negative) => down,
                    None => up || down,
                };
                crossed.then_some(at)
            }
        }
    }

    /// Start now from the master position `master` and the slave's commanded position
    /// `slave`.
    pub fn start_at(&mut self, master: f64, slave: f64) {
        self.master_origin = master;
        self.phase = CouplingPhase::InSync;
        self.slave_origin = 0.0;
        let x = self.coordinate(master);
        let y = self.value(x);
        self.slave_origin = if self.slave_absolute {
            0.0
        } else {
            slave - self.slave_scaling * y
        };
    }

    /// Try to start if the cam is immediate (at the command).
    pub fn start_if_immediate(&mut self, master: f64, slave: f64) {
        if self.start == CamStart::Immediate {
            self.start_at(master, slave);
        }
    }

    /// The table coordinate of master position `m`.
    fn coordinate(&self, m: f64) -> f64 {
        let base = if self.master_absolute {
            0.0
        } else {
            self.master_origin
        };
        let x = (m - base - self.master_offset) * self.per_master_unit;
        if self.master_absolute {
            x
        } else {
            x + self.x0
        }
    }

    /// The table's value at x, with the periods' rise added on a periodic cam (the same sums
    /// as [`Cam::step`]).
    fn value(&self, x: f64) -> f64 {
        let (x0, x1) = self.table.master_range();
        if !self.periodic {
            return self.table.sample(x).y;
        }
        let (y0, y1) = self.table.slave_range();
        let period = x1 - x0;
        let k = ((x - x0) / period).floor();
        self.table.sample(x - k * period).y + k * (y1 - y0)
    }

    /// The slave position for table value `y`.
    fn slave_at(&self, y: f64) -> f64 {
        self.slave_origin + self.slave_scaling * y + self.slave_offset
    }

    /// This tick's step for the master's state `master` (already this tick's).
    pub fn step(&mut self, master: MotionState) -> CamStep {
        if self.phase == CouplingPhase::Waiting {
            return CamStep::Wait;
        }
        let x = self.coordinate(master.p);
        let (x0, x1, rise) = (self.x0, self.x1, self.rise);
        let at_rest = |p: f64| MotionState { p, v: 0.0, a: 0.0 };
        let (k, wrapped) = if self.periodic {
            let k = self.period_of(x);
            (k, x - k * (x1 - x0))
        } else if x < x0 || x > x1 {
            // HMC single cam: leaving the table cancels the cam; the slave stands at the end.
            let s = self.table.sample(x.clamp(x0, x1));
            return CamStep::End(at_rest(self.slave_at(s.y)));
        } else {
            (0.0, x)
        };
        if self.periodic {
            self.cycle = k as i64;
            if self.loop_count > 0 && self.cycle >= i64::from(self.loop_count) {
                // NMC loop count / HMC CancelREPCam: end exactly at the last period's end.
                let y = self.table.slave_range().0 + f64::from(self.loop_count) * rise;
                return CamStep::End(at_rest(self.slave_at(y)));
            }
        }
        let s = self.table.sample_from(wrapped, &mut self.span);
        let xv = master.v * self.per_master_unit;
        let xa = master.a * self.per_master_unit;
        CamStep::Follow(MotionState {
            p: self.slave_at(s.y + k * rise),
            v: self.slave_scaling * s.dy * xv,
            a: self.slave_scaling * (s.ddy * xv * xv + s.dy * xa),
        })
    }

    /// The period of table coordinate `x`: floor((x − x0) / period), from the cache when `x`
    /// lies well inside the last period found. The margin (10⁻⁹ of the magnitudes) is far
    /// above the rounding of the division and of the bounds, so the cached k is the one the
    /// division would give; where the period is too small for a margin the range is empty.
    #[inline]
    fn period_of(&mut self, x: f64) -> f64 {
        let (k, lo, hi) = self.period_cache;
        if lo <= x && x < hi {
            return k;
        }
        let period = self.x1 - self.x0;
        let k = ((x - self.x0) / period).floor();
        let margin = 1e-9 * (x.abs() + self.x0.abs() + period);
        self.period_cache = (
            k,
            self.x0 + k * period + margin,
            self.x0 + (k + 1.0) * period - margin,
        );
        k
    }

    /// The capture channel that starts the cam, while it waits for it.
    pub fn waits_for_capture(&self) -> Option<u8> {
        match self.start {
            CamStart::Capture(ch) if self.phase == CouplingPhase::Waiting => Some(ch),
            _ => None,
        }
    }

    /// The start channel has latched `count` edges since it was armed, the newest at master
    /// position `latched` (by the cam's master source); None: the channel is not armed. The
    /// first call sets what counts as old; a later, higher count is a new edge.
    pub fn offer_capture(&mut self, count: Option<u32>, latched: f64) {
        let count = count.unwrap_or(0);
        match self.capture_seen {
            Some(seen) if count > seen => self.captured = Some(latched),
            _ => self.capture_seen = Some(count),
        }
    }

    /// Before [`Cam::step`] of a waiting cam: start it if its condition holds this tick.
    pub fn check_start(&mut self, previous: f64, master: f64, input: bool, slave: f64) {
        if self.phase != CouplingPhase::Waiting {
            return;
        }
        if let Some(at) = self.started(previous, master, input) {
            self.start_at(at, slave);
        }
    }
}
