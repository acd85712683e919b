//! NMC Follow (issue 12 item 2; digest 001 §2.17, §4.7, S-FOLLOW, TV 59): per slave axis two
//! FIFOs of up to 32 segments (master distance, slave distance, type), a loop count, switching
//! between the FIFOs and a start when the master crosses a position in a direction.
//!
//! Each FIFO's points are cumulative from its start point (0, 0) (S-FOLLOW pushes running
//! sums; digest 001 §8 item 30). A *pass* runs the active FIFO once; each pass continues where
//! the last ended (the slave's positions add up, as a periodic cam's). Within a segment the
//! slave/master ratio runs linearly, by PT's rules with master travel for time: NORMAL ends at
//! 2·Δs/Δm − its start, EVEN is Δs/Δm, STOP ends at 0; a pass's first segment starts at ratio 0,
//! a CONTINUOUS first segment at the last pass's end ratio (type 3, "keep velocity continuous
//! across FIFOs"). After `loop_count` passes (0 = for ever), or at the end of the pass after
//! `follow_switch`, the other FIFO becomes active if it has data and the finished one is emptied
//! for the host to refill; with nothing to switch to the Follow ends (the slave ramps down
//! from the velocity it has). The segments of a FIFO are computed when it becomes active (≤ 32,
//! closed form); a tick samples one of them.

use super::{axis_ref, CamStep, Couplings, Env, Law};
use crate::command::{
    bounded, AxisIndex, CamPoint, Direction, EngineError, FollowClear, FollowConfig,
    FollowDirection, FollowEvent, FollowPush, FollowSegment, FollowStart, FollowSwitch,
    MasterSource, Reply, FOLLOW_FIFOS, FOLLOW_FIFO_SEGMENTS,
};
use crate::profile::MotionState;
use crate::status::{CouplingPhase, FollowState, FollowStatus};

const SEGMENTS: usize = FOLLOW_FIFO_SEGMENTS as usize;
/// Most passes one tick finishes: bounds a tick's work when a master jumps far; the rest is
/// caught up in the following ticks.
const MAX_PASSES_PER_TICK: usize = 64;

/// One segment: the slave/master ratio runs linearly from `r0` to `r1` over master travel `h`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Segment {
    x0: f64,
    y0: f64,
    h: f64,
    r0: f64,
    r1: f64,
}

impl Segment {
    /// Slave travel, ratio and its derivative at master coordinate `x` (clamped to the segment).
    fn sample(&self, x: f64) -> (f64, f64, f64) {
        let u = (x - self.x0).clamp(0.0, self.h);
        let slope = (self.r1 - self.r0) / self.h;
        (
            self.y0 + u * (self.r0 + 0.5 * slope * u),
            self.r0 + slope * u,
            slope,
        )
    }
}

/// The segments of one pass through `points`, the first starting from `end_ratio` when it is
/// CONTINUOUS.
fn segments(points: &[CamPoint], end_ratio: f64, out: &mut Vec<Segment>) {
    out.clear();
    let (mut x0, mut y0, mut r) = (0.0, 0.0, 0.0);
    for (i, p) in points.iter().take(SEGMENTS).enumerate() {
        let h = p.master - x0;
        let chord = (p.slave - y0) / h;
        let (r0, r1) = match p.segment {
            FollowSegment::Continuous if i == 0 => (end_ratio, 2.0 * chord - end_ratio),
            FollowSegment::Normal | FollowSegment::Continuous => (r, 2.0 * chord - r),
            FollowSegment::Even => (chord, chord),
            FollowSegment::Stop => (2.0 * chord, 0.0),
        };
        out.push(Segment { x0, y0, h, r0, r1 });
        (x0, y0, r) = (p.master, p.slave, r1);
    }
}

/// A started Follow.
#[derive(Clone, Debug)]
struct Run {
    fifo: usize,
    waiting: bool,
    switch_pending: bool,
    loops_done: u32,
    /// Master travel since the start (in the followed direction only, with a filter).
    coordinate: f64,
    /// `coordinate` and the slave's position where the current pass began.
    pass_master: f64,
    pass_slave: f64,
    /// The ratio at the end of the last pass.
    end_ratio: f64,
    segments: Vec<Segment>,
    segment: usize,
}

/// A Follow slave's settings, FIFOs and run (NMC keeps them per axis, set before the start).
#[derive(Clone, Debug, Default)]
pub struct FollowSlave {
    axis: AxisIndex,
    master: Option<AxisIndex>,
    source: MasterSource,
    loop_count: u32,
    event: FollowEvent,
    start_position: f64,
    start_direction: Option<Direction>,
    direction: FollowDirection,
    fifos: [Vec<CamPoint>; FOLLOW_FIFOS as usize],
    run: Option<Run>,
}

impl FollowSlave {
    fn fifo(&self, k: usize) -> &[CamPoint] {
        self.fifos.get(k).map_or(&[], |f| f.as_slice())
    }

    fn status(&self) -> FollowStatus {
        let space = |k: usize| FOLLOW_FIFO_SEGMENTS.saturating_sub(self.fifo(k).len() as u16);
        let run = self.run.as_ref();
        FollowStatus {
            axis: self.axis,
            master: self.master,
            master_source: self.source,
            loop_count: self.loop_count,
            event: self.event,
            start_position: self.start_position,
            start_direction: self.start_direction,
            direction: self.direction,
            state: match run {
                None => FollowState::Idle,
                Some(r) if r.waiting => FollowState::Waiting,
                Some(_) => FollowState::Running,
            },
            active_fifo: run.map_or(self.first_fifo(), |r| r.fifo) as u8,
            space: [space(0), space(1)],
            loops_done: run.map_or(0, |r| r.loops_done),
            segment: run.map_or(0, |r| r.segment) as u16,
            switch_pending: run.is_some_and(|r| r.switch_pending),
        }
    }

    /// The FIFO a start runs first: FIFO 0 unless only FIFO 1 has data.
    fn first_fifo(&self) -> usize {
        usize::from(self.fifo(0).is_empty() && !self.fifo(1).is_empty())
    }

    /// Its run ended (a refused setpoint): the FIFOs stay.
    pub(super) fn end(&mut self) {
        self.run = None;
    }

    /// The coupling phase its link shows.
    fn phase(&self) -> CouplingPhase {
        match &self.run {
            Some(r) if !r.waiting => CouplingPhase::InSync,
            _ => CouplingPhase::Waiting,
        }
    }

    fn start(&mut self) {
        let fifo = self.first_fifo();
        let mut run = Run {
            fifo,
            waiting: self.event == FollowEvent::MasterCrossing,
            switch_pending: false,
            loops_done: 0,
            coordinate: 0.0,
            pass_master: 0.0,
            pass_slave: 0.0,
            end_ratio: 0.0,
            segments: Vec::with_capacity(SEGMENTS),
            segment: 0,
        };
        segments(self.fifo(fifo), 0.0, &mut run.segments);
        self.run = Some(run);
    }

    /// Master travel `delta` (with velocity `v` and acceleration `a`) as the direction filter
    /// lets it through.
    fn filtered(&self, delta: f64, v: f64, a: f64) -> (f64, f64, f64) {
        let blocked = match self.direction {
            FollowDirection::Both => false,
            FollowDirection::Positive => delta < 0.0,
            FollowDirection::Negative => delta > 0.0,
        };
        if blocked {
            (0.0, 0.0, 0.0)
        } else {
            (delta, v, a)
        }
    }

    /// Whether the master's move from `previous` to `now` crosses the start position in the
    /// start direction.
    fn crossed(&self, previous: f64, now: f64) -> bool {
        let at = self.start_position;
        let up = previous < at && at <= now;
        let down = previous > at && at >= now;
        match self.start_direction {
            Some(Direction::Positive) => up,
            Some(Direction::Negative) => down,
            None => up || down,
        }
    }

    /// This tick's step for the master's state `master` (this tick's) and its position of the
    /// last tick `previous`; `origin` is the slave's position at the start.
    fn step(&mut self, master: MotionState, previous: f64, origin: f64) -> CamStep {
        let crossed = self.crossed(previous, master.p);
        let (delta, v, a) = self.filtered(master.p - previous, master.v, master.a);
        let start_position = self.start_position;
        let loop_count = self.loop_count;
        let Some(run) = self.run.as_mut() else {
            return CamStep::Wait;
        };
        if run.waiting {
            if !crossed {
                return CamStep::Wait;
            }
            // Start exactly at the crossed position: the travel past it this tick counts.
            run.waiting = false;
            run.coordinate = (master.p - start_position) * delta.signum().abs();
        } else {
            run.coordinate += delta;
        }
        let mut x = run.coordinate - run.pass_master;
        for _ in 0..MAX_PASSES_PER_TICK {
            let Some(last) = self.fifos.get(run.fifo).and_then(|f| f.last()).copied() else {
                break;
            };
            if x < last.master {
                break;
            }
            run.pass_master += last.master;
            run.pass_slave += last.slave;
            x -= last.master;
            run.loops_done = run.loops_done.saturating_add(1);
            run.end_ratio = run.segments.last().map_or(0.0, |s| s.r1);
            let other = 1 - run.fifo;
            let loops_over = loop_count > 0 && run.loops_done >= loop_count;
            let has_other = self.fifos.get(other).is_some_and(|f| !f.is_empty());
            if (run.switch_pending || loops_over) && has_other {
                if let Some(done) = self.fifos.get_mut(run.fifo) {
                    done.clear();
                }
                run.fifo = other;
                run.loops_done = 0;
                run.switch_pending = false;
                run.segment = 0;
            } else if loops_over {
                // Nothing to switch to: the Follow ends at the pass's end.
                return CamStep::End(MotionState {
                    p: origin + run.pass_slave,
                    v: run.end_ratio * v,
                    a: 0.0,
                });
            }
            segments(
                self.fifos.get(run.fifo).map_or(&[], |f| f.as_slice()),
                run.end_ratio,
                &mut run.segments,
            );
        }
        // Master back before the pass's start: the slave waits there.
        let x = x.max(0.0);
        let n = run.segments.len();
        while run.segment + 1 < n && run.segments.get(run.segment + 1).is_some_and(|s| x >= s.x0) {
            run.segment += 1;
        }
        while run.segment > 0 && run.segments.get(run.segment).is_some_and(|s| x < s.x0) {
            run.segment -= 1;
        }
        let Some(seg) = run.segments.get(run.segment) else {
            return CamStep::Wait;
        };
        let (y, r, dr) = seg.sample(x);
        CamStep::Follow(MotionState {
            p: origin + run.pass_slave + y,
            v: r * v,
            a: dr * v * v + r * a,
        })
    }
}

/// What the coupling registry keeps of a running Follow: the slave's position at the start and
/// what its status shows (the run itself is the slave's [`FollowSlave`]).
#[derive(Clone, Copy, Debug)]
pub struct FollowLink {
    origin: f64,
    phase: CouplingPhase,
    segment: u32,
    loops: u32,
}

impl FollowLink {
    pub fn phase(&self) -> CouplingPhase {
        self.phase
    }

    pub fn segment(&self) -> u32 {
        self.segment
    }

    pub fn loops(&self) -> u32 {
        self.loops
    }

    /// Step the Follow of `slave` (its run in `follows`) for this tick's master.
    pub(super) fn step(
        &mut self,
        follow: Option<&mut FollowSlave>,
        master: MotionState,
        previous: f64,
    ) -> CamStep {
        let Some(f) = follow else {
            return CamStep::Wait;
        };
        let step = f.step(master, previous, self.origin);
        self.phase = f.phase();
        if let Some(r) = &f.run {
            self.segment = r.segment as u32;
            self.loops = r.loops_done;
        }
        if matches!(step, CamStep::End(_)) {
            f.run = None;
        }
        step
    }
}

fn invalid(axis: AxisIndex, reason: impl Into<String>) -> EngineError {
    EngineError::InvalidFollow {
        axis,
        reason: reason.into(),
    }
}

/// A FIFO number as an index.
fn fifo_index(axis: AxisIndex, fifo: u8) -> Result<usize, EngineError> {
    if fifo < FOLLOW_FIFOS {
        Ok(usize::from(fifo))
    } else {
        Err(invalid(axis, format!("no FIFO {fifo}: FIFOs are 0 and 1")))
    }
}

impl Couplings {
    fn follow_entry(
        &mut self,
        env: &Env,
        axis: AxisIndex,
    ) -> Result<&mut FollowSlave, EngineError> {
        axis_ref(env.axes, axis)?;
        Ok(self.follows.entry(axis).or_insert_with(|| FollowSlave {
            axis,
            ..FollowSlave::default()
        }))
    }

    /// `follow_config`: the settings given replace the slave's; refused while it runs.
    pub(super) fn follow_config(
        &mut self,
        env: &mut Env,
        c: &FollowConfig,
    ) -> Result<Reply, EngineError> {
        if let Some(m) = c.master {
            axis_ref(env.axes, m)?;
            if m == c.axis {
                return Err(EngineError::CoupledToItself { axis: c.axis });
            }
        }
        let start_position = c
            .start_position
            .map(|p| bounded("start_position", p))
            .transpose()?;
        let f = self.follow_entry(env, c.axis)?;
        if f.run.is_some() {
            return Err(invalid(
                c.axis,
                "running: stop it before changing its settings",
            ));
        }
        if let Some(m) = c.master {
            f.master = Some(m);
        }
        if let Some(s) = c.master_source {
            f.source = s;
        }
        if let Some(n) = c.loop_count {
            f.loop_count = n;
        }
        if let Some(e) = c.event {
            f.event = e;
        }
        if let Some(p) = start_position {
            f.start_position = p;
        }
        if c.start_direction.is_some() {
            f.start_direction = c.start_direction;
        }
        if let Some(d) = c.direction {
            f.direction = d;
        }
        Ok(Reply::Done)
    }

    /// `follow_push`: all the points or none; masters strictly increasing from the FIFO's last
    /// point (or its start point 0).
    pub(super) fn follow_push(
        &mut self,
        env: &mut Env,
        c: &FollowPush,
    ) -> Result<Reply, EngineError> {
        let k = fifo_index(c.axis, c.fifo)?;
        let f = self.follow_entry(env, c.axis)?;
        if f.run.as_ref().is_some_and(|r| r.fifo == k) {
            return Err(invalid(
                c.axis,
                format!("FIFO {k} is running: push into the other FIFO"),
            ));
        }
        if c.points.is_empty() {
            return Err(invalid(c.axis, "no points"));
        }
        let fifo = f.fifo(k);
        let space = FOLLOW_FIFO_SEGMENTS.saturating_sub(fifo.len() as u16);
        if c.points.len() > usize::from(space) {
            return Err(EngineError::FollowFull {
                axis: c.axis,
                fifo: c.fifo,
                space,
                count: u32::try_from(c.points.len()).unwrap_or(u32::MAX),
            });
        }
        let mut last = fifo.last().map_or(0.0, |p| p.master);
        for (i, p) in c.points.iter().enumerate() {
            bounded("master", p.master)?;
            bounded("slave", p.slave)?;
            if p.master <= last {
                return Err(invalid(
                    c.axis,
                    format!(
                        "point {i}: master {} is not after {last} (masters are cumulative from the FIFO's start, increasing)",
                        p.master
                    ),
                ));
            }
            last = p.master;
        }
        if let Some(fifo) = f.fifos.get_mut(k) {
            fifo.extend_from_slice(&c.points);
        }
        Ok(Reply::Done)
    }

    /// `follow_clear`: refused for the FIFO a running Follow runs.
    pub(super) fn follow_clear(
        &mut self,
        env: &mut Env,
        c: &FollowClear,
    ) -> Result<Reply, EngineError> {
        let k = fifo_index(c.axis, c.fifo)?;
        let f = self.follow_entry(env, c.axis)?;
        if f.run.as_ref().is_some_and(|r| r.fifo == k) {
            return Err(invalid(c.axis, format!("FIFO {k} is running")));
        }
        if let Some(fifo) = f.fifos.get_mut(k) {
            fifo.clear();
        }
        Ok(Reply::Done)
    }

    /// `follow_start`: every axis's Follow or none, coupled in this command (so all in the
    /// same tick).
    pub(super) fn follow_start(
        &mut self,
        env: &mut Env,
        c: &FollowStart,
    ) -> Result<Reply, EngineError> {
        if c.axes.is_empty() {
            return Err(EngineError::InvalidArgument {
                name: "axes",
                value: 0.0,
                reason: "name at least one axis",
            });
        }
        for (i, &axis) in c.axes.iter().enumerate() {
            if c.axes.iter().take(i).any(|&a| a == axis) {
                return Err(invalid(axis, "named twice"));
            }
            axis_ref(env.axes, axis)?;
            let f = self
                .follows
                .get(&axis)
                .ok_or_else(|| invalid(axis, "no master: follow_config first"))?;
            let master = f
                .master
                .ok_or_else(|| invalid(axis, "no master: follow_config first"))?;
            if f.fifo(0).is_empty() && f.fifo(1).is_empty() {
                return Err(invalid(axis, "both FIFOs are empty"));
            }
            self.check_new(env.axes, master, axis)?;
        }
        let mut started = Vec::with_capacity(c.axes.len());
        for &axis in &c.axes {
            match self.follow_couple(env, axis) {
                Ok(()) => started.push(axis),
                Err(e) => {
                    // A loop through two of these axes: undo the ones coupled here.
                    for &a in &started {
                        let _ = self.decouple(env, a, crate::status::CouplingKind::Follow);
                    }
                    return Err(e);
                }
            }
        }
        Ok(Reply::Done)
    }

    fn follow_couple(&mut self, env: &mut Env, axis: AxisIndex) -> Result<(), EngineError> {
        let (master, source) = match self.follows.get(&axis) {
            Some(f) => (f.master.unwrap_or(axis), f.source),
            None => return Err(invalid(axis, "no master: follow_config first")),
        };
        self.check_new(env.axes, master, axis)?;
        let (m, slave) = super::positions(env, master, axis, source)?;
        let Some(f) = self.follows.get_mut(&axis) else {
            return Err(invalid(axis, "no master: follow_config first"));
        };
        f.start();
        let link = FollowLink {
            origin: slave.p,
            phase: f.phase(),
            segment: 0,
            loops: 0,
        };
        self.insert(env, (master, axis, source), Law::Follow(link), m);
        Ok(())
    }

    /// `follow_switch`: each running Follow moves to its other FIFO at the end of its pass.
    pub(super) fn follow_switch(
        &mut self,
        env: &mut Env,
        c: &FollowSwitch,
    ) -> Result<Reply, EngineError> {
        for &axis in &c.axes {
            axis_ref(env.axes, axis)?;
            let f = self.follows.get(&axis);
            let Some(run) = f.and_then(|f| f.run.as_ref()) else {
                return Err(EngineError::NotCoupled {
                    axis,
                    what: "a running Follow",
                });
            };
            if f.is_some_and(|f| f.fifo(1 - run.fifo).is_empty()) {
                return Err(invalid(
                    axis,
                    format!("FIFO {} is empty: nothing to switch to", 1 - run.fifo),
                ));
            }
        }
        for axis in &c.axes {
            if let Some(run) = self.follows.get_mut(axis).and_then(|f| f.run.as_mut()) {
                run.switch_pending = true;
            }
        }
        Ok(Reply::Done)
    }

    /// The run of `axis`'s Follow ended (follow_out, a refused setpoint).
    pub(super) fn follow_ended(&mut self, axis: AxisIndex) {
        if let Some(f) = self.follows.get_mut(&axis) {
            f.run = None;
        }
    }

    /// The Follow slaves' records, by axis.
    pub fn follows_into(&self, out: &mut Vec<FollowStatus>) {
        out.clear();
        out.extend(self.follows.values().map(FollowSlave::status));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(master: f64, slave: f64, segment: FollowSegment) -> CamPoint {
        CamPoint {
            master,
            slave,
            segment,
        }
    }

    #[test]
    fn segments_follow_pt_rules_with_master_travel_for_time() {
        // S-FOLLOW's FIFO (digest 001 §5, TV 59): NORMAL from rest, ratio 0 → 1 → 1 → 0.
        let pts = [
            point(20_000.0, 10_000.0, FollowSegment::Normal),
            point(40_000.0, 30_000.0, FollowSegment::Normal),
            point(60_000.0, 40_000.0, FollowSegment::Normal),
        ];
        let mut s = Vec::new();
        segments(&pts, 0.0, &mut s);
        let ratios: Vec<(f64, f64)> = s.iter().map(|g| (g.r0, g.r1)).collect();
        assert_eq!(ratios, vec![(0.0, 1.0), (1.0, 1.0), (1.0, 0.0)]);
        for (g, p) in s.iter().zip(&pts) {
            assert_eq!(g.sample(p.master).0, p.slave);
        }
        // EVEN and STOP, and a CONTINUOUS first segment taking the last pass's end ratio.
        let pts = [
            point(100.0, 50.0, FollowSegment::Continuous),
            point(200.0, 150.0, FollowSegment::Even),
            point(300.0, 200.0, FollowSegment::Stop),
        ];
        segments(&pts, 0.25, &mut s);
        let ratios: Vec<(f64, f64)> = s.iter().map(|g| (g.r0, g.r1)).collect();
        assert_eq!(ratios, vec![(0.25, 0.75), (1.0, 1.0), (1.0, 0.0)]);
        assert_eq!(s[2].sample(300.0).0, 200.0);
    }
}
