//! Errors of the control API and the JSON bodies they answer with, and the JSON body extractor.
//!
//! Two families, told apart by their key:
//! - request and runtime errors: `{"error": "<code>", "detail": "<what is wrong>", …}`;
//! - engine refusals (422): the typed [`EngineError`] as `{"code": "<variant>", <its data>,
//!   "message": "<Display text>"}`, plus `index` and `replies` when a command array stopped.

use axum::body::Bytes;
use axum::extract::rejection::BytesRejection;
use axum::extract::{FromRequest, Request};
use axum::http::{header, HeaderMap, HeaderValue, StatusCode};
use axum::response::{IntoResponse, Response};
use axum::Json;
use serde::de::DeserializeOwned;
use serde_json::{json, Map, Value};

use super::names::flag_names;
use axes::command::{EngineError, Reply};
use axes::runtime::{AdvanceError, CallError, SubmitError};

/// Largest request body, bytes.
pub const MAX_BODY_BYTES: usize = 1 << 20;

/// Why a request was not carried out.
#[derive(Debug, thiserror::Error)]
pub enum ApiError {
    #[error("the body is not valid JSON: {detail}")]
    MalformedJson {
        detail: String,
        line: usize,
        column: usize,
    },
    /// Valid JSON of the wrong shape: wrong type, unknown or missing field, unknown variant.
    #[error("{detail}")]
    InvalidBody {
        detail: String,
        field: Option<String>,
        line: usize,
        column: usize,
    },
    #[error("send the body as JSON, with `Content-Type: application/json` (got {found})")]
    UnsupportedMediaType { found: String },
    #[error("the body is larger than {limit} bytes")]
    BodyTooLarge { limit: usize },
    #[error("the body did not arrive within {seconds} s")]
    BodyTimeout { seconds: u64 },
    #[error("cannot read the body: {0}")]
    UnreadableBody(String),
    /// Well-formed but meaningless values (both `ticks` and `seconds`, a negative duration …).
    #[error("{0}")]
    InvalidRequest(String),
    #[error("no route {method} {path}; the API lives under /api/v1 (GET /api/v1 lists it)")]
    NotFound { method: String, path: String },
    #[error("{method} is not allowed on {path}")]
    MethodNotAllowed { method: String, path: String },
    #[error("time advances only on the virtual clock; this machine runs `{clock}` (start it with --clock virtual)")]
    NotVirtual { clock: String },
    #[error("no such front-end running: `{name}` (running: {running})")]
    NoSuchFrontend { name: String, running: String },
    #[error("front-end `{name}` has no broadcast (ascii_user has)")]
    NoBroadcast { name: String },
    #[error("a broadcast is at most {limit} bytes (ASCII_ServerBroadcast); this one is {length}")]
    BroadcastTooLong { length: usize, limit: usize },
    #[error("no trace: POST /api/v1/trace/start, run, then GET /api/v1/trace")]
    NoTrace,
    #[error("the trace was restarted while it was being read; read it again")]
    TraceRestarted,
    #[error("this machine has no CAN bus ([frontends.canopen] is absent or disabled)")]
    NoCanBus,
    #[error("the CAN bus is already logged to {path}; POST /api/v1/canopen/log/stop first")]
    AlreadyLogging { path: String },
    #[error("no CAN bus log is running")]
    NotLogging,
    #[error("{path} exists; the API writes a log only to a new file")]
    LogExists { path: String },
    #[error("cannot create {path}: {reason}")]
    LogNotWritable { path: String, reason: String },
    #[error("the engine's command queue is full ({capacity} requests); retry later")]
    Busy { capacity: usize },
    #[error("{limit} requests are being handled; retry later")]
    TooManyRequests { limit: usize },
    #[error(
        "{limit} streams are open (`[frontends.control] stream_max_clients`); close one first"
    )]
    TooManyStreams { limit: usize },
    #[error("this control port needs its token: send `Authorization: Bearer <token>` (printed by `mcemu run`, or `[frontends.control] token`)")]
    Unauthorized,
    #[error("cross-origin request refused: Origin `{origin}` is not this server ({host})")]
    CrossOrigin { origin: String, host: String },
    #[error("the runtime is stopped")]
    Stopped,
    #[error("the servo thread died; the engine is lost")]
    ServoDied,
    #[error("internal error: {0}")]
    Internal(String),
    /// The engine refused a command; `index` is set when it was one of an array, `replies` then
    /// holds the replies of the commands before it (they were applied).
    #[error("{error}")]
    Engine {
        error: EngineError,
        index: Option<usize>,
        replies: Vec<Reply>,
    },
}

impl ApiError {
    pub fn status(&self) -> StatusCode {
        use ApiError::*;
        match self {
            MalformedJson { .. }
            | InvalidBody { .. }
            | UnreadableBody(_)
            | InvalidRequest(_)
            | NoSuchFrontend { .. }
            | NoBroadcast { .. }
            | LogNotWritable { .. } => StatusCode::BAD_REQUEST,
            BroadcastTooLong { .. } => StatusCode::UNPROCESSABLE_ENTITY,
            UnsupportedMediaType { .. } => StatusCode::UNSUPPORTED_MEDIA_TYPE,
            BodyTooLarge { .. } => StatusCode::PAYLOAD_TOO_LARGE,
            BodyTimeout { .. } => StatusCode::REQUEST_TIMEOUT,
            NotFound { .. } => StatusCode::NOT_FOUND,
            MethodNotAllowed { .. } => StatusCode::METHOD_NOT_ALLOWED,
            NotVirtual { .. }
            | NoTrace
            | TraceRestarted
            | NoCanBus
            | AlreadyLogging { .. }
            | NotLogging
            | LogExists { .. } => StatusCode::CONFLICT,
            Busy { .. } | TooManyRequests { .. } | TooManyStreams { .. } | Stopped => {
                StatusCode::SERVICE_UNAVAILABLE
            }
            Unauthorized => StatusCode::UNAUTHORIZED,
            CrossOrigin { .. } => StatusCode::FORBIDDEN,
            ServoDied | Internal(_) => StatusCode::INTERNAL_SERVER_ERROR,
            Engine { .. } => StatusCode::UNPROCESSABLE_ENTITY,
        }
    }

    /// The stable `error` code of the request/runtime family.
    fn code(&self) -> &'static str {
        use ApiError::*;
        match self {
            MalformedJson { .. } => "malformed_json",
            InvalidBody { .. } => "invalid_body",
            UnsupportedMediaType { .. } => "unsupported_media_type",
            BodyTooLarge { .. } => "body_too_large",
            BodyTimeout { .. } => "body_timeout",
            UnreadableBody(_) => "unreadable_body",
            InvalidRequest(_) => "invalid_request",
            NotFound { .. } => "not_found",
            MethodNotAllowed { .. } => "method_not_allowed",
            NotVirtual { .. } => "not_virtual_clock",
            NoSuchFrontend { .. } => "no_such_frontend",
            NoBroadcast { .. } => "no_broadcast",
            BroadcastTooLong { .. } => "broadcast_too_long",
            NoTrace => "no_trace",
            TraceRestarted => "trace_restarted",
            NoCanBus => "no_can_bus",
            AlreadyLogging { .. } => "already_logging",
            NotLogging => "not_logging",
            LogExists { .. } => "log_exists",
            LogNotWritable { .. } => "log_not_writable",
            Busy { .. } => "runtime_busy",
            TooManyRequests { .. } => "too_many_requests",
            TooManyStreams { .. } => "too_many_streams",
            Unauthorized => "unauthorized",
            CrossOrigin { .. } => "cross_origin",
            Stopped => "runtime_stopped",
            ServoDied => "servo_died",
            Internal(_) => "internal",
            Engine { .. } => "engine",
        }
    }

    /// The JSON body.
    pub fn body(&self) -> Value {
        Value::Object(self.fields().into_iter().collect())
    }

    /// The body's fields in the order they are sent: the code first, so a human reading a
    /// response sees what kind of error it is before the details.
    fn fields(&self) -> Vec<(String, Value)> {
        if let ApiError::Engine {
            error,
            index,
            replies,
        } = self
        {
            let mut fields = engine_error_fields(error);
            if let Some(index) = index {
                fields.push(("index".into(), json!(index)));
                fields.push(("replies".into(), json!(replies)));
            }
            return fields;
        }
        let mut fields = vec![
            ("error".into(), json!(self.code())),
            ("detail".into(), json!(self.to_string())),
        ];
        let (field, line, column) = match self {
            ApiError::MalformedJson { line, column, .. } => (None, *line, *column),
            ApiError::InvalidBody {
                field,
                line,
                column,
                ..
            } => (field.as_ref(), *line, *column),
            _ => (None, 0, 0),
        };
        if let Some(field) = field {
            fields.push(("field".into(), json!(field)));
        }
        // Line 0: no position known (bodies parsed in two steps).
        if line > 0 {
            fields.push(("line".into(), json!(line)));
            fields.push(("column".into(), json!(column)));
        }
        fields
    }
}

/// Serializes fields as a JSON object in their order (`serde_json::Map` would sort them).
struct Ordered(Vec<(String, Value)>);

impl serde::Serialize for Ordered {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let mut map = serializer.serialize_map(Some(self.0.len()))?;
        for (key, value) in &self.0 {
            map.serialize_entry(key, value)?;
        }
        map.end()
    }
}

impl IntoResponse for ApiError {
    fn into_response(self) -> Response {
        let mut response = (self.status(), Json(Ordered(self.fields()))).into_response();
        if matches!(
            self,
            ApiError::Busy { .. }
                | ApiError::TooManyRequests { .. }
                | ApiError::TooManyStreams { .. }
        ) {
            response
                .headers_mut()
                .insert(header::RETRY_AFTER, HeaderValue::from_static("1"));
        }
        if matches!(self, ApiError::Unauthorized) {
            response
                .headers_mut()
                .insert(header::WWW_AUTHENTICATE, HeaderValue::from_static("Bearer"));
        }
        response
    }
}

/// `code`, the variant's data (fault sets as lists of flag names), `message` (its Display).
pub fn engine_error_fields(error: &EngineError) -> Vec<(String, Value)> {
    let mut fields = vec![("code".to_string(), json!(error.kind().name()))];
    // A refused item (a move of `move_together` …): which list and item, and the item's own
    // error with its fields, under `error`.
    if let EngineError::Item {
        list,
        index,
        error: inner,
    } = error
    {
        fields.push(("list".into(), json!(list)));
        fields.push(("item".into(), json!(index)));
        fields.push(("error".into(), json!(Ordered(engine_error_fields(inner)))));
        fields.push(("message".into(), json!(error.to_string())));
        return fields;
    }
    // Every variant serializes to a map; should one not, the code and message still go out.
    if let Ok(Value::Object(data)) = serde_json::to_value(error) {
        fields.extend(data.into_iter().filter(|(k, _)| k != "code"));
    }
    // bitflags writes sets as "DRIVE_ALARM | ESTOP"; the API names flags as /state does.
    if let EngineError::AxisInError { faults, .. } | EngineError::CauseStillPresent { faults, .. } =
        error
    {
        for (key, value) in &mut fields {
            if key == "faults" {
                *value = json!(flag_names(*faults));
            }
        }
    }
    fields.push(("message".into(), json!(error.to_string())));
    fields
}

impl From<CallError> for ApiError {
    fn from(e: CallError) -> Self {
        match e {
            CallError::Engine(error) => ApiError::Engine {
                error,
                index: None,
                replies: Vec::new(),
            },
            CallError::Submit(e) => e.into(),
            CallError::NoReply => ApiError::ServoDied,
            // Handlers run on tokio threads, never on the servo thread.
            CallError::OnServoThread => ApiError::Internal(e.to_string()),
        }
    }
}

impl From<SubmitError> for ApiError {
    fn from(e: SubmitError) -> Self {
        match e {
            SubmitError::QueueFull { capacity } => ApiError::Busy { capacity },
            SubmitError::Stopped => ApiError::Stopped,
        }
    }
}

impl From<AdvanceError> for ApiError {
    fn from(e: AdvanceError) -> Self {
        match e {
            AdvanceError::NotVirtual(clock) => ApiError::NotVirtual {
                clock: crate::config::ClockSetting(clock).to_string(),
            },
            AdvanceError::Submit(e) => e.into(),
            AdvanceError::NoReply => ApiError::ServoDied,
            AdvanceError::OnServoThread | AdvanceError::ConditionPanicked { .. } => {
                ApiError::Internal(e.to_string())
            }
        }
    }
}

impl From<BytesRejection> for ApiError {
    fn from(rejection: BytesRejection) -> Self {
        if rejection.status() == StatusCode::PAYLOAD_TOO_LARGE {
            ApiError::BodyTooLarge {
                limit: MAX_BODY_BYTES,
            }
        } else {
            ApiError::UnreadableBody(rejection.body_text())
        }
    }
}

/// Parse a JSON body into `T`, with errors that say what and where. Also used for bodies that
/// were split by hand (command arrays, tagged shapes).
pub fn parse_json<T: DeserializeOwned>(bytes: &[u8]) -> Result<T, ApiError> {
    let mut de = serde_json::Deserializer::from_slice(bytes);
    let value: T = serde_path_to_error::deserialize(&mut de).map_err(|e| {
        let path = e.path().clone();
        let inner = e.into_inner();
        // Only a body that is valid JSON has fields to point at.
        let body = match inner.classify() {
            serde_json::error::Category::Data => serde_json::from_slice(bytes).ok(),
            _ => None,
        };
        json_error(inner, Some(&path), body.as_ref())
    })?;
    de.end().map_err(|e| json_error(e, None, None))?;
    Ok(value)
}

/// Deserialize `T` from an already parsed value (no positions then).
pub fn from_value<T: DeserializeOwned>(value: Value) -> Result<T, ApiError> {
    serde_path_to_error::deserialize(value.clone()).map_err(|e| {
        let path = e.path().clone();
        json_error(e.into_inner(), Some(&path), Some(&value))
    })
}

fn json_error(
    e: serde_json::Error,
    path: Option<&serde_path_to_error::Path>,
    body: Option<&Value>,
) -> ApiError {
    let (line, column) = (e.line(), e.column());
    let text = e.to_string();
    // serde_json appends the position to its message; it goes to its own fields instead.
    let suffix = format!(" at line {line} column {column}");
    let detail = text.strip_suffix(&suffix).unwrap_or(&text).to_string();
    match e.classify() {
        serde_json::error::Category::Data => ApiError::InvalidBody {
            field: match path {
                Some(path) => field_of(path, body, &detail),
                None => field_in_message(&detail),
            },
            detail,
            line,
            column,
        },
        _ => ApiError::MalformedJson {
            detail,
            line,
            column,
        },
    }
}

/// The field an error is about: serde's path, completed where it stops short. Internally
/// tagged enums such as `Command` buffer their content, so the path ends at the object; serde
/// still names the field in "unknown/missing field `x`", and an invalid value or variant can
/// be matched against the object's values (only when exactly one matches).
fn field_of(
    path: &serde_path_to_error::Path,
    body: Option<&Value>,
    detail: &str,
) -> Option<String> {
    use serde_path_to_error::Segment;
    let mut at = body;
    for segment in path.iter() {
        at = match segment {
            Segment::Seq { index } => at.and_then(|v| v.get(*index)),
            Segment::Map { key } => at.and_then(|v| v.get(key)),
            _ => None,
        };
    }
    let inner = at
        .and_then(Value::as_object)
        .and_then(|object| field_in_object(object, detail))
        .or_else(|| field_in_message(detail));
    let path = path.to_string();
    match (path.as_str(), inner) {
        (".", inner) => inner,
        (p, Some(field)) if !p.ends_with(&format!(".{field}")) && p != field => {
            Some(format!("{p}.{field}"))
        }
        (p, _) => Some(p.to_string()),
    }
}

/// serde names the field in "unknown field `x`", "missing field `x`", "duplicate field `x`".
fn field_in_message(detail: &str) -> Option<String> {
    ["unknown field `", "missing field `", "duplicate field `"]
        .iter()
        .find_map(|prefix| detail.strip_prefix(prefix))
        .and_then(|rest| rest.split('`').next())
        .map(str::to_string)
}

/// The one key of `object` whose value is the one serde's "invalid type: X" / "invalid value:
/// X" / "unknown variant `X`" is about.
fn field_in_object(object: &Map<String, Value>, detail: &str) -> Option<String> {
    if field_in_message(detail).is_some() {
        return None;
    }
    let matches = |v: &Value| -> bool {
        if let Some(rest) = detail.strip_prefix("unknown variant `") {
            return rest.split('`').next() == v.as_str();
        }
        let Some(unexpected) = detail
            .strip_prefix("invalid type: ")
            .or_else(|| detail.strip_prefix("invalid value: "))
            .and_then(|rest| rest.split(", expected").next())
        else {
            return false;
        };
        // serde's `Unexpected` wording.
        let described = match v {
            Value::Null => return unexpected == "unit value" || unexpected == "null",
            Value::Bool(b) => format!("boolean `{b}`"),
            Value::String(s) => format!("string {s:?}"),
            Value::Array(_) => "sequence".into(),
            Value::Object(_) => "map".into(),
            Value::Number(n) => match (n.as_i64(), n.as_u64(), n.as_f64()) {
                (Some(i), _, _) => format!("integer `{i}`"),
                (_, Some(u), _) => format!("integer `{u}`"),
                (_, _, Some(f)) => {
                    let text = f.to_string();
                    let point = if text.contains(['.', 'e', 'E']) {
                        ""
                    } else {
                        ".0"
                    };
                    format!("floating point `{text}{point}`")
                }
                _ => return false,
            },
        };
        described == unexpected
    };
    let mut found = object.iter().filter(|(_, v)| matches(v)).map(|(k, _)| k);
    match (found.next(), found.next()) {
        (Some(key), None) => Some(key.clone()),
        _ => None,
    }
}

/// Content types taken as JSON: `application/json` and `application/*+json`, any parameters.
///
/// Requiring one also keeps browsers out: a cross-site page cannot send it without a CORS
/// preflight, which this API never grants, so it cannot drive the machine behind a user's back.
fn check_json_content_type(headers: &HeaderMap) -> Result<(), ApiError> {
    let found = headers
        .get(header::CONTENT_TYPE)
        .map(|v| String::from_utf8_lossy(v.as_bytes()).into_owned());
    let is_json = found.as_deref().is_some_and(|v| {
        let essence = v
            .split(';')
            .next()
            .unwrap_or("")
            .trim()
            .to_ascii_lowercase();
        essence == "application/json"
            || (essence.starts_with("application/") && essence.ends_with("+json"))
    });
    if is_json {
        Ok(())
    } else {
        Err(ApiError::UnsupportedMediaType {
            found: found.map_or_else(|| "no Content-Type".into(), |v| format!("`{v}`")),
        })
    }
}

/// How long a client may take to send a body: a stalled upload must not hold one of the
/// bounded request slots for ever.
pub const BODY_TIMEOUT: std::time::Duration = std::time::Duration::from_secs(10);

async fn read_body<S: Send + Sync>(req: Request, state: &S) -> Result<Bytes, ApiError> {
    match tokio::time::timeout(BODY_TIMEOUT, Bytes::from_request(req, state)).await {
        Ok(read) => Ok(read?),
        Err(_) => Err(ApiError::BodyTimeout {
            seconds: BODY_TIMEOUT.as_secs(),
        }),
    }
}

/// A JSON request body (`Content-Type: application/json`, at most [`MAX_BODY_BYTES`]).
pub struct JsonBody(pub Bytes);

impl<S: Send + Sync> FromRequest<S> for JsonBody {
    type Rejection = ApiError;

    async fn from_request(req: Request, state: &S) -> Result<Self, ApiError> {
        check_json_content_type(req.headers())?;
        Ok(JsonBody(read_body(req, state).await?))
    }
}

/// A JSON body that may be absent: an empty body (any content type) is `None`.
pub struct OptionalJsonBody(pub Option<Bytes>);

impl<S: Send + Sync> FromRequest<S> for OptionalJsonBody {
    type Rejection = ApiError;

    async fn from_request(req: Request, state: &S) -> Result<Self, ApiError> {
        let headers = req.headers().clone();
        let bytes = read_body(req, state).await?;
        if bytes.iter().all(u8::is_ascii_whitespace) {
            return Ok(OptionalJsonBody(None));
        }
        check_json_content_type(&headers)?;
        Ok(OptionalJsonBody(Some(bytes)))
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

    use super::*;
    use axes::command::{Command, Direction};
    use axes::AxisFlags;

    fn err(body: &str) -> ApiError {
        match parse_json::<Command>(body.as_bytes()) {
            Err(e) => e,
            Ok(c) => panic!("parsed {c:?}"),
        }
    }

    #[test]
    fn syntax_errors_are_malformed_json_with_a_position() {
        let e = err(r#"{"type": "enable", "axis": 0"#);
        assert!(
            matches!(e, ApiError::MalformedJson { line: 1, .. }),
            "{e:?}"
        );
        assert_eq!(e.body()["error"], "malformed_json");
        assert!(matches!(
            err(r#"{"type":"enable","axis":0} x"#),
            ApiError::MalformedJson { .. }
        ));
        // JSON has no NaN, and 1e400 is no f64.
        let e = err(r#"{"type":"move_absolute","axis":0,"position":1e400}"#);
        assert!(e.to_string().contains("number out of range"), "{e}");
        assert_eq!(e.status(), StatusCode::BAD_REQUEST);
    }

    #[test]
    fn shape_errors_name_the_field() {
        let e = err(r#"{"type":"move_absolute","axis":0,"positon":1}"#);
        let body = e.body();
        assert_eq!(body["error"], "invalid_body");
        assert_eq!(body["field"], "positon");
        assert!(body["detail"].as_str().unwrap().contains("unknown field"));
        let e = err(r#"{"type":"move_absolute","axis":0}"#);
        assert_eq!(e.body()["field"], "position");
        let e = err(r#"{"type":"move_absolutely","axis":0}"#);
        assert!(e.to_string().contains("unknown variant"), "{e}");
        let e = err(r#"{"type":"enable","axis":"zero"}"#);
        assert!(e.to_string().contains("invalid type"), "{e}");
        let e = match parse_json::<Vec<Command>>(br#"[{"type":"enable","axis":0},{"type":"x"}]"#) {
            Err(e) => e,
            Ok(_) => panic!("parsed"),
        };
        assert_eq!(e.body()["field"], "[1].type");
        let e = match parse_json::<Vec<Command>>(
            br#"[{"type":"enable","axis":0},{"type":"move_absolute","axis":0,"positon":1}]"#,
        ) {
            Err(e) => e,
            Ok(_) => panic!("parsed"),
        };
        assert_eq!(e.body()["field"], "[1].positon");
    }

    #[test]
    fn invalid_values_are_matched_to_their_field() {
        let field = |body: &str| err(body).body()["field"].clone();
        assert_eq!(field(r#"{"type":"enable","axis":"zero"}"#), "axis");
        assert_eq!(field(r#"{"type":"enable","axis":-1}"#), "axis");
        assert_eq!(field(r#"{"type":"enable","axis":1.5}"#), "axis");
        assert_eq!(field(r#"{"type":"enable","axis":70000}"#), "axis");
        assert_eq!(field(r#"{"type":"enable","axis":null}"#), "axis");
        assert_eq!(field(r#"{"type":"stop","axis":0,"mode":"fast"}"#), "mode");
        assert_eq!(field(r#"{"type":"move_absolutely","axis":0}"#), "type");
        assert_eq!(
            field(r#"{"type":"move_absolute","axis":0,"position":true}"#),
            "position"
        );
        // Ambiguous: not guessed.
        let body = err(r#"{"type":"move_absolute","axis":0,"position":"x","velocity":"x"}"#).body();
        assert!(body.get("field").is_none(), "{body}");
    }

    #[test]
    fn engine_errors_keep_their_code_and_data_and_add_the_message() {
        let e = ApiError::Engine {
            error: EngineError::LimitActive {
                axis: 0,
                direction: Direction::Positive,
            },
            index: Some(2),
            replies: vec![Reply::Done, Reply::Accepted { id: 4 }],
        };
        assert_eq!(e.status(), StatusCode::UNPROCESSABLE_ENTITY);
        assert_eq!(
            e.body(),
            json!({
                "code": "limit_active", "axis": 0, "direction": "positive",
                "message": "axis 0: positive limit active; motion further into it is refused",
                "index": 2,
                "replies": [{"reply": "done"}, {"reply": "accepted", "id": 4}],
            })
        );
        let e = ApiError::Engine {
            error: EngineError::AxisInError {
                axis: 1,
                faults: AxisFlags::DRIVE_ALARM | AxisFlags::ESTOP,
            },
            index: None,
            replies: vec![],
        };
        let keys: Vec<String> = e.fields().into_iter().map(|(k, _)| k).collect();
        assert_eq!(keys, ["code", "axis", "faults", "message"]);
        assert_eq!(e.body()["faults"], json!(["drive_alarm", "estop"]));
        let keys: Vec<String> = ApiError::NoTrace
            .fields()
            .into_iter()
            .map(|(k, _)| k)
            .collect();
        assert_eq!(keys, ["error", "detail"]);
    }

    #[test]
    fn a_refused_item_carries_its_list_its_place_and_its_own_error() {
        let e = ApiError::Engine {
            error: EngineError::item(
                "axes",
                1,
                EngineError::AxisInError {
                    axis: 1,
                    faults: AxisFlags::ESTOP,
                },
            ),
            index: Some(3),
            replies: vec![],
        };
        let keys: Vec<String> = e.fields().into_iter().map(|(k, _)| k).collect();
        assert_eq!(
            keys,
            ["code", "list", "item", "error", "message", "index", "replies"]
        );
        assert_eq!(
            e.body(),
            json!({
                "code": "axis_in_error", "list": "axes", "item": 1,
                "error": {
                    "code": "axis_in_error", "axis": 1, "faults": ["estop"],
                    "message": "axis 1 is in error stop (ESTOP)",
                },
                "message": "axes[1]: axis 1 is in error stop (ESTOP)",
                "index": 3, "replies": [],
            })
        );
    }

    #[test]
    fn content_types() {
        let mut h = HeaderMap::new();
        assert!(check_json_content_type(&h).is_err());
        for ok in [
            "application/json",
            "Application/JSON; charset=utf-8",
            "application/merge-patch+json",
        ] {
            h.insert(header::CONTENT_TYPE, HeaderValue::from_static(ok));
            assert!(check_json_content_type(&h).is_ok(), "{ok}");
        }
        for bad in ["text/plain", "application/x-www-form-urlencoded", "json"] {
            h.insert(header::CONTENT_TYPE, HeaderValue::from_static(bad));
            let e = check_json_content_type(&h).unwrap_err();
            assert_eq!(e.status(), StatusCode::UNSUPPORTED_MEDIA_TYPE, "{bad}");
        }
    }
}
