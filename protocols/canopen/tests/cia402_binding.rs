//! The CiA 402 binding on the engine's virtual runtime: a master's frames reach the engine's
//! drive inside the servo tick, and the drive's state comes back as SDO answers, TPDOs on SYNC
//! and EMCY. The master here is hand-written frames (expedited SDO), so every byte is checked.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::collections::VecDeque;
use std::sync::{Arc, Mutex};

use axes::cia402::DriveConfig;
use axes::command::{AxisInput, Command, ForceInput, GetCommandState};
use axes::config::{AxisConfig, EngineConfig};
use axes::runtime::{ClockMode, EngineHandle, Runtime, RuntimeGuard, RuntimeOptions};
use axes::Engine;
use mcemu_canopen::cia402::{CanopenFieldbus, DriveNodeSpec, FramePort};
use mcemu_canopen::{CanFrame, NodeConfig};

const NODE: u8 = 5;

/// Two queues: what the master sends, what the nodes sent.
#[derive(Clone, Default)]
struct TestPort {
    to_nodes: Arc<Mutex<VecDeque<CanFrame>>>,
    from_nodes: Arc<Mutex<Vec<CanFrame>>>,
}

impl FramePort for TestPort {
    fn try_recv(&mut self) -> Option<CanFrame> {
        self.to_nodes.lock().unwrap().pop_front()
    }

    fn send(&mut self, frame: CanFrame) {
        self.from_nodes.lock().unwrap().push(frame);
    }
}

struct Rig {
    handle: EngineHandle,
    _guard: RuntimeGuard,
    port: TestPort,
}

impl Rig {
    fn new() -> Rig {
        let config = EngineConfig {
            axes: vec![AxisConfig::default()],
            drives: vec![DriveConfig {
                increments_per_unit: 1000.0,
                ..DriveConfig::default()
            }],
            ..EngineConfig::default()
        };
        let engine = Engine::new(&config).unwrap();
        let (handle, guard) =
            Runtime::start(engine, RuntimeOptions::with_clock(ClockMode::Virtual)).unwrap();
        let port = TestPort::default();
        let spec = DriveNodeSpec {
            slave: 0,
            config: NodeConfig {
                node_id: NODE,
                ..NodeConfig::default()
            },
            objects: Vec::new(),
            stored_image: None,
        };
        handle
            .add_fieldbus(CanopenFieldbus::new(port.clone(), vec![spec]))
            .unwrap();
        Rig {
            handle,
            _guard: guard,
            port,
        }
    }

    /// Frames the nodes sent since the last call.
    fn sent(&self) -> Vec<CanFrame> {
        std::mem::take(&mut *self.port.from_nodes.lock().unwrap())
    }

    /// Send a frame and let the node answer at the current tick (no time passes).
    fn send(&self, id: u16, data: &[u8]) -> Vec<CanFrame> {
        self.port
            .to_nodes
            .lock()
            .unwrap()
            .push_back(CanFrame::new(id, data).unwrap());
        self.handle.poke();
        // A command queued after the poke: when it is answered, the poke was served.
        let _ = self.handle.call(Command::from(GetCommandState { id: 0 }));
        self.sent()
    }

    fn sdo_upload(&self, index: u16, sub: u8) -> u32 {
        let [lo, hi] = index.to_le_bytes();
        let reply = self.send(0x600 + u16::from(NODE), &[0x40, lo, hi, sub, 0, 0, 0, 0]);
        let r = reply
            .iter()
            .find(|f| f.id() == 0x580 + u16::from(NODE))
            .unwrap_or_else(|| panic!("no SDO answer for {index:04x}:{sub}: {reply:?}"));
        let d = r.data();
        assert_eq!(
            d[0] & 0xF3,
            0x43,
            "expedited upload of {index:04x}:{sub}: {d:02x?}"
        );
        u32::from_le_bytes([d[4], d[5], d[6], d[7]])
    }

    fn sdo_download(&self, index: u16, sub: u8, value: &[u8]) {
        let [lo, hi] = index.to_le_bytes();
        let n = value.len() as u8;
        let mut data = [0x23 | ((4 - n) << 2), lo, hi, sub, 0, 0, 0, 0];
        data[4..4 + value.len()].copy_from_slice(value);
        let reply = self.send(0x600 + u16::from(NODE), &data);
        let r = reply
            .iter()
            .find(|f| f.id() == 0x580 + u16::from(NODE))
            .unwrap_or_else(|| panic!("no SDO answer for {index:04x}:{sub}"));
        assert_eq!(
            r.data()[0],
            0x60,
            "download {index:04x}:{sub} = {value:02x?}: {:02x?}",
            r.data()
        );
    }

    fn advance(&self, ticks: u64) {
        self.handle.advance(ticks).unwrap();
    }

    fn statusword(&self) -> u16 {
        self.sdo_upload(0x6041, 0) as u16
    }
}

#[test]
fn boot_up_then_sdo_answers_while_virtual_time_stands_still() {
    let rig = Rig::new();
    rig.advance(1);
    let boot = rig.sent();
    assert!(
        boot.iter()
            .any(|f| f.id() == 0x700 + u16::from(NODE) && f.data() == [0]),
        "{boot:?}"
    );
    let tick = rig.handle.snapshot().tick;
    // 0x1000 device type of a CiA 402 drive: profile 402 in the low word.
    assert_eq!(rig.sdo_upload(0x1000, 0) & 0xFFFF, 402);
    assert_eq!(rig.handle.snapshot().tick, tick, "the answer took no tick");
    // An object the drive has is answered from the drive's own dictionary.
    assert_eq!(
        rig.sdo_upload(0x6061, 0),
        rig.handle.snapshot().drives[0].mode as u8 as u32
    );
}

#[test]
fn a_master_enables_the_drive_and_makes_a_profile_position_move() {
    let rig = Rig::new();
    rig.advance(2);
    rig.send(0x000, &[0x01, NODE]); // NMT start
    for cw in [0x06u16, 0x07, 0x0F] {
        rig.sdo_download(0x6040, 0, &cw.to_le_bytes());
        rig.advance(5);
    }
    let sw = rig.statusword();
    assert_eq!(sw & 0x6F, 0x27, "operation enabled: {sw:#06x}");
    assert!(rig.handle.snapshot().axes[0]
        .flags
        .contains(axes::status::AxisFlags::ENABLED));
    // Profile position: 1000 increments = 1 unit at 10 units/s.
    rig.sdo_download(0x6060, 0, &[1]);
    rig.sdo_download(0x607A, 0, &1000i32.to_le_bytes());
    rig.sdo_download(0x6081, 0, &10_000u32.to_le_bytes());
    rig.sdo_download(0x6083, 0, &100_000u32.to_le_bytes());
    rig.sdo_download(0x6084, 0, &100_000u32.to_le_bytes());
    rig.sdo_download(0x6040, 0, &0x1Fu16.to_le_bytes()); // new set-point
    rig.advance(2);
    rig.sdo_download(0x6040, 0, &0x0Fu16.to_le_bytes());
    let mut reached = false;
    for _ in 0..400 {
        rig.advance(5);
        if rig.statusword() & (1 << 10) != 0 {
            reached = true;
            break;
        }
    }
    assert!(reached, "target reached within 2 s");
    assert_eq!(rig.sdo_upload(0x6064, 0) as i32, 1000);
    let axis = &rig.handle.snapshot().axes[0];
    assert!((axis.act_pos - 1.0).abs() < 1e-9, "{}", axis.act_pos);
}

#[test]
fn a_tpdo_mapped_by_the_master_goes_out_on_sync_and_a_drive_fault_is_an_emcy() {
    let rig = Rig::new();
    rig.advance(2);
    // TPDO1: statusword, synchronous every SYNC, mapped with the CiA 301 procedure.
    let cob = 0x180 + u32::from(NODE);
    rig.sdo_download(0x1800, 1, &(cob | 0x8000_0000).to_le_bytes());
    rig.sdo_download(0x1A00, 0, &[0]);
    rig.sdo_download(0x1A00, 1, &0x6041_0010u32.to_le_bytes());
    rig.sdo_download(0x1A00, 0, &[1]);
    rig.sdo_download(0x1800, 2, &[1]);
    rig.sdo_download(0x1800, 1, &cob.to_le_bytes());
    rig.send(0x000, &[0x01, NODE]);
    rig.sent();
    // SYNC: the TPDO samples the statusword as the last step left it, at once.
    let frames = rig.send(0x080, &[]);
    let tpdo = frames
        .iter()
        .find(|f| u32::from(f.id()) == cob)
        .unwrap_or_else(|| panic!("no TPDO1 after SYNC: {frames:?}"));
    let sw = u16::from_le_bytes([tpdo.data()[0], tpdo.data()[1]]);
    assert_eq!(sw, rig.handle.snapshot().drives[0].statusword);
    // A drive alarm: the drive faults with 0xFF00 and the node says so on 0x80 + id.
    rig.handle
        .call(Command::from(ForceInput {
            axis: 0,
            input: AxisInput::DriveAlarm,
            value: Some(true),
        }))
        .unwrap();
    rig.advance(3);
    let frames = rig.sent();
    let emcy = frames
        .iter()
        .find(|f| f.id() == 0x80 + u16::from(NODE))
        .unwrap_or_else(|| panic!("no EMCY: {frames:?}"));
    assert_eq!(
        u16::from_le_bytes([emcy.data()[0], emcy.data()[1]]),
        rig.handle.snapshot().drives[0].error_code
    );
    assert_ne!(rig.handle.snapshot().drives[0].error_code, 0);
}
