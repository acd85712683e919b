//! Traces: one CSV row per tick per axis, the columns named exactly as below (scenarios write
//! them with `--trace`, the control API serves them at `GET /api/v1/trace`).

use std::io::{self, Write};

use axes::{AxisFlags, AxisStatus};

/// The header row, in column order.
pub const HEADER: &str = "time_s,axis,state,cmd_pos,cmd_vel,cmd_acc,act_pos,act_vel,following_error,pulses,encoder_counts,limit_pos,limit_neg,home_switch,homed,error";

/// Write one row: `time` in seconds of engine time, booleans as 0/1, `state` as its snake_case
/// name, `error` the name of the last engine error or empty. Floats are written in Rust's
/// shortest round-trip form, so a reader gets back the exact values.
pub fn write_row(out: &mut impl Write, time: f64, axis: usize, s: &AxisStatus) -> io::Result<()> {
    let flag = |f: AxisFlags| u8::from(s.flags.contains(f));
    writeln!(
        out,
        "{time},{axis},{},{},{},{},{},{},{},{},{},{},{},{},{},{}",
        s.state.name(),
        s.cmd_pos,
        s.cmd_vel,
        s.cmd_acc,
        s.act_pos,
        s.act_vel,
        s.following_error,
        s.pulses,
        s.encoder_counts,
        flag(AxisFlags::HW_LIMIT_POS),
        flag(AxisFlags::HW_LIMIT_NEG),
        flag(AxisFlags::HOME_SWITCH),
        flag(AxisFlags::HOMED),
        s.last_error.map_or("", |e| e.name()),
    )
}
