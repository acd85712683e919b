//! Traces: one CSV row per tick per axis, the columns named exactly as below (scenarios write
//! them with `--trace`, the control API serves them at `GET /api/v1/trace`). An axis in a group
//! carries its group's columns (`group`, `path_velocity`, `segment`, `user_segment`: the same
//! values on every member's row, and on the row of an HMC result axis, which is bound to the
//! group like a member); they are empty for a free axis. The next three columns are the
//! axis's capture and compare channels (issue 12 items 4–5): edges latched, the newest latch's
//! actual position, outputs fired (a compare output shows in the row of the tick it fires).
//! Then `output_pos` and `compensation` (item 8), `gantry_deviation` (item 6, 0 off a gantry),
//! and the coupling and stream columns: the kind of the coupling whose slave the axis is
//! (`gear`, `cam`, `superimpose`, `tangential`, `gantry`; empty when none), whether it is in
//! sync (0/1), and the points held in its PT/PVT buffer. Last, the HIMC status quantities
//! (issue 14, digest 004 §3.7, §5.3): `move_time` and `settling_time` of the last finished move
//! (s), `position_offset` (the user frame's origin offset), `rollover_turns` and `torque` (a
//! fraction of rated torque). Then HMC's `z_output` (the Z-phase output's level, 0/1, that
//! SwitchTZ drives, issue 12 item 5) and `compensation_offset` (the axis position compensation
//! offset, item 8).
//!
//! Numbers are written in their shortest round-trip form (`zmij`, `itoa`): a reader that parses
//! them gets back the exact f64 the engine had. Integral floats drop the `.0` (`100`, not
//! `100.0`); very large or small magnitudes use an exponent (`1e-7`, `2.5e+20`), which every CSV
//! reader parses.

use std::io::{self, Write};

use axes::{AxisFlags, AxisStatus, Engine};

/// The header row, in column order.
pub const HEADER: &str = "time_s,axis,state,cmd_pos,cmd_vel,cmd_acc,act_pos,act_vel,following_error,pulses,encoder_counts,limit_pos,limit_neg,home_switch,homed,error,group,path_velocity,segment,user_segment,captures,capture_position,compare_outputs,output_pos,compensation,gantry_deviation,coupling,in_sync,stream_used,move_time,settling_time,position_offset,rollover_turns,torque,z_output,compensation_offset";

/// The group columns of a member axis's row (issue 11 item 7).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct GroupColumns {
    pub group: u16,
    /// Commanded velocity along the path.
    pub path_velocity: f64,
    /// Ordinal of the motion being executed since the group was created.
    pub segment: u64,
    /// The running motion's `user_segment` (0: none given).
    pub user_segment: u32,
}

impl GroupColumns {
    /// The columns of `axis`'s group, if it is in one.
    pub fn of(engine: &Engine, axis: usize) -> Option<GroupColumns> {
        let id = engine.axis(axis)?.group()?;
        let g = engine.groups().get(id)?;
        Some(GroupColumns {
            group: id,
            path_velocity: g.path_velocity(),
            segment: g.segment(),
            user_segment: g.user_segment(),
        })
    }
}

/// Write one row: `time` in seconds of engine time, booleans as 0/1, `state` as its snake_case
/// name, `error` the name of the last engine error or empty, the group columns empty.
pub fn write_row(out: &mut impl Write, time: f64, axis: usize, s: &AxisStatus) -> io::Result<()> {
    write_member_row(out, time, axis, s, None)
}

/// [`write_row`] with the group columns of a member axis.
pub fn write_member_row(
    out: &mut impl Write,
    time: f64,
    axis: usize,
    s: &AxisStatus,
    group: Option<&GroupColumns>,
) -> io::Result<()> {
    let mut row = Vec::with_capacity(192);
    push_f64(&mut row, &mut zmij::Buffer::new(), time);
    format_fields(&mut row, axis, s, group);
    out.write_all(&row)
}

/// Append one row (with its newline) to `buf`; [`write_row`] without the I/O.
pub fn format_row(buf: &mut Vec<u8>, time: f64, axis: usize, s: &AxisStatus) {
    push_f64(buf, &mut zmij::Buffer::new(), time);
    format_fields(buf, axis, s, None);
}

/// Everything after the time column, from its comma to the newline.
fn format_fields(buf: &mut Vec<u8>, axis: usize, s: &AxisStatus, group: Option<&GroupColumns>) {
    let mut ints = itoa::Buffer::new();
    let mut floats = zmij::Buffer::new();
    buf.push(b',');
    buf.extend_from_slice(ints.format(axis).as_bytes());
    buf.push(b',');
    buf.extend_from_slice(s.state.name().as_bytes());
    for v in [
        s.cmd_pos,
        s.cmd_vel,
        s.cmd_acc,
        s.act_pos,
        s.act_vel,
        s.following_error,
    ] {
        buf.push(b',');
        push_f64(buf, &mut floats, v);
    }
    for v in [s.pulses, s.encoder_counts] {
        buf.push(b',');
        buf.extend_from_slice(ints.format(v).as_bytes());
    }
    for f in [
        AxisFlags::HW_LIMIT_POS,
        AxisFlags::HW_LIMIT_NEG,
        AxisFlags::HOME_SWITCH,
        AxisFlags::HOMED,
    ] {
        buf.push(b',');
        buf.push(if s.flags.contains(f) { b'1' } else { b'0' });
    }
    buf.push(b',');
    if let Some(e) = s.last_error {
        buf.extend_from_slice(e.name().as_bytes());
    }
    match group {
        Some(g) => {
            buf.push(b',');
            buf.extend_from_slice(ints.format(g.group).as_bytes());
            buf.push(b',');
            push_f64(buf, &mut floats, g.path_velocity);
            buf.push(b',');
            buf.extend_from_slice(ints.format(g.segment).as_bytes());
            buf.push(b',');
            buf.extend_from_slice(ints.format(g.user_segment).as_bytes());
        }
        None => buf.extend_from_slice(b",,,,"),
    }
    buf.push(b',');
    buf.extend_from_slice(ints.format(s.captures).as_bytes());
    buf.push(b',');
    push_f64(buf, &mut floats, s.capture_position);
    buf.push(b',');
    buf.extend_from_slice(ints.format(s.compare_outputs).as_bytes());
    // Compensation after the planner (issue 12 item 8): what the drive receives, and why.
    // Gantry (issue 12 item 6): the deviation from the master, 0 off a gantry.
    for v in [s.output_pos, s.compensation, s.gantry_deviation] {
        buf.push(b',');
        push_f64(buf, &mut floats, v);
    }
    // Couplings and streams (issue 12 items 1–3, 9).
    buf.push(b',');
    if let Some(kind) = s.coupling {
        buf.extend_from_slice(kind.name().as_bytes());
    }
    buf.push(b',');
    buf.push(if s.flags.contains(AxisFlags::IN_SYNC) {
        b'1'
    } else {
        b'0'
    });
    buf.push(b',');
    buf.extend_from_slice(ints.format(s.stream.used).as_bytes());
    // HIMC status quantities (issue 14): GetMoveTime, GetSettlingTime, GetPosOffset,
    // GetRolloverTurns, the torque behind GetCurrFb.
    for v in [s.move_time, s.settling_time, s.position_offset] {
        buf.push(b',');
        push_f64(buf, &mut floats, v);
    }
    buf.push(b',');
    buf.extend_from_slice(ints.format(s.rollover_turns).as_bytes());
    buf.push(b',');
    push_f64(buf, &mut floats, s.torque);
    // HMC SwitchTZ's Z-phase output and the axis position compensation offset (issue 12).
    buf.push(b',');
    buf.push(if s.z_output { b'1' } else { b'0' });
    buf.push(b',');
    push_f64(buf, &mut floats, s.compensation_offset);
    buf.push(b'\n');
}

fn push_f64(buf: &mut Vec<u8>, floats: &mut zmij::Buffer, v: f64) {
    if v == 0.0 && v.is_sign_positive() {
        // Most columns of an axis at rest: skip the formatter.
        buf.push(b'0');
        return;
    }
    let text = if v.is_finite() {
        floats.format_finite(v)
    } else if v.is_nan() {
        "NaN"
    } else if v > 0.0 {
        "inf"
    } else {
        "-inf"
    };
    buf.extend_from_slice(text.strip_suffix(".0").unwrap_or(text).as_bytes());
}

/// Engine time of `tick` as a trace writes it. When the period is 1/N s for an integer N (1 ms,
/// 62.5 µs …) this is `tick / N`, the f64 nearest the decimal time, so rows read `0.035` rather
/// than `tick × period` = `0.035000000000000003`; otherwise `tick × period`.
#[derive(Clone, Copy, Debug)]
pub struct TickClock {
    period: f64,
    /// Ticks per second when that is an integer whose reciprocal is exactly `period`.
    rate: Option<f64>,
}

impl TickClock {
    pub fn new(period: f64) -> TickClock {
        let rate = (1.0 / period).round();
        let exact = (1.0..1e15).contains(&rate) && 1.0 / rate == period;
        TickClock {
            period,
            rate: exact.then_some(rate),
        }
    }

    pub fn time(&self, tick: u64) -> f64 {
        match self.rate {
            Some(rate) => tick as f64 / rate,
            None => tick as f64 * self.period,
        }
    }
}

/// Writes a trace: the header, then each tick's rows, buffered so that the underlying writer sees
/// few large writes.
pub struct TraceWriter<W: Write> {
    out: W,
    buf: Vec<u8>,
    /// The current tick's time column.
    time: Vec<u8>,
    clock: TickClock,
    rows: u64,
    bytes: u64,
}

/// Rows are collected up to this many bytes before one write.
const CHUNK: usize = 256 * 1024;

impl<W: Write> TraceWriter<W> {
    /// Start a trace of a machine with servo period `period` (seconds): writes the header.
    pub fn new(out: W, period: f64) -> TraceWriter<W> {
        let mut buf = Vec::with_capacity(CHUNK + 4096);
        buf.extend_from_slice(HEADER.as_bytes());
        buf.push(b'\n');
        TraceWriter {
            out,
            buf,
            time: Vec::with_capacity(32),
            clock: TickClock::new(period),
            rows: 0,
            bytes: 0,
        }
    }

    /// The rows of one tick, axis by axis, each with its group's columns (if any).
    pub fn write_tick<'a>(
        &mut self,
        tick: u64,
        axes: impl IntoIterator<Item = (&'a AxisStatus, Option<&'a GroupColumns>)>,
    ) -> io::Result<()> {
        // Every axis's row starts with the same time: format it once.
        self.time.clear();
        push_f64(
            &mut self.time,
            &mut zmij::Buffer::new(),
            self.clock.time(tick),
        );
        for (axis, (status, group)) in axes.into_iter().enumerate() {
            self.buf.extend_from_slice(&self.time);
            format_fields(&mut self.buf, axis, status, group);
            self.rows += 1;
        }
        if self.buf.len() >= CHUNK {
            self.flush_buffer()?;
        }
        Ok(())
    }

    fn flush_buffer(&mut self) -> io::Result<()> {
        self.out.write_all(&self.buf)?;
        self.bytes += self.buf.len() as u64;
        self.buf.clear();
        Ok(())
    }

    /// Rows written so far (the header not counted).
    pub fn rows(&self) -> u64 {
        self.rows
    }

    /// Write what is buffered, flush the writer, and return it with the bytes written.
    pub fn finish(mut self) -> io::Result<(W, u64)> {
        self.flush_buffer()?;
        self.out.flush()?;
        Ok((self.out, self.bytes))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use axes::command::ErrorKind;
    use axes::AxisState;

    fn row(s: &AxisStatus, time: f64) -> String {
        let mut out = Vec::new();
        write_row(&mut out, time, 3, s).unwrap();
        String::from_utf8(out).unwrap()
    }

    #[test]
    fn a_row_has_every_column_and_reads_back_exactly() {
        let s = AxisStatus {
            state: AxisState::DiscreteMotion,
            flags: AxisFlags::HW_LIMIT_NEG | AxisFlags::HOMED | AxisFlags::ENABLED,
            cmd_pos: 0.1 + 0.2,
            cmd_vel: -1234.5,
            cmd_acc: 1e-7,
            act_pos: 100.0,
            act_vel: -0.0,
            following_error: 2.5e20,
            pulses: -42,
            encoder_counts: i64::MAX,
            last_error: Some(ErrorKind::LimitReached),
            ..AxisStatus::default()
        };
        let line = row(&s, 0.035);
        assert_eq!(
            line,
            "0.035,3,discrete_motion,0.30000000000000004,-1234.5,1e-7,100,-0,2.5e+20,-42,9223372036854775807,0,1,0,1,limit_reached,,,,,0,0,0,0,0,0,,0,0,0,0,0,0,0,0,0
"
        );
        assert_eq!(
            line.trim_end().split(',').count(),
            HEADER.split(',').count()
        );
        let floats: Vec<f64> = line
            .split(',')
            .skip(3)
            .take(6)
            .map(|f| f.parse().unwrap())
            .collect();
        assert_eq!(
            floats,
            [
                s.cmd_pos,
                s.cmd_vel,
                s.cmd_acc,
                s.act_pos,
                s.act_vel,
                s.following_error
            ]
        );
        assert!(floats[4].is_sign_negative());
        let idle = row(&AxisStatus::default(), 0.0);
        assert_eq!(
            idle,
            "0,3,disabled,0,0,0,0,0,0,0,0,0,0,0,0,,,,,,0,0,0,0,0,0,,0,0,0,0,0,0,0,0,0
"
        );
        let mut member = Vec::new();
        let g = GroupColumns {
            group: 2,
            path_velocity: 12.5,
            segment: 3,
            user_segment: 40,
        };
        write_member_row(&mut member, 0.0, 1, &AxisStatus::default(), Some(&g)).unwrap();
        assert_eq!(
            String::from_utf8(member).unwrap(),
            "0,1,disabled,0,0,0,0,0,0,0,0,0,0,0,0,,2,12.5,3,40,0,0,0,0,0,0,,0,0,0,0,0,0,0,0,0
"
        );
    }

    #[test]
    fn the_himc_status_quantities_then_z_output_and_compensation_offset_are_the_last_columns() {
        let s = AxisStatus {
            move_time: 0.125,
            settling_time: 0.012,
            position_offset: -100.0,
            rollover_turns: -3,
            torque: 0.5,
            z_output: true,
            compensation_offset: -0.25,
            ..AxisStatus::default()
        };
        let line = row(&s, 1.0);
        let columns: Vec<&str> = line.trim_end().split(',').collect();
        let names: Vec<&str> = HEADER.split(',').collect();
        assert_eq!(columns.len(), names.len());
        let tail: Vec<(&str, &str)> = names.iter().copied().zip(columns).skip(29).collect();
        assert_eq!(
            tail,
            [
                ("move_time", "0.125"),
                ("settling_time", "0.012"),
                ("position_offset", "-100"),
                ("rollover_turns", "-3"),
                ("torque", "0.5"),
                ("z_output", "1"),
                ("compensation_offset", "-0.25")
            ]
        );
    }

    /// HMC's result axis is bound to its group: its row carries the group's columns as the
    /// members' rows do.
    #[test]
    fn a_result_axis_row_has_its_groups_columns() {
        use axes::command::{Command, Enable, GroupCreate, GroupEnable, MoveLinearAbsolute};
        use axes::config::AxisConfig;
        let mut e = Engine::new(&axes::EngineConfig {
            axes: vec![AxisConfig::default(); 4],
            ..axes::EngineConfig::default()
        })
        .unwrap();
        for axis in 0..3 {
            e.apply(Command::from(Enable { axis })).unwrap();
        }
        let create = GroupCreate {
            group: 1,
            axes: vec![0, 1],
            queue_capacity: None,
            lookahead: None,
            result_axis: Some(2),
            orientation: Default::default(),
        };
        e.apply(Command::from(create)).unwrap();
        e.apply(Command::from(GroupEnable { group: 1 })).unwrap();
        let line: MoveLinearAbsolute =
            serde_json::from_str(r#"{"group":1,"position":[300,400],"user_segment":7}"#).unwrap();
        e.apply(Command::from(line)).unwrap();
        for _ in 0..10 {
            e.step();
        }
        let member = GroupColumns::of(&e, 0).unwrap();
        let result = GroupColumns::of(&e, 2).unwrap();
        assert_eq!(result, member);
        assert_eq!(
            (result.group, result.segment, result.user_segment),
            (1, 1, 7)
        );
        assert!(result.path_velocity > 0.0);
        assert_eq!(GroupColumns::of(&e, 3), None);
    }

    #[test]
    fn tick_times_are_the_decimal_times_when_the_period_allows() {
        let ms = TickClock::new(1e-3);
        assert_eq!(ms.time(35).to_string(), "0.035");
        assert_eq!(ms.time(3_600_000), 3600.0);
        let us = TickClock::new(62.5e-6);
        assert_eq!(us.time(3), 187.5e-6);
        let odd = TickClock::new(3e-4);
        assert_eq!(odd.time(7), 7.0 * 3e-4);
    }

    #[test]
    fn the_writer_starts_with_the_header_and_counts() {
        let mut w = TraceWriter::new(Vec::new(), 1e-3);
        let a = AxisStatus::default();
        w.write_tick(0, [(&a, None), (&a, None)]).unwrap();
        w.write_tick(1, [(&a, None), (&a, None)]).unwrap();
        assert_eq!(w.rows(), 4);
        let (out, bytes) = w.finish().unwrap();
        let text = String::from_utf8(out).unwrap();
        assert_eq!(bytes as usize, text.len());
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines[0], HEADER);
        assert_eq!(lines.len(), 5);
        assert!(lines[3].starts_with("0.001,0,"));
    }
}
