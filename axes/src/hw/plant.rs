//! The drive and motor (ARCHITECTURE §3.3 step 4): ideal, first-order lag, or the HMC closed
//! position loop driving a velocity-mode motor.

use serde::{Deserialize, Serialize};

/// Gains and output shaping of the HMC position loop (HMC §2.1 fig. 3, §2.5, §2.9).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LoopGains {
    pub kp: f64,
    pub ki: f64,
    pub kd: f64,
    pub kov: f64,
    pub kvff: f64,
    pub kaff: f64,
    pub ko: f64,
    pub dac_high: f64,
    pub dac_low: f64,
    pub pos_offset: f64,
    pub neg_offset: f64,
    pub zero_window: f64,
    /// `servo_loop` = 0: output this fixed value instead (HMC `DAC`).
    pub open_loop_dac: Option<f64>,
}

impl LoopGains {
    /// For plants without a position loop, which never read the gains.
    pub const UNUSED: LoopGains = LoopGains {
        kp: 0.0,
        ki: 0.0,
        kd: 0.0,
        kov: 0.0,
        kvff: 0.0,
        kaff: 0.0,
        ko: 0.0,
        dac_high: 0.0,
        dac_low: 0.0,
        pos_offset: 0.0,
        neg_offset: 0.0,
        zero_window: 0.0,
        open_loop_dac: None,
    };
}

/// What the controller hands the plant each tick.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlantInput {
    /// Physical position command (after the pulse stage for steppers).
    pub position: f64,
    /// Commanded velocity and acceleration (feed-forward terms).
    pub velocity: f64,
    pub acceleration: f64,
    /// Measured position and velocity (feedback of the closed loop).
    pub measured_position: f64,
    pub measured_velocity: f64,
    /// Power stage on.
    pub enabled: bool,
}

/// One axis's drive + motor.
#[derive(Clone, Debug)]
pub struct Plant {
    model: PlantModel,
    /// exp(−period/τ) of the lag or of the velocity loop.
    lag_factor: f64,
    velocity_factor: f64,
    full_scale_velocity: f64,
    period: f64,
    /// 1/period: velocities are differences times this (a division per tick costs ~20 cycles).
    rate: f64,
    position: f64,
    velocity: f64,
    integral: f64,
    previous_error: f64,
    dac_out: f64,
}

/// Largest magnitude of the 16-bit servo output that maps to full-scale velocity.
const DAC_FULL_SCALE: f64 = 32767.0;

impl Plant {
    pub fn new(config: &PlantConfig, period: f64, position: f64) -> Plant {
        let factor = |tau: f64| {
            if tau > 0.0 {
                (-period / tau).exp()
            } else {
                0.0
            }
        };
        Plant {
            model: config.model,
            lag_factor: factor(config.time_constant),
            velocity_factor: factor(config.velocity_time_constant),
            full_scale_velocity: config.full_scale_velocity,
            period,
            rate: 1.0 / period,
            position,
            velocity: 0.0,
            integral: 0.0,
            previous_error: 0.0,
            dac_out: 0.0,
        }
    }

    pub fn model(&self) -> PlantModel {
        self.model
    }

    /// Motor position, physical frame.
    pub fn position(&self) -> f64 {
        self.position
    }

    pub fn velocity(&self) -> f64 {
        self.velocity
    }

    /// Servo output of the position loop (0 for position-mode plants).
    pub fn dac_out(&self) -> f64 {
        self.dac_out
    }

    /// Clear the loop's memory (integrator, derivative) — on enable, so a stale integral never
    /// kicks the motor.
    pub fn reset_loop(&mut self) {
        self.integral = 0.0;
        self.previous_error = 0.0;
        self.dac_out = 0.0;
    }

    /// Advance one tick. `gains` is used by the position loop only.
    #[inline]
    pub fn update(&mut self, input: &PlantInput, gains: &LoopGains) {
        let before = self.position;
        match self.model {
            PlantModel::Ideal => {
                if input.enabled {
                    self.position = input.position;
                }
            }
            PlantModel::Lag => {
                if input.enabled {
                    self.position =
                        input.position + (self.position - input.position) * self.lag_factor;
                }
            }
            PlantModel::PositionLoop => {
                let dac = if input.enabled {
                    self.servo_output(input, gains)
                } else {
                    0.0
                };
                self.dac_out = dac;
                let target_velocity = dac / DAC_FULL_SCALE * self.full_scale_velocity;
                self.velocity =
                    target_velocity + (self.velocity - target_velocity) * self.velocity_factor;
                self.position += self.velocity * self.period;
                return;
            }
        }
        self.velocity = (self.position - before) * self.rate;
    }

    /// HMC §2.1: DACOut = clamp(deadband(Ko·(Kp·FE + Ki·ΣFE·dt + Kd·dFE/dt + Kvff·v + Kaff·a −
    /// Kov·MpSpeed))). The order (Ko, then dead band, then clamp) and the sign of Kov follow the
    /// figure; see docs/decisions.md.
    fn servo_output(&mut self, input: &PlantInput, g: &LoopGains) -> f64 {
        if let Some(dac) = g.open_loop_dac {
            return dac.clamp(g.dac_low, g.dac_high);
        }
        let error = input.position - input.measured_position;
        let derivative = (error - self.previous_error) * self.rate;
        self.previous_error = error;
        let candidate_integral = self.integral + error * self.period;
        let raw = g.ko
            * (g.kp * error
                + g.ki * candidate_integral
                + g.kd * derivative
                + g.kvff * input.velocity
                + g.kaff * input.acceleration
                - g.kov * input.measured_velocity);
        let shaped = if raw.abs() <= g.zero_window {
            (g.pos_offset + g.neg_offset) / 2.0
        } else if raw > 0.0 {
            raw + g.pos_offset
        } else {
            raw + g.neg_offset
        };
        let clamped = shaped.clamp(g.dac_low, g.dac_high);
        // Anti-windup: integrate only while the output is not saturated.
        if clamped == shaped {
            self.integral = candidate_integral;
        }
        if clamped.is_finite() {
            clamped
        } else {
            0.0
        }
    }

    /// Redefine nothing, but let a disabled motor be pushed (tests, external forces).
    pub fn set_position(&mut self, position: f64) {
        self.position = position;
        self.velocity = 0.0;
    }
}

/// The drive and motor that turn the command into actual motion.
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PlantModel {
    /// The motor follows its position command exactly.
    #[default]
    Ideal,
    /// The motor follows its position command with a first-order lag (`time_constant`).
    Lag,
    /// The controller closes the HMC position loop (HMC §2.1 fig. 3: gains `kp` … `ko`, dead band,
    /// DAC clamp) and drives a velocity-mode motor. Required by the closed-loop axis types (analog
    /// servo 20, bus velocity 41/51).
    PositionLoop,
}

/// The drive and motor model: how the actual position follows the command.
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PlantConfig {
    /// How the motor follows the command.
    pub model: PlantModel,
    /// Lag time constant, seconds (model `lag`).
    pub time_constant: f64,
    /// Motor velocity at servo output 32767, user units/s (model `position_loop`).
    pub full_scale_velocity: f64,
    /// Time constant of the drive's velocity loop, seconds, 0 = instant (model `position_loop`).
    pub velocity_time_constant: f64,
}

impl Default for PlantConfig {
    fn default() -> Self {
        PlantConfig {
            model: PlantModel::Ideal,
            time_constant: 0.01,
            full_scale_velocity: 1000.0,
            velocity_time_constant: 0.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn gains() -> LoopGains {
        LoopGains {
            kp: 1.0,
            ki: 0.0,
            kd: 0.0,
            kov: 0.0,
            kvff: 0.0,
            kaff: 0.0,
            ko: 1.0,
            dac_high: 32767.0,
            dac_low: -32768.0,
            pos_offset: 0.0,
            neg_offset: 0.0,
            zero_window: 0.0,
            open_loop_dac: None,
        }
    }

    fn input(position: f64, plant: &Plant) -> PlantInput {
        PlantInput {
            position,
            velocity: 0.0,
            acceleration: 0.0,
            measured_position: plant.position(),
            measured_velocity: plant.velocity(),
            enabled: true,
        }
    }

    #[test]
    fn ideal_follows_and_stays_when_disabled() {
        let mut p = Plant::new(&PlantConfig::default(), 1e-3, 0.0);
        p.update(&input(5.0, &p), &gains());
        assert_eq!(p.position(), 5.0);
        assert!((p.velocity() - 5000.0).abs() < 1e-9);
        let mut i = input(9.0, &p);
        i.enabled = false;
        p.update(&i, &gains());
        assert_eq!(p.position(), 5.0);
    }

    #[test]
    fn lag_reaches_63_percent_after_one_time_constant() {
        let config = PlantConfig {
            model: PlantModel::Lag,
            time_constant: 0.1,
            ..PlantConfig::default()
        };
        let mut p = Plant::new(&config, 1e-3, 0.0);
        for _ in 0..100 {
            p.update(&input(1.0, &p), &gains());
        }
        assert!((p.position() - (1.0 - (-1.0f64).exp())).abs() < 1e-9);
    }

    #[test]
    fn position_loop_converges_and_clamps() {
        let config = PlantConfig {
            model: PlantModel::PositionLoop,
            full_scale_velocity: 100.0,
            ..PlantConfig::default()
        };
        let mut p = Plant::new(&config, 1e-3, 0.0);
        let mut g = gains();
        g.kp = 3276.7; // 10 units of error = full scale
        for _ in 0..5000 {
            p.update(&input(50.0, &p), &g);
        }
        assert!((p.position() - 50.0).abs() < 1e-6, "{}", p.position());
        // Huge error saturates at the clamp and moves at full scale.
        let mut p = Plant::new(&config, 1e-3, 0.0);
        p.update(&input(1e6, &p), &g);
        assert_eq!(p.dac_out(), 32767.0);
        assert!((p.velocity() - 100.0).abs() < 1e-9);
    }

    #[test]
    fn hmc_dead_band_example() {
        // HMC §3.10.6 (digest 000 TV53): NegOffset = −3278, PosOffset = 6553.
        let config = PlantConfig {
            model: PlantModel::PositionLoop,
            ..PlantConfig::default()
        };
        let mut g = gains();
        g.pos_offset = 6553.0;
        g.neg_offset = -3278.0;
        let out = |error: f64, g: &LoopGains| {
            let mut p = Plant::new(&config, 1e-3, 0.0);
            p.update(&input(error, &p), g);
            p.dac_out()
        };
        assert_eq!(out(0.0, &g), 1637.5);
        assert_eq!(out(1000.0, &g), 7553.0);
        assert_eq!(out(-1000.0, &g), -4278.0);
        // Open loop (servo_loop = 0): the fixed DAC value.
        g.open_loop_dac = Some(1234.0);
        assert_eq!(out(500.0, &g), 1234.0);
    }
}
