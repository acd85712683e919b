//! What one Modbus front-end shares between its connections and the control API: counters,
//! faults, listen-only mode and the last engine refusal.

use std::sync::atomic::{AtomicBool, Ordering};

use mcemu_frontend::refusal::LastRefusal;
use serde::Serialize;
use serde_json::{Map, Value};

use crate::counters::{Counters, CountersSnapshot, LastError, RefusedRequest};
use crate::faults::{self, FaultError, FaultSpec, Faults};
pub use crate::framing::Framing;
use crate::model::Peer;
use crate::pdu::Exception;

/// Shared state of one front-end (one listener or one serial line).
#[derive(Debug)]
pub struct FrontendState {
    name: String,
    framing: Framing,
    pub counters: Counters,
    pub faults: Faults,
    /// FC 8 sub-function 0x04 (Modbus Application Protocol V1.1b3 §6.8.1): nothing is
    /// executed or answered until sub-function 0x01.
    listen_only: AtomicBool,
    last_error: LastRefusal<RefusedRequest>,
}

impl FrontendState {
    /// `name` is the config section (`modbus_tcp` …), which control-API requests use; `faults`
    /// are those configured at start.
    pub fn new(
        name: impl Into<String>,
        framing: Framing,
        faults: &[FaultSpec],
    ) -> Result<FrontendState, FaultError> {
        let state = FrontendState {
            name: name.into(),
            framing,
            counters: Counters::default(),
            faults: Faults::new(framing),
            listen_only: AtomicBool::new(false),
            last_error: LastRefusal::default(),
        };
        for f in faults {
            state.faults.install(f.clone())?;
        }
        Ok(state)
    }

    pub fn name(&self) -> &str {
        &self.name
    }

    pub fn framing(&self) -> Framing {
        self.framing
    }

    pub fn listen_only(&self) -> bool {
        self.listen_only.load(Ordering::Relaxed)
    }

    pub(crate) fn set_listen_only(&self, on: bool) {
        self.listen_only.store(on, Ordering::Relaxed);
    }

    pub fn last_error(&self) -> Option<LastError> {
        self.last_error.get()
    }

    pub(crate) fn record_error(
        &self,
        peer: &Peer,
        unit: u8,
        function: u8,
        exception: Exception,
        reason: &str,
    ) {
        let request = RefusedRequest {
            unit,
            function,
            exception: exception.code(),
        };
        self.last_error.record(peer.to_string(), request, reason);
    }

    /// A control-API fault request (`{"fault": ...}`); answers the active faults as JSON.
    pub fn inject(&self, request: &Map<String, Value>) -> Result<Value, FaultError> {
        let active = self.faults.apply(faults::parse(request)?)?;
        Ok(serde_json::json!({ "active_faults": active }))
    }

    pub fn snapshot(&self) -> FrontendSnapshot {
        FrontendSnapshot {
            name: self.name.clone(),
            framing: self.framing,
            listen_only: self.listen_only(),
            counters: self.counters.snapshot(),
            active_faults: self.faults.active(),
            last_error: self.last_error(),
        }
    }
}

/// One front-end in `GET /state`.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct FrontendSnapshot {
    pub name: String,
    pub framing: Framing,
    /// FC 8 listen-only mode is on: requests are counted, not answered.
    pub listen_only: bool,
    pub counters: CountersSnapshot,
    /// Faults in force, with what remains of their counts.
    pub active_faults: Vec<FaultSpec>,
    /// The last request the engine refused (exception 04).
    pub last_error: Option<LastError>,
}
