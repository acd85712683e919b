//! The homing state machine (contract and rule in the `homing` module doc).

use super::method::{Dir, Kind, MethodDef, Region, Signal, SwitchMethod};
use super::{
    AfterHome, HomingError, HomingHardware, HomingInput, HomingInputs, HomingOutput, HomingPhase,
    HomingSpec, HomingStatus, Latch, MotionRequest,
};

/// Switch levels as last sampled.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Levels {
    home: bool,
    limit_pos: bool,
    limit_neg: bool,
}

impl Levels {
    fn of(inputs: &HomingInputs) -> Levels {
        Levels {
            home: inputs.home,
            limit_pos: inputs.limit_pos,
            limit_neg: inputs.limit_neg,
        }
    }
}

/// Exact edge positions reported since the last sample.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Edges {
    home: Option<f64>,
    limit_pos: Option<f64>,
    limit_neg: Option<f64>,
}

/// A change of the reference signal, seen at a sampling tick.
#[derive(Clone, Copy, Debug)]
struct Transition {
    /// The signal became active.
    rising: bool,
    /// Where it changed (the tick position when no edge was reported).
    exact: f64,
    /// Where the axis was when the change was seen.
    polled: f64,
}

impl Transition {
    fn latched(&self, latch: Latch) -> f64 {
        match latch {
            Latch::Exact => self.exact,
            Latch::Polled => self.polled,
        }
    }
}

/// What follows a stop.
#[derive(Clone, Debug, PartialEq)]
enum Then {
    /// Begin the run (it started while the axis was moving).
    Begin,
    /// Apply the search rule again.
    Replan,
    /// Move to this position, then search again (the re-scan quirk).
    Rescan(f64),
}

/// What the machine is doing; `dir` is the direction the axis is moving in.
#[derive(Clone, Debug, PartialEq)]
enum Leg {
    /// Started; the first `step` issues the first request.
    Begin,
    /// The initial back-off `MoveTo`; `stopping` once a limit cut it short.
    Backoff {
        dir: Dir,
        stopping: bool,
    },
    /// Velocity search: at the switch velocity, or `slow` at the zero velocity.
    Search {
        dir: Dir,
        slow: bool,
    },
    /// Stop requested; `limit` is the limit that caused it (not re-reported while stopping).
    Reversing {
        dir: Dir,
        limit: Option<Dir>,
        then: Then,
    },
    /// The re-scan `MoveTo` back past the edge.
    Rescan {
        dir: Dir,
    },
    /// Searching the index; an index must lie beyond `beyond` (the edge) in the tick the edge
    /// was seen.
    Index {
        dir: Dir,
        beyond: Option<f64>,
    },
    /// Home set; stopping, then possibly returning to `return_to`.
    Homed {
        return_to: Option<f64>,
    },
    Returning,
    /// Stopping after an error.
    Failing(HomingError),
    Done,
}

impl Leg {
    fn phase(&self) -> Option<HomingPhase> {
        Some(match self {
            Leg::Begin => HomingPhase::Search,
            Leg::Backoff { .. } => HomingPhase::Backoff,
            Leg::Search { slow: false, .. } => HomingPhase::Search,
            Leg::Search { slow: true, .. } => HomingPhase::Approach,
            Leg::Reversing { .. } => HomingPhase::Reversing,
            Leg::Rescan { .. } => HomingPhase::Rescan,
            Leg::Index { .. } => HomingPhase::Index,
            Leg::Homed { .. } => HomingPhase::Stopping,
            Leg::Returning => HomingPhase::Returning,
            Leg::Failing(_) => HomingPhase::Aborting,
            Leg::Done => return None,
        })
    }
}

/// One homing run.
#[derive(Clone, Debug, PartialEq)]
pub struct Homing {
    spec: HomingSpec,
    def: MethodDef,
    start_time: f64,
    /// Steps until the switches are read again.
    until_sample: u32,
    levels: Levels,
    edges: Edges,
    /// Where the axis is relative to the reference signal; `None` = outside a cam, side unknown.
    region: Option<Region>,
    /// The region was entered by crossing the signal's edge (so that edge is close).
    near: bool,
    /// The reversal limit has been used.
    reversed: bool,
    rescan_pending: bool,
    leg: Leg,
    /// Incremented on every leg change: `motion_done` only ends a leg entered in an earlier step.
    leg_serial: u64,
    /// Where the current search leg started (maximum search distance).
    leg_start: f64,
    phase: HomingPhase,
    home_found: bool,
    result: Option<Result<(), HomingError>>,
}

impl Homing {
    /// Validate `spec` for an axis with `hw` and read the switches of the current tick. Then call
    /// [`Homing::step`] every tick, starting with this one.
    pub fn start(
        spec: &HomingSpec,
        hw: HomingHardware,
        inputs: &HomingInputs,
    ) -> Result<Homing, HomingError> {
        let def = MethodDef::lookup(spec.method)?;
        def.check_hardware(spec.method, hw)?;
        validate(spec, &def)?;
        let mut homing = Homing {
            spec: *spec,
            def,
            start_time: inputs.time,
            until_sample: 0,
            levels: Levels::of(inputs),
            edges: Edges::default(),
            region: None,
            near: false,
            reversed: false,
            rescan_pending: spec.quirks.rescan.is_some() && def.kind != Kind::Current,
            leg: Leg::Begin,
            leg_serial: 0,
            leg_start: inputs.position,
            phase: HomingPhase::Search,
            home_found: false,
            result: None,
        };
        homing.region = homing.initial_region();
        Ok(homing)
    }

    /// Advance one servo tick.
    pub fn step(&mut self, inputs: &HomingInputs) -> HomingOutput {
        let mut out = HomingOutput {
            phase: self.phase,
            ..HomingOutput::default()
        };
        if self.leg == Leg::Done {
            return out;
        }
        let transition = self.sample(inputs);
        if self.leg == Leg::Begin {
            self.begin(inputs, &mut out);
        } else if self.timed_out(inputs) {
            let seconds = self.spec.timeout;
            self.fail(HomingError::Timeout { seconds }, &mut out);
        } else {
            let serial = self.leg_serial;
            if let Some(t) = transition {
                self.on_transition(t, inputs, &mut out);
            }
            self.check_index(inputs, &mut out);
            self.check_limits(inputs, &mut out);
            self.check_distance(inputs, &mut out);
            if self.leg_serial == serial && inputs.motion_done {
                self.on_motion_done(inputs, &mut out);
            }
        }
        out.phase = self.phase;
        out
    }

    /// Stop the run from outside; keep stepping until `done` reports `Aborted`.
    pub fn abort(&mut self) -> HomingOutput {
        let mut out = HomingOutput::default();
        self.fail(HomingError::Aborted, &mut out);
        out.phase = self.phase;
        out
    }

    /// The current phase (the last one once done).
    pub fn phase(&self) -> HomingPhase {
        self.phase
    }

    pub fn status(&self) -> HomingStatus {
        match &self.result {
            None => HomingStatus::Running(self.phase),
            Some(Ok(())) => HomingStatus::Succeeded,
            Some(Err(e)) => HomingStatus::Failed(e.clone()),
        }
    }

    pub fn spec(&self) -> &HomingSpec {
        &self.spec
    }

    // ---- the search rule ----

    fn switch(&self) -> Option<SwitchMethod> {
        match self.def.kind {
            Kind::Switch(s) => Some(s),
            Kind::IndexOnly | Kind::Current => None,
        }
    }

    fn signal_level(&self, levels: Levels) -> bool {
        match self.switch().map(|s| s.signal) {
            Some(Signal::Home) => levels.home,
            Some(Signal::LimitNeg) => levels.limit_neg,
            Some(Signal::LimitPos) => levels.limit_pos,
            None => false,
        }
    }

    fn initial_region(&self) -> Option<Region> {
        let sw = self.switch()?;
        if self.signal_level(self.levels) {
            Some(Region::Inside)
        } else {
            sw.inactive_region()
        }
    }

    /// Direction and slowness of the next search: get to the region from which moving in the
    /// approach direction crosses the home edge, then move in that direction.
    fn policy(&self) -> (Dir, bool) {
        let a = self.def.approach;
        let Some(sw) = self.switch() else {
            return (a, true);
        };
        let ready = sw.ready_region(a);
        match self.region {
            None => (sw.nominal(), false),
            Some(r) if r == ready => (a, ready == Region::Inside || self.near),
            Some(r) if r < ready => (Dir::Pos, false),
            Some(_) => (Dir::Neg, false),
        }
    }

    fn speed(&self, slow: bool) -> f64 {
        if slow {
            self.spec.zero_velocity
        } else {
            self.spec.switch_velocity
        }
    }

    fn velocity(&self, dir: Dir, slow: bool) -> MotionRequest {
        MotionRequest::Velocity {
            velocity: dir.sign() * self.speed(slow),
            acceleration: self.spec.acceleration,
        }
    }

    fn stop(&self) -> MotionRequest {
        MotionRequest::Stop {
            deceleration: self.spec.acceleration,
        }
    }

    /// The signal changed while moving in `dir`: update the region.
    fn note(&mut self, rising: bool, dir: Dir) {
        self.region = Some(if rising {
            Region::Inside
        } else {
            Region::outside(dir)
        });
        self.near = true;
    }

    fn is_home_edge(&self, sw: SwitchMethod, rising: bool, dir: Dir) -> bool {
        let a = self.def.approach;
        dir == a && rising == (sw.ready_region(a) != Region::Inside)
    }

    /// A limit on side `dir` is active and is not the method's reference signal.
    fn limit_ahead(&self, dir: Dir) -> bool {
        let (active, signal) = match dir {
            Dir::Pos => (self.levels.limit_pos, Signal::LimitPos),
            Dir::Neg => (self.levels.limit_neg, Signal::LimitNeg),
        };
        active && self.switch().map(|s| s.signal) != Some(signal)
    }

    fn set_leg(&mut self, leg: Leg) {
        self.leg_serial += 1;
        if let Some(phase) = leg.phase() {
            self.phase = phase;
        }
        self.leg = leg;
    }

    // ---- per-tick pieces ----

    /// Read the switches if this tick is a sampling tick; report a change of the signal.
    fn sample(&mut self, inputs: &HomingInputs) -> Option<Transition> {
        if inputs.home_edge.is_some() {
            self.edges.home = inputs.home_edge;
        }
        if inputs.limit_pos_edge.is_some() {
            self.edges.limit_pos = inputs.limit_pos_edge;
        }
        if inputs.limit_neg_edge.is_some() {
            self.edges.limit_neg = inputs.limit_neg_edge;
        }
        // Scan countdown: sample in the first step, then every N steps.
        if self.until_sample > 0 {
            self.until_sample -= 1;
            return None;
        }
        self.until_sample = self.spec.quirks.switch_scan_ticks.saturating_sub(1);
        let new = Levels::of(inputs);
        let before = self.signal_level(self.levels);
        let after = self.signal_level(new);
        let edge = match self.switch().map(|s| s.signal) {
            Some(Signal::Home) => self.edges.home,
            Some(Signal::LimitNeg) => self.edges.limit_neg,
            Some(Signal::LimitPos) => self.edges.limit_pos,
            None => None,
        };
        self.levels = new;
        self.edges = Edges::default();
        (before != after).then(|| Transition {
            rising: after,
            exact: edge.unwrap_or(inputs.position),
            polled: inputs.position,
        })
    }

    fn timed_out(&self, inputs: &HomingInputs) -> bool {
        // The timeout bounds the search: once the home point is set, the stop or return leg
        // always ends.
        self.spec.timeout > 0.0
            && !self.home_found
            && !matches!(self.leg, Leg::Failing(_) | Leg::Done)
            && inputs.time - self.start_time >= self.spec.timeout
    }

    fn begin(&mut self, inputs: &HomingInputs, out: &mut HomingOutput) {
        self.region = self.initial_region();
        if inputs.velocity != 0.0 && self.def.kind != Kind::Current {
            // Every leg starts from rest; stop whatever motion the axis had first.
            out.motion = Some(self.stop());
            self.set_leg(Leg::Reversing {
                dir: if inputs.velocity < 0.0 {
                    Dir::Neg
                } else {
                    Dir::Pos
                },
                limit: None,
                then: Then::Begin,
            });
            return;
        }
        if self.def.kind == Kind::Current {
            // Methods 35/37: the current position is the home point (HIMC: 6064h = 607Ch).
            self.home_found = true;
            out.home_found = Some(inputs.position);
            if !self.spec.quirks.trial {
                out.set_home = Some(inputs.position);
            }
            self.finish(Ok(()), out);
            return;
        }
        let backoff = self.spec.quirks.initial_backoff;
        let dir = self.def.nominal().reverse();
        if backoff > 0.0 && !self.limit_ahead(dir) {
            out.motion = Some(MotionRequest::MoveTo {
                position: inputs.position + dir.sign() * backoff,
                velocity: self.spec.switch_velocity,
                acceleration: self.spec.acceleration,
            });
            self.set_leg(Leg::Backoff {
                dir,
                stopping: false,
            });
        } else {
            self.search_from_rest(inputs, out);
        }
    }

    /// Start the next search leg with the axis at rest.
    fn search_from_rest(&mut self, inputs: &HomingInputs, out: &mut HomingOutput) {
        let (mut dir, mut slow) = self.policy();
        if self.limit_ahead(dir) {
            // On the reversal limit already: reverse before moving; otherwise an error.
            self.on_limit(dir, inputs, out);
            if self.leg_is_final() {
                return;
            }
            (dir, slow) = self.policy();
            if self.limit_ahead(dir) {
                self.on_limit(dir, inputs, out);
                return;
            }
        }
        out.motion = Some(self.velocity(dir, slow));
        self.leg_start = inputs.position;
        if self.switch().is_some() {
            self.set_leg(Leg::Search { dir, slow });
        } else {
            self.set_leg(Leg::Index { dir, beyond: None });
        }
    }

    /// Re-apply the rule while moving in `dir`: reverse through a stop, or change speed.
    fn replan_moving(&mut self, dir: Dir, slow: bool, out: &mut HomingOutput) {
        let (new_dir, new_slow) = self.policy();
        if new_dir != dir {
            out.motion = Some(self.stop());
            self.set_leg(Leg::Reversing {
                dir,
                limit: None,
                then: Then::Replan,
            });
        } else if new_slow != slow {
            out.motion = Some(self.velocity(new_dir, new_slow));
            self.set_leg(Leg::Search {
                dir: new_dir,
                slow: new_slow,
            });
        }
    }

    fn on_transition(&mut self, t: Transition, inputs: &HomingInputs, out: &mut HomingOutput) {
        let Some(sw) = self.switch() else {
            return;
        };
        match self.leg.clone() {
            Leg::Search { dir, slow } => {
                if self.is_home_edge(sw, t.rising, dir) {
                    self.on_home_edge(t, dir, inputs, out);
                } else {
                    self.note(t.rising, dir);
                    self.replan_moving(dir, slow, out);
                }
            }
            Leg::Reversing {
                dir,
                then: Then::Replan,
                ..
            } if self.is_home_edge(sw, t.rising, dir) => self.on_home_edge(t, dir, inputs, out),
            Leg::Backoff { dir, .. }
            | Leg::Rescan { dir }
            | Leg::Reversing { dir, .. }
            | Leg::Index { dir, .. } => self.note(t.rising, dir),
            Leg::Begin | Leg::Homed { .. } | Leg::Returning | Leg::Failing(_) | Leg::Done => {}
        }
    }

    /// The home edge was crossed in the approach direction.
    fn on_home_edge(
        &mut self,
        t: Transition,
        dir: Dir,
        inputs: &HomingInputs,
        out: &mut HomingOutput,
    ) {
        self.note(t.rising, dir);
        let at = t.latched(self.spec.quirks.switch_latch);
        if self.rescan_pending {
            self.start_rescan(at, dir, out);
        } else if self.def.index {
            if !matches!(self.leg, Leg::Search { slow: true, .. }) {
                out.motion = Some(self.velocity(dir, true));
            }
            self.leg_start = inputs.position;
            self.set_leg(Leg::Index {
                dir,
                beyond: Some(t.exact),
            });
        } else {
            self.home_event(at, out);
        }
    }

    /// NMC re-scan (digest 001 §4.5 step 3): stop, back off past `at`, approach again slowly.
    fn start_rescan(&mut self, at: f64, dir: Dir, out: &mut HomingOutput) {
        self.rescan_pending = false;
        let distance = self.spec.quirks.rescan.unwrap_or(0.0);
        out.motion = Some(self.stop());
        self.set_leg(Leg::Reversing {
            dir,
            limit: None,
            then: Then::Rescan(at - self.def.approach.sign() * distance),
        });
    }

    fn check_index(&mut self, inputs: &HomingInputs, out: &mut HomingOutput) {
        let Leg::Index { dir, beyond } = self.leg else {
            return;
        };
        if let Some(ix) = inputs.index {
            if beyond.is_none_or(|edge| (ix - edge) * dir.sign() > 0.0) {
                let at = match self.spec.quirks.index_latch {
                    Latch::Exact => ix,
                    Latch::Polled => inputs.position,
                };
                if self.rescan_pending {
                    self.start_rescan(at, dir, out);
                } else {
                    self.home_event(at, out);
                }
                return;
            }
        }
        // Only the tick of the edge needs the ordering test.
        self.leg = Leg::Index { dir, beyond: None };
    }

    fn check_limits(&mut self, inputs: &HomingInputs, out: &mut HomingOutput) {
        match self.leg.clone() {
            Leg::Search { dir, .. } if self.limit_ahead(dir) => self.on_limit(dir, inputs, out),
            Leg::Reversing { dir, limit, .. } if limit != Some(dir) && self.limit_ahead(dir) => {
                self.on_limit(dir, inputs, out)
            }
            Leg::Index { dir, .. } | Leg::Rescan { dir } if self.limit_ahead(dir) => {
                self.fail(
                    HomingError::LimitHit {
                        direction: dir.public(),
                    },
                    out,
                );
            }
            Leg::Backoff {
                dir,
                stopping: false,
            } if self.limit_ahead(dir) => {
                // The back-off only leaves the start area; a limit ends it early.
                out.motion = Some(self.stop());
                self.set_leg(Leg::Backoff {
                    dir,
                    stopping: true,
                });
            }
            _ => {}
        }
    }

    /// A limit on side `dir` is active while searching (or about to search) towards it.
    fn on_limit(&mut self, dir: Dir, inputs: &HomingInputs, out: &mut HomingOutput) {
        let reversal = self.switch().and_then(|s| s.reversal);
        match reversal {
            Some(limit) if limit == dir && !self.reversed => {
                // Methods 7–14, 23–30: the limit reverses the search; beyond the cam on that side.
                self.reversed = true;
                self.region = Some(if self.signal_level(self.levels) {
                    Region::Inside
                } else {
                    Region::outside(dir)
                });
                self.near = false;
                match self.leg.clone() {
                    Leg::Reversing { then, .. } => {
                        self.leg = Leg::Reversing {
                            dir,
                            limit: Some(dir),
                            then,
                        }
                    }
                    Leg::Search { .. } => {
                        out.motion = Some(self.stop());
                        self.set_leg(Leg::Reversing {
                            dir,
                            limit: Some(dir),
                            then: Then::Replan,
                        });
                    }
                    // At rest: the caller re-plans.
                    _ => {}
                }
            }
            Some(_) => {
                // A cam method swept to the far limit (or back to the reversal limit).
                let distance = (inputs.position - self.leg_start).abs();
                self.fail(
                    HomingError::NotFound {
                        input: HomingInput::HomeSwitch,
                        distance,
                    },
                    out,
                );
            }
            None => self.fail(
                HomingError::LimitHit {
                    direction: dir.public(),
                },
                out,
            ),
        }
    }

    fn check_distance(&mut self, inputs: &HomingInputs, out: &mut HomingOutput) {
        let max = self.spec.quirks.max_search_distance;
        if max <= 0.0 {
            return;
        }
        let input = match (&self.leg, self.switch()) {
            (Leg::Search { .. }, Some(sw)) => sw.signal.input(),
            (Leg::Index { .. }, _) => HomingInput::Index,
            _ => return,
        };
        if (inputs.position - self.leg_start).abs() > max {
            self.fail(
                HomingError::NotFound {
                    input,
                    distance: max,
                },
                out,
            );
        }
    }

    fn on_motion_done(&mut self, inputs: &HomingInputs, out: &mut HomingOutput) {
        match self.leg.clone() {
            Leg::Reversing {
                then: Then::Begin, ..
            } => self.begin(inputs, out),
            Leg::Backoff { .. } => {
                self.after_backoff();
                self.search_from_rest(inputs, out);
            }
            Leg::Reversing {
                then: Then::Replan, ..
            }
            | Leg::Rescan { .. } => self.search_from_rest(inputs, out),
            Leg::Reversing {
                then: Then::Rescan(target),
                ..
            } => {
                out.motion = Some(MotionRequest::MoveTo {
                    position: target,
                    velocity: self.spec.switch_velocity,
                    acceleration: self.spec.acceleration,
                });
                self.set_leg(Leg::Rescan {
                    dir: Dir::towards(inputs.position, target),
                });
            }
            Leg::Homed {
                return_to: Some(target),
            } => {
                out.motion = Some(MotionRequest::MoveTo {
                    position: target,
                    velocity: self.spec.zero_velocity,
                    acceleration: self.spec.acceleration,
                });
                self.set_leg(Leg::Returning);
            }
            Leg::Homed { return_to: None } | Leg::Returning => self.finish(Ok(()), out),
            Leg::Failing(e) => self.finish(Err(e), out),
            Leg::Begin | Leg::Search { .. } | Leg::Index { .. } | Leg::Done => {}
        }
    }

    /// After the back-off: the level says inside; outside, keep a side learnt from a crossing.
    fn after_backoff(&mut self) {
        let Some(sw) = self.switch() else {
            return;
        };
        let crossed = matches!(self.region, Some(Region::Left | Region::Right)) && self.near;
        if self.signal_level(self.levels) {
            self.region = Some(Region::Inside);
        } else if !crossed {
            self.region = sw.inactive_region();
        }
        // The back-off may have ended far from the edge it crossed.
        self.near = false;
    }

    /// The home point is `at` (current frame).
    fn home_event(&mut self, at: f64, out: &mut HomingOutput) {
        self.home_found = true;
        out.home_found = Some(at);
        let target = if self.spec.quirks.trial {
            at
        } else {
            out.set_home = Some(at);
            self.spec.offset
        };
        let (motion, return_to) = match self.spec.quirks.after_home {
            AfterHome::Decelerate => (self.stop(), None),
            AfterHome::ReturnToHome => (self.stop(), Some(target)),
            AfterHome::StopImmediately => (MotionRequest::StopImmediately, None),
        };
        out.motion = Some(motion);
        self.set_leg(Leg::Homed { return_to });
    }

    fn fail(&mut self, error: HomingError, out: &mut HomingOutput) {
        if self.leg_is_final() {
            return;
        }
        out.motion = Some(self.stop());
        self.set_leg(Leg::Failing(error));
    }

    fn leg_is_final(&self) -> bool {
        matches!(self.leg, Leg::Failing(_) | Leg::Done)
    }

    fn finish(&mut self, result: Result<(), HomingError>, out: &mut HomingOutput) {
        out.done = Some(result.clone());
        self.result = Some(result);
        self.set_leg(Leg::Done);
    }
}

fn validate(spec: &HomingSpec, def: &MethodDef) -> Result<(), HomingError> {
    let bad = |name: &str, value: f64, requirement: &str| HomingError::BadParameter {
        name: name.to_owned(),
        value,
        requirement: requirement.to_owned(),
    };
    if def.kind != Kind::Current {
        for (name, value) in [
            ("switch_velocity", spec.switch_velocity),
            ("zero_velocity", spec.zero_velocity),
            ("acceleration", spec.acceleration),
        ] {
            if !(value.is_finite() && value > 0.0) {
                return Err(bad(name, value, "must be positive: homing would not move"));
            }
        }
    }
    if !spec.offset.is_finite() {
        return Err(bad("offset", spec.offset, "must be finite"));
    }
    let q = &spec.quirks;
    for (name, value) in [
        ("timeout", spec.timeout),
        ("max_search_distance", q.max_search_distance),
        ("initial_backoff", q.initial_backoff),
        ("rescan", q.rescan.unwrap_or(0.0)),
    ] {
        if !(value.is_finite() && value >= 0.0) {
            return Err(bad(name, value, "must be zero or positive"));
        }
    }
    Ok(())
}
