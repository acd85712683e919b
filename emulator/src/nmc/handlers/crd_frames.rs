//! Coordinate transforms, arc sections, the A axis's corner velocity, the buffer offset and the
//! break point, family 0x17xx (digest 001 §2.7, §2.20 C3§10.5, §3.7; S-TRANS-ROTATE,
//! S-TRANS-XYZA). The rotary and XYZA transforms are the engine group's (`group/frames.rs`):
//! set, then selected for the moves that follow. The polar transform of the crd's own X and Y
//! axes is the engine group's output map (`group/polar.rs`: Cartesian paths fed as θ and r);
//! on axes outside the crd it serves `NMC_CrdRunToPolarPos/Theta` only (decisions.md, "NMC
//! coordinate transforms, break point and move protection", "Polar machine").

use std::f64::consts::TAU;

use axes::command::{
    Command, CoordinateSystem, ErrorKind, GroupDeletePolarTransform, GroupDeleteTransform,
    GroupEnable, GroupId, GroupSetCoordinateSystem, GroupSetRotaryTransform, GroupSetXyzaTransform,
    MoveLinearAbsolute, PositionFrame, SetPosition,
};
use axes::status::GroupState;
use mcemu_dialects::nmc::{acceleration_to_engine, code_for_kind, velocity_to_engine};
use mcemu_nmc::crd::CRD_MAX_AXES;
use mcemu_nmc::crd_frames::ArcSecSetting;
use mcemu_nmc::table::{self, Function};

use super::crd::{crd, group, here, member_scale, members, origin_command, state, update};
use super::crd_segment::read_longs;
use super::crd_status::path_scale;
use super::motion::ptp_move;
use super::sync_args::axis_number;
use crate::nmc::crd_frames::{chord_commands, turn_vel_command, CrdFrames, CrdTransform};
use crate::nmc::service::{pulses, Call, Handler, Refusal};

pub const HANDLERS: &[(Function, Handler)] = &[
    (table::CRD_SET_TRANS_ROTATE, crd_set_trans_rotate),
    (table::CRD_DEL_TRANS_ROTATE, crd_del_trans_rotate),
    (table::CRD_SET_TRANS_POLAR, crd_set_trans_polar),
    (table::CRD_RUN_TO_POLAR_POS, crd_run_to_polar_pos),
    (table::CRD_RUN_TO_POLAR_THETA, crd_run_to_polar_theta),
    (table::CRD_DEL_TRANS_POLAR, crd_del_trans_polar),
    (table::CRD_SET_TRANS_XYZA, crd_set_trans_xyza),
    (table::CRD_DEL_TRANS_XYZA, crd_del_trans_xyza),
    (table::CRD_SET_XYZA_TOOL_CALC, crd_set_xyza_tool_calc),
    (table::CRD_SET_XYZA_PARA, crd_set_xyza_para),
    (table::CRD_GET_XYZA_PARA, crd_get_xyza_para),
    (table::CRD_SET_OFFSET, crd_set_offset),
    (table::CRD_SET_ARC_SEC_PARA, crd_set_arc_sec_para),
    (table::CRD_GET_ARC_SEC_PARA, crd_get_arc_sec_para),
    (
        table::CRD_SET_FOURTH_AXIS_TO_TURN_VEL,
        crd_set_fourth_axis_to_turn_vel,
    ),
    (table::CRD_GOTO_BREAK, crd_goto_break),
];

fn frames(c: &Call<'_>, n: usize) -> CrdFrames {
    c.service.frames().crd.get(n).copied().unwrap_or_default()
}

fn set_frames(c: &Call<'_>, n: usize, f: impl FnOnce(&mut CrdFrames)) {
    if let Some(x) = c.service.frames().crd.get_mut(n) {
        f(x);
    }
}

/// Send `commands` in push order: behind what waits for `NMC_CrdStartMtn` if anything does
/// (the segments pushed before a transform call keep the frame they were pushed in), else now.
fn send(c: &mut Call<'_>, n: usize, commands: Vec<Command>) {
    let s = state(c, n);
    if !s.started && !s.pending.is_empty() {
        update(c, n, |now| now.pending.extend(commands));
    } else {
        c.plan.commands.extend(commands);
    }
}

/// The engine group must exist (`NMC_CrdConfig` made it).
fn configured(c: &Call<'_>, n: usize) -> Result<Vec<usize>, Refusal> {
    let axes = members(&state(c, n))?;
    if group(c, n).is_none() {
        return Err(Refusal::new(
            code_for_kind(ErrorKind::InvalidGroup),
            "the coordinate system has no group yet: NMC_CrdConfig first",
        ));
    }
    Ok(axes)
}

/// The engine axis of NMC axis number `a` (local, or a bus drive from 16).
fn device_axis(c: &Call<'_>, name: &str, a: i16) -> Result<usize, Refusal> {
    axis_number(c, name, i64::from(a))
}

fn finite(name: &str, v: f64) -> Result<f64, Refusal> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(Refusal::range(name, v, "finite numbers"))
    }
}

fn positive(name: &str, v: f64, unit: &str) -> Result<f64, Refusal> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(Refusal::range(name, v, &format!("(0, ∞) {unit}")))
    }
}

/// Drop the engine group's transform (if it has one) and select the machine coordinates.
fn delete_transform(c: &mut Call<'_>, n: usize) {
    let had = frames(c, n).transform;
    if matches!(had, CrdTransform::Rotary { .. } | CrdTransform::Xyza { .. })
        && group(c, n).is_some()
    {
        send(
            c,
            n,
            vec![GroupDeleteTransform {
                group: n as GroupId,
            }
            .into()],
        );
    }
    if group(c, n).is_some_and(|g| g.polar) {
        c.command(GroupDeletePolarTransform {
            group: n as GroupId,
        });
    }
    set_frames(c, n, |f| f.transform = CrdTransform::None);
}

/// `NMC_CrdSetTransRotate(crd, rotAxisNo, angleRadEqual, firstAxisInitPos, secAxisInitPos)`:
/// the workpiece on a table (axis rotAxisNo, not a member: S-TRANS-ROTATE turns it with buffered
/// axis moves between segments) turning about (X, Y) = the centre, user coordinates. Segments
/// pushed from now on are placed on the table at the angle the pushed table moves leave it.
fn crd_set_trans_rotate(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    let axis = c.input.i16()?;
    let rad = c.input.f64()?;
    let (cx, cy) = (c.input.i64()?, c.input.i64()?);
    let axes = configured(c, n)?;
    let axis = device_axis(c, "rotAxisNo", axis)?;
    if axes.contains(&axis) {
        return Err(Refusal::range(
            "rotAxisNo",
            axis,
            "the axes outside the coordinate system (the table turns between segments, S-TRANS-ROTATE)",
        ));
    }
    let (Some(&x), Some(&y)) = (axes.first(), axes.get(1)) else {
        return Err(Refusal::new(
            code_for_kind(ErrorKind::InvalidGroup),
            "the rotary transform turns X and Y: the coordinate system needs 2 axes",
        ));
    };
    if !(rad.is_finite() && rad != 0.0 && rad.abs() <= TAU) {
        return Err(Refusal::range(
            "angleRadEqual",
            rad,
            "[-2π, 0) ∪ (0, 2π] rad/pulse",
        ));
    }
    let rotary = GroupSetRotaryTransform {
        group: n as GroupId,
        rotary_axis: axis as u16,
        rad_per_unit: rad * c.scale(axis).pulses_per_unit,
        center: [
            c.scale(x).to_engine(cx as f64),
            c.scale(y).to_engine(cy as f64),
        ],
        plane: None,
    };
    let select = GroupSetCoordinateSystem {
        group: n as GroupId,
        coordinate_system: CoordinateSystem::Rotary,
    };
    send(c, n, vec![rotary.into(), select.into()]);
    set_frames(c, n, |f| {
        f.transform = CrdTransform::Rotary {
            axis,
            rad_per_pulse: rad,
            center: [cx, cy],
        }
    });
    Ok(())
}

fn crd_del_trans_rotate(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    if matches!(frames(c, n).transform, CrdTransform::Rotary { .. }) {
        delete_transform(c, n);
    }
    Ok(())
}

/// `NMC_CrdSetTransPolar(crd, rotAxNo, transAxNo, rotEquiv)`: which axis turns (rotEquiv rad per
/// pulse, 2π / pulses per turn) and which moves along the radius. Replaces another transform.
/// When the two are the coordinate system's X and Y axes (either order) the crd motions pushed
/// from now on are Cartesian and the engine group feeds the two axes θ and r
/// (`group_set_polar_transform`, the rotary axis's whole turns kept); the transform changes
/// only with nothing pushed or moving. Other axes: only `RunToPolarPos/Theta` use it
/// (decisions.md, "Polar machine").
fn crd_set_trans_polar(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    let (rot, trans, equiv) = (c.input.i16()?, c.input.i16()?, c.input.f64()?);
    let rot = device_axis(c, "rotAxNo", rot)?;
    let trans = device_axis(c, "transAxNo", trans)?;
    if rot == trans {
        return Err(Refusal::range(
            "transAxNo",
            trans,
            "an axis other than rotAxNo",
        ));
    }
    if !(equiv.is_finite() && equiv > 0.0 && equiv <= TAU) {
        return Err(Refusal::range(
            "rotEquiv",
            equiv,
            "(0, 2π] rad/pulse (2π / pulses per turn)",
        ));
    }
    let s = state(c, n);
    let xy = s.axes().get(..2).map(<[usize]>::to_vec);
    let path =
        group(c, n).is_some() && xy.is_some_and(|xy| xy.contains(&rot) && xy.contains(&trans));
    if path {
        check_polar_change(c, n)?;
        if c.scale(rot) != c.scale(trans) {
            return Err(Refusal::range(
                "rotAxNo",
                rot,
                "an axis with the pulses per unit of transAxNo (X and Y are in its pulses)",
            ));
        }
    }
    delete_transform(c, n);
    let polar = CrdTransform::Polar {
        rot_axis: rot,
        trans_axis: trans,
        rot_equiv: equiv,
        path,
    };
    if let Some(command) = polar.polar_command(n, |a| c.scale(a).pulses_per_unit) {
        c.command(command);
    }
    set_frames(c, n, |f| f.transform = polar);
    Ok(())
}

/// The polar transform of the path changes only with nothing pushed waiting for
/// `NMC_CrdStartMtn` (those segments were given in the other coordinates) and the path at
/// rest (the engine refuses a moving group's change).
fn check_polar_change(c: &Call<'_>, n: usize) -> Result<(), Refusal> {
    let s = state(c, n);
    if !s.started && !s.pending.is_empty() {
        return Err(Refusal::new(
            code_for_kind(ErrorKind::GroupState),
            "segments are pushed: the polar transform changes before them (NMC_CrdBufClr)",
        ));
    }
    Ok(())
}

fn crd_del_trans_polar(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    if let CrdTransform::Polar { path, .. } = frames(c, n).transform {
        if path {
            check_polar_change(c, n)?;
        }
        delete_transform(c, n);
    }
    Ok(())
}

/// The polar transform's axes and rad/pulse, and whether they are the path's X and Y, or a
/// refusal naming the missing call.
fn polar(c: &Call<'_>, n: usize) -> Result<(usize, usize, f64, bool), Refusal> {
    match frames(c, n).transform {
        CrdTransform::Polar {
            rot_axis,
            trans_axis,
            rot_equiv,
            path,
        } => Ok((rot_axis, trans_axis, rot_equiv, path)),
        _ => Err(Refusal::new(
            code_for_kind(ErrorKind::InvalidState),
            "no polar transform: NMC_CrdSetTransPolar first",
        )),
    }
}

/// "圈数清零": the rotary axis's commanded position less its whole turns, in [0, one turn).
fn clear_turns(c: &Call<'_>, axis: usize, equiv: f64) -> Option<Command> {
    let scale = c.scale(axis);
    let turn = TAU / equiv;
    let now = pulses(scale, c.status(axis)?.cmd_pos) as f64;
    let kept = now.rem_euclid(turn).round();
    (kept != now).then(|| {
        SetPosition {
            axis: axis as u16,
            position: scale.to_engine(kept),
            frame: PositionFrame::Commanded,
        }
        .into()
    })
}

/// One PTP of `axis` to `target` pulses at `vel` pulse/ms, with the axis's own PTP parameters.
fn ptp(c: &Call<'_>, axis: usize, target: f64, vel: f64) -> Result<Vec<Command>, Refusal> {
    let target = in_range(target)?;
    let para = c.settings(axis).ptp;
    ptp_move(c, axis, para, vel, target as i64, false)
}

fn in_range(target: f64) -> Result<f64, Refusal> {
    let target = target.round();
    if target.abs() > 2_147_483_647.0 {
        return Err(Refusal::range(
            "position",
            target,
            "[-2147483647, 2147483647] pulses",
        ));
    }
    Ok(target)
}

/// The moves of `RunToPolarPos/Theta`: each axis of `moves` (axis, target pulses, velocity
/// pulse/ms) to its target with its own PTP acc/dec, the rotary axis's turns cleared first when
/// `clear` is `Some(rotEquiv)`. Axes outside the coordinate system: single-axis PTPs. The path's
/// own X and Y (members of the engine group, which refuses single-axis motion): one group line
/// in machine coordinates with the polar transform lifted, each axis at most at its velocity,
/// acceleration and deceleration (both arrive together); the transform is set again before the
/// next motion (`crd::polar_resume`), and the path goes on from the point the axes reach.
fn run_to_polar(
    c: &mut Call<'_>,
    n: usize,
    path: bool,
    moves: &[(usize, f64, f64)],
    clear: Option<(usize, f64)>,
) -> Result<(), Refusal> {
    let mut commands: Vec<Command> = clear
        .and_then(|(axis, equiv)| clear_turns(c, axis, equiv))
        .into_iter()
        .collect();
    if !path {
        for &(axis, target, vel) in moves {
            commands.extend(ptp(c, axis, target, vel)?);
        }
        c.plan.commands.extend(commands);
        return Ok(());
    }
    check_polar_change(c, n)?;
    let g = group(c, n).copied();
    if let Some(g) = g.filter(|g| !matches!(g.state, GroupState::Disabled | GroupState::Standby)) {
        return Err(Refusal::new(
            code_for_kind(ErrorKind::GroupState),
            format!(
                "the coordinate system is {:?}: the polar axes move when it is at rest",
                g.state
            ),
        ));
    }
    let mut s = state(c, n);
    let axes = members(&s)?;
    let origin = s.origin();
    // Machine coordinates (members less the origin), after the turns are cleared.
    let mut position: Vec<f64> = axes
        .iter()
        .zip(origin)
        .map(|(a, o)| {
            let p = c.status(*a).map_or(0, |st| pulses(c.scale(*a), st.cmd_pos));
            p as f64 - o as f64
        })
        .collect();
    if let Some((k, equiv)) =
        clear.and_then(|(a, equiv)| Some((axes.iter().position(|m| *m == a)?, equiv)))
    {
        let now = position[k] + origin[k] as f64;
        position[k] = now.rem_euclid(TAU / equiv).round() - origin[k] as f64;
    }
    // Each moving axis's distance and its velocity, acceleration and deceleration.
    let mut steps: Vec<(f64, [f64; 3])> = Vec::new();
    for &(axis, target, vel) in moves {
        let target = in_range(target)?;
        if let Some(k) = axes.iter().position(|m| *m == axis) {
            let para = c.settings(axis).ptp;
            let delta = target - origin[k] as f64 - position[k];
            position[k] = target - origin[k] as f64;
            steps.push((delta.abs(), [vel, para.acc, para.dec]));
        }
    }
    let length = steps.iter().map(|(d, _)| d * d).sum::<f64>().sqrt();
    if g.is_some_and(|g| g.polar) {
        commands.push(
            GroupDeletePolarTransform {
                group: n as GroupId,
            }
            .into(),
        );
    }
    if length > 0.0 {
        // Path limits such that each axis's share stays within its own (pulses; the scales of
        // the two are equal, `crd_set_trans_polar`).
        let least = |i: usize| {
            steps
                .iter()
                .filter(|(d, _)| *d > 0.0)
                .map(|(d, limits)| limits[i] * length / d)
                .fold(f64::INFINITY, f64::min)
        };
        let (vel, acc, dec) = (least(0), least(1), least(2));
        if !(acc.is_finite() && acc > 0.0 && dec.is_finite() && dec > 0.0) {
            return Err(Refusal::range(
                "TPtpPara.acc/dec",
                format!("{acc}/{dec}"),
                "(0, ∞) pulse/ms² for the polar axes (NMC_MtSetPtpPara)",
            ));
        }
        if g.is_some_and(|g| g.state == GroupState::Disabled) {
            commands.push(
                GroupEnable {
                    group: n as GroupId,
                }
                .into(),
            );
        }
        commands.push(machine_line(c, n, &axes, &position, [vel, acc, dec]));
    }
    // The path goes on from the reached point, in the program's (Cartesian) coordinates.
    if let CrdTransform::Polar {
        rot_axis,
        trans_axis,
        rot_equiv,
        ..
    } = frames(c, n).transform
    {
        let at = |axis: usize| {
            let k = axes.iter().position(|m| *m == axis).unwrap_or(0);
            position[k] + origin[k] as f64
        };
        let (theta, r) = (at(rot_axis) * rot_equiv, at(trans_axis));
        let (x, y) = (r * theta.cos(), r * theta.sin());
        // X and Y are the plane's coordinates 0 and 1, whichever axis each is.
        s.end[0] = (x - origin[0] as f64).round() as i64;
        s.end[1] = (y - origin[1] as f64).round() as i64;
        update(c, n, |now| now.end = s.end);
    }
    c.plan.commands.extend(commands);
    Ok(())
}

/// A line of group `n` to `position` (each member's pulses, user coordinates) at `vel`, `acc`,
/// `dec` (pulse/ms, pulse/ms² of the path's scale) in machine coordinates, whatever transform
/// is selected.
fn machine_line(
    c: &Call<'_>,
    n: usize,
    axes: &[usize],
    position: &[f64],
    [vel, acc, dec]: [f64; 3],
) -> Command {
    let scale = path_scale(c, &state(c, n));
    MoveLinearAbsolute {
        group: n as GroupId,
        position: axes
            .iter()
            .zip(position)
            .map(|(a, p)| c.scale(*a).to_engine(*p))
            .collect(),
        velocity: Some(velocity_to_engine(scale, vel)),
        acceleration: Some(acceleration_to_engine(scale, acc)),
        deceleration: Some(acceleration_to_engine(scale, dec)),
        jerk: None,
        buffer_mode: Default::default(),
        transition: Default::default(),
        user_segment: None,
        independent: Default::default(),
        coordinate_system: Some(CoordinateSystem::MCS),
    }
    .into()
}

/// (xPos, yPos) in polar coordinates: the rotary axis, its turns cleared first, to the angle
/// atan2(y, x) ∈ [0, 2π) and the linear axis to the radius √(x² + y²) (digest 001 C3§10.5:
/// (5000, 5000) → 45°, √2·5000), each at its velocity (`run_to_polar`).
fn crd_run_to_polar_pos(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    let x = finite("xPos", c.input.f64()?)?;
    let y = finite("yPos", c.input.f64()?)?;
    let rot_vel = positive("rotVel", c.input.f64()?, "pulse/ms")?;
    let trans_vel = positive("transVel", c.input.f64()?, "pulse/ms")?;
    let (rot, trans, equiv, path) = polar(c, n)?;
    let theta = y.atan2(x).rem_euclid(TAU);
    let moves = [
        (rot, theta / equiv, rot_vel),
        (trans, x.hypot(y), trans_vel),
    ];
    run_to_polar(c, n, path, &moves, Some((rot, equiv)))
}

/// The rotary axis to angle `theta` (rad), turns cleared first when clrRoundFlag is 1.
fn crd_run_to_polar_theta(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    let theta = finite("theta", c.input.f64()?)?;
    let vel = positive("vel", c.input.f64()?, "pulse/ms")?;
    let clear = c.input.i16()?;
    if !(0..=1).contains(&clear) {
        return Err(Refusal::range("clrRoundFlag", clear, "{0, 1}"));
    }
    let (rot, _, equiv, path) = polar(c, n)?;
    let clear = (clear == 1).then_some((rot, equiv));
    run_to_polar(c, n, path, &[(rot, theta / equiv, vel)], clear)
}

/// The engine's XYZA transform of `f`'s parameters for the members `axes` (X, Y, Z, A).
fn xyza_command(c: &Call<'_>, n: usize, f: &CrdFrames, axes: &[usize]) -> Command {
    let scale = |k: usize| {
        axes.get(k).map_or(
            mcemu_dialects::PulseScale {
                pulses_per_unit: 1.0,
            },
            |a| c.scale(*a),
        )
    };
    GroupSetXyzaTransform {
        group: n as GroupId,
        rad_per_unit: f.pulse2rad * scale(3).pulses_per_unit,
        tool: [
            scale(0).to_engine(f.tool[0] as f64),
            scale(1).to_engine(f.tool[1] as f64),
        ],
    }
    .into()
}

/// `pAxisMapArray` = X, Y, Z, A: the coordinate system's 4 axes in their order (the engine's
/// XYZA is group coordinates 0–3), with the parameters of `NMC_CrdSetXYZAPara`.
fn crd_set_trans_xyza(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    let count = usize::from(c.input.u16()?);
    let mut map = Vec::with_capacity(count.min(CRD_MAX_AXES));
    for _ in 0..count {
        let a = c.input.i16()?;
        if map.len() < CRD_MAX_AXES {
            map.push(a);
        }
    }
    let axes = configured(c, n)?;
    let same = map.len() == CRD_MAX_AXES
        && map
            .iter()
            .zip(&axes)
            .all(|(m, a)| axis_number(c, "pAxisMapArray[i]", i64::from(*m)).ok() == Some(*a));
    let axes_in_order = match <[usize; CRD_MAX_AXES]>::try_from(axes.as_slice()) {
        Ok(a) if same => a,
        _ => {
            return Err(Refusal::range(
                "pAxisMapArray",
                format!("{map:?}"),
                &format!(
                    "the coordinate system's 4 axes in order, X Y Z A ({axes:?}, NMC_CrdConfig)"
                ),
            ))
        }
    };
    let mut f = frames(c, n);
    f.transform = CrdTransform::Xyza { map: axes_in_order };
    let commands = vec![
        xyza_command(c, n, &f, &axes),
        GroupSetCoordinateSystem {
            group: n as GroupId,
            coordinate_system: CoordinateSystem::Xyza,
        }
        .into(),
    ];
    send(c, n, commands);
    set_frames(c, n, |now| *now = f);
    Ok(())
}

fn crd_del_trans_xyza(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    if matches!(frames(c, n).transform, CrdTransform::Xyza { .. }) {
        delete_transform(c, n);
    }
    Ok(())
}

/// The tool offset from a measurement: A turned by deltaTheta from 0, then X and Y moved by
/// (deltaX, deltaY) to bring the tip back to the same point. That move is −(R(Δθ) − I)·tool,
/// the engine's XYZA compensation, so tool = −(R − I)⁻¹·Δ (decisions.md). Computed only; the
/// manual's example passes the result to `NMC_CrdSetXYZAPara`.
fn crd_set_xyza_tool_calc(c: &mut Call<'_>) -> Result<(), Refusal> {
    crd(c)?;
    let theta = c.input.f64()?;
    let (dx, dy) = (c.input.i64()?, c.input.i64()?);
    let (tx, ty) = path::frames::xyza_tool_offset(theta, dx as f64, dy as f64).map_err(|e| {
        Refusal::range(
            "deltaTheta",
            theta,
            &format!("a finite angle that is not a whole number of turns ({e})"),
        )
    })?;
    c.output.i64(-tx.round() as i64).i64(-ty.round() as i64);
    Ok(())
}

/// Stored; a set XYZA transform takes them for the moves pushed afterwards.
fn crd_set_xyza_para(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    let rad = c.input.f64()?;
    let tool = [c.input.i64()?, c.input.i64()?];
    if !(rad.is_finite() && rad.abs() <= TAU) {
        return Err(Refusal::range("pulse2Rad", rad, "[-2π, 2π] rad/pulse"));
    }
    let mut f = frames(c, n);
    f.pulse2rad = rad;
    f.tool = tool;
    if let CrdTransform::Xyza { map } = f.transform {
        if group(c, n).is_some() {
            let command = xyza_command(c, n, &f, &map);
            send(c, n, vec![command]);
        }
    }
    set_frames(c, n, |now| *now = f);
    Ok(())
}

fn crd_get_xyza_para(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    let f = frames(c, n);
    c.output.f64(f.pulse2rad).i64(f.tool[0]).i64(f.tool[1]);
    Ok(())
}

/// The buffered motion's offset of the first `count` coordinates: `TCrdPara.offset` with
/// orgFlag 1 (the user origin, `group_set_origin`), as `NMC_CrdSetPara` sets it; the other
/// coordinates keep theirs (decisions.md).
fn crd_set_offset(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    let count = c.input.i16()?;
    let values = read_longs(c)?;
    let mut s = state(c, n);
    let axes = members(&s)?;
    let k = usize::try_from(count)
        .ok()
        .filter(|k| (1..=axes.len()).contains(k))
        .ok_or_else(|| {
            Refusal::range(
                "count",
                count,
                &format!("[1, {}] (the coordinate system's axes)", axes.len()),
            )
        })?;
    if values.len() != k {
        return Err(Refusal::range(
            "pOffsetArray",
            format!("{} values", values.len()),
            &format!("{k} values"),
        ));
    }
    let old = s.origin();
    s.para.org_flag = 1;
    for (o, v) in s.para.offset.iter_mut().zip(&values) {
        *o = *v;
    }
    let new = s.origin();
    for j in 0..CRD_MAX_AXES {
        s.end[j] = s.end[j].saturating_add(old[j]).saturating_sub(new[j]);
    }
    if group(c, n).is_some() && old != new {
        let command = origin_command(c, n, &s, &axes);
        c.command(command);
    }
    update(c, n, |now| *now = s);
    Ok(())
}

/// minSectionLen ∈ [1, 10000] pulses; maxArcDiff, the radii and errors finite and ≥ 0; the
/// radii ascending (all 0: the table is off).
fn check_arc_sec(a: &ArcSecSetting) -> Result<(), Refusal> {
    if !(a.min_section_len.is_finite() && (1.0..=10000.0).contains(&a.min_section_len)) {
        return Err(Refusal::range(
            "minSectionLen",
            a.min_section_len,
            "[1, 10000] pulses",
        ));
    }
    let values = [("maxArcDiff", a.max_arc_diff)]
        .into_iter()
        .chain(a.r.iter().map(|v| ("r", *v)))
        .chain(a.err.iter().map(|v| ("err", *v)));
    for (name, v) in values {
        if !(v.is_finite() && v >= 0.0) {
            return Err(Refusal::range(name, v, "[0, ∞) pulses"));
        }
    }
    let on = a.r.iter().any(|r| *r > 0.0);
    if on && a.r.windows(2).any(|w| w[0] >= w[1]) {
        return Err(Refusal::range(
            "r",
            format!("{:?}", a.r),
            "ascending radii r0 < r1 (all 0: off)",
        ));
    }
    Ok(())
}

fn crd_set_arc_sec_para(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    let a = ArcSecSetting::read(&mut c.input)?;
    check_arc_sec(&a)?;
    if group(c, n).is_some() {
        let axes = state(c, n).axes();
        for command in chord_commands(n, member_scale(c, &axes, 0), &a) {
            c.command(command);
        }
    }
    set_frames(c, n, |f| f.arc_sec = a);
    Ok(())
}

fn crd_get_arc_sec_para(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    frames(c, n).arc_sec.write(c.output);
    Ok(())
}

/// "设置 4 维插补下，A 轴的最大容忍转弯速度，若大于该速度，则需要进行降速处理": where the path
/// turns at a junction, it slows so that the A axis (the fourth coordinate) is no faster than
/// tolVel pulse/ms there (the engine's `fourth_coordinate_corner_velocity`; 0 = off, the
/// default). Kept across `NMC_CrdConfig`; a coordinate system of fewer than 4 axes has no A.
fn crd_set_fourth_axis_to_turn_vel(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    let v = c.input.f64()?;
    if !(v.is_finite() && v >= 0.0) {
        return Err(Refusal::range("tolVel", v, "[0, ∞) pulse/ms (0: off)"));
    }
    if group(c, n).is_some() {
        let axes = state(c, n).axes();
        let command = turn_vel_command(n, member_scale(c, &axes, 3), v);
        c.command(command);
    }
    set_frames(c, n, |f| f.fourth_axis_turn_vel = v);
    Ok(())
}

/// Back to the break point, a line at `vel` and `acc` in user coordinates. After
/// `NMC_CrdStopMtn` the members stand on the path where it halted: that is the break point and
/// `NMC_CrdStartMtn` goes on from it, so there is nothing to move. After `NMC_CrdEstopMtn`
/// (and `NMC_CrdClrError`) the line goes back to where the path was when it was stopped; the
/// engine dropped the rest of the path (decisions.md).
fn crd_goto_break(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    let acc = positive("acc", c.input.f64()?, "pulse/ms²")?;
    let vel = positive("vel", c.input.f64()?, "pulse/ms")?;
    let axes = configured(c, n)?;
    let state_now = group(c, n).map(|g| g.state);
    let refuse = |text: &str| -> Result<(), Refusal> {
        Err(Refusal::new(code_for_kind(ErrorKind::GroupState), text))
    };
    match state_now {
        Some(GroupState::Moving | GroupState::Stopping) => {
            return refuse("the coordinate system is moving: NMC_CrdStopMtn first")
        }
        Some(GroupState::ErrorStop) => return refuse("NMC_CrdClrError first"),
        // Halted by NMC_CrdStopMtn: on the path, nothing to return from.
        Some(GroupState::Halted) if frames(c, n).break_point.is_none() => return Ok(()),
        _ => {}
    }
    let mut s = state(c, n);
    let Some(point) = frames(c, n).break_point else {
        return refuse(
            "no break point: the path was not stopped (NMC_CrdStopMtn, NMC_CrdEstopMtn)",
        );
    };
    let dims = axes.len().min(CRD_MAX_AXES);
    // Halted after NMC_CrdEstopMtn (the path kept): the engine takes the line back in front
    // of the path's remainder, even of length 0; NMC_CrdStartMtn goes on.
    let kept = state_now == Some(GroupState::Halted);
    if !kept && here(c, n, &s).get(..dims) == point.get(..dims) {
        set_frames(c, n, |f| f.break_point = None);
        return Ok(());
    }
    if state_now == Some(GroupState::Disabled) {
        c.command(GroupEnable {
            group: n as GroupId,
        });
    }
    let position: Vec<f64> = point.iter().map(|p| *p as f64).collect();
    c.command(machine_line(c, n, &axes, &position, [vel, acc, acc]));
    if !kept {
        s.end = point;
        update(c, n, |now| now.end = s.end);
    }
    set_frames(c, n, |f| f.break_point = None);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nmc::crd_frames::chord_error;
    use mcemu_nmc::crd_frames::MAX_ERR_TABLE_SECTION;

    #[test]
    fn the_bands_go_to_the_engine_and_all_zero_radii_turn_them_off() {
        let mut a = ArcSecSetting {
            r: [100.0, 1000.0],
            err: [0.5, 0.2, 2.0],
            ..ArcSecSetting::default()
        };
        assert_eq!(chord_error(&a), (0.5, [100.0, 1000.0], [0.2, 2.0]));
        a.r = [0.0; MAX_ERR_TABLE_SECTION];
        a.err = [1.0; MAX_ERR_TABLE_SECTION + 1];
        assert_eq!(chord_error(&a), (0.0, [0.0; 2], [0.0; 2]));
        assert!(check_arc_sec(&a).is_ok());
        a.r = [1000.0, 100.0];
        assert!(check_arc_sec(&a).is_err());
        a.r = [100.0, 1000.0];
        a.min_section_len = 0.5;
        assert!(check_arc_sec(&a).is_err());
    }
}
