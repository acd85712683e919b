//! Power commands of an axis: enable, disable, reset (PLCopen MC_Power, MC_Reset).

use super::*;

impl Axis {
    pub(crate) fn enable(&mut self, ctx: &mut Context) -> Result<Reply, EngineError> {
        if !self.class.can_move() {
            return self.refuse(EngineError::Unsupported {
                what: format!(
                    "enabling axis {} of type {}",
                    self.index,
                    self.param(ParamId::AxisType)
                ),
            });
        }
        if !self.blocking.is_empty() {
            return self.refuse(EngineError::AxisInError {
                axis: self.index,
                faults: self.blocking,
            });
        }
        if self.inputs.drive_alarm {
            return self.refuse(EngineError::AxisInError {
                axis: self.index,
                faults: AxisFlags::DRIVE_ALARM,
            });
        }
        if !self.enabled {
            self.enabled = true;
            self.plant.reset_loop();
            self.track_actual();
            self.activity = Activity::Idle;
            self.target_pos = self.raw.p;
            let _ = ctx;
        }
        Ok(Reply::Done)
    }

    pub(crate) fn disable(&mut self, ctx: &mut Context) -> Result<Reply, EngineError> {
        self.power_off(ctx, CommandState::Aborted);
        Ok(Reply::Done)
    }

    /// Remove power: the FIFO is cleared (HIMC Disable "clears existing path planning").
    pub(in crate::axis) fn power_off(&mut self, ctx: &mut Context, state: CommandState) {
        self.abort_all(ctx, state);
        self.activity = Activity::Idle;
        self.enabled = false;
        self.source = Source::Hold;
        self.raw.v = 0.0;
        self.raw.a = 0.0;
    }

    /// Clear latched errors whose cause is gone; report those that remain.
    pub(crate) fn reset(&mut self, _ctx: &mut Context) -> Result<Reply, EngineError> {
        self.reset_faults(AxisFlags::all())
    }

    /// Clear the latched errors in `faults` whose cause is gone (all of them: `reset`; some:
    /// NMC_MtClrStsByBits, digest 001 §2.4); report those of `faults` that remain. Latches
    /// outside `faults` stay, and so does the last error unless `faults` has MOTION_ERROR.
    pub(crate) fn reset_faults(&mut self, faults: AxisFlags) -> Result<Reply, EngineError> {
        let present = self.fault_causes_present();
        let clearable = self.latched & faults & !present;
        self.latched &= !clearable;
        self.blocking &= !clearable;
        if faults.contains(AxisFlags::FE_FAULT) {
            self.fe_over = 0;
        }
        if faults.contains(AxisFlags::MOTION_ERROR) {
            self.last_error = None;
        }
        let remaining = self.latched & faults & present;
        if remaining.is_empty() {
            Ok(Reply::Done)
        } else {
            self.refuse(EngineError::CauseStillPresent {
                axis: self.index,
                faults: remaining,
            })
        }
    }

    /// Latched faults whose cause is still there.
    pub(super) fn fault_causes_present(&self) -> AxisFlags {
        let mut present = AxisFlags::empty();
        present.set(AxisFlags::DRIVE_ALARM, self.inputs.drive_alarm);
        present.set(
            AxisFlags::ENCODER_LOSS,
            self.forces.encoder_loss.unwrap_or(false),
        );
        let fe = (self.cmd.p - self.act_pos).abs();
        let limit = self.param(ParamId::FeLimit);
        present.set(AxisFlags::FE_FAULT, limit > 0.0 && fe > limit);
        present.set(
            AxisFlags::COMPENSATION_LIMIT,
            self.compensation_over_limit(),
        );
        present.set(AxisFlags::HW_LIMIT_POS, self.inputs.limit_pos);
        present.set(AxisFlags::HW_LIMIT_NEG, self.inputs.limit_neg);
        present.set(
            AxisFlags::SW_LIMIT_POS,
            self.flags.contains(AxisFlags::SW_LIMIT_POS),
        );
        present.set(
            AxisFlags::SW_LIMIT_NEG,
            self.flags.contains(AxisFlags::SW_LIMIT_NEG),
        );
        present
    }
}
