//! HMC_GantryInit (manual §4.4.11.2, digest 000 §4.4 "Gantry"): `gantry_home` homes a
//! gantry's axes one after the other and aligns them on their reference switches.
//!
//! The manual's steps: "1. each axis in turn returns to its reference point, the other gantry
//! axes following it synchronously; 2. once all have, every gantry axis is redefined at the
//! same time; 3. the deviation between the axes is computed: over the threshold the command
//! ends; within it each axis is shifted to remove it". The states are HMC_GetGantryInitState's:
//! Homing, ReturnBack, DefPos, Compsate, Finish.
//!
//! A sequencer over the engine's own commands, as a host would send them between two ticks:
//! `gantry_enable` (the followers), `home` (HMC_Home/HomeEx with the axis's parameters),
//! `gantry_disable`, `set_position`, `move_absolute`. At the top of each tick
//! it looks at the commands it is waiting for and, when they are all done, makes the next
//! step. Positions are compared in the axes' motor frames, which no homing or redefinition
//! moves, so the skew it finds is mechanical. Bounded work: ≤ 8 axes, a few commands a step.

use super::Engine;
use crate::command::{
    AxisIndex, CommandId, CommandState, EngineError, GantryDisable, GantryEnable, GantryHome,
    GetCommandState, Home, MoveAbsolute, PositionFrame, Reply, SetPosition, MAX_GANTRY_HOME_AXES,
};
use crate::homing::vendor::hmc;
use crate::param::ParamId;
use crate::status::{GantryHomePhase, GantryHomeStatus};

/// One `gantry_home`, running or ended.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct GantryHoming {
    c: GantryHome,
    phase: GantryHomePhase,
    /// The index in `c.axes` of the axis homing (phase Homing).
    next: usize,
    /// The commands the current step waits for.
    waiting: Vec<CommandId>,
    /// Per axis: its motor position at its reference, and the first axis's motor position at
    /// that moment (the gantry moves rigidly, so their differences are the skew).
    reference: Vec<f64>,
    first_at: Vec<f64>,
    deviations: Vec<f64>,
    error: Option<String>,
}

/// How the commands a step waits for stand.
enum Wait {
    Pending,
    Done,
    Failed(String),
}

fn invalid(reason: &'static str) -> EngineError {
    EngineError::InvalidArgument {
        name: "gantry_home",
        value: f64::NAN,
        reason,
    }
}

fn accepted_id(reply: Reply) -> Option<CommandId> {
    match reply {
        Reply::Accepted { id } => Some(id),
        _ => None,
    }
}

impl GantryHoming {
    fn status(&self) -> GantryHomeStatus {
        GantryHomeStatus {
            axes: self.c.axes.clone(),
            phase: self.phase,
            homing_axis: match self.phase {
                GantryHomePhase::Homing => self.c.axes.get(self.next).copied(),
                _ => None,
            },
            deviations: self.deviations.clone(),
            error: self.error.clone(),
        }
    }

    fn running(&self) -> bool {
        !matches!(
            self.phase,
            GantryHomePhase::Finish | GantryHomePhase::Failed
        )
    }
}

impl Engine {
    /// `gantry_home`: checks the axes and the numbers, then starts the first axis's homing.
    pub(super) fn start_gantry_home(&mut self, c: GantryHome) -> Result<Reply, EngineError> {
        let n = c.axes.len();
        if !(2..=MAX_GANTRY_HOME_AXES).contains(&n) {
            return Err(invalid("give 2 to 8 axes (HMC_GantryInit: ucAxisNum ≤ 8)"));
        }
        for (i, &a) in c.axes.iter().enumerate() {
            self.axis(usize::from(a)).ok_or(EngineError::InvalidAxis {
                axis: u32::from(a),
                count: self.axes.len() as u32,
            })?;
            if c.axes.iter().take(i).any(|&b| b == a) {
                return Err(invalid("an axis is listed twice"));
            }
        }
        if c.home_mode > 5 {
            return Err(EngineError::InvalidArgument {
                name: "home_mode",
                value: f64::from(c.home_mode),
                reason: "HMC home modes are 0 to 5",
            });
        }
        if !c.reference_position.is_finite() || c.reference_position.abs() > 1e12 {
            return Err(EngineError::InvalidArgument {
                name: "reference_position",
                value: c.reference_position,
                reason: "must be a finite position",
            });
        }
        if !(c.position_error.is_finite() && c.position_error >= 0.0) {
            return Err(EngineError::InvalidArgument {
                name: "position_error",
                value: c.position_error,
                reason: "must be ≥ 0 (0: no limit)",
            });
        }
        if self
            .gantry_homes
            .iter()
            .any(|h| h.running() && h.c.axes.iter().any(|a| c.axes.contains(a)))
        {
            return Err(invalid("an axis is already in a running gantry_home"));
        }
        let mut run = GantryHoming {
            phase: GantryHomePhase::Homing,
            next: 0,
            waiting: Vec::new(),
            reference: vec![0.0; n],
            first_at: vec![0.0; n],
            deviations: Vec::new(),
            error: None,
            c,
        };
        // The first step is made now, so that a refusal (an axis busy, coupled, disabled)
        // refuses the command and leaves nothing behind.
        self.start_axis_homing(&mut run)?;
        // Ended runs of these axes make way for this one.
        self.gantry_homes
            .retain(|h| !h.c.axes.iter().any(|a| run.c.axes.contains(a)));
        self.gantry_homes.push(run);
        Ok(Reply::Done)
    }

    /// Gang the others to the axis `run.next` and start its homing.
    fn start_axis_homing(&mut self, run: &mut GantryHoming) -> Result<(), EngineError> {
        let axis = run
            .c
            .axes
            .get(run.next)
            .copied()
            .ok_or(invalid("no axis"))?;
        self.gang(axis, &run.c.axes)?;
        let params = self
            .axis(usize::from(axis))
            .map(|a| a.params().clone())
            .unwrap_or_default();
        let spec = hmc(
            run.c.instruction,
            run.c.home_mode,
            params.get(ParamId::Speed),
            params.get(ParamId::CreepSpeed),
            params.get(ParamId::Accel),
        )
        .map_err(EngineError::Homing)?;
        let home = Home::with_spec(axis, &spec);
        match self.apply(home.into()) {
            Ok(reply) => {
                run.waiting.extend(accepted_id(reply));
                Ok(())
            }
            Err(e) => {
                let _ = self.apply(GantryDisable { master: axis }.into());
                Err(e)
            }
        }
    }

    /// Gang every axis of `axes` but `master` to `master`, without limits.
    fn gang(&mut self, master: AxisIndex, axes: &[AxisIndex]) -> Result<(), EngineError> {
        let slaves = axes.iter().copied().filter(|&a| a != master).collect();
        self.apply(
            GantryEnable {
                master,
                slaves,
                warning_limit: 0.0,
                fault_limit: 0.0,
                require_disabled: false,
                closed_loop: false,
            }
            .into(),
        )?;
        Ok(())
    }

    /// `move_absolute` of `axis` with its own profile; the id to wait for.
    fn move_to(
        &mut self,
        axis: AxisIndex,
        position: f64,
    ) -> Result<Option<CommandId>, EngineError> {
        let reply = self.apply(
            MoveAbsolute {
                axis,
                position,
                velocity: None,
                acceleration: None,
                deceleration: None,
                jerk: None,
                buffer_mode: Default::default(),
            }
            .into(),
        )?;
        Ok(accepted_id(reply))
    }

    fn motor(&self, axis: AxisIndex) -> f64 {
        self.axis(usize::from(axis))
            .map_or(0.0, |a| a.commanded_motor_frame())
    }

    fn wait(&mut self, ids: &[CommandId]) -> Wait {
        let mut pending = false;
        for &id in ids {
            match self.apply(GetCommandState { id }.into()) {
                Ok(Reply::CommandState { state, .. }) => match state {
                    CommandState::Done => {}
                    CommandState::Waiting | CommandState::Running => pending = true,
                    other => return Wait::Failed(format!("command {id} ended {other:?}")),
                },
                Ok(_) => {}
                Err(e) => return Wait::Failed(e.to_string()),
            }
        }
        if pending {
            Wait::Pending
        } else {
            Wait::Done
        }
    }

    /// At the top of a tick: advance every running `gantry_home` whose commands are done.
    pub(super) fn step_gantry_homes(&mut self) {
        if self.gantry_homes.iter().all(|h| !h.running()) {
            return;
        }
        let mut runs = std::mem::take(&mut self.gantry_homes);
        for run in runs.iter_mut().filter(|r| r.running()) {
            let waiting = std::mem::take(&mut run.waiting);
            match self.wait(&waiting) {
                Wait::Pending => run.waiting = waiting,
                Wait::Done => {
                    if let Err(e) = self.advance_gantry_home(run) {
                        self.fail_gantry_home(run, e.to_string());
                    }
                }
                Wait::Failed(why) => self.fail_gantry_home(run, why),
            }
        }
        // A gantry_home applied by a command of this step cannot exist; keep the order.
        self.gantry_homes = runs;
    }

    fn fail_gantry_home(&mut self, run: &mut GantryHoming, why: String) {
        if let GantryHomePhase::Homing | GantryHomePhase::ReturnBack = run.phase {
            let master = match run.phase {
                GantryHomePhase::Homing => run.c.axes.get(run.next),
                _ => run.c.axes.first(),
            };
            if let Some(&master) = master {
                let _ = self.apply(GantryDisable { master }.into());
            }
        }
        run.phase = GantryHomePhase::Failed;
        run.error = Some(why);
    }

    /// The step after the one whose commands are all done.
    fn advance_gantry_home(&mut self, run: &mut GantryHoming) -> Result<(), EngineError> {
        let axes = run.c.axes.clone();
        let first = axes.first().copied().ok_or(invalid("no axis"))?;
        match run.phase {
            GantryHomePhase::Homing => {
                let axis = axes.get(run.next).copied().ok_or(invalid("no axis"))?;
                // The axis stands on its reference (HMC homing returns to the origin).
                if let (Some(r), Some(f)) = (
                    run.reference.get_mut(run.next),
                    run.first_at.get_mut(run.next),
                ) {
                    *r = self.motor(axis);
                    *f = self.motor(first);
                }
                self.apply(GantryDisable { master: axis }.into())?;
                run.next += 1;
                if run.next < axes.len() {
                    self.start_axis_homing(run)?;
                } else {
                    // Back to where the first axis found its reference, all together.
                    run.phase = GantryHomePhase::ReturnBack;
                    self.gang(first, &axes)?;
                    let back = run.first_at.first().copied().unwrap_or(0.0) - self.motor(first);
                    let to = self
                        .axis(usize::from(first))
                        .map_or(0.0, |a| a.commanded().p)
                        + back;
                    run.waiting.extend(self.move_to(first, to)?);
                }
            }
            GantryHomePhase::ReturnBack => {
                self.apply(GantryDisable { master: first }.into())?;
                run.phase = GantryHomePhase::DefPos;
            }
            GantryHomePhase::DefPos => {
                // Every axis at once: its reference reads `reference_position`.
                for (j, &a) in axes.iter().enumerate() {
                    let r = run.reference.get(j).copied().unwrap_or(0.0);
                    let position = run.c.reference_position + self.motor(a) - r;
                    self.apply(
                        SetPosition {
                            axis: a,
                            position,
                            frame: PositionFrame::default(),
                        }
                        .into(),
                    )?;
                }
                let a0 = run.first_at.first().copied().unwrap_or(0.0);
                run.deviations = run.first_at.iter().map(|&f| f - a0).collect();
                let worst = run.deviations.iter().fold(0.0f64, |w, d| w.max(d.abs()));
                if run.c.position_error > 0.0 && worst > run.c.position_error {
                    run.phase = GantryHomePhase::Failed;
                    run.error = Some(format!(
                        "the axes deviate by {worst}, over the limit {}",
                        run.c.position_error
                    ));
                    return Ok(());
                }
                run.phase = GantryHomePhase::Compensate;
                for &a in &axes {
                    run.waiting
                        .extend(self.move_to(a, run.c.reference_position)?);
                }
            }
            GantryHomePhase::Compensate => run.phase = GantryHomePhase::Finish,
            GantryHomePhase::Finish | GantryHomePhase::Failed => {}
        }
        Ok(())
    }

    /// The gantry homings, as `Snapshot::gantry_homes` shows them.
    pub(super) fn gantry_homes_into(&self, out: &mut Vec<GantryHomeStatus>) {
        out.clear();
        out.extend(self.gantry_homes.iter().map(GantryHoming::status));
    }
}
