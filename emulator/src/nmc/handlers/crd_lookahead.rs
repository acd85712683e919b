//! Coordinate systems, family 0x14xx (digest 001 §2.7, §3.4, §3.9): the look-ahead parameters
//! mapped onto the engine group's look-ahead rules, the packed status, the buffered position
//! wait and the pushed path length.

use axes::command::{GroupWaitPosition, PositionCondition, PositionSource};
use mcemu_dialects::nmc::{axis_status, velocity_from_engine, AxisExtra};
use mcemu_nmc::crd::CRD_MAX_AXES;
use mcemu_nmc::crd_lookahead::{LookaheadPara, PackedCrdSts4};
use mcemu_nmc::table::{self, Function};

use super::axis::motion_io;
use super::crd::{centri_command, corner_commands, crd, group, non_negative, state, update};
use super::crd_segment::{marker, Push};
use super::crd_status::{free, path_scale, used, user_seg, word};
use super::io::group_value;
use super::sync_args::axis_number;
use crate::nmc::service::{pulses, Call, Handler, Refusal};

pub const HANDLERS: &[(Function, Handler)] = &[
    (table::CRD_SET_LOOKAHEAD_PARA, crd_set_lookahead_para),
    (table::CRD_GET_LOOKAHEAD_PARA, crd_get_lookahead_para),
    (table::CRD_GET_STS_PACK4, crd_get_sts_pack4),
    (table::CRD_BUF_WAIT_POS, crd_buf_wait_pos),
    (table::CRD_SET_BUF_LENGTH_FLAG, crd_set_buf_length_flag),
    (table::CRD_GET_BUF_LENGTH, crd_get_buf_length),
];

fn flag(name: &str, v: i16) -> Result<(), Refusal> {
    if (0..=1).contains(&v) {
        Ok(())
    } else {
        Err(Refusal::range(name, v, "{0, 1}"))
    }
}

/// Every field in its documented range (digest 001 §3.9); the doubles finite and ≥ 0.
fn check(p: &LookaheadPara) -> Result<(), Refusal> {
    if p.look_ahead_switch < 0 {
        return Err(Refusal::range(
            "lookAheadSwitch",
            p.look_ahead_switch,
            "[0, n]",
        ));
    }
    flag("centAccEn", p.cent_acc_en)?;
    flag("crossEn", p.cross_en)?;
    flag("preHandleEn", p.pre_handle_en)?;
    if p.event_time < 0 {
        return Err(Refusal::range("eventTime", p.event_time, "[0, 32767] ms"));
    }
    if !(0..=2).contains(&p.ax_prop_time_unit_prop) {
        return Err(Refusal::range(
            "axPropTimeUnitProp",
            p.ax_prop_time_unit_prop,
            "{0, 1 (s), 2 (ms)}",
        ));
    }
    let scalars = [
        ("accMax", p.acc_max),
        ("T", p.t),
        ("slowAng", p.slow_ang),
        ("stopAng", p.stop_ang),
        ("crossProp", p.cross_prop),
        ("centAcc", p.cent_acc),
        ("radiusCoef", p.radius_coef),
        ("radiusErr", p.radius_err),
        ("radiusAng", p.radius_ang),
        ("radiusAngMax", p.radius_ang_max),
        ("radiusAngMin", p.radius_ang_min),
        ("preHandleDisAngMin", p.pre_handle_dis_ang_min),
        ("preHandleDisAngMax", p.pre_handle_dis_ang_max),
        ("preHandleTol", p.pre_handle_tol),
        ("minCornerVel", p.min_corner_vel),
    ];
    for (name, v) in scalars {
        non_negative(name, v, "")?;
    }
    for (name, a) in [
        ("dvMax", p.dv_max),
        ("daMax", p.da_max),
        ("axProp", p.ax_prop),
    ] {
        for (k, v) in a.iter().enumerate() {
            non_negative(&format!("{name}[{k}]"), *v, "")?;
        }
    }
    if p.stop_ang > 180.0 || p.slow_ang > p.stop_ang {
        return Err(Refusal::range(
            "slowAng/stopAng",
            format!("{}°/{}°", p.slow_ang, p.stop_ang),
            "0 ≤ slowAng ≤ stopAng ≤ 180°",
        ));
    }
    Ok(())
}

/// lookAheadSwitch, T and eventTime are `TExtCrdPara`'s (one setting, either call writes it);
/// centAccEn/centAcc are `NMC_CrdSetLookAheadCentriAcc`'s; accMax, slowAng and stopAng go to the
/// engine's corner rules; the rest is stored and read back (decisions.md).
fn crd_set_lookahead_para(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    let p = LookaheadPara::read(&mut c.input)?;
    check(&p)?;
    let mut s = state(c, n);
    s.lookahead = Some(p);
    s.ext.look_ahead_switch = p.look_ahead_switch;
    s.ext.t = p.t;
    s.ext.event_time = p.event_time;
    s.centri_acc = if p.cent_acc_en == 1 { p.cent_acc } else { 0.0 };
    if group(c, n).is_some() {
        let centri = centri_command(c, n, &s);
        c.command(centri);
        for command in corner_commands(c, n, &s) {
            c.command(command);
        }
    }
    update(c, n, |now| *now = s);
    Ok(())
}

/// defaultFlag 1: the manual's defaults; 0: the current values (the shared settings as the
/// other calls last wrote them).
fn crd_get_lookahead_para(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    let default_flag = c.input.i16()?;
    flag("defaultFlag", default_flag)?;
    let p = if default_flag == 1 {
        LookaheadPara::default()
    } else {
        let s = state(c, n);
        LookaheadPara {
            look_ahead_switch: s.ext.look_ahead_switch,
            t: s.ext.t,
            event_time: s.ext.event_time,
            cent_acc_en: i16::from(s.centri_acc > 0.0),
            cent_acc: s.centri_acc,
            ..s.lookahead.unwrap_or_default()
        }
    };
    p.write(c.output);
    Ok(())
}

/// The §3.4 pack: the status word, the members' status words, positions (planned in user and
/// machine coordinates, encoder) and motion I/O, the segment, the path velocity, DI/DO group 0
/// and the buffer counts.
fn crd_get_sts_pack4(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    let s = state(c, n);
    let origin = s.origin();
    let mut p = PackedCrdSts4 {
        crd_sts: (word(c, n) & 0x3F) as i16,
        user_seg: user_seg(c, n),
        prf_vel: group(c, n).map_or(0.0, |g| {
            velocity_from_engine(path_scale(c, &s), g.path_velocity)
        }),
        gp_di: group_value(&c.snapshot.io.di, 0),
        gp_do: group_value(&c.snapshot.io.do_, 0),
        crd_free_space: free(c, n, &s) as i64,
        crd_used_space: used(c, n, &s) as i64,
        ..PackedCrdSts4::default()
    };
    for (k, axis) in s.axes().into_iter().enumerate().take(CRD_MAX_AXES) {
        let Some(st) = c.status(axis) else { continue };
        let planned = pulses(c.scale(axis), st.cmd_pos);
        p.ax_sts[k] = axis_status(st, AxisExtra::default()) as i16;
        p.prf_pos[k] = planned.saturating_sub(origin[k]);
        p.axis_pos[k] = planned;
        p.enc_pos[k] = c.service.ax().enc_pos(axis, st);
        p.mot_di[k] = motion_io(st) as i16;
    }
    p.write(c.output);
    Ok(())
}

/// Stand until axis `axisNo` (any axis of the device, machine position in pulses) is ≤ pos
/// (condition 0) or ≥ pos (1), by its encoder (posSrc 0) or planned (1) position; overTime ms
/// (0: no limit; past it MVERR).
fn crd_buf_wait_pos(c: &mut Call<'_>) -> Result<(), Refusal> {
    let p = Push::begin(c)?;
    let _seg_no = c.input.i64()?;
    let (axis, condition, pos) = (c.input.i16()?, c.input.i16()?, c.input.i64()?);
    let (source, time) = (c.input.i16()?, c.input.i64()?);
    let axis = axis_number(c, "axisNo", i64::from(axis))?;
    let condition = match condition {
        0 => PositionCondition::AtMost,
        1 => PositionCondition::AtLeast,
        v => return Err(Refusal::range("condition", v, "{0 (≤), 1 (≥)}")),
    };
    let source = match source {
        0 => PositionSource::Actual,
        1 => PositionSource::Commanded,
        v => return Err(Refusal::range("posSrc", v, "{0 (encoder), 1 (planned)}")),
    };
    if time < 0 {
        return Err(Refusal::range("overTime", time, "[0, ∞) ms"));
    }
    let command = GroupWaitPosition {
        group: p.group(),
        axis: axis as u16,
        position: c.scale(axis).to_engine(pos as f64),
        tolerance: None,
        timeout: (time > 0).then_some(time as f64 / 1e3),
        condition,
        source: Some(source),
    };
    marker(c, p, vec![command.into()])
}

/// flag 1: from now on the path length of every pushed segment is summed (until
/// `NMC_CrdBufClr`); 0: not (the default; decisions.md).
fn crd_set_buf_length_flag(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    let f = c.input.i16()?;
    flag("flag", f)?;
    update(c, n, |s| s.length_flag = f == 1);
    Ok(())
}

/// The path length pushed since `NMC_CrdBufClr` while the flag was 1, pulses (the path
/// crate's geometry, as the planner runs it).
fn crd_get_buf_length(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    c.output.f64(state(c, n).pushed_length);
    Ok(())
}
