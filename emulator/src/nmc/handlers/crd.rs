//! Coordinate systems: handles, the axis map, parameters and control (digest 001 §2.2, §2.7,
//! §4.4). Coordinate system n is the engine's group n; what the engine does not keep (the
//! manual's parameters, the commands pushed before `NMC_CrdStartMtn`) is the service's
//! (`crate::nmc::crd`).

use axes::command::{
    Command, GroupContinue, GroupCreate, GroupDelete, GroupEmergencyStop, GroupEnable, GroupHalt,
    GroupId, GroupParameter, GroupReset, GroupSetOrigin, GroupSetOverride, GroupSetParameter,
    GroupStop, Reset,
};
use axes::status::{GroupState, GroupStatus};
use mcemu_dialects::nmc::acceleration_to_engine;
use mcemu_nmc::crd::{CrdConfig, CrdPara, CrdSafePara, ExtCrdPara, CRD_MAX_AXES};
use mcemu_nmc::errors::{RTN_INVALID_HANDLE, RTN_WRONG_HANDLE_KIND};
use mcemu_nmc::handle::{Handle, HandleKind};
use mcemu_nmc::table::{self, Function};

use crate::nmc::crd::{CrdState, CRD_BUFFER, CRD_COUNT};
use crate::nmc::crd_frames::CrdTransform;
use crate::nmc::service::{pulses, Call, Handler, Refusal};

pub const HANDLERS: &[(Function, Handler)] = &[
    (table::CRD_OPEN, crd_open),
    (table::CRD_OPEN_EX, crd_open_ex),
    (table::CRD_CLOSE, crd_close),
    (table::CRD_CONFIG, crd_config),
    (table::CRD_GET_CONFIG, crd_get_config),
    (table::CRD_DELETE, crd_delete),
    (table::CRD_SET_PARA, crd_set_para),
    (table::CRD_GET_PARA, crd_get_para),
    (table::CRD_SET_EXT_PARA, crd_set_ext_para),
    (table::CRD_GET_EXT_PARA, crd_get_ext_para),
    (table::CRD_SET_SAFE_PARA, crd_set_safe_para),
    (
        table::CRD_SET_LOOK_AHEAD_CENTRI_ACC,
        crd_set_look_ahead_centri_acc,
    ),
    (table::CRD_START_MTN, crd_start_mtn),
    (table::CRD_END_MTN, crd_end_mtn),
    (table::CRD_STOP_MTN, crd_stop_mtn),
    (table::CRD_ESTOP_MTN, crd_estop_mtn),
    (table::CRD_CLR_ERROR, crd_clr_error),
    (table::CRD_BUF_CLR, crd_buf_clr),
    (table::CRD_SET_OVERRIDE, crd_set_override),
    (table::CRD_GET_OVERRIDE, crd_get_override),
    (table::CRD_SET_OVER_RIDE, crd_set_override),
    (table::CRD_GET_OVER_RIDE, crd_get_override),
];

/// The coordinate-system handle that starts the request: its number.
pub(super) fn crd(c: &mut Call<'_>) -> Result<usize, Refusal> {
    let h = c.input.u16()?;
    match Handle::decode(h) {
        Some(x) if x.kind == HandleKind::Crd && usize::from(x.item) < CRD_COUNT => {
            Ok(usize::from(x.item))
        }
        Some(x) if x.kind == HandleKind::Crd => Err(Refusal::new(
            RTN_INVALID_HANDLE,
            format!(
                "{h:#06x} names coordinate system {}; there are {CRD_COUNT}",
                x.item
            ),
        )),
        Some(_) => Err(Refusal::new(
            RTN_WRONG_HANDLE_KIND,
            format!("{h:#06x} is not a coordinate-system handle"),
        )),
        None => Err(Refusal::new(
            RTN_INVALID_HANDLE,
            format!("{h:#06x} is not a handle"),
        )),
    }
}

/// The engine group of coordinate system `n`, if it exists.
pub(super) fn group<'a>(c: &'a Call<'_>, n: usize) -> Option<&'a GroupStatus> {
    c.snapshot.groups.iter().find(|g| usize::from(g.group) == n)
}

/// A copy of coordinate system `n`'s state.
pub(super) fn state(c: &Call<'_>, n: usize) -> CrdState {
    c.service
        .crd()
        .get(n)
        .cloned()
        .unwrap_or_else(CrdState::fresh)
}

pub(super) fn update(c: &Call<'_>, n: usize, f: impl FnOnce(&mut CrdState)) {
    if let Some(s) = c.service.crd().get_mut(n) {
        f(s);
    }
}

/// The configured members, or a refusal naming the missing `NMC_CrdConfig`.
pub(super) fn members(s: &CrdState) -> Result<Vec<usize>, Refusal> {
    let axes = s.axes();
    if axes.is_empty() {
        return Err(Refusal::new(
            mcemu_dialects::nmc::code_for_kind(axes::command::ErrorKind::InvalidGroup),
            "the coordinate system has no axes: NMC_CrdConfig first",
        ));
    }
    Ok(axes)
}

/// Where the coordinate system's path stands now, pulses in user coordinates (members'
/// commanded positions less the origin; under the polar transform of its X and Y axes, X and
/// Y are the Cartesian point of the two axes' θ and r).
pub(super) fn here(c: &Call<'_>, n: usize, s: &CrdState) -> [i64; CRD_MAX_AXES] {
    let origin = s.origin();
    let mut out = [0; CRD_MAX_AXES];
    let axes = s.axes();
    for (k, axis) in axes.iter().enumerate().take(CRD_MAX_AXES) {
        let p = c
            .status(*axis)
            .map_or(0, |st| pulses(c.scale(*axis), st.cmd_pos));
        out[k] = p.saturating_sub(origin[k]);
    }
    let polar = c.service.frames().crd.get(n).map(|f| f.transform);
    if let Some(CrdTransform::Polar {
        rot_axis,
        trans_axis,
        rot_equiv,
        path: true,
    }) = polar
    {
        let exact = |axis: usize| {
            c.status(axis)
                .map_or(0.0, |st| st.cmd_pos * c.scale(axis).pulses_per_unit)
        };
        let (theta, r) = (exact(rot_axis) * rot_equiv, exact(trans_axis));
        out[0] = (r * theta.cos()).round() as i64 - origin[0];
        out[1] = (r * theta.sin()).round() as i64 - origin[1];
    }
    out
}

/// The polar transform again, before motions go to the engine group, if `RunToPolarPos/Theta`
/// lifted it to move the crd's X and Y axes in machine coordinates.
pub(super) fn polar_resume(c: &Call<'_>, n: usize) -> Option<Command> {
    let transform = c.service.frames().crd.get(n).map(|f| f.transform)?;
    if group(c, n)?.polar {
        return None;
    }
    transform.polar_command(n, |a| c.scale(a).pulses_per_unit)
}

fn open(c: &mut Call<'_>, n: i16) -> Result<(), Refusal> {
    let item = u8::try_from(n)
        .ok()
        .filter(|i| usize::from(*i) < CRD_COUNT)
        .ok_or_else(|| Refusal::range("itemNo", n, "[0, 1] (TV04)"))?;
    c.output.u16(Handle::crd(0, item).encode());
    Ok(())
}

/// Coordinate system 0.
fn crd_open(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    open(c, 0)
}

fn crd_open_ex(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let n = c.input.i16()?;
    open(c, n)
}

/// The handle is the library's to forget; the coordinate system and its motion stay.
fn crd_close(c: &mut Call<'_>) -> Result<(), Refusal> {
    crd(c)?;
    Ok(())
}

/// 1–4 distinct axes of the device (TV52), the unused entries −1.
fn check_config(c: &Call<'_>, config: &CrdConfig) -> Result<Vec<usize>, Refusal> {
    let n = usize::try_from(config.ax_cnts)
        .ok()
        .filter(|n| (1..=CRD_MAX_AXES).contains(n))
        .ok_or_else(|| Refusal::range("axCnts", config.ax_cnts, "[1, 4] (TV52)"))?;
    let count = c.snapshot.axes.len();
    let mut axes = Vec::with_capacity(n);
    for (k, a) in config.ax.iter().take(n).enumerate() {
        // Local axes, or bus drives from 16 on an `ecat` card (`ecat_bus`).
        let axis = u8::try_from(*a)
            .ok()
            .and_then(|a| c.service.bus().engine_axis(a, count))
            .filter(|a| !axes.contains(a))
            .ok_or_else(|| {
                Refusal::range(
                    &format!("pAxArray[{k}]"),
                    a,
                    &format!("a distinct axis of {}", c.service.bus().numbers_text(count)),
                )
            })?;
        axes.push(axis);
    }
    Ok(axes)
}

/// The engine origin of `s` for its `n` members (pulses → each member's units).
pub(super) fn origin_command(c: &Call<'_>, n: usize, s: &CrdState, axes: &[usize]) -> Command {
    let origin = s.origin();
    GroupSetOrigin {
        group: n as GroupId,
        offset: axes
            .iter()
            .enumerate()
            .map(|(k, a)| {
                c.scale(*a)
                    .to_engine(origin.get(k).copied().unwrap_or(0) as f64)
            })
            .collect(),
    }
    .into()
}

/// (Re)make group n of the mapped axes, with the buffer size and the origin; the group is
/// enabled at `NMC_CrdStartMtn` (the members may still be off now).
fn crd_config(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    let config = CrdConfig::read(&mut c.input)?;
    let axes = check_config(c, &config)?;
    if group(c, n).is_some() {
        c.command(GroupDelete {
            group: n as GroupId,
        });
    }
    c.command(GroupCreate {
        group: n as GroupId,
        axes: axes.iter().map(|a| *a as u16).collect(),
        queue_capacity: Some(CRD_BUFFER as u32),
        lookahead: None,
        result_axis: None,
        orientation: Default::default(),
    });
    let mut s = state(c, n);
    s.config = Some(config);
    let origin = origin_command(c, n, &s, &axes);
    c.command(origin);
    if s.centri_acc > 0.0 {
        let centri = centri_command(c, n, &s);
        c.command(centri);
    }
    for command in corner_commands(c, n, &s) {
        c.command(command);
    }
    for command in stop_commands(c, n, &s) {
        c.command(command);
    }
    // The 0x17xx family: transforms and the break point go with the old group; the
    // arc-section table is the new group's chord error.
    let table = c.service.frames().on_config(n);
    if crate::nmc::crd_frames::chord_error(&table) != (0.0, [0.0; 2], [0.0; 2]) {
        let scale = member_scale(c, &axes, 0);
        for command in crate::nmc::crd_frames::chord_commands(n, scale, &table) {
            c.command(command);
        }
    }
    let turn_vel = c.service.frames().crd_turn_vel(n);
    if turn_vel > 0.0 {
        let command =
            crate::nmc::crd_frames::turn_vel_command(n, member_scale(c, &axes, 3), turn_vel);
        c.command(command);
    }
    s.pending.clear();
    s.started = false;
    s.end = here(c, n, &s);
    update(c, n, |now| *now = s);
    Ok(())
}

fn crd_get_config(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    state(c, n).config.unwrap_or_default().write(c.output);
    Ok(())
}

/// The axes go back to single-axis mode; the parameters stay (the manual deletes them too, but
/// a later `NMC_CrdConfig` then starts from the defaults either way).
fn crd_delete(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    if group(c, n).is_some() {
        c.command(GroupDelete {
            group: n as GroupId,
        });
    }
    update(c, n, |s| *s = CrdState::fresh());
    c.service.frames().on_delete(n);
    Ok(())
}

fn positive(name: &str, v: f64, unit: &str) -> Result<(), Refusal> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(Refusal::range(name, v, &format!("(0, ∞) {unit}")))
    }
}

pub(super) fn non_negative(name: &str, v: f64, unit: &str) -> Result<(), Refusal> {
    if v.is_finite() && v >= 0.0 {
        Ok(())
    } else {
        Err(Refusal::range(name, v, &format!("[0, ∞) {unit}")))
    }
}

/// Origin and path limits. The origin moves the user coordinates: only while nothing is
/// queued (the engine refuses it otherwise).
fn crd_set_para(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    let p = CrdPara::read(&mut c.input)?;
    if !(0..=1).contains(&p.org_flag) {
        return Err(Refusal::range("orgFlag", p.org_flag, "{0, 1}"));
    }
    positive("synAccMax", p.syn_acc_max, "pulse/ms²")?;
    positive("synVelMax", p.syn_vel_max, "pulse/ms")?;
    let mut s = state(c, n);
    let old = s.origin();
    s.para = p;
    let new = s.origin();
    for k in 0..CRD_MAX_AXES {
        s.end[k] = s.end[k].saturating_add(old[k]).saturating_sub(new[k]);
    }
    let axes = s.axes();
    if group(c, n).is_some() && old != new {
        let origin = origin_command(c, n, &s, &axes);
        c.command(origin);
    }
    if group(c, n).is_some() {
        for command in stop_commands(c, n, &s) {
            c.command(command);
        }
    }
    update(c, n, |now| *now = s);
    Ok(())
}

fn crd_get_para(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    state(c, n).para.write(c.output);
    Ok(())
}

/// Stored; `smoothDec` is `NMC_CrdStopMtn`'s deceleration (and the move protection's stop's,
/// [`stop_commands`]) and `lookAheadSwitch` 0 makes every segment stop at its end
/// (decisions.md).
fn crd_set_ext_para(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    let p = ExtCrdPara::read(&mut c.input)?;
    non_negative("startVel", p.start_vel, "pulse/ms")?;
    non_negative("T", p.t, "ms")?;
    non_negative(
        "smoothDec",
        p.smooth_dec,
        "pulse/ms² (0: the path acceleration)",
    )?;
    non_negative(
        "abruptDec",
        p.abrupt_dec,
        "pulse/ms² (0: the axes' estpDec)",
    )?;
    if p.look_ahead_switch < 0 {
        return Err(Refusal::range(
            "lookAheadSwitch",
            p.look_ahead_switch,
            "[0, n]",
        ));
    }
    if p.event_time < 0 {
        return Err(Refusal::range("eventTime", p.event_time, "[0, 32767] ms"));
    }
    let mut s = state(c, n);
    s.ext = p;
    if group(c, n).is_some() {
        for command in stop_commands(c, n, &s) {
            c.command(command);
        }
    }
    update(c, n, |now| *now = s);
    Ok(())
}

fn crd_get_ext_para(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    state(c, n).ext.write(c.output);
    Ok(())
}

/// maxVel and maxAcc clamp every segment's (as TSafePara does an axis's); estpDec is the axes'
/// own E-stop deceleration in the engine and is kept for reading only.
fn crd_set_safe_para(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    let p = CrdSafePara::read(&mut c.input)?;
    positive("estpDec", p.estp_dec, "pulse/ms²")?;
    positive("maxAcc", p.max_acc, "pulse/ms²")?;
    positive("maxVel", p.max_vel, "pulse/ms")?;
    update(c, n, |s| s.safe = p);
    Ok(())
}

/// Run what was pushed: after `NMC_CrdStopMtn` the halted path goes on; otherwise the group is
/// enabled if needed and the pending commands go to the engine in one batch.
fn crd_start_mtn(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    let mut s = state(c, n);
    members(&s)?;
    let g = group(c, n).map(|g| g.state);
    match g {
        Some(GroupState::Halted) => c.command(GroupContinue {
            group: n as GroupId,
        }),
        Some(GroupState::Disabled) => c.command(GroupEnable {
            group: n as GroupId,
        }),
        _ => {}
    }
    if g.is_some() && s.override_factor != 1.0 {
        c.command(GroupSetOverride {
            group: n as GroupId,
            factor: s.override_factor,
        });
    }
    if !s.pending.is_empty() {
        if let Some(polar) = polar_resume(c, n) {
            c.command(polar);
        }
    }
    c.plan.commands.append(&mut s.pending);
    s.started = true;
    update(c, n, |now| *now = s);
    Ok(())
}

/// Every pushed command is already with the engine or waits for `NMC_CrdStartMtn`: there is no
/// host-side look-ahead to flush (decisions.md).
fn crd_end_mtn(c: &mut Call<'_>) -> Result<(), Refusal> {
    crd(c)?;
    Ok(())
}

/// A smooth stop along the path that keeps the buffer (TV49): the engine's halt, with
/// `smoothDec` (0: the path's own deceleration).
fn crd_stop_mtn(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    let s = state(c, n);
    if group(c, n).is_none_or(|g| g.state != GroupState::Moving) {
        return Ok(());
    }
    let deceleration = (s.ext.smooth_dec > 0.0).then(|| {
        let scale = s.axes().first().map_or(
            mcemu_dialects::PulseScale {
                pulses_per_unit: 1.0,
            },
            |a| c.scale(*a),
        );
        acceleration_to_engine(scale, s.ext.smooth_dec)
    });
    c.command(GroupHalt {
        group: n as GroupId,
        deceleration,
    });
    Ok(())
}

/// The engine's group e-stop that keeps the path ("急停(并不清空指令缓冲区)", digest 001
/// §2.7): every member stops with its estpDec, off the path, and the group latches MVERR
/// until `NMC_CrdClrError`; then `NMC_CrdGotoBreak` and `NMC_CrdStartMtn` finish the path
/// (decisions.md, "`NMC_CrdGotoBreak(acc, vel)`").
fn crd_estop_mtn(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    if group(c, n).is_some_and(|g| g.state != GroupState::Disabled) {
        // Where NMC_CrdGotoBreak returns to (0x17xx family).
        let at = here(c, n, &state(c, n));
        c.service.frames().note_break(n, at);
        c.command(GroupEmergencyStop {
            group: n as GroupId,
            keep_path: true,
        });
    }
    Ok(())
}

/// The members' errors, then the group's (digest 001 §2.7: "clear crd errors and the errors of
/// its axes").
fn crd_clr_error(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    let s = state(c, n);
    for axis in s.axes() {
        c.command(Reset { axis: axis as u16 });
    }
    if group(c, n).is_some_and(|g| g.state == GroupState::ErrorStop) {
        c.command(GroupReset {
            group: n as GroupId,
        });
    }
    Ok(())
}

/// Empty the buffer (pending and the engine's queue); refused while the path moves.
fn crd_buf_clr(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    let mut s = state(c, n);
    match group(c, n).map(|g| g.state) {
        Some(GroupState::Moving | GroupState::Stopping) => {
            return Err(Refusal::new(
                mcemu_dialects::nmc::code_for_kind(axes::command::ErrorKind::GroupState),
                "the coordinate system is moving: NMC_CrdStopMtn first",
            ))
        }
        Some(GroupState::Halted) => c.command(GroupStop {
            group: n as GroupId,
            deceleration: None,
        }),
        _ => {}
    }
    s.pending.clear();
    s.started = false;
    s.pushed = 0;
    s.pushed_length = 0.0;
    s.end = here(c, n, &s);
    s.ext_end.clear();
    update(c, n, |now| *now = s);
    Ok(())
}

/// (0, 10), open at both ends (TV51).
fn crd_set_override(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    let factor = c.input.f64()?;
    if !(factor.is_finite() && factor > 0.0 && factor < 10.0) {
        return Err(Refusal::range("override", factor, "(0, 10) (TV51)"));
    }
    if group(c, n).is_some() {
        c.command(GroupSetOverride {
            group: n as GroupId,
            factor,
        });
    }
    update(c, n, |s| s.override_factor = factor);
    Ok(())
}

fn crd_get_override(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    c.output.f64(state(c, n).override_factor);
    Ok(())
}

/// The engine's `arc_acceleration` (v ≤ √(A·r) on arcs) in the first member's units;
/// isUsingSetAcc 0 turns it off.
pub(super) fn centri_command(c: &Call<'_>, n: usize, s: &CrdState) -> Command {
    let scale = s.axes().first().map_or(
        mcemu_dialects::PulseScale {
            pulses_per_unit: 1.0,
        },
        |a| c.scale(*a),
    );
    GroupSetParameter {
        group: n as GroupId,
        name: GroupParameter::ArcAcceleration,
        value: acceleration_to_engine(scale, s.centri_acc),
    }
    .into()
}

fn crd_set_look_ahead_centri_acc(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    let using = c.input.i16()?;
    let acc = c.input.f64()?;
    if !(0..=1).contains(&using) {
        return Err(Refusal::range("isUsingSetAcc", using, "{0, 1}"));
    }
    non_negative("centriAcc", acc, "pulse/ms²")?;
    let mut s = state(c, n);
    s.centri_acc = if using == 1 { acc } else { 0.0 };
    if group(c, n).is_some() {
        let command = centri_command(c, n, &s);
        c.command(command);
    }
    update(c, n, |now| *now = s);
    Ok(())
}

fn parameter(n: usize, name: GroupParameter, value: f64) -> Command {
    GroupSetParameter {
        group: n as GroupId,
        name,
        value,
    }
    .into()
}

/// The group's own acceleration and deceleration: what the engine's move protection stops
/// with (and `group_stop` without one; every NMC segment carries its own). smoothDec is the
/// crd's stop deceleration ("停止减速度 (默认accMax)", digest 001 §3.9); 0 or unset is the crd's
/// synAccMax, which bounds every segment's synAcc, so the stop brakes as the path does.
pub(super) fn stop_commands(c: &Call<'_>, n: usize, s: &CrdState) -> Vec<Command> {
    let scale = s.axes().first().map_or(
        mcemu_dialects::PulseScale {
            pulses_per_unit: 1.0,
        },
        |a| c.scale(*a),
    );
    let acc = s.para.syn_acc_max;
    let dec = if s.ext.smooth_dec > 0.0 {
        s.ext.smooth_dec
    } else {
        acc
    };
    vec![
        parameter(
            n,
            GroupParameter::Acceleration,
            acceleration_to_engine(scale, acc),
        ),
        parameter(
            n,
            GroupParameter::Deceleration,
            acceleration_to_engine(scale, dec),
        ),
    ]
}

/// The engine's corner rules for `s`'s look-ahead parameters (none until
/// `NMC_CrdSetLookaheadPara`): accMax is the corner acceleration, slowAng/stopAng the corner
/// angles (degrees → radians; both 0: no slowing, only a reversal stops). stopAng goes to π
/// first so that every step keeps slow ≤ stop, as the engine requires.
pub(super) fn corner_commands(c: &Call<'_>, n: usize, s: &CrdState) -> Vec<Command> {
    let Some(p) = s.lookahead else {
        return Vec::new();
    };
    let scale = s.axes().first().map_or(
        mcemu_dialects::PulseScale {
            pulses_per_unit: 1.0,
        },
        |a| c.scale(*a),
    );
    let (slow, stop) = if p.stop_ang == 0.0 {
        (180.0, 180.0)
    } else {
        (p.slow_ang, p.stop_ang)
    };
    vec![
        parameter(
            n,
            GroupParameter::CornerAcceleration,
            acceleration_to_engine(scale, p.acc_max),
        ),
        parameter(n, GroupParameter::CornerStopAngle, std::f64::consts::PI),
        parameter(n, GroupParameter::CornerSlowAngle, slow.to_radians()),
        parameter(n, GroupParameter::CornerStopAngle, stop.to_radians()),
    ]
}

/// The pulse scale of member `k` of `axes` (1 pulse per unit without one): the chord errors
/// are in the first member's pulses, the A axis's corner speed in the fourth's.
pub(super) fn member_scale(c: &Call<'_>, axes: &[usize], k: usize) -> mcemu_dialects::PulseScale {
    axes.get(k).map_or(
        mcemu_dialects::PulseScale {
            pulses_per_unit: 1.0,
        },
        |a| c.scale(*a),
    )
}
