//! Kinematic test double for the homing machine (a mock for this layer only): executes
//! [`MotionRequest`]s with constant-acceleration ramps and computes switch levels, exact edges and
//! index pulses from a [`Layout`]. The axis's real profile generator, plant and switches are
//! tested elsewhere.

use super::{
    Homing, HomingError, HomingHardware, HomingInputs, HomingOutput, HomingPhase, HomingSpec,
    MotionRequest,
};

pub const DT: f64 = 0.001;

/// Physical positions of the machine's inputs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Layout {
    /// Active for x ≤ position.
    pub limit_neg: Option<f64>,
    /// Active for x ≥ position.
    pub limit_pos: Option<f64>,
    /// Active on [low, high]; infinite bounds make a one-edge switch.
    pub home: Option<(f64, f64)>,
    /// Index pulses at `index_phase + k · index_pitch`; pitch 0 = none.
    pub index_pitch: f64,
    pub index_phase: f64,
}

impl Layout {
    /// Limits at ±100, home cam [10, 30], index pulses at 4k + 1 (…, 9, 13, …, 29, 33, …).
    pub fn cam() -> Layout {
        Layout {
            limit_neg: Some(-100.0),
            limit_pos: Some(100.0),
            home: Some((10.0, 30.0)),
            index_pitch: 4.0,
            index_phase: 1.0,
        }
    }

    /// As `cam` with a positive home switch, active for x ≥ 10.
    pub fn positive_switch() -> Layout {
        Layout {
            home: Some((10.0, f64::INFINITY)),
            ..Layout::cam()
        }
    }

    /// As `cam` with a negative home switch, active for x ≤ 30.
    pub fn negative_switch() -> Layout {
        Layout {
            home: Some((f64::NEG_INFINITY, 30.0)),
            ..Layout::cam()
        }
    }

    fn home_at(&self, x: f64) -> bool {
        self.home.is_some_and(|(lo, hi)| lo <= x && x <= hi)
    }

    fn limit_neg_at(&self, x: f64) -> bool {
        self.limit_neg.is_some_and(|p| x <= p)
    }

    fn limit_pos_at(&self, x: f64) -> bool {
        self.limit_pos.is_some_and(|p| x >= p)
    }

    /// The first index pulse passed moving from x0 to x1 (x0 excluded).
    fn index_between(&self, x0: f64, x1: f64) -> Option<f64> {
        if self.index_pitch <= 0.0 || x0 == x1 {
            return None;
        }
        let (pitch, phase) = (self.index_pitch, self.index_phase);
        if x1 > x0 {
            let p = phase + (((x0 - phase) / pitch).floor() + 1.0) * pitch;
            (p <= x1).then_some(p)
        } else {
            let p = phase + (((x0 - phase) / pitch).ceil() - 1.0) * pitch;
            (p >= x1).then_some(p)
        }
    }
}

/// The boundary crossed between x0 and x1 among `bounds`, if the level changed.
fn crossed(bounds: &[f64], x0: f64, x1: f64) -> Option<f64> {
    let (lo, hi) = if x0 < x1 { (x0, x1) } else { (x1, x0) };
    bounds.iter().copied().find(|b| lo <= *b && *b <= hi)
}

#[derive(Clone, Debug, PartialEq)]
pub struct Sim {
    pub layout: Layout,
    pub t: f64,
    /// Physical position and velocity.
    pub x: f64,
    pub v: f64,
    /// Reading = x + shift.
    pub shift: f64,
    request: Option<MotionRequest>,
    /// Physical target of a MoveTo.
    target: f64,
    done: bool,
}

impl Sim {
    pub fn new(layout: Layout, x: f64) -> Sim {
        Sim {
            layout,
            t: 0.0,
            x,
            v: 0.0,
            shift: 0.0,
            request: None,
            target: x,
            done: true,
        }
    }

    pub fn request(&mut self, m: MotionRequest) {
        self.request = Some(m);
        self.done = false;
        if let MotionRequest::MoveTo { position, .. } = m {
            self.target = position - self.shift;
        }
    }

    /// Redefine the reading so that `reading` reads `offset`.
    pub fn set_home(&mut self, reading: f64, offset: f64) {
        self.shift += offset - reading;
    }

    fn ramp(&mut self, vt: f64, a: f64) {
        let dv = vt - self.v;
        let max = a * DT;
        if dv.abs() <= max {
            let t1 = dv.abs() / a;
            self.x += (self.v + vt) / 2.0 * t1 + vt * (DT - t1);
            self.v = vt;
        } else {
            let v1 = self.v + max * dv.signum();
            self.x += (self.v + v1) / 2.0 * DT;
            self.v = v1;
        }
    }

    /// Advance one tick and report what the axis would.
    pub fn tick(&mut self) -> HomingInputs {
        let x0 = self.x;
        match self.request {
            None => {}
            Some(MotionRequest::Velocity {
                velocity,
                acceleration,
            }) => {
                self.ramp(velocity, acceleration);
                self.done = velocity == 0.0 && self.v == 0.0;
            }
            Some(MotionRequest::Stop { deceleration }) => {
                self.ramp(0.0, deceleration);
                self.done = self.v == 0.0;
            }
            Some(MotionRequest::StopImmediately) => {
                self.v = 0.0;
                self.done = true;
            }
            Some(MotionRequest::MoveTo {
                velocity,
                acceleration,
                ..
            }) => {
                // A braking-feasible velocity towards the target; snap on arrival.
                let e = self.target - self.x;
                let vd = e.signum() * velocity.min((2.0 * acceleration * e.abs()).sqrt());
                self.ramp(vd, acceleration);
                let e1 = self.target - self.x;
                if e1 * e <= 0.0 || e1.abs() < 1e-12 {
                    self.x = self.target;
                    self.v = 0.0;
                    self.done = true;
                }
            }
        }
        self.t += DT;
        self.inputs(x0)
    }

    pub fn inputs(&self, x0: f64) -> HomingInputs {
        let l = &self.layout;
        let x1 = self.x;
        let reading = |x: f64| x + self.shift;
        let edge = |changed: bool, bounds: &[f64]| {
            if changed {
                crossed(bounds, x0, x1).map(reading)
            } else {
                None
            }
        };
        let home_bounds: Vec<f64> = l.home.map(|(a, b)| vec![a, b]).unwrap_or_default();
        let neg: Vec<f64> = l.limit_neg.into_iter().collect();
        let pos: Vec<f64> = l.limit_pos.into_iter().collect();
        HomingInputs {
            time: self.t,
            position: reading(x1),
            velocity: self.v,
            motion_done: self.done,
            limit_pos: l.limit_pos_at(x1),
            limit_neg: l.limit_neg_at(x1),
            home: l.home_at(x1),
            home_edge: edge(l.home_at(x0) != l.home_at(x1), &home_bounds),
            limit_pos_edge: edge(l.limit_pos_at(x0) != l.limit_pos_at(x1), &pos),
            limit_neg_edge: edge(l.limit_neg_at(x0) != l.limit_neg_at(x1), &neg),
            index: l.index_between(x0, x1).map(reading),
        }
    }
}

/// What one homing run did, in physical coordinates unless said otherwise.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Run {
    pub result: Option<Result<(), HomingError>>,
    /// Physical position of the found home point.
    pub home: Option<f64>,
    /// Physical position and speed of the axis in the tick the home point was found.
    pub detect_x: Option<f64>,
    pub detect_speed: Option<f64>,
    pub final_x: f64,
    pub final_v: f64,
    pub final_reading: f64,
    /// Directions of travel, in order (+1/−1), without repeats.
    pub dirs: Vec<i8>,
    /// Phases, in order, without repeats.
    pub phases: Vec<HomingPhase>,
    pub outputs: Vec<HomingOutput>,
    pub ticks: u64,
    pub time: f64,
}

pub const MAX_TICKS: u64 = 200_000;

/// Home with `spec` from physical position `x`.
pub fn run(spec: &HomingSpec, hw: HomingHardware, layout: Layout, x: f64) -> Run {
    run_with(spec, hw, layout, x, |_, _| false)
}

/// As `run`; `abort(tick, homing)` returning true aborts the run at that tick.
pub fn run_with(
    spec: &HomingSpec,
    hw: HomingHardware,
    layout: Layout,
    x: f64,
    abort: impl FnMut(u64, &Homing) -> bool,
) -> Run {
    run_sim(spec, hw, Sim::new(layout, x), abort)
}

/// Home with `spec` from the state of `sim` (which may be moving).
pub fn run_sim(
    spec: &HomingSpec,
    hw: HomingHardware,
    mut sim: Sim,
    mut abort: impl FnMut(u64, &Homing) -> bool,
) -> Run {
    let mut inputs = sim.inputs(sim.x);
    let mut r = Run::default();
    match Homing::start(spec, hw, &inputs) {
        Err(e) => r.result = Some(Err(e)),
        Ok(mut homing) => {
            for tick in 0..MAX_TICKS {
                let out = if abort(tick, &homing) {
                    let mut out = homing.abort();
                    // The abort replaces this tick's step.
                    out.phase = homing.phase();
                    out
                } else {
                    homing.step(&inputs)
                };
                if r.phases.last() != Some(&out.phase) {
                    r.phases.push(out.phase);
                }
                if let Some(found) = out.home_found {
                    r.home = Some(found - sim.shift);
                    r.detect_x = Some(sim.x);
                    r.detect_speed = Some(sim.v.abs());
                }
                if let Some(p) = out.set_home {
                    sim.set_home(p, spec.offset);
                }
                if let Some(m) = out.motion {
                    sim.request(m);
                }
                let done = out.done.clone();
                r.outputs.push(out);
                if let Some(result) = done {
                    r.result = Some(result);
                    break;
                }
                inputs = sim.tick();
                r.ticks += 1;
                let dir = if sim.v > 0.0 {
                    1
                } else if sim.v < 0.0 {
                    -1
                } else {
                    0
                };
                if dir != 0 && r.dirs.last() != Some(&dir) {
                    r.dirs.push(dir);
                }
            }
        }
    }
    r.final_x = sim.x;
    r.final_v = sim.v;
    r.final_reading = sim.x + sim.shift;
    r.time = sim.t;
    r
}
