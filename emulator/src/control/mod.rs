//! The HTTP + JSON control API (ARCHITECTURE §6): the back door tests and users need, versioned
//! under `/api/v1`. Routes, shapes and status codes: docs/decisions.md "Control API".
//!
//! | route | does |
//! |---|---|
//! | `GET /api/v1` | lists the routes |
//! | `GET /api/v1/state` | machine, clock, axes, I/O, drives, runtime statistics, trace status |
//! | `POST /api/v1/commands` | one `axes::Command` or an array, applied in order (`?atomic=true`: in one tick, all or none) |
//! | `POST /api/v1/inputs` | force or release an axis input, a digital or an analog input |
//! | `POST /api/v1/faults` | inject or clear a drive alarm, encoder loss, following error |
//! | `POST /api/v1/time/advance` | virtual clock: run ticks or seconds, optionally until … |
//! | `POST /api/v1/trace/start`, `/trace/stop`, `GET /api/v1/trace` | record every tick, CSV |
//! | `POST /api/v1/canopen/log/start`, `/canopen/log/stop` | a `candump -L` log of the CAN bus |
//!
//! Nothing from a request can panic a handler: bodies are bounded, parsed by hand into typed
//! errors, and every engine call goes through the runtime's queue.

mod commands;
pub(crate) mod error;
mod names;
mod recorder;
mod security;
mod state;
mod stream;
mod time;

use std::sync::Arc;

use axes::runtime::EngineHandle;
use axum::extract::{DefaultBodyLimit, State};
use axum::http::{header, HeaderValue, Method, Uri};
use axum::middleware::{self, Next};
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use axum::{Json, Router};
use serde_json::Value;
use tokio::sync::Semaphore;

pub use commands::{AxisFault, CommandBody, FaultRequest, InputRequest, MAX_COMMANDS_PER_REQUEST};
pub use error::{ApiError, MAX_BODY_BYTES};
pub use names::{flag_by_name, flag_names, FLAG_NAMES};
pub use recorder::{TraceRecorder, TraceStart, TraceState, TraceStatus, MAX_TRACE_ROWS};
pub use security::{generate_token, Access};
pub use stream::{StreamClients, StreamRequest, StreamStatus, CHANNELS, CLIENT_QUEUE};
pub use time::MAX_ADVANCE_TICKS;

use crate::config::{ClockSetting, Config};
use crate::frontend::{CanLog, Frontend};

/// What the config says about the machine, for `/state`.
#[derive(Debug, Default)]
pub struct MachineInfo {
    pub name: String,
    /// `realtime`, `virtual` or `scaled:K`.
    pub clock: String,
    pub axis_names: Vec<Option<String>>,
}

impl MachineInfo {
    pub fn axis_name(&self, axis: usize) -> Option<&str> {
        self.axis_names.get(axis).and_then(|n| n.as_deref())
    }
}

/// Traces rendered at once (each may be 110 MB of CSV); more wait their turn.
const CONCURRENT_TRACE_READS: usize = 2;

/// What every handler needs.
#[derive(Clone)]
pub struct ControlState {
    pub handle: EngineHandle,
    pub machine: Arc<MachineInfo>,
    pub trace: TraceRecorder,
    /// The running protocol front-ends.
    pub frontends: Arc<Vec<Arc<dyn Frontend>>>,
    /// The CAN bus's log, when the machine has a bus (`[frontends.canopen]` enabled).
    pub can_log: Option<Arc<dyn CanLog>>,
    /// `[frontends.control] max_requests` permits, and that number for the 503 reply.
    requests: (Arc<Semaphore>, usize),
    trace_reads: Arc<Semaphore>,
    /// The open dashboard streams, at most `stream_max_clients`.
    pub streams: Arc<StreamClients>,
    pub stream_max_clients: usize,
    /// Who may use the API: the token, if one is required.
    pub access: Access,
}

impl ControlState {
    pub fn new(handle: EngineHandle, config: &Config) -> ControlState {
        ControlState {
            machine: Arc::new(MachineInfo {
                name: config.machine.name.clone(),
                clock: ClockSetting(handle.clock()).to_string(),
                axis_names: config.axes.iter().map(|a| a.name.clone()).collect(),
            }),
            handle,
            trace: TraceRecorder::with_limit(config.frontends.control.trace_max_rows),
            frontends: Arc::new(Vec::new()),
            can_log: None,
            requests: (
                Arc::new(Semaphore::new(config.frontends.control.max_requests)),
                config.frontends.control.max_requests,
            ),
            trace_reads: Arc::new(Semaphore::new(CONCURRENT_TRACE_READS)),
            streams: Arc::default(),
            stream_max_clients: config.frontends.control.stream_max_clients,
            access: Access::open(),
        }
    }

    /// The same state serving `frontends`.
    pub fn with_frontends(mut self, frontends: Vec<Arc<dyn Frontend>>) -> ControlState {
        self.frontends = Arc::new(frontends);
        self
    }

    /// The same state requiring `access`'s token.
    pub fn with_access(mut self, access: Access) -> ControlState {
        self.access = access;
        self
    }

    /// The same state with the CAN bus's log.
    pub fn with_can_log(mut self, log: Option<Arc<dyn CanLog>>) -> ControlState {
        self.can_log = log;
        self
    }
}

/// The routes, with their method, as `GET /api/v1` lists them.
const ROUTES: [(&str, &str, &str); 13] = [
    (
        "GET",
        "/api/v1/state",
        "machine, clock, axes, I/O, drives, runtime statistics, trace",
    ),
    (
        "POST",
        "/api/v1/commands",
        "one command or an array, e.g. {\"type\":\"enable\",\"axis\":0}; ?atomic=true: an array in one tick, all or none",
    ),
    (
        "POST",
        "/api/v1/inputs",
        "{\"axis\":0,\"input\":\"limit_pos\",\"value\":true}, {\"di\":N,…}, {\"ai\":N,…}",
    ),
    (
        "POST",
        "/api/v1/faults",
        "{\"axis\":0,\"fault\":\"drive_alarm\",\"active\":true}, encoder_loss, following_error",
    ),
    (
        "POST",
        "/api/v1/frontends/{name}/broadcast",
        "{\"message\":\"test\\n\\r\"}: to every client of ascii_user (at most 128 bytes, sent as given)",
    ),
    (
        "POST",
        "/api/v1/time/advance",
        "virtual clock: {\"ticks\":N} or {\"seconds\":S}, optional until",
    ),
    (
        "POST",
        "/api/v1/trace/start",
        "optional {\"axes\":[0,1],\"max_rows\":N}",
    ),
    ("POST", "/api/v1/trace/stop", "stop recording"),
    ("GET", "/api/v1/trace", "the recording as CSV"),
    (
        "POST",
        "/api/v1/canopen/log/start",
        "{\"path\":\"bus.log\"}: a candump -L log of the CAN bus to a new file",
    ),
    (
        "POST",
        "/api/v1/canopen/log/stop",
        "stop the CAN bus log (the config's too)",
    ),
    (
        "GET",
        "/api/v1/stream",
        "server-sent events: every tick of ?axes=0,1&channels=cmd_pos,act_pos&io=true&batch=N, batched",
    ),
    ("GET", "/api/v1", "this list"),
];

/// The API's routes, versioned under `/api/v1`, and the dashboard at `/`.
pub fn router(state: ControlState) -> Router {
    let api = Router::new()
        .route("/api/v1", get(index))
        .route("/api/v1/state", get(state::get_state))
        .route("/api/v1/commands", post(commands::post_commands))
        .route("/api/v1/inputs", post(commands::post_inputs))
        .route("/api/v1/faults", post(commands::post_faults))
        .route(
            "/api/v1/frontends/{name}/broadcast",
            post(commands::post_broadcast),
        )
        .route("/api/v1/time/advance", post(time::post_advance))
        .route("/api/v1/trace/start", post(trace_start))
        .route("/api/v1/trace/stop", post(trace_stop))
        .route("/api/v1/trace", get(trace_csv))
        .route("/api/v1/canopen/log/start", post(can_log_start))
        .route("/api/v1/canopen/log/stop", post(can_log_stop))
        .route("/api/v1/stream", get(stream::get_stream))
        .fallback(not_found)
        .method_not_allowed_fallback(method_not_allowed)
        .layer(DefaultBodyLimit::max(MAX_BODY_BYTES))
        .layer(middleware::from_fn_with_state(
            state.requests.clone(),
            limit_requests,
        ))
        // Outermost: refused requests take no request permit.
        .layer(middleware::from_fn_with_state(
            state.access.clone(),
            security::guard,
        ))
        .with_state(state);
    // The dashboard's files need no token: they hold nothing, and the page asks for it.
    crate::dashboard::routes().merge(api)
}

/// Requests beyond `max_requests` are answered 503 at once; each may hold a 1 MiB body.
async fn limit_requests(
    State((permits, limit)): State<(Arc<Semaphore>, usize)>,
    request: axum::extract::Request,
    next: Next,
) -> Response {
    match permits.try_acquire_owned() {
        Ok(_permit) => next.run(request).await,
        Err(_) => ApiError::TooManyRequests { limit }.into_response(),
    }
}

async fn index() -> Response {
    #[derive(serde::Serialize)]
    struct Route {
        method: &'static str,
        path: &'static str,
        does: &'static str,
    }
    #[derive(serde::Serialize)]
    struct Index {
        api: &'static str,
        version: u32,
        routes: Vec<Route>,
    }
    let index = Index {
        api: "mcemu control",
        version: 1,
        routes: ROUTES
            .iter()
            .map(|&(method, path, does)| Route { method, path, does })
            .collect(),
    };
    Json(index).into_response()
}

async fn not_found(method: Method, uri: Uri) -> ApiError {
    ApiError::NotFound {
        method: method.to_string(),
        path: uri.path().to_string(),
    }
}

async fn method_not_allowed(method: Method, uri: Uri) -> ApiError {
    ApiError::MethodNotAllowed {
        method: method.to_string(),
        path: uri.path().to_string(),
    }
}

async fn trace_start(
    State(state): State<ControlState>,
    error::OptionalJsonBody(body): error::OptionalJsonBody,
) -> Response {
    let request = match body
        .map(|b| error::parse_json::<TraceStart>(&b))
        .transpose()
    {
        Ok(r) => r.unwrap_or_default(),
        Err(e) => return e.into_response(),
    };
    match state.trace.start(&state.handle, request).await {
        Ok(status) => Json(status).into_response(),
        Err(e) => e.into_response(),
    }
}

async fn trace_stop(State(state): State<ControlState>) -> Response {
    match state.trace.stop(&state.handle).await {
        Ok(status) => Json(status).into_response(),
        Err(e) => e.into_response(),
    }
}

/// `text/csv`; `X-Mcemu-Trace-State` (recording, stopped, full) and `X-Mcemu-Trace-Rows` say
/// what it holds. Rendering a large trace takes a while, so it runs off the async workers.
async fn trace_csv(State(state): State<ControlState>) -> Response {
    let Ok(_turn) = state.trace_reads.acquire().await else {
        return ApiError::Internal("trace reader semaphore closed".into()).into_response();
    };
    let period = state.handle.snapshot().period;
    let recorder = state.trace.clone();
    let rendered = tokio::task::spawn_blocking(move || recorder.csv(period)).await;
    let (csv, status) = match rendered {
        Ok(Ok(done)) => done,
        Ok(Err(e)) => return e.into_response(),
        Err(e) => {
            return ApiError::Internal(format!("trace rendering failed: {e}")).into_response()
        }
    };
    let mut response = csv.into_response();
    let headers = response.headers_mut();
    headers.insert(
        header::CONTENT_TYPE,
        HeaderValue::from_static("text/csv; charset=utf-8"),
    );
    headers.insert(
        "x-mcemu-trace-state",
        HeaderValue::from_static(status.state.name()),
    );
    headers.insert("x-mcemu-trace-rows", HeaderValue::from(status.rows));
    response
}

/// `POST /canopen/log/start` body.
#[derive(Debug, serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct CanLogStart {
    /// The file to create; relative paths start from the config file's directory.
    path: String,
}

async fn can_log_start(
    State(state): State<ControlState>,
    error::JsonBody(body): error::JsonBody,
) -> Response {
    let Some(log) = state.can_log.clone() else {
        return ApiError::NoCanBus.into_response();
    };
    let request = match error::parse_json::<CanLogStart>(&body) {
        Ok(r) => r,
        Err(e) => return e.into_response(),
    };
    // Creating the file and starting its writer thread touch the disk: off the async workers.
    run_blocking(move || log.start(&request.path)).await
}

/// No body needed; the writer flushes the whole log before the answer.
async fn can_log_stop(State(state): State<ControlState>) -> Response {
    let Some(log) = state.can_log.clone() else {
        return ApiError::NoCanBus.into_response();
    };
    run_blocking(move || log.stop()).await
}

async fn run_blocking(f: impl FnOnce() -> Result<Value, ApiError> + Send + 'static) -> Response {
    match tokio::task::spawn_blocking(f).await {
        Ok(Ok(reply)) => Json(reply).into_response(),
        Ok(Err(e)) => e.into_response(),
        Err(e) => ApiError::Internal(format!("the log request failed: {e}")).into_response(),
    }
}
