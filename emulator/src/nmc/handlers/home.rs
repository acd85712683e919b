//! Homing run by the controller (digest 001 §2.6, §3.13, §4.5): `THomeSetting` is the
//! device's, `NMC_MtHome` maps it onto a CiA 402 method with the vendor quirks
//! (`axes::homing::vendor::nmc`).

use axes::command::{BufferMode, Home, Stop, StopMode};
use axes::homing::vendor::{
    nmc, nmc_home_failure, NmcHomeSetting, NMC_HOME_ERR_MV, NMC_HOME_FAIL, NMC_HOME_OK,
    NMC_HOME_RUNNING, NMC_PASS_THROUGH,
};
use axes::{AxisFlags, AxisState};
use mcemu_dialects::nmc::{acceleration_to_engine, velocity_to_engine};
use mcemu_nmc::structs::HomeSetting;
use mcemu_nmc::table::{self, Function};

use super::ecat_drive::{bus_axis_of, stop_drive_homing, DriveHoming};
use crate::nmc::service::{pulses, Call, Handler, Refusal};

pub const HANDLERS: &[(Function, Handler)] = &[
    (table::MT_SET_HOME_PARA, mt_set_home_para),
    (table::MT_GET_HOME_PARA, mt_get_home_para),
    (table::MT_HOME, mt_home),
    (table::MT_TRY_HOME, mt_try_home),
    (table::MT_HOME_STOP, mt_home_stop),
    (table::MT_GET_HOME_STS, mt_get_home_sts),
    (table::MT_GET_HOME_ERROR, mt_get_home_error),
];

fn mt_set_home_para(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let h = HomeSetting::read(&mut c.input)?;
    c.update(axis, |s| s.home = h);
    Ok(())
}

fn mt_get_home_para(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    c.settings(axis).home.write(c.output);
    Ok(())
}

/// Bad parameters start nothing and show as home status bit 3 (TV30) as well as the code.
fn home(c: &mut Call<'_>, trial: bool) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let h = c.settings(axis).home;
    // `1000 + method` on a bus axis: the drive's own homing, as NMC_EcatStartHome (TV36).
    if let (Some(bus), false, true) = (bus_axis_of(c, axis), trial, h.mode > NMC_PASS_THROUGH) {
        let homing = DriveHoming::checked(
            i32::from(h.mode - NMC_PASS_THROUGH),
            h.scan1st_vel,
            h.scan2nd_vel,
            h.acc,
            h.offset,
        );
        c.update(axis, |s| s.home_param_error = homing.is_err());
        return homing?.start(c, bus);
    }
    let scale = c.scale(axis);
    let setting = NmcHomeSetting {
        mode: h.mode,
        dir: h.dir,
        offset: scale.to_engine(h.offset as f64),
        scan1st_vel: velocity_to_engine(scale, h.scan1st_vel),
        scan2nd_vel: velocity_to_engine(scale, h.scan2nd_vel),
        acc: acceleration_to_engine(scale, h.acc),
        rescan_en: h.re_scan_en != 0,
        home_edge: h.home_edge,
        lmt_edge: h.lmt_edge,
        z_edge: h.z_edge,
        ini_ret_pos: scale.to_engine(h.ini_ret_pos as f64),
        ret_sw_offset: scale.to_engine(h.ret_sw_offset as f64),
        safe_len: scale.to_engine(h.safe_len as f64),
    };
    let spec = match nmc(&setting) {
        Ok(spec) => spec,
        Err(e) => {
            c.update(axis, |s| s.home_param_error = true);
            return Err(Refusal::new(
                mcemu_nmc::errors::RTN_ARG_RANGE,
                format!("THomeSetting: {e}"),
            ));
        }
    };
    c.update(axis, |s| s.home_param_error = false);
    let mut quirks = spec.quirks;
    quirks.trial = trial;
    c.command(Home {
        axis: axis as u16,
        method: Some(spec.method),
        switch_velocity: Some(spec.switch_velocity),
        zero_velocity: Some(spec.zero_velocity),
        acceleration: Some(spec.acceleration),
        offset: Some(spec.offset),
        timeout: Some(spec.timeout),
        quirks,
        buffer_mode: BufferMode::Aborting,
    });
    Ok(())
}

fn mt_home(c: &mut Call<'_>) -> Result<(), Refusal> {
    home(c, false)
}

/// Finds home without redefining the position (digest 001 §2.6).
fn mt_try_home(c: &mut Call<'_>) -> Result<(), Refusal> {
    home(c, true)
}

fn mt_home_stop(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    if let Some(bus) = bus_axis_of(c, axis) {
        stop_drive_homing(c, bus);
    }
    c.command(Stop {
        axis: axis as u16,
        mode: StopMode::Smooth,
        deceleration: None,
    });
    Ok(())
}

/// bit0 homing, bit1 done, bit2 failed, bit3 bad parameters, bit4 no switch (digest 001
/// §3.13): a failure's bits from the engine's reason (`nmc_home_failure`), parameters the
/// front-end refused as bit 3.
fn mt_get_home_sts(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let param_error = c.settings(axis).home_param_error;
    // A drive homing requested and not yet seen by the drive (ecat_drive).
    let pending =
        bus_axis_of(c, axis).is_some_and(|b| c.service.bus().homing_pending(b.k, c.snapshot.tick));
    let word = match c.status(axis) {
        _ if param_error => NMC_HOME_FAIL | NMC_HOME_ERR_MV,
        _ if pending => NMC_HOME_RUNNING,
        Some(s) if s.state == AxisState::Homing => NMC_HOME_RUNNING,
        Some(s) if s.flags.contains(AxisFlags::HOMING_FAILED) => {
            s.homing_failure.map_or(NMC_HOME_FAIL, nmc_home_failure)
        }
        Some(s) if s.flags.contains(AxisFlags::HOMED) => NMC_HOME_OK,
        _ => 0,
    };
    c.output.u16(word);
    Ok(())
}

/// The home point the last `NMC_MtHome`/`MtTryHome` found minus the one the last completed
/// `NMC_MtHome` defined, in pulses (digest 001 §2.6, §4.5; TV32: ≈ 0 when nothing slipped).
fn mt_get_home_error(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let scale = c.scale(axis);
    let e = c.status(axis).map_or(0, |s| pulses(scale, s.home_error));
    c.output.i64(e);
    Ok(())
}
