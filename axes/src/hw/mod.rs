//! Simulated hardware of one axis: pulse output, encoder, plant, switches (ARCHITECTURE §3.3
//! steps 3–6). Each part is a small state machine advanced once per tick; none allocates.
//!
//! Positions here are *physical* motor positions in user units: the frame the machine had at
//! power-on, which `set_position` and homing never change. Switch positions in the config are in
//! this frame.

pub mod encoder;
pub mod plant;
pub mod pulse;
pub mod switch;

pub use encoder::Encoder;
pub use plant::Plant;
pub use pulse::PulseOutput;
pub use switch::{Debounce, HomeSwitch, LimitSwitch, SwitchTick, Switches};

/// `x.round() as i64` (half away from zero, saturating, NaN → 0) without the libm call that
/// `f64::round` compiles to on baseline x86-64: the conversion runs every tick for every axis.
#[inline]
pub fn round_to_i64(x: f64) -> i64 {
    let t = x as i64; // truncates toward zero, saturates
    let frac = x - t as f64;
    if frac >= 0.5 {
        t.saturating_add(1)
    } else if frac <= -0.5 {
        t.saturating_sub(1)
    } else {
        t
    }
}

/// What the `axis_type` parameter (HMC EmAxisType, HMC §2.1) means for the simulation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AxisClass {
    /// Not solved; motion commands refused (type −1).
    Unused,
    /// No hardware: actual = commanded (type 0).
    Virtual,
    /// Pulse/direction output into a position-mode drive (types 10–12).
    Stepper,
    /// The controller closes the position loop and outputs a velocity command (types 20, 41, 51).
    ClosedLoop,
    /// Position setpoints over a bus into a position-mode drive (types 40, 43, 50) or a torque
    /// drive (42, 52: treated as position-mode here).
    BusPosition,
    /// Feedback only: motion commands refused (types 30–33).
    EncoderOnly,
}

impl AxisClass {
    pub fn of(axis_type: f64) -> AxisClass {
        match axis_type as i64 {
            0 => AxisClass::Virtual,
            10..=12 => AxisClass::Stepper,
            20 | 41 | 51 => AxisClass::ClosedLoop,
            40 | 42 | 43 | 50 | 52 => AxisClass::BusPosition,
            30..=33 => AxisClass::EncoderOnly,
            _ => AxisClass::Unused,
        }
    }

    pub fn is_closed_loop(self) -> bool {
        self == AxisClass::ClosedLoop
    }

    /// Whether the axis accepts motion commands.
    pub fn can_move(self) -> bool {
        !matches!(self, AxisClass::Unused | AxisClass::EncoderOnly)
    }

    pub fn has_pulse_output(self) -> bool {
        self == AxisClass::Stepper
    }
}

#[cfg(test)]
mod tests {
    use super::round_to_i64;

    #[test]
    fn round_to_i64_matches_f64_round() {
        let cases = [
            0.0,
            0.49999999999999994,
            0.5,
            1.5,
            2.5,
            -0.5,
            -1.5,
            -2.4999,
            1e15 + 0.5,
            -1e15 - 0.5,
            123456.789,
            -987654.321,
            4503599627370495.5,
            f64::MAX,
            f64::MIN,
            1e300,
            -1e300,
        ];
        for x in cases {
            assert_eq!(round_to_i64(x), x.round() as i64, "{x}");
        }
        assert_eq!(round_to_i64(f64::NAN), 0);
        let mut r = crate::rng::Rng::new(9);
        for _ in 0..100_000 {
            let x = (r.next_signed() * 1e6).trunc() + r.next_signed();
            assert_eq!(round_to_i64(x), x.round() as i64, "{x}");
        }
    }
}
