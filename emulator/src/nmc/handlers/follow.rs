//! Electronic cam "Follow" (digest 001 §2.17, S-FOLLOW, TV59): the engine keeps each slave's
//! settings and its two FIFOs (`follow_config`, `follow_push` … and `Snapshot::follows`); each
//! setter sends only its own field, each getter reads the snapshot. Positions are the master's
//! pulses (master positions, the start position) and the slave's (slave positions).

use axes::command::{
    CamPoint, Command, Direction, FollowClear, FollowConfig, FollowDirection, FollowEvent,
    FollowOut, FollowPush, FollowSegment, FollowStart, FollowSwitch, MasterSource, FOLLOW_FIFOS,
};
use axes::status::{FollowState, FollowStatus};
use mcemu_dialects::PulseScale;
use mcemu_nmc::table::{self, Function};

use super::sync_args::{axes_to_start, axis_number, finite};
use crate::nmc::service::{pulses, Call, Handler, Refusal};

pub const HANDLERS: &[(Function, Handler)] = &[
    (table::MT_FOLLOW_SET_MASTER, mt_follow_set_master),
    (table::MT_FOLLOW_GET_MASTER, mt_follow_get_master),
    (table::MT_FOLLOW_SET_EVENT, mt_follow_set_event),
    (table::MT_FOLLOW_GET_EVENT, mt_follow_get_event),
    (table::MT_FOLLOW_SET_DIR, mt_follow_set_dir),
    (table::MT_FOLLOW_GET_DIR, mt_follow_get_dir),
    (table::MT_FOLLOW_SET_LOOP_COUNT, mt_follow_set_loop_count),
    (table::MT_FOLLOW_GET_LOOP_COUNT, mt_follow_get_loop_count),
    (table::MT_FOLLOW_PUSH_DATA, mt_follow_push_data),
    (table::MT_FOLLOW_GET_SPACE, mt_follow_get_space),
    (table::MT_FOLLOW_CLEAR, mt_follow_clear),
    (table::MT_FOLLOW_START, mt_follow_start),
    (table::MT_FOLLOW_SWITCH, mt_follow_switch),
];

/// `MT_FOLLOW_PRF_MODE` (digest 001 §3.2): what `NMC_MtGetPrfMode` reads once Follow runs.
const MT_FOLLOW_PRF_MODE: i16 = 8;

/// The slave's Follow as the engine shows it (the defaults before any setting).
fn follow(c: &Call<'_>, axis: usize) -> FollowStatus {
    c.snapshot
        .follows
        .iter()
        .find(|f| usize::from(f.axis) == axis)
        .copied()
        .unwrap_or(FollowStatus {
            axis: axis as u16,
            space: [32, 32],
            ..FollowStatus::default()
        })
}

/// The scale of the slave's master (the slave's own before a master is set).
fn master_scale(c: &Call<'_>, axis: usize) -> PulseScale {
    c.scale(follow(c, axis).master.map_or(axis, usize::from))
}

fn config(axis: usize) -> FollowConfig {
    FollowConfig {
        axis: axis as u16,
        master: None,
        master_source: None,
        loop_count: None,
        event: None,
        start_position: None,
        start_direction: None,
        direction: None,
    }
}

fn fifo(v: i16) -> Result<u8, Refusal> {
    u8::try_from(v)
        .ok()
        .filter(|f| *f < FOLLOW_FIFOS)
        .ok_or_else(|| Refusal::range("fifoNo", v, "{0, 1}"))
}

/// masterType 1 planned position, 2 feedback, 3 encoder (PROFILE_FOLLOW_MASTER_*); 0 (none)
/// is refused: the engine's Follow always has a master (decisions.md).
fn mt_follow_set_master(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let (no, kind) = (c.input.i16()?, c.input.i16()?);
    let master = axis_number(c, "masterNo", i64::from(no))?;
    if master == axis {
        return Err(Refusal::range(
            "masterNo",
            no,
            "another axis than the slave's",
        ));
    }
    let source = match kind {
        1 => MasterSource::Commanded,
        2 => MasterSource::Actual,
        3 => MasterSource::Encoder,
        k => {
            return Err(Refusal::range(
                "masterType",
                k,
                "{1 AXIS_PRF, 2 AXIS_ENC, 3 ENC}",
            ))
        }
    };
    c.command(FollowConfig {
        master: Some(master as u16),
        master_source: Some(source),
        ..config(axis)
    });
    Ok(())
}

/// −1 and PROFILE_FOLLOW_MASTER_NONE (0) before a master is set.
fn mt_follow_get_master(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let f = follow(c, axis);
    let (no, kind) = match f.master {
        None => (-1, 0),
        Some(m) => (
            c.service
                .bus()
                .nmc_number(usize::from(m), c.snapshot.axes.len())
                .map_or(-1, i16::from),
            match f.master_source {
                MasterSource::Commanded => 1,
                MasterSource::Actual => 2,
                MasterSource::Encoder => 3,
            },
        ),
    };
    c.output.i16(no).i16(kind);
    Ok(())
}

/// eventType 1 at the start call, 2 when the master crosses `pos` moving in masterDir (1
/// positive, −1 negative).
fn mt_follow_set_event(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let (event, dir, pos) = (c.input.i16()?, c.input.i16()?, c.input.i64()?);
    let event = match event {
        1 => FollowEvent::Immediate,
        2 => FollowEvent::MasterCrossing,
        e => {
            return Err(Refusal::range(
                "eventType",
                e,
                "{1 at start, 2 master crossing}",
            ))
        }
    };
    let direction = match dir {
        1 => Direction::Positive,
        -1 => Direction::Negative,
        d => return Err(Refusal::range("masterDir", d, "{1 positive, −1 negative}")),
    };
    let scale = master_scale(c, axis);
    c.command(FollowConfig {
        event: Some(event),
        start_position: Some(scale.to_engine(pos as f64)),
        start_direction: Some(direction),
        ..config(axis)
    });
    Ok(())
}

fn mt_follow_get_event(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let f = follow(c, axis);
    let event = match f.event {
        FollowEvent::Immediate => 1,
        FollowEvent::MasterCrossing => 2,
    };
    let dir = match f.start_direction {
        Some(Direction::Negative) => -1,
        _ => 1,
    };
    let pos = pulses(master_scale(c, axis), f.start_position);
    c.output.i16(event).i16(dir).i64(pos);
    Ok(())
}

/// 0 both directions, > 0 the master's positive travel only, < 0 its negative only.
fn mt_follow_set_dir(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let dir = c.input.i16()?;
    let direction = match dir {
        0 => FollowDirection::Both,
        d if d > 0 => FollowDirection::Positive,
        _ => FollowDirection::Negative,
    };
    c.command(FollowConfig {
        direction: Some(direction),
        ..config(axis)
    });
    Ok(())
}

fn mt_follow_get_dir(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let dir = match follow(c, axis).direction {
        FollowDirection::Both => 0,
        FollowDirection::Positive => 1,
        FollowDirection::Negative => -1,
    };
    c.output.i16(dir);
    Ok(())
}

/// Passes through the FIFO, 0 for ever (the S-FOLLOW example).
fn mt_follow_set_loop_count(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let n = c.input.i64()?;
    let loop_count =
        u32::try_from(n).map_err(|_| Refusal::range("loopCnt", n, "[0 (for ever), 4294967295]"))?;
    c.command(FollowConfig {
        loop_count: Some(loop_count),
        ..config(axis)
    });
    Ok(())
}

/// The setting; while the Follow runs, the passes done (digest 001 §2.17).
fn mt_follow_get_loop_count(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let f = follow(c, axis);
    let n = match f.state {
        FollowState::Idle => f.loop_count,
        FollowState::Waiting | FollowState::Running => f.loops_done,
    };
    c.output.i64(i64::from(n));
    Ok(())
}

/// One point: master and slave positions from the FIFO's start (pulses), segment type 0
/// normal, 1 even, 2 decelerate to 0, 3 continuous across FIFOs.
fn mt_follow_push_data(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let (master, slave) = (c.input.i64()?, finite("slavePos", c.input.f64()?)?);
    let (kind, fifo_no) = (c.input.i16()?, c.input.i16()?);
    let segment = match kind {
        0 => FollowSegment::Normal,
        1 => FollowSegment::Even,
        2 => FollowSegment::Stop,
        3 => FollowSegment::Continuous,
        t => {
            return Err(Refusal::range(
                "type",
                t,
                "{0 normal, 1 even, 2 stop, 3 continuous}",
            ))
        }
    };
    let fifo = fifo(fifo_no)?;
    let point = CamPoint {
        master: master_scale(c, axis).to_engine(master as f64),
        slave: c.scale(axis).to_engine(slave),
        segment,
    };
    c.command(FollowPush {
        axis: axis as u16,
        fifo,
        points: vec![point],
    });
    Ok(())
}

fn mt_follow_get_space(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let fifo = usize::from(fifo(c.input.i16()?)?);
    let space = follow(c, axis).space.get(fifo).copied().unwrap_or(0);
    c.output.i16(space as i16);
    Ok(())
}

fn mt_follow_clear(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let fifo = fifo(c.input.i16()?)?;
    c.command(FollowClear {
        axis: axis as u16,
        fifo,
    });
    Ok(())
}

/// Starts the handle's axis and the others named, all in one tick.
fn mt_follow_start(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axes = axes_to_start(c)?;
    c.command(Command::from(FollowStart {
        axes: axes.iter().map(|a| *a as u16).collect(),
    }));
    for a in axes {
        c.update(a, |s| s.prf_mode = MT_FOLLOW_PRF_MODE);
    }
    Ok(())
}

/// What `NMC_MtStop` sends to axis `axis` while it runs a Follow (or waits for its start).
pub(super) fn follow_out(c: &Call<'_>, axis: usize) -> Option<Command> {
    let f = follow(c, axis);
    (f.state != FollowState::Idle).then(|| FollowOut { axis: axis as u16 }.into())
}

/// Each axis changes to its other FIFO at the end of the current pass.
fn mt_follow_switch(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axes = axes_to_start(c)?;
    c.command(Command::from(FollowSwitch {
        axes: axes.iter().map(|a| *a as u16).collect(),
    }));
    Ok(())
}
