//! One test per vendor table row, plus end-to-end runs of the manuals' test vectors against the
//! kinematic test double.

use super::*;
use crate::command::Direction;
use crate::homing::sim::{run, Layout, Run, DT};
use crate::homing::{HomingHardware, HomingInput};

const ALL: HomingHardware = HomingHardware::ALL;
const EPS: f64 = 1e-9;

fn ok(spec: Result<HomingSpec, HomingError>) -> HomingSpec {
    spec.unwrap_or_else(|e| panic!("{e}"))
}

fn status_of(r: &Run) -> HomingStatus {
    match &r.result {
        Some(Ok(())) => HomingStatus::Succeeded,
        Some(Err(e)) => HomingStatus::Failed(e.clone()),
        None => HomingStatus::Idle,
    }
}

// ---- HMC ----

#[test]
fn homing_vendor_hmc_rows() {
    // (mode, method) per digest 000 §5.
    let rows = [(0, 19), (1, 21), (2, 34), (3, 33), (4, 3), (5, 5)];
    for (mode, method) in rows {
        for (instruction, latch) in [
            (HmcInstruction::Home, Latch::Polled),
            (HmcInstruction::HomeEx, Latch::Exact),
        ] {
            let s = ok(hmc(instruction, mode, 1000.0, 100.0, 2000.0));
            assert_eq!(s.method, method, "mode {mode}");
            assert_eq!((s.switch_velocity, s.zero_velocity), (1000.0, 100.0));
            assert_eq!((s.acceleration, s.offset, s.timeout), (2000.0, 0.0, 0.0));
            assert_eq!(s.quirks.after_home, AfterHome::ReturnToHome);
            assert_eq!(
                (s.quirks.switch_latch, s.quirks.index_latch),
                (latch, latch)
            );
        }
    }
    for mode in [6, 7, 255] {
        assert_eq!(
            hmc(HmcInstruction::Home, mode, 1000.0, 100.0, 2000.0),
            Err(HomingError::UnsupportedMethod {
                method: i16::from(mode)
            })
        );
    }
    // CreepSpeed 0 (allowed as a parameter value) cannot home.
    let s = ok(hmc(HmcInstruction::Home, 0, 1000.0, 0.0, 2000.0));
    assert!(matches!(
        crate::homing::Homing::start(&s, ALL, &crate::homing::HomingInputs::default()),
        Err(HomingError::BadParameter { .. })
    ));
}

/// HomeState values over a run, without repeats, ending with the idle 0.
fn home_states(mode: u8, r: &Run) -> Vec<u8> {
    let mut states: Vec<u8> = Vec::new();
    for p in &r.phases {
        let s = hmc_home_state(mode, &HomingStatus::Running(*p));
        if states.last() != Some(&s) {
            states.push(s);
        }
    }
    states.push(hmc_home_state(mode, &status_of(r)));
    states
}

#[test]
fn homing_vendor_hmc_runs_return_to_the_origin() {
    let (speed, creep) = (20.0, 5.0);
    // (mode, layout, start, origin, HomeState sequence)
    let cases: [(u8, Layout, f64, f64, &[u8]); 8] = [
        (0, Layout::positive_switch(), 0.0, 10.0, &[1, 2, 3, 4, 0]),
        // DI = 1 at the start: straight to phase 3.
        (0, Layout::positive_switch(), 20.0, 10.0, &[3, 4, 0]),
        (1, Layout::negative_switch(), 50.0, 30.0, &[1, 2, 3, 4, 0]),
        (2, Layout::cam(), 0.0, 1.0, &[1, 2, 0]),
        (3, Layout::cam(), 0.0, -3.0, &[1, 2, 0]),
        (4, Layout::positive_switch(), 0.0, 9.0, &[1, 2, 3, 4, 0]),
        (5, Layout::negative_switch(), 50.0, 33.0, &[1, 2, 3, 4, 0]),
        (5, Layout::negative_switch(), 20.0, 33.0, &[3, 4, 0]),
    ];
    for (mode, layout, start, origin, states) in cases {
        for instruction in [HmcInstruction::Home, HmcInstruction::HomeEx] {
            let s = ok(hmc(instruction, mode, speed, creep, 2000.0));
            let r = run(&s, ALL, layout, start);
            assert_eq!(r.result, Some(Ok(())), "mode {mode}");
            let found = r.home.unwrap_or(f64::NAN);
            match instruction {
                HmcInstruction::HomeEx => assert_eq!(found, origin, "mode {mode}"),
                // Polled once per servo period at the creep speed.
                HmcInstruction::Home => {
                    assert!(
                        (found - origin).abs() <= creep * DT + EPS,
                        "mode {mode}: {found}"
                    )
                }
            }
            // The axis ends on the origin, reading 0.
            assert!(
                r.final_reading.abs() < EPS,
                "mode {mode}: {}",
                r.final_reading
            );
            assert!((r.final_x - found).abs() < EPS);
            assert_eq!(home_states(mode, &r), states, "mode {mode}");
        }
    }
    assert_eq!(hmc_home_state(0, &HomingStatus::Idle), 0);
}

// ---- NMC ----

fn nmc_setting(mode: i16, dir: i16) -> NmcHomeSetting {
    NmcHomeSetting {
        mode,
        dir,
        scan1st_vel: 20.0,
        scan2nd_vel: 5.0,
        acc: 2000.0,
        ..NmcHomeSetting::default()
    }
}

#[test]
fn homing_vendor_nmc_rows() {
    // (mode, dir, method, zero velocity without a second scan)
    let rows = [
        (1, 1, 24, 20.0),
        (1, 0, 28, 20.0),
        (2, 1, 18, 20.0),
        (2, 0, 17, 20.0),
        (3, 1, 34, 20.0),
        (3, 0, 33, 20.0),
        (4, 1, 8, 5.0),
        (4, 0, 12, 5.0),
        (5, 1, 7, 5.0),
        (5, 0, 11, 5.0),
        (6, 1, 2, 5.0),
        (6, 0, 1, 5.0),
    ];
    for (mode, dir, method, zero) in rows {
        let s = ok(nmc(&nmc_setting(mode, dir)));
        assert_eq!(s.method, method, "mode {mode} dir {dir}");
        assert_eq!((s.switch_velocity, s.zero_velocity), (20.0, zero));
        assert_eq!(s.quirks.switch_latch, Latch::Exact);
        assert_eq!(s.quirks.after_home, AfterHome::Decelerate);
        assert_eq!(s.quirks.rescan, None);
        // The second scan runs at scan2ndVel.
        let s = ok(nmc(&NmcHomeSetting {
            rescan_en: true,
            ret_sw_offset: 3.0,
            ..nmc_setting(mode, dir)
        }));
        assert_eq!((s.zero_velocity, s.quirks.rescan), (5.0, Some(3.0)));
    }
    // Search distance, initial back-off, offset sign.
    let s = ok(nmc(&NmcHomeSetting {
        safe_len: 1000.0,
        ini_ret_pos: 50.0,
        offset: 100.0,
        ..nmc_setting(1, 1)
    }));
    assert_eq!(s.quirks.max_search_distance, 1000.0);
    assert_eq!(s.quirks.initial_backoff, 50.0);
    assert_eq!(s.offset, -100.0);
    // 1000 + method: the drive's CiA 402 homing (TV36: 1021 = EcatStartHome method 21).
    let s = ok(nmc(&NmcHomeSetting {
        offset: 100.0,
        ..nmc_setting(1021, 7)
    }));
    assert_eq!(s.method, 21);
    assert_eq!(
        (s.switch_velocity, s.zero_velocity, s.offset),
        (20.0, 5.0, 100.0)
    );
    assert_eq!(s.quirks, HomingQuirks::default());
}

#[test]
fn homing_vendor_nmc_parameter_errors() {
    let refused = |s: NmcHomeSetting| match nmc(&s) {
        Ok(spec) => panic!("accepted {spec:?}"),
        Err(e) => e,
    };
    // TV30: scan1stVel = 0 → bit 3, no motion.
    let e = refused(NmcHomeSetting {
        scan1st_vel: 0.0,
        ..nmc_setting(1, 1)
    });
    assert!(matches!(&e, HomingError::BadParameter { name, .. } if name == "scan1stVel"));
    assert_eq!(
        nmc_home_status(&HomingStatus::Failed(e)),
        NMC_HOME_FAIL | NMC_HOME_ERR_MV
    );
    let e = refused(NmcHomeSetting {
        scan2nd_vel: 0.0,
        ..nmc_setting(4, 1)
    });
    assert!(matches!(&e, HomingError::BadParameter { name, .. } if name == "scan2ndVel"));
    assert!(matches!(
        refused(nmc_setting(1, 2)),
        HomingError::BadParameter { .. }
    ));
    for mode in [0, 7, 999, 1000] {
        assert_eq!(
            refused(nmc_setting(mode, 1)),
            HomingError::UnsupportedMethod { method: mode }
        );
    }
}

#[test]
fn homing_vendor_nmc_status_words() {
    use HomingPhase::*;
    let not_found = HomingError::NotFound {
        input: HomingInput::HomeSwitch,
        distance: 1.0,
    };
    let rows: [(HomingStatus, u16, u8); 10] = [
        (HomingStatus::Idle, 0, 0b001),
        (HomingStatus::Running(Search), 0x01, 0b000),
        (HomingStatus::Running(Index), 0x01, 0b000),
        (HomingStatus::Running(Stopping), 0x01, 0b010),
        (HomingStatus::Running(Aborting), 0x01, 0b100),
        (HomingStatus::Succeeded, 0x02, 0b011),
        (HomingStatus::Failed(not_found), 0x14, 0b101),
        (
            HomingStatus::Failed(HomingError::LimitHit {
                direction: Direction::Positive,
            }),
            0x14,
            0b101,
        ),
        (
            HomingStatus::Failed(HomingError::Timeout { seconds: 1.0 }),
            0x04,
            0b101,
        ),
        (HomingStatus::Failed(HomingError::Aborted), 0x04, 0b001),
    ];
    for (status, word, ecat) in rows {
        assert_eq!(nmc_home_status(&status), word, "{status:?}");
        assert_eq!(nmc_ecat_home_status(&status), ecat, "{status:?}");
    }
}

#[test]
fn homing_vendor_nmc_runs() {
    // TV29: HM_MODE1, negative search, switch at −3000 becomes position 0 (offset 0).
    let far = Layout {
        limit_neg: Some(-5000.0),
        limit_pos: Some(5000.0),
        home: Some((-3100.0, -3000.0)),
        index_pitch: 0.0,
        index_phase: 0.0,
    };
    let fast = NmcHomeSetting {
        scan1st_vel: 400.0,
        acc: 40_000.0,
        ..nmc_setting(1, 0)
    };
    let r = run(&ok(nmc(&fast)), ALL, far, 0.0);
    assert_eq!(r.result, Some(Ok(())));
    assert_eq!(r.home, Some(-3000.0));
    assert!(r.final_reading <= 0.0 && r.final_reading > -3.0);
    assert_eq!(nmc_home_status(&status_of(&r)), NMC_HOME_OK);
    // TV31: safeLen 1000 and no switch within it → bits 2 and 4, stopped.
    let r = run(
        &ok(nmc(&NmcHomeSetting {
            safe_len: 1000.0,
            ..fast
        })),
        ALL,
        far,
        0.0,
    );
    assert_eq!(
        r.result,
        Some(Err(HomingError::NotFound {
            input: HomingInput::HomeSwitch,
            distance: 1000.0
        }))
    );
    assert_eq!(r.final_v, 0.0);
    assert_eq!(
        nmc_home_status(&status_of(&r)),
        NMC_HOME_FAIL | NMC_HOME_ERR_SWT
    );
    // Second scan: find the switch, back off retSwOffset, approach again at scan2ndVel.
    let s = ok(nmc(&NmcHomeSetting {
        rescan_en: true,
        ret_sw_offset: 2.0,
        ..nmc_setting(1, 1)
    }));
    let r = run(&s, ALL, Layout::cam(), 0.0);
    assert_eq!(r.result, Some(Ok(())));
    assert_eq!((r.home, r.dirs.clone()), (Some(10.0), vec![1, -1, 1]));
    assert!((r.detect_speed.unwrap_or(f64::NAN) - 5.0).abs() < EPS);
    // MODE4 forward / MODE5 reverse from the home switch to the index; MODE6 from the limit.
    for (mode, dir, home) in [
        (4, 1, 13.0),
        (5, 1, 9.0),
        (4, 0, 29.0),
        (5, 0, 33.0),
        (6, 0, -99.0),
    ] {
        let r = run(&ok(nmc(&nmc_setting(mode, dir))), ALL, Layout::cam(), 0.0);
        assert_eq!(r.home, Some(home), "mode {mode} dir {dir}");
    }
    // The offset moves the zero `offset` past the found point.
    let s = ok(nmc(&NmcHomeSetting {
        offset: 100.0,
        ..nmc_setting(3, 1)
    }));
    let r = run(&s, ALL, Layout::cam(), 0.0);
    assert!((r.final_reading - (r.final_x - 1.0) + 100.0).abs() < EPS);
}

// ---- HIMC ----

#[test]
fn homing_vendor_himc_rows() {
    let supported: Vec<i16> = (-5..=40).filter(|m| himc_method_supported(*m)).collect();
    assert_eq!(
        supported,
        vec![1, 2, 7, 8, 9, 10, 11, 12, 13, 14, 17, 18, 23, 24, 25, 26, 27, 28, 29, 30, 33, 34, 37]
    );
    for method in supported {
        let s = ok(himc(&HimcHomeSettings {
            method,
            ..HimcHomeSettings::default()
        }));
        assert_eq!(s.method, method);
        assert_eq!(s.quirks, HomingQuirks::default());
    }
    // TV75: refused as SetHomeMethod refuses them.
    for method in [0, 3, 4, 5, 6, 15, 16, 19, 20, 21, 22, 31, 32, 35, 36, 38] {
        assert_eq!(
            himc(&HimcHomeSettings {
                method,
                ..HimcHomeSettings::default()
            }),
            Err(HomingError::UnsupportedMethod { method })
        );
    }
    // Defaults: HOME_METHOD_33, 20, 5, 2000, 0, 120 s.
    let s = ok(himc(&HimcHomeSettings::default()));
    assert_eq!(
        (
            s.method,
            s.switch_velocity,
            s.zero_velocity,
            s.acceleration,
            s.offset,
            s.timeout
        ),
        (33, 20.0, 5.0, 2000.0, 0.0, 120.0)
    );
    let s: HimcHomeSettings = serde_json::from_str("{}").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(s, HimcHomeSettings::default());
}

#[test]
fn homing_vendor_himc_runs() {
    // TV76: method 37 at any position: feedback = home offset.
    let s = ok(himc(&HimcHomeSettings {
        method: 37,
        offset: 12.5,
        ..HimcHomeSettings::default()
    }));
    let r = run(&s, ALL, Layout::cam(), 61.0);
    assert_eq!((r.result.clone(), r.final_reading), (Some(Ok(())), 12.5));
    // TV77: method 33 without an index pulse, timeout 10 000 ms.
    let s = ok(himc(&HimcHomeSettings {
        timeout_ms: 10_000.0,
        ..HimcHomeSettings::default()
    }));
    let no_index = Layout {
        index_pitch: 0.0,
        ..Layout::cam()
    };
    let r = run(&s, ALL, no_index, 0.0);
    assert_eq!(r.result, Some(Err(HomingError::Timeout { seconds: 10.0 })));
    assert!(r.time >= 10.0 && r.time < 10.01);
    // "Fails if no negative limit is assigned."
    let s = ok(himc(&HimcHomeSettings {
        method: 1,
        ..HimcHomeSettings::default()
    }));
    let hw = HomingHardware {
        limit_neg: false,
        ..ALL
    };
    assert_eq!(
        run(&s, hw, Layout::cam(), 0.0).result,
        Some(Err(HomingError::MissingInput {
            method: 1,
            input: HomingInput::NegativeLimit
        }))
    );
}

// ---- CPU 226H ----

#[test]
fn homing_vendor_cpu226h_rows() {
    let methods = [5, 3, 21, 19, 33, 34, 7, 8, 9, 10, 11, 12, 13, 14];
    for (mode, method) in (1u8..).zip(methods) {
        let s = ok(cpu226h(mode, 2000.0, 500.0, 1e5, 4));
        assert_eq!(s.method, method, "mode {mode}");
        assert_eq!(
            (s.switch_velocity, s.zero_velocity, s.acceleration),
            (2000.0, 500.0, 1e5)
        );
        assert_eq!((s.offset, s.timeout), (0.0, 0.0));
        let q = s.quirks;
        assert_eq!(q.after_home, AfterHome::StopImmediately);
        assert_eq!(
            (q.switch_latch, q.index_latch),
            (Latch::Polled, Latch::Exact)
        );
        assert_eq!(q.switch_scan_ticks, 4);
    }
    // TV-25: mode 0 or 15 → STATUS.Bit0.
    for mode in [0, 15, 255] {
        let e = match cpu226h(mode, 2000.0, 500.0, 1e5, 1) {
            Ok(s) => panic!("accepted {s:?}"),
            Err(e) => e,
        };
        assert_eq!(
            cpu226h_status(&HomingStatus::Failed(e)),
            CPU226H_PARAMETER_ERROR
        );
    }
    // Speeds are clamped to what the pulse output can do, never refused.
    let s = ok(cpu226h(1, 0.0, 1e6, 1e5, 1));
    assert_eq!((s.switch_velocity, s.zero_velocity), (5.0, 200_000.0));
    assert_eq!(cpu226h_status(&HomingStatus::Idle), 0);
    assert_eq!(
        cpu226h_status(&HomingStatus::Running(HomingPhase::Search)),
        CPU226H_RUNNING
    );
    assert_eq!(
        cpu226h_status(&HomingStatus::Failed(HomingError::LimitHit {
            direction: Direction::Negative
        })),
        CPU226H_DONE
    );
}

#[test]
fn homing_vendor_cpu226h_runs() {
    let spec = |mode, scan| ok(cpu226h(mode, 20.0, 5.0, 2000.0, scan));
    // TV-26: mode 5, Z pulse on the negative side: origin there, immediate stop.
    let r = run(&spec(5, 1), ALL, Layout::cam(), 0.0);
    assert_eq!((r.home, r.dirs.clone()), (Some(-3.0), vec![-1]));
    assert_eq!(Some(r.final_x), r.detect_x);
    assert!(r.final_reading.abs() <= 5.0 * DT + EPS);
    assert_eq!(
        cpu226h_status(&status_of(&r)),
        CPU226H_DONE | CPU226H_ORIGIN_FOUND
    );
    // TV-27: mode 3 from the positive side of the switch: negative search, reverse out, origin
    // at the falling edge, immediate stop.
    let r = run(&spec(3, 1), ALL, Layout::negative_switch(), 50.0);
    assert_eq!(r.dirs, vec![-1, 1]);
    let late = r.home.unwrap_or(f64::NAN) - 30.0;
    assert!((0.0..=5.0 * DT + EPS).contains(&late), "{late}");
    assert_eq!(Some(r.final_x), r.detect_x);
    // TV-28: inside the switch, modes 9/10 start positive, 7/8 negative.
    for (mode, first) in [(7, -1), (8, -1), (9, 1), (10, 1)] {
        let r = run(&spec(mode, 1), ALL, Layout::cam(), 20.0);
        assert_eq!(r.dirs.first(), Some(&first), "mode {mode}");
        assert_eq!(r.result, Some(Ok(())));
    }
    // TV-29: mode 13 outside, switch on the positive side: negative to the limit, reverse.
    let r = run(&spec(13, 1), ALL, Layout::cam(), 0.0);
    assert_eq!((r.dirs.clone(), r.home), (vec![-1, 1], Some(13.0)));
    // TV-30: a scan of N ticks makes the switch origin late by up to N ticks of travel; the Z
    // is captured in hardware.
    const N: u32 = 10;
    let r = run(&spec(4, N), ALL, Layout::positive_switch(), 0.0);
    let late = 10.0 - r.home.unwrap_or(f64::NAN);
    assert!(
        (0.0..=f64::from(N) * 5.0 * DT + EPS).contains(&late),
        "{late}"
    );
    let r = run(&spec(2, N), ALL, Layout::positive_switch(), 0.0);
    assert_eq!(r.home, Some(9.0));
    // Modes 1–6 use no limit switch: reaching one is an error.
    let far = Layout {
        home: Some((150.0, f64::INFINITY)),
        ..Layout::cam()
    };
    assert_eq!(
        run(&spec(4, 1), ALL, far, 0.0).result,
        Some(Err(HomingError::LimitHit {
            direction: Direction::Positive
        }))
    );
}
