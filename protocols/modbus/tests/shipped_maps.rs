//! The shipped maps at the service level, over the machines their fixtures describe: each
//! compiles, and the behaviour its header documents happens in the engine.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::{AxisFlags, ParamId};
use common::map_unit::{
    abcd_to_f64, cdab_to_f64, f64_to_cdab, register_bytes, shipped_map, start_engine, MapUnit,
};
use mcemu_modbus::map::{Binding, MachineShape};
use mcemu_modbus::pdu::{Exception, Response};

/// The CPU 226H fixture's E10 on Modbus (fixtures/cpu226h.toml, axis 4), alone.
const E10: &str = r#"
[[axes]]
[axes.params]
axis_type = "bus_position"
units = 1
rep_mode = "cyclic_symmetric"
rep_dist = 2147483648
speed = 500000
accel_time = 0.1
decel_time = 0.2
fast_decel = 50000000
fe_limit = 30000
[axes.encoder]
counts_per_rev = 10000
[axes.plant]
model = "lag"
time_constant = 0.005
"#;

/// The shipped map `map` over the first `axes` axes of `machine_toml`, as unit 2.
fn unit(machine_toml: &str, map: &str, axes: usize) -> MapUnit {
    let shape = MachineShape {
        axes,
        ..MachineShape::default()
    };
    let binding = Binding {
        axes: (0..axes).collect(),
    };
    let map = shipped_map(map, &shape, &binding);
    MapUnit::new(start_engine(machine_toml), map, Some(2))
}

#[tokio::test]
async fn the_e10_answers_the_cpu_226h_networks() {
    let e10 = unit(E10, "ct-e10-servo", 1);
    // Network 6 on a drive at rest, disabled, at 0: 30 zero registers (digest 003 TV-06).
    let r = e10.pdu(&[0x03, 0x00, 0xC8, 0x00, 0x1E]).await;
    assert_eq!(
        r,
        Response::Registers {
            function: 3,
            words: vec![0; 30]
        }
    );
    // Network 3: P281 = 0, P282 = 1 → the servo is enabled (TV-01, TV-02).
    let r = e10
        .pdu(&[0x10, 0x01, 0x19, 0x00, 0x02, 0x04, 0x00, 0x00, 0x00, 0x01])
        .await;
    assert_eq!(
        r,
        Response::WriteMultiple {
            function: 0x10,
            address: 0x0119,
            quantity: 2
        }
    );
    assert!(e10.handle.snapshot().axes[0]
        .flags
        .contains(AxisFlags::ENABLED));
    // Network 4: P324 = 100, echoed (TV-03).
    let r = e10.pdu(&[0x06, 0x01, 0x44, 0x00, 0x64]).await;
    assert_eq!(
        r,
        Response::WriteSingle {
            function: 6,
            address: 0x0144,
            value: 100
        }
    );
    // Network 5 as corrected: P113 = 100 ms, P114 = 200 ms (TV-04) …
    let r = e10
        .pdu(&[0x10, 0x00, 0x71, 0x00, 0x02, 0x04, 0x00, 0x64, 0x00, 0xC8])
        .await;
    assert!(matches!(r, Response::WriteMultiple { quantity: 2, .. }));
    let params = &e10.handle.snapshot().params[0];
    assert_eq!(params.get(ParamId::AccelTime), 0.1);
    assert_eq!(params.get(ParamId::DecelTime), 0.2);
    // … and as printed (quantity 4, byte count 0): exception 03 (TV-05).
    let r = e10
        .pdu(&[0x10, 0x00, 0x71, 0x00, 0x04, 0x00, 0x00, 0x64, 0x00, 0xC8])
        .await;
    assert_eq!(r, Response::exception(0x10, Exception::IllegalDataValue));
    // R204 bit 0: servo ready after the enable (TV-08's readiness bit).
    let r = e10.pdu(&[0x03, 0x00, 0xCC, 0x00, 0x01]).await;
    assert!(
        matches!(r, Response::Registers { ref words, .. } if words[0] & 1 == 1),
        "{r:?}"
    );
}

#[tokio::test]
async fn the_e10_runs_at_an_internal_speed_and_positions_to_p290() {
    let e10 = unit(E10, "ct-e10-servo", 1);
    // P97 (3rd internal speed) = 600 rpm = 100 000 counts/s; enable; P281 = 3.
    e10.pdu(&[0x06, 0x00, 0x61, 0x02, 0x58]).await;
    e10.pdu(&[0x06, 0x01, 0x1A, 0x00, 0x01]).await;
    e10.pdu(&[0x06, 0x01, 0x19, 0x00, 0x03]).await;
    e10.handle.advance(500).unwrap();
    let s = e10.handle.snapshot();
    assert!(
        (s.axes[0].cmd_vel - 100_000.0).abs() < 1e-6,
        "{}",
        s.axes[0].cmd_vel
    );
    // R221 feedback speed in rpm.
    let r = e10.pdu(&[0x03, 0x00, 0xDD, 0x00, 0x01]).await;
    assert!(
        matches!(r, Response::Registers { ref words, .. } if (i32::from(words[0] as i16) - 600).abs() <= 1),
        "{r:?}"
    );
    // P281 = 0 stops; then P290 = 123 456 and a rising P282 bit 1 positions there.
    e10.pdu(&[0x06, 0x01, 0x19, 0x00, 0x00]).await;
    e10.handle
        .advance_until(|s| !s.axes[0].flags.contains(AxisFlags::MOVING), 10_000)
        .unwrap();
    let target: i32 = 123_456;
    let [a, b, c, d] = target.to_be_bytes();
    e10.pdu(&[0x10, 0x01, 0x22, 0x00, 0x02, 0x04, a, b, c, d])
        .await;
    e10.pdu(&[0x06, 0x01, 0x1A, 0x00, 0x03]).await;
    e10.handle
        .advance_until(
            |s| s.axes[0].cmd_pos == 123_456.0 && !s.axes[0].flags.contains(AxisFlags::MOVING),
            60_000,
        )
        .unwrap();
    e10.handle.advance(200).unwrap();
    let r = e10.pdu(&[0x03, 0x00, 0xD8, 0x00, 0x02]).await;
    let Response::Registers { words, .. } = r else {
        panic!("{r:?}")
    };
    let pos = i32::from_be_bytes([
        (words[0] >> 8) as u8,
        words[0] as u8,
        (words[1] >> 8) as u8,
        words[1] as u8,
    ]);
    assert!((pos - target).abs() <= 1, "R216 = {pos}");
}

/// Two stepper axes in mm with limit switches at ±50 mm.
const STEPPERS: &str = r#"
[[axes]]
[axes.params]
axis_type = "stepper"
units = 1000
rep_mode = "finite"
speed = 100
accel = 1000
decel = 1000
[axes.switches.limit_pos]
position = 50
[axes.switches.limit_neg]
position = -50
[[axes]]
[axes.params]
axis_type = "stepper"
units = 1000
rep_mode = "finite"
speed = 100
accel = 1000
decel = 1000
[axes.switches.limit_pos]
position = 50
[axes.switches.limit_neg]
position = -50
"#;

/// An f64 as the bytes of four registers, low word first.
fn f64_cdab_bytes(v: f64) -> Vec<u8> {
    register_bytes(&f64_to_cdab(v))
}

/// Holding-register reads and writes through request PDUs.
impl MapUnit {
    async fn registers(&self, address: u16, quantity: u16) -> Vec<u16> {
        let [ah, al] = address.to_be_bytes();
        let [qh, ql] = quantity.to_be_bytes();
        match self.pdu(&[0x03, ah, al, qh, ql]).await {
            Response::Registers { words, .. } => words,
            other => panic!("read {address}: {other:?}"),
        }
    }

    async fn write(&self, address: u16, data: &[u8]) -> Response {
        let [ah, al] = address.to_be_bytes();
        let n = (data.len() / 2) as u16;
        let mut pdu = vec![0x10, ah, al, 0, n as u8, data.len() as u8];
        pdu.extend_from_slice(data);
        self.pdu(&pdu).await
    }
}

#[tokio::test]
async fn the_himc_map_enables_moves_and_reports_errors_as_the_controller_does() {
    let himc = unit(STEPPERS, "himc", 2);
    assert_eq!(himc.registers(8208, 1).await, [2], "synchronous: ready");
    // HR 30 = 1 enables axis 0 (digest 004 §1.9); HR 130 is axis 1's.
    himc.pdu(&[0x06, 0x00, 0x1E, 0x00, 0x01]).await;
    assert_eq!(
        himc.registers(0, 2).await,
        [0b101, 0],
        "motion status: enabled, in position"
    );
    assert_eq!(himc.registers(100, 2).await, [0, 0]);
    // Target 12.5 mm, command 1 (move absolute), in one request.
    let mut data = f64_cdab_bytes(12.5);
    data.extend_from_slice(&[0, 0, 0, 0, 0, 0, 0, 0, 0, 1]);
    himc.write(40, &data).await;
    himc.handle
        .advance_until(
            |s| s.axes[0].act_pos == 12.5 && !s.axes[0].flags.contains(AxisFlags::MOVING),
            60_000,
        )
        .unwrap();
    himc.handle.advance(50).unwrap();
    assert_eq!(cdab_to_f64(&himc.registers(4, 4).await), 12.5);
    assert_eq!(
        himc.registers(0, 1).await[0] & 0b101,
        0b101,
        "enabled, in position"
    );
    // Max velocity reads the parameter, low word first.
    assert_eq!(cdab_to_f64(&himc.registers(16, 4).await), 100.0);
    // Drive into the + limit: fault bit 3, error stop, 0x8300_07EE at 58 and at 8210.
    let mut data = f64_cdab_bytes(80.0);
    data.extend_from_slice(&[0, 0, 0, 0, 0, 0, 0, 0, 0, 1]);
    himc.pdu(&[0x06, 0x00, 0x30, 0x00, 0x00]).await; // command 0 first, so 1 is written anew
    himc.write(40, &data).await;
    himc.handle.advance(2000).unwrap();
    let fault = himc.registers(2, 2).await;
    assert_ne!(fault[0] & 1 << 3, 0, "right hardware limit: {fault:?}");
    let code = |w: Vec<u16>| u32::from(w[1]) << 16 | u32::from(w[0]);
    assert_eq!(code(himc.registers(58, 2).await), 0x8300_07EE);
    assert_eq!(code(himc.registers(8210, 2).await), 0x8300_07EE);
    assert_eq!(code(himc.registers(158, 2).await), 0, "axis 1 has no error");
    // The user table holds floats low word first (0.85 → 0x999A, 0x3F59).
    himc.write(8704, &[0x99, 0x9A, 0x3F, 0x59]).await;
    let w = himc.registers(8704, 2).await;
    assert_eq!(
        f32::from_bits(u32::from(w[1]) << 16 | u32::from(w[0])),
        0.85
    );
    // Axis 2 does not exist on this machine: its block is not mapped.
    let r = himc.pdu(&[0x03, 0x00, 200, 0x00, 0x01]).await;
    assert_eq!(r, Response::exception(3, Exception::IllegalDataAddress));
}

/// Table 5.1.1.5's motion_status bits 5 gantry, 6 input shape, 7 VSF and 8 gear (slave), from
/// the engine's couplings and command filters.
#[tokio::test]
async fn the_himc_motion_status_shows_gantry_shapers_vsf_and_gear() {
    let himc = unit(STEPPERS, "himc", 2);
    let call = |json: &str| {
        himc.handle
            .call(serde_json::from_str(json).unwrap())
            .unwrap_or_else(|e| panic!("{json}: {e}"));
    };
    let mode_bits = |w: &[u16]| (w[0] >> 5) & 0b1111;
    call(r#"{"type":"filter_vsf","axis":0,"frequency":40}"#);
    call(r#"{"type":"filter_input_shaping","axis":1,"frequency":10}"#);
    assert_eq!(
        mode_bits(&himc.registers(0, 2).await),
        0b0100,
        "axis 0: VSF"
    );
    assert_eq!(
        mode_bits(&himc.registers(100, 2).await),
        0b0010,
        "axis 1: input shape"
    );
    call(r#"{"type":"filter_disable","axis":0}"#);
    call(r#"{"type":"filter_disable","axis":1}"#);
    call(r#"{"type":"enable","axis":0}"#);
    call(r#"{"type":"enable","axis":1}"#);
    call(r#"{"type":"gear_in","master":0,"slave":1,"numerator":1,"denominator":2}"#);
    assert_eq!(mode_bits(&himc.registers(0, 2).await), 0, "a gear's master");
    assert_eq!(
        mode_bits(&himc.registers(100, 2).await),
        0b1000,
        "a gear's slave"
    );
    call(r#"{"type":"gear_out","slave":1}"#);
    himc.handle.advance(1).unwrap();
    call(r#"{"type":"gantry_enable","master":0,"slaves":[1]}"#);
    himc.handle.advance(1).unwrap();
    assert_eq!(
        mode_bits(&himc.registers(0, 2).await),
        0b0001,
        "gantry master"
    );
    assert_eq!(
        mode_bits(&himc.registers(100, 2).await),
        0b0001,
        "gantry slave"
    );
}

#[tokio::test]
async fn the_hmc_map_reads_and_writes_parameters_as_the_hmc_allows_and_runs_instructions() {
    let hmc = unit(STEPPERS, "hollysys-mc", 2);
    // Speed (offset 42 in the block, f64 high word first) reads the parameter; axis 1's block
    // starts at 200, and its AxisID reads 1.
    assert_eq!(abcd_to_f64(&hmc.registers(200 + 42, 4).await), 100.0);
    assert_eq!(hmc.registers(200, 1).await, [1]);
    // The HMC rule: a negative Speed is made positive and latches AxisStatus bit 2.
    let r = hmc.write(42, &(-40.0f64).to_be_bytes()).await;
    assert!(matches!(r, Response::WriteMultiple { .. }), "{r:?}");
    assert_eq!(abcd_to_f64(&hmc.registers(42, 4).await), 40.0);
    let status = hmc.registers(8, 2).await;
    assert_eq!(status, [0, 4], "AxisStatus bit 2");
    // MPos is read-only: 02.
    let r = hmc.write(13, &1.0f64.to_be_bytes()).await;
    assert_eq!(r, Response::exception(0x10, Exception::IllegalDataAddress));
    // Drive enable, then HMC_MoveAbs to 3.5 (argument 1, command 14).
    hmc.pdu(&[0x06, 0x00, 199, 0x00, 0x01]).await;
    let mut data = 3.5f64.to_be_bytes().to_vec();
    data.extend_from_slice(&[0; 8]);
    data.extend_from_slice(&[0, 14]);
    let r = hmc.write(190, &data).await;
    assert!(matches!(r, Response::WriteMultiple { .. }), "{r:?}");
    // MCmdType shows HMC__MoveAbs (14) while it runs.
    hmc.handle.advance(1).unwrap();
    assert_eq!(hmc.registers(6, 1).await, [14]);
    hmc.handle
        .advance_until(
            |s| !s.axes[0].flags.contains(AxisFlags::MOVING) && s.axes[0].cmd_pos == 3.5,
            60_000,
        )
        .unwrap();
    assert_eq!(abcd_to_f64(&hmc.registers(17, 4).await), 3.5, "DPos");
    // HMC_Reverse (20) jogs at −Speed.
    hmc.pdu(&[0x06, 0x00, 198, 0x00, 20]).await;
    hmc.handle.advance(1000).unwrap();
    assert_eq!(hmc.handle.snapshot().axes[0].cmd_vel, -40.0);
}
