//! Interference protection between the two coordinate systems (`NMC_SetMvProtect`,
//! `TmvProtectPara`; digest 001 §2.7, §3.7, §4.4): the engine's move protection 0
//! (`group/protection.rs`). The parameters are stored by `NMC_SetMvProtectMode01Para` and go
//! to the engine with the mode when `NMC_SetMvProtect` enables it (again when they change
//! while enabled).

use axes::command::{
    ErrorKind, GroupId, MoveProtectionDisable, MoveProtectionEnable, ProtectionMode,
};
use axes::status::InterferenceStatus;
use mcemu_dialects::nmc::{acceleration_to_engine, code_for_kind, velocity_to_engine};
use mcemu_nmc::crd_frames::MvProtectPara;
use mcemu_nmc::table::{self, Function};

use super::crd::{group, members, state};
use crate::nmc::crd::CRD_COUNT;
use crate::nmc::service::{Call, Handler, Refusal};

pub const HANDLERS: &[(Function, Handler)] = &[
    (table::SET_MV_PROTECT, set_mv_protect),
    (table::DEL_MV_PROTECT, del_mv_protect),
    (
        table::SET_MV_PROTECT_MODE01_PARA,
        set_mv_protect_mode01_para,
    ),
    (
        table::GET_MV_PROTECT_MODE01_PARA,
        get_mv_protect_mode01_para,
    ),
    (table::GET_MV_PROTECT_STS, get_mv_protect_sts),
];

/// The engine's number of NMC's one protection.
const PROTECTION: u16 = 0;

/// "目前只有两个坐标系, 所以该值为0": groupNo is 0.
fn group_no(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let g = c.input.i16()?;
    if g == 0 {
        Ok(())
    } else {
        Err(Refusal::range(
            "groupNo",
            g,
            "{0} (one pair of coordinate systems)",
        ))
    }
}

/// Two different coordinate systems, X/Y/Z of each, directions ±1, distances and the retreat's
/// velocity and acceleration ≥ 0 (0: the group's own). stopCrdNo is checked when mode 1 is on.
fn check(p: &MvProtectPara) -> Result<(), Refusal> {
    let crds = CRD_COUNT as i16;
    for (k, v) in p.crd_no.iter().enumerate() {
        if !(0..crds).contains(v) {
            return Err(Refusal::range(&format!("crdNo[{k}]"), v, "[0, 1]"));
        }
    }
    if p.crd_no[0] == p.crd_no[1] {
        return Err(Refusal::range(
            "crdNo[1]",
            p.crd_no[1],
            "the other coordinate system than crdNo[0]",
        ));
    }
    for (k, v) in p.crd_ax_no.iter().enumerate() {
        if !(0..=2).contains(v) {
            return Err(Refusal::range(
                &format!("crdAxNo[{k}]"),
                v,
                "{0 (X), 1 (Y), 2 (Z)}",
            ));
        }
    }
    for (k, v) in p.move_dir.iter().enumerate() {
        if !matches!(v, 1 | -1) {
            return Err(Refusal::range(&format!("moveDir[{k}]"), v, "{1, -1}"));
        }
    }
    if p.mv_protect_dis < 0 {
        return Err(Refusal::range(
            "mvProtectDis",
            p.mv_protect_dis,
            "[0, ∞) pulses",
        ));
    }
    for (name, v) in [
        ("mvToSafeAcc", p.mv_to_safe_acc),
        ("mvToSafeVel", p.mv_to_safe_vel),
    ] {
        if !(v.is_finite() && v >= 0.0) {
            return Err(Refusal::range(
                name,
                v,
                "[0, ∞) (0: the coordinate system's own)",
            ));
        }
    }
    Ok(())
}

/// The engine command enabling `p` in `mode`.
fn enable_command(
    c: &Call<'_>,
    p: &MvProtectPara,
    mode: i16,
) -> Result<MoveProtectionEnable, Refusal> {
    check(p)?;
    let mut axes = [0usize; 2];
    let mut scales = Vec::with_capacity(2);
    for (k, slot) in axes.iter_mut().enumerate() {
        let n = usize::try_from(p.crd_no[k]).unwrap_or(0);
        let members = members(&state(c, n))?;
        if group(c, n).is_none() {
            return Err(Refusal::new(
                code_for_kind(ErrorKind::InvalidGroup),
                format!("coordinate system {n} has no group: NMC_CrdConfig first"),
            ));
        }
        let coordinate = usize::try_from(p.crd_ax_no[k]).unwrap_or(0);
        let axis = members.get(coordinate).copied().ok_or_else(|| {
            Refusal::range(
                &format!("crdAxNo[{k}]"),
                coordinate,
                &format!("the {} coordinates of coordinate system {n}", members.len()),
            )
        })?;
        *slot = coordinate;
        scales.push(c.scale(axis));
    }
    let scale = scales
        .first()
        .copied()
        .unwrap_or(mcemu_dialects::PulseScale {
            pulses_per_unit: 1.0,
        });
    let (mode, stop_group, safe, stop_scale) = match mode {
        0 => (ProtectionMode::BothStop, None, None, scale),
        1 => {
            let k = p
                .crd_no
                .iter()
                .position(|n| *n == p.stop_crd_no)
                .ok_or_else(|| {
                    Refusal::range(
                        "stopCrdNo",
                        p.stop_crd_no,
                        &format!("one of crdNo {:?} (mode 1)", p.crd_no),
                    )
                })?;
            let stop_scale = scales.get(k).copied().unwrap_or(scale);
            (
                ProtectionMode::Retreat,
                Some(p.stop_crd_no as GroupId),
                Some(stop_scale.to_engine(p.safe_wait_pos as f64)),
                stop_scale,
            )
        }
        m => {
            return Err(Refusal::range(
                "mode",
                m,
                "{0 (both stop), 1 (laser: one retreats)}",
            ))
        }
    };
    Ok(MoveProtectionEnable {
        protection: PROTECTION,
        groups: [p.crd_no[0] as GroupId, p.crd_no[1] as GroupId],
        axes,
        move_direction: [p.move_dir[0] as i8, p.move_dir[1] as i8],
        origin_distance: scale.to_engine(p.org_dis as f64),
        protection_distance: scale.to_engine(p.mv_protect_dis as f64),
        mode,
        stop_group,
        safe_wait_position: safe,
        retreat_velocity: (p.mv_to_safe_vel > 0.0)
            .then(|| velocity_to_engine(stop_scale, p.mv_to_safe_vel)),
        retreat_acceleration: (p.mv_to_safe_acc > 0.0)
            .then(|| acceleration_to_engine(stop_scale, p.mv_to_safe_acc)),
    })
}

/// mode 0: both coordinate systems stop when they would come closer than mvProtectDis; 1
/// ("laser"): stopCrdNo stops and its axis goes to safeWaitPos, the other waits.
fn set_mv_protect(c: &mut Call<'_>) -> Result<(), Refusal> {
    group_no(c)?;
    let mode = c.input.i16()?;
    if !(0..=1).contains(&mode) {
        return Err(Refusal::range(
            "mode",
            mode,
            "{0 (both stop), 1 (laser: one retreats)}",
        ));
    }
    let p = c.service.frames().protect.para;
    if p.crd_no[0] == p.crd_no[1] {
        return Err(Refusal::new(
            code_for_kind(ErrorKind::InvalidState),
            "no protection parameters: NMC_SetMvProtectMode01Para first",
        ));
    }
    let command = enable_command(c, &p, mode)?;
    c.command(command);
    c.service.frames().protect.mode = Some(mode);
    Ok(())
}

fn del_mv_protect(c: &mut Call<'_>) -> Result<(), Refusal> {
    group_no(c)?;
    if c.service.frames().protect.mode.take().is_some() {
        c.command(MoveProtectionDisable {
            protection: PROTECTION,
        });
    }
    Ok(())
}

/// Stored; while the protection is on it is enabled again with them.
fn set_mv_protect_mode01_para(c: &mut Call<'_>) -> Result<(), Refusal> {
    group_no(c)?;
    let p = MvProtectPara::read(&mut c.input)?;
    check(&p)?;
    let mode = c.service.frames().protect.mode;
    if let Some(mode) = mode {
        let command = enable_command(c, &p, mode)?;
        c.command(command);
    }
    c.service.frames().protect.para = p;
    Ok(())
}

fn get_mv_protect_mode01_para(c: &mut Call<'_>) -> Result<(), Refusal> {
    group_no(c)?;
    let p = c.service.frames().protect.para;
    p.write(c.output);
    Ok(())
}

/// 0 not enabled, 1 no interference, 2 interference (the engine's status of crdNo[0]).
fn get_mv_protect_sts(c: &mut Call<'_>) -> Result<(), Refusal> {
    group_no(c)?;
    let protect = c.service.frames().protect;
    let sts = match protect.mode {
        None => 0,
        Some(_) => {
            let n = usize::try_from(protect.para.crd_no[0]).unwrap_or(0);
            match group(c, n).map(|g| g.interference) {
                Some(InterferenceStatus::Interference) => 2,
                _ => 1,
            }
        }
    };
    c.output.i16(sts);
    Ok(())
}
