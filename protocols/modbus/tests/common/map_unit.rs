//! The rig of the register-map tests (map_service.rs, shipped_maps.rs): a map served over a
//! real engine on the virtual clock, without sockets (ARCHITECTURE §5: the service layer is
//! tested alone), and the word orders of the values they read and write.

use std::sync::Arc;

use axes::runtime::{ClockMode, EngineHandle, Runtime, RuntimeGuard, RuntimeOptions};
use axes::{Engine, EngineConfig};
use mcemu_modbus::map::{compile, load, shipped, Binding, MachineShape, MapFile, UnitMap};
use mcemu_modbus::map::{MapModel, UnitService};
use mcemu_modbus::model::{DataModel, Peer, RequestContext};
use mcemu_modbus::pdu::{decode_request, Exception, Request, Response};

/// The engine of a machine config (TOML) on the virtual clock: nothing moves until a test
/// advances it.
pub fn start_engine(machine_toml: &str) -> (EngineHandle, RuntimeGuard) {
    let config: EngineConfig = toml::from_str(machine_toml).unwrap();
    Runtime::start(
        Engine::new(&config).unwrap(),
        RuntimeOptions::with_clock(ClockMode::Virtual),
    )
    .unwrap()
}

/// A map written in the test (TOML), compiled for `machine` with `binding`.
pub fn compile_map(map_toml: &str, machine: &MachineShape, binding: &Binding) -> UnitMap {
    let file: MapFile = toml::from_str(map_toml).unwrap();
    compile(&file, machine, binding).unwrap()
}

/// A shipped map by name (`generic`, `himc` …), compiled for `machine` with `binding`.
pub fn shipped_map(name: &str, machine: &MachineShape, binding: &Binding) -> UnitMap {
    let text = shipped(name).unwrap_or_else(|| panic!("no shipped map {name}"));
    load(text, &format!("{name}.toml"), machine, binding).unwrap()
}

/// A request from a serial line to `unit`, not a broadcast.
pub fn serial_request(unit: u8) -> RequestContext {
    RequestContext {
        unit,
        broadcast: false,
        peer: Peer::Serial("test".into()),
    }
}

/// One map served over a running engine.
pub struct MapUnit {
    pub handle: EngineHandle,
    pub model: MapModel,
    /// The unit requests are addressed to.
    pub unit: u8,
    _guard: RuntimeGuard,
}

impl MapUnit {
    /// `map` over `engine`, served as unit `served`; `None` serves every unit id, and requests
    /// then go to unit 1.
    pub fn new(engine: (EngineHandle, RuntimeGuard), map: UnitMap, served: Option<u8>) -> Self {
        let (handle, guard) = engine;
        let service = Arc::new(UnitService::new(map, handle.clone()));
        MapUnit {
            handle,
            model: MapModel::new(vec![(served, service)]),
            unit: served.unwrap_or(1),
            _guard: guard,
        }
    }

    /// Run a typed request: the response, or the exception and its reason.
    pub async fn run(&self, request: Request<'_>) -> Result<Response, (Exception, String)> {
        self.model
            .execute(&serial_request(self.unit), &request)
            .await
            .map_err(|e| (e.exception, e.reason))
    }

    /// Run a request PDU as the unit would, decode refusals included.
    pub async fn pdu(&self, pdu: &[u8]) -> Response {
        let request = match decode_request(pdu) {
            Ok(r) => r,
            Err(refusal) => return refusal.into(),
        };
        match self
            .model
            .execute(&serial_request(self.unit), &request)
            .await
        {
            Ok(r) => r,
            Err(e) => Response::exception(request.function(), e.exception),
        }
    }
}

/// An f64 as four registers, low word first (CDAB).
pub fn f64_to_cdab(v: f64) -> [u16; 4] {
    let b = v.to_be_bytes();
    let w = |i: usize| u16::from_be_bytes([b[2 * i], b[2 * i + 1]]);
    [w(3), w(2), w(1), w(0)]
}

/// Four registers, low word first (CDAB), as an f64.
pub fn cdab_to_f64(words: &[u16]) -> f64 {
    let mut b = [0u8; 8];
    for (i, w) in words.iter().rev().enumerate() {
        b[2 * i..2 * i + 2].copy_from_slice(&w.to_be_bytes());
    }
    f64::from_be_bytes(b)
}

/// Four registers, high word first (ABCD), as an f64.
pub fn abcd_to_f64(words: &[u16]) -> f64 {
    f64::from_be_bytes(register_bytes(words).try_into().unwrap())
}

/// Two registers, low word first (CDAB), as an f32.
pub fn cdab_to_f32(words: &[u16]) -> f32 {
    f32::from_bits(u32::from(words[1]) << 16 | u32::from(words[0]))
}

/// Registers as the bytes a request carries (each big-endian).
pub fn register_bytes(words: &[u16]) -> Vec<u8> {
    words.iter().flat_map(|w| w.to_be_bytes()).collect()
}
