//! Parameter commands of an axis: set (validated, with its access rule) and get.

use super::*;

impl Axis {
    pub(crate) fn set_parameter(
        &mut self,
        id: ParamId,
        value: f64,
        lenient: bool,
    ) -> Result<Reply, EngineError> {
        match self.try_set_parameter(id, value, lenient) {
            Ok(()) => Ok(Reply::Done),
            Err(e) => self.refuse(e),
        }
    }

    pub(super) fn try_set_parameter(
        &mut self,
        id: ParamId,
        value: f64,
        lenient: bool,
    ) -> Result<(), EngineError> {
        let def = id.def();
        let idle = self.fifo.is_empty() && matches!(self.activity, Activity::Idle);
        match def.access {
            ParamAccess::ReadOnly => return Err(EngineError::ReadOnlyParameter { name: def.name }),
            ParamAccess::WriteWhenIdle if !idle => {
                return Err(self.invalid_state("change this parameter while commands are queued"))
            }
            ParamAccess::WriteWhenDisabled if self.enabled => {
                return Err(self.invalid_state("change this parameter while enabled"))
            }
            _ => {}
        }
        let (value, corrected) = if lenient {
            def.lenient(value)?
        } else {
            (def.validate(value)?, false)
        };
        let refuse = |reason: String| EngineError::InvalidParameter {
            name: def.name,
            value,
            reason,
        };
        match id {
            ParamId::AxisType => {
                let class = AxisClass::of(value);
                if class.is_closed_loop()
                    != (self.plant.model() == crate::config::PlantModel::PositionLoop)
                {
                    return Err(refuse(
                        "the axis's plant model does not match: closed-loop types (20, 41, 51) need plant model `position_loop` and the others must not use it".into(),
                    ));
                }
                if self.enabled {
                    return Err(self.invalid_state("change the axis type while enabled"));
                }
                self.class = class;
            }
            ParamId::KsNumerator | ParamId::KsDenominator => {
                let other = if id == ParamId::KsNumerator {
                    self.param(ParamId::KsDenominator)
                } else {
                    self.param(ParamId::KsNumerator)
                };
                if other * value <= 0.0 {
                    return Err(refuse(
                        "Ks numerator and denominator must have the same sign (HMC_SetKs: Ks > 0)"
                            .into(),
                    ));
                }
            }
            ParamId::SmoothTime if !self.source_at_rest() => {
                return Err(
                    self.invalid_state("change the smoothing time while moving (HIMC SetSMTime)")
                );
            }
            ParamId::Rollover => {
                apply_rollover(&mut self.params, value);
                self.setup = Setup::from_params(&self.params);
                self.wiring_changed();
                self.params_version += 1;
                return Ok(());
            }
            _ => {}
        }
        self.params.set_unchecked(id, value);
        self.setup = Setup::from_params(&self.params);
        self.wiring_changed();
        self.params_version += 1;
        if corrected {
            // HMC §3.5.1: the corrected write latches AxisStatus bit 2.
            self.latched |= AxisFlags::PARAMETER_ERROR;
        }
        match id {
            ParamId::Units | ParamId::KsNumerator | ParamId::KsDenominator => {
                let motor = self.motor_position();
                self.pulse
                    .set_pulses_per_unit(pulses_per_unit(&self.params), motor);
            }
            ParamId::KeNumerator | ParamId::KeDenominator => {}
            _ => {}
        }
        if matches!(
            id,
            ParamId::Units | ParamId::KeNumerator | ParamId::KeDenominator
        ) {
            let motor = self.plant.position();
            let before = self.encoder.position();
            self.encoder
                .set_counts_per_unit(counts_per_unit(&self.params), motor);
            // Keep the user-frame actual position continuous across the rescale.
            self.encoder_pos = self.encoder.position();
            self.act_offset += before - self.encoder_pos;
        }
        if id == ParamId::SmoothTime {
            self.smoothing =
                smoothing_window(value, self.period).and_then(|n| MovingAverage::new(n).ok());
            if let Some(f) = self.smoothing.as_mut() {
                f.reset(self.raw.p);
            }
        }
        if matches!(
            id,
            ParamId::Speed
                | ParamId::Accel
                | ParamId::Decel
                | ParamId::Jerk
                | ParamId::JerkMode
                | ParamId::VelScale
                | ParamId::MaxVelocity
                | ParamId::MaxAccel
                | ParamId::AccelTime
                | ParamId::DecelTime
                | ParamId::StartVelocity
                | ParamId::HoldSpeed
        ) {
            self.limits_dirty = true;
        }
        Ok(())
    }

    pub(crate) fn get_parameter(&self, id: ParamId) -> f64 {
        crate::param::parameter_value(id, &self.status(), &self.params)
    }
}
