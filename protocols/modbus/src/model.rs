//! The boundary between the wire and the data behind it.
//!
//! The server side (`server`, `transport`) owns everything about frames, unit ids, broadcast,
//! diagnostics (FC 8), counters and fault injection. A [`DataModel`] owns the data: which units
//! exist, what FC 1–6, 15, 16, 22 and 23 read and write, and the identity FC 17 and FC 43/14
//! report. The register maps implement it over the engine; tests and benchmarks implement it
//! over plain memory.

use std::fmt;
use std::future::Future;
use std::net::SocketAddr;
use std::sync::Arc;

use crate::pdu::{Exception, Request, Response};

/// Where a request came from, for logs and last-error records.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Peer {
    Tcp(SocketAddr),
    /// A serial line: the device path (a pty's `/dev/pts/N` included).
    Serial(Arc<str>),
}

impl fmt::Display for Peer {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Peer::Tcp(a) => write!(f, "{a}"),
            Peer::Serial(p) => f.write_str(p),
        }
    }
}

/// Who sent a request and how.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RequestContext {
    /// Unit identifier (TCP) or slave address (RTU).
    pub unit: u8,
    /// An RTU broadcast (address 0): executed, never answered. Only writes reach the model.
    pub broadcast: bool,
    pub peer: Peer,
}

/// Why a data request failed: the exception to answer and, for an engine refusal (04), the
/// engine's reason, which the server logs and records as the front-end's last error.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ExecError {
    pub exception: Exception,
    pub reason: String,
}

impl ExecError {
    pub fn new(exception: Exception, reason: impl Into<String>) -> ExecError {
        ExecError {
            exception,
            reason: reason.into(),
        }
    }
}

/// What FC 17 (Report Server ID) and FC 43/14 (Read Device Identification) answer.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct DeviceIdentity {
    /// FC 17: the server id bytes (device specific).
    pub server_id: Vec<u8>,
    /// FC 43/14 basic objects 0x00–0x02.
    pub vendor_name: String,
    pub product_code: String,
    pub revision: String,
    /// FC 43/14 regular objects 0x03–0x06; empty ones are not reported.
    pub vendor_url: String,
    pub product_name: String,
    pub model_name: String,
    pub user_application_name: String,
}

/// The data behind a Modbus server: one or more units.
pub trait DataModel: Send + Sync + 'static {
    /// Whether `unit` is served. On RTU a request for another unit is ignored silently; on TCP
    /// it is answered with exception 0x0B (gateway target failed to respond).
    fn serves(&self, unit: u8) -> bool;

    /// The identity of a served unit.
    fn identity(&self, unit: u8) -> Option<&DeviceIdentity>;

    /// Execute a data request — FC 1, 2, 3, 4, 5, 6, 15, 16, 22 or 23 — already decoded and
    /// checked for quantity and value (exception 03). The model checks addresses (02), values
    /// its points refuse (03) and executes (04 when the engine refuses).
    fn execute<'a>(
        &'a self,
        context: &'a RequestContext,
        request: &'a Request<'a>,
    ) -> impl Future<Output = Result<Response, ExecError>> + Send + 'a;
}
