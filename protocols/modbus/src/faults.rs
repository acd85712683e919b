//! Modbus fault injection over the kit's fault list ([`mcemu_frontend::fault`]): configured at
//! start (`faults = [...]` in a transport's config) and changed at run time through the control
//! API (`POST /faults` with `{"frontend": NAME, "fault": KIND, ...}`). What is Modbus here: the
//! forced error's payload (an exception code, for a function and/or an address) and the faults
//! of RTU framing.
//!
//! Every fault applies to the next `count` matching events, or until cleared when `count` is
//! absent. Nothing is random. The server checks the fault list only while it is non-empty (one
//! atomic load otherwise), so an unfaulted server takes no lock per request.
//!
//! | fault | fields | effect |
//! |---|---|---|
//! | `delay` | `ms`, `count` | each reply waits `ms` before it is sent |
//! | `no_reply` | `count` | the request is swallowed: not executed, not answered |
//! | `exception` | `code`, `function`, `address`, `count` | answer exception `code` instead of executing, for requests with that function code and/or whose address range covers `address` (neither: every request) |
//! | `drop_bytes` | `bytes`, `count` | RTU framing only: the last `bytes` bytes of the reply are not sent |
//! | `corrupt` | `byte`, `bit`, `count` | RTU framing only: one bit of the reply is flipped (default: bit 0 of the last PDU byte), so its CRC fails |
//! | `close` | `count` | TCP and RTU over TCP: the connection is closed instead of answering; the request is not executed |
//! | `clear` | `kind` | remove every fault, or those of one kind |

use std::time::Duration;

pub use mcemu_frontend::fault::CommonFault;
use mcemu_frontend::fault::{self, parse_request, Common, Fault, FaultList, Parsed};
use serde::{Deserialize, Serialize};
use serde_json::{Map, Value};

pub use mcemu_frontend::fault::{FaultError, MAX_DELAY_MS};

use crate::counters::FaultsApplied;
use crate::framing::Framing;
use crate::pdu::Exception;

/// One fault. `count: None` means until cleared; in the active list it is what remains.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
#[serde(tag = "fault", rename_all = "snake_case")]
pub enum FaultSpec {
    Exception {
        code: u8,
        #[serde(skip_serializing_if = "Option::is_none")]
        function: Option<u8>,
        #[serde(skip_serializing_if = "Option::is_none")]
        address: Option<u16>,
        #[serde(skip_serializing_if = "Option::is_none")]
        count: Option<u32>,
    },
    DropBytes {
        bytes: u8,
        #[serde(skip_serializing_if = "Option::is_none")]
        count: Option<u32>,
    },
    /// `delay`, `no_reply`, `corrupt` (its `byte` indexes the reply frame, 0 = the address
    /// byte; default the last PDU byte) and `close`.
    #[serde(untagged)]
    Common(CommonFault),
}

/// Modbus's kinds and their fields, in the order error messages list them.
const KINDS: [(&str, &[&str]); 6] = [
    fault::DELAY,
    fault::NO_REPLY,
    ("exception", &["code", "function", "address", "count"]),
    ("drop_bytes", &["bytes", "count"]),
    fault::CORRUPT,
    fault::CLOSE,
];

impl Fault for FaultSpec {
    fn kind(&self) -> &'static str {
        match self {
            FaultSpec::Exception { .. } => "exception",
            FaultSpec::DropBytes { .. } => "drop_bytes",
            FaultSpec::Common(c) => c.kind(),
        }
    }

    fn count_mut(&mut self) -> &mut Option<u32> {
        match self {
            FaultSpec::Exception { count, .. } | FaultSpec::DropBytes { count, .. } => count,
            FaultSpec::Common(c) => c.count_mut(),
        }
    }

    fn common(&self) -> Option<Common> {
        match self {
            FaultSpec::Common(c) => Some(c.effect()),
            FaultSpec::Exception { .. } | FaultSpec::DropBytes { .. } => None,
        }
    }

    /// Exceptions for different functions or addresses coexist; otherwise one per kind.
    fn replaced_by(&self, other: &FaultSpec) -> bool {
        match (self, other) {
            (
                FaultSpec::Exception {
                    function: f1,
                    address: a1,
                    ..
                },
                FaultSpec::Exception {
                    function: f2,
                    address: a2,
                    ..
                },
            ) => f1 == f2 && a1 == a2,
            _ => self.kind() == other.kind(),
        }
    }
}

/// A run-time request: install a fault or clear some (`None`: every fault).
pub type FaultRequest = fault::FaultRequest<FaultSpec>;

/// Parse `{"fault": KIND, ...}` (the control API's body without `frontend`).
pub fn parse(map: &Map<String, Value>) -> Result<FaultRequest, FaultError> {
    let (kind, f) = match parse_request(map, &KINDS)? {
        Parsed::Clear(kind) => return Ok(FaultRequest::Clear(kind)),
        Parsed::Set { kind, fields } => (kind, fields),
    };
    if let Some(c) = f.common(kind)? {
        return Ok(FaultRequest::Set(FaultSpec::Common(c)));
    }
    let spec = match kind {
        "exception" => {
            let code = f.required("code", 1, 255)?;
            if Exception::from_code(code as u8).is_none() {
                return Err(FaultError::field(
                    "code",
                    format!("`code` {code} is not an exception code: 1, 2, 3, 4, 5, 6, 10 or 11"),
                ));
            }
            FaultSpec::Exception {
                code: code as u8,
                function: f.uint("function", 1, 127)?.map(|f| f as u8),
                address: f.uint("address", 0, 0xFFFF)?.map(|a| a as u16),
                count: f.count()?,
            }
        }
        _ => FaultSpec::DropBytes {
            bytes: f.required("bytes", 1, 255)? as u8,
            count: f.count()?,
        },
    };
    Ok(FaultRequest::Set(spec))
}

/// Config form: the same objects as the run-time requests (`clear` excluded), e.g.
/// `faults = [{ fault = "delay", ms = 100 }]`.
impl<'de> Deserialize<'de> for FaultSpec {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        fault::deserialize_config(deserializer, parse)
    }
}

#[cfg(feature = "schema")]
impl schemars::JsonSchema for FaultSpec {
    fn schema_name() -> std::borrow::Cow<'static, str> {
        "FaultSpec".into()
    }

    fn json_schema(_: &mut schemars::SchemaGenerator) -> schemars::Schema {
        schemars::json_schema!({
            "type": "object",
            "description": "A fault: `{fault = \"delay\", ms, count}`, `{fault = \"no_reply\", \
                count}`, `{fault = \"exception\", code, function, address, count}`, on TCP \
                connections `{fault = \"close\", count}`, and on RTU framing \
                `{fault = \"drop_bytes\", bytes, count}`, `{fault = \"corrupt\", byte, bit, \
                count}`; without `count` a fault lasts until cleared.",
            "required": ["fault"],
            "properties": {
                "fault": {
                    "type": "string",
                    "enum": ["delay", "no_reply", "exception", "drop_bytes", "corrupt", "close"]
                }
            }
        })
    }
}

/// The active faults of one front-end.
#[derive(Debug)]
pub struct Faults {
    framing: Framing,
    list: FaultList<FaultSpec>,
}

impl Faults {
    pub fn new(framing: Framing) -> Faults {
        Faults {
            framing,
            list: FaultList::default(),
        }
    }

    /// Install a fault, replacing one of the same kind (and, for exceptions, the same filter).
    pub fn install(&self, spec: FaultSpec) -> Result<(), FaultError> {
        let kind = spec.kind();
        if matches!(
            spec,
            FaultSpec::DropBytes { .. } | FaultSpec::Common(CommonFault::Corrupt { .. })
        ) && !self.framing.is_rtu()
        {
            return Err(FaultError::field(
                "fault",
                format!(
                    "`{kind}` changes RTU frames; this front-end uses {} framing",
                    self.framing.name()
                ),
            ));
        }
        if matches!(spec, FaultSpec::Common(CommonFault::Close { .. }))
            && self.framing == Framing::Rtu
        {
            return Err(FaultError::field(
                "fault",
                "`close` closes a TCP connection; a serial line has none",
            ));
        }
        self.list.install(spec);
        Ok(())
    }

    /// Remove every fault, or those of one kind.
    pub fn clear(&self, kind: Option<&str>) {
        self.list.clear(kind);
    }

    /// Apply a run-time request; the answer is the list of active faults.
    pub fn apply(&self, request: FaultRequest) -> Result<Vec<FaultSpec>, FaultError> {
        match request {
            FaultRequest::Set(spec) => self.install(spec)?,
            FaultRequest::Clear(kind) => self.clear(kind),
        }
        Ok(self.active())
    }

    pub fn active(&self) -> Vec<FaultSpec> {
        self.list.active()
    }

    /// A `no_reply` fault swallows this request.
    pub(crate) fn take_no_reply(&self, applied: &FaultsApplied) -> bool {
        self.list.take_no_reply(&applied.no_reply)
    }

    /// A `close` fault closes the connection instead of answering this request.
    pub(crate) fn take_close(&self, applied: &FaultsApplied) -> bool {
        self.list.take_close(&applied.close)
    }

    /// The exception an `exception` fault forces on a request with `function` whose address
    /// range `covers` an address.
    pub(crate) fn take_exception(
        &self,
        function: u8,
        covers: impl Fn(u16) -> bool,
        applied: &FaultsApplied,
    ) -> Option<Exception> {
        let e = self.list.take(|f| match f {
            FaultSpec::Exception {
                code,
                function: f,
                address,
                ..
            } if f.is_none_or(|f| f == function) && address.is_none_or(&covers) => {
                Exception::from_code(*code)
            }
            _ => None,
        })?;
        applied.exception.inc();
        Some(e)
    }

    /// How long this reply waits.
    pub(crate) fn take_delay(&self, applied: &FaultsApplied) -> Option<Duration> {
        self.list.take_delay(&applied.delay)
    }

    /// Damage an RTU reply frame (address … CRC) as `corrupt` and `drop_bytes` say.
    pub(crate) fn mangle_rtu_reply(&self, frame: &mut Vec<u8>, applied: &FaultsApplied) {
        if let Some((byte, bit)) = self.list.take_corrupt(&applied.corrupt) {
            // By default the last PDU byte: the CRC's two bytes follow it.
            let last_pdu_byte = frame.len().saturating_sub(3);
            fault::flip_bit(frame, byte, bit, last_pdu_byte);
        }
        if let Some(n) = self.list.take(|f| match f {
            FaultSpec::DropBytes { bytes, .. } => Some(*bytes),
            _ => None,
        }) {
            frame.truncate(frame.len().saturating_sub(usize::from(n)));
            applied.drop_bytes.inc();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(json: &str) -> Result<FaultRequest, FaultError> {
        let v: Value = serde_json::from_str(json).unwrap_or(Value::Null);
        match v {
            Value::Object(map) => super::parse(&map),
            _ => panic!("not an object: {json}"),
        }
    }

    fn parse_json(json: &str) -> Result<FaultRequest, FaultError> {
        parse(json)
    }

    fn field(json: &str) -> Option<String> {
        parse(json).err().and_then(|e| e.field)
    }

    #[test]
    fn requests_parse_and_errors_name_the_field() {
        assert_eq!(
            parse(r#"{"fault":"delay","ms":200,"count":3}"#),
            Ok(FaultRequest::Set(FaultSpec::Common(CommonFault::Delay {
                ms: 200,
                count: Some(3)
            })))
        );
        assert_eq!(
            parse(r#"{"fault":"exception","code":4}"#),
            Ok(FaultRequest::Set(FaultSpec::Exception {
                code: 4,
                function: None,
                address: None,
                count: None
            }))
        );
        assert_eq!(parse(r#"{"fault":"clear"}"#), Ok(FaultRequest::Clear(None)));
        assert_eq!(
            parse(r#"{"fault":"clear","kind":"no_reply"}"#),
            Ok(FaultRequest::Clear(Some("no_reply")))
        );
        assert_eq!(field(r#"{"fault":"delay"}"#).as_deref(), Some("ms"));
        assert_eq!(field(r#"{"fault":"delay","ms":-1}"#).as_deref(), Some("ms"));
        assert_eq!(
            field(r#"{"fault":"delay","ms":1,"cnt":1}"#).as_deref(),
            Some("cnt")
        );
        assert_eq!(
            field(r#"{"fault":"delay","ms":1,"count":0}"#).as_deref(),
            Some("count")
        );
        assert_eq!(
            field(r#"{"fault":"exception","code":9}"#).as_deref(),
            Some("code")
        );
        assert_eq!(
            field(r#"{"fault":"exception","code":2,"function":300}"#).as_deref(),
            Some("function")
        );
        assert_eq!(
            field(r#"{"fault":"corrupt","bit":8}"#).as_deref(),
            Some("bit")
        );
        assert_eq!(field(r#"{"fault":"explode"}"#).as_deref(), Some("fault"));
        assert_eq!(field(r#"{"ms":1}"#).as_deref(), Some("fault"));
        assert_eq!(
            field(r#"{"fault":"clear","kind":"all"}"#).as_deref(),
            Some("kind")
        );
        let e = parse(r#"{"fault":"delay","ms":"soon"}"#)
            .err()
            .map(|e| e.message);
        assert!(e.is_some_and(|m| m.contains("`ms`")));
    }

    #[test]
    fn counts_run_out_and_kinds_replace_each_other() {
        let f = Faults::new(Framing::Rtu);
        let applied = FaultsApplied::default();
        assert_eq!(f.take_delay(&applied), None);
        f.install(FaultSpec::Common(CommonFault::Delay {
            ms: 5,
            count: Some(2),
        }))
        .unwrap_or(());
        f.install(FaultSpec::Common(CommonFault::Delay {
            ms: 7,
            count: Some(2),
        }))
        .unwrap_or(());
        assert_eq!(f.active().len(), 1, "a second delay replaces the first");
        assert_eq!(f.take_delay(&applied), Some(Duration::from_millis(7)));
        assert_eq!(f.take_delay(&applied), Some(Duration::from_millis(7)));
        assert_eq!(f.take_delay(&applied), None);
        assert_eq!(applied.delay.get(), 2);
        assert!(f.active().is_empty());

        f.install(FaultSpec::Exception {
            code: 4,
            function: Some(3),
            address: None,
            count: None,
        })
        .unwrap_or(());
        f.install(FaultSpec::Exception {
            code: 6,
            function: None,
            address: Some(100),
            count: Some(1),
        })
        .unwrap_or(());
        assert_eq!(f.active().len(), 2, "different filters coexist");
        assert_eq!(f.take_exception(6, |a| a == 5, &applied), None);
        assert_eq!(
            f.take_exception(6, |a| (99..=101).contains(&a), &applied),
            Some(Exception::ServerDeviceBusy)
        );
        assert_eq!(
            f.take_exception(6, |a| a == 100, &applied),
            None,
            "count used up"
        );
        assert_eq!(
            f.take_exception(3, |_| false, &applied),
            Some(Exception::ServerDeviceFailure)
        );
        assert_eq!(
            f.take_exception(3, |_| false, &applied),
            Some(Exception::ServerDeviceFailure)
        );
        f.clear(Some("exception"));
        assert_eq!(f.take_exception(3, |_| false, &applied), None);
    }

    #[test]
    fn rtu_replies_are_damaged_and_tcp_refuses_rtu_faults() {
        let f = Faults::new(Framing::RtuOverTcp);
        let applied = FaultsApplied::default();
        f.install(FaultSpec::Common(CommonFault::Corrupt {
            byte: None,
            bit: 0,
            count: Some(1),
        }))
        .unwrap_or(());
        f.install(FaultSpec::DropBytes {
            bytes: 2,
            count: Some(1),
        })
        .unwrap_or(());
        let mut frame = vec![1, 3, 2, 0, 7, 0xAA, 0xBB];
        f.mangle_rtu_reply(&mut frame, &applied);
        assert_eq!(
            frame,
            [1, 3, 2, 0, 6],
            "bit 0 of the last PDU byte, then 2 bytes dropped"
        );
        let mut frame = vec![1, 3, 2, 0, 7, 0xAA, 0xBB];
        f.mangle_rtu_reply(&mut frame, &applied);
        assert_eq!(frame, [1, 3, 2, 0, 7, 0xAA, 0xBB], "counts used up");
        assert_eq!((applied.corrupt.get(), applied.drop_bytes.get()), (1, 1));

        let tcp = Faults::new(Framing::Tcp);
        let e = tcp.install(FaultSpec::DropBytes {
            bytes: 1,
            count: None,
        });
        assert_eq!(e.err().and_then(|e| e.field).as_deref(), Some("fault"));
    }

    #[test]
    fn close_needs_a_connection_and_is_used_up_like_the_others() {
        let applied = FaultsApplied::default();
        let serial = Faults::new(Framing::Rtu);
        let e = serial.install(FaultSpec::Common(CommonFault::Close { count: None }));
        assert_eq!(e.err().and_then(|e| e.field).as_deref(), Some("fault"));
        let tcp = Faults::new(Framing::Tcp);
        assert_eq!(
            parse_json(r#"{"fault":"close","count":2}"#),
            Ok(FaultRequest::Set(FaultSpec::Common(CommonFault::Close {
                count: Some(2)
            })))
        );
        assert_eq!(
            parse_json(r#"{"fault":"clear","kind":"close"}"#),
            Ok(FaultRequest::Clear(Some("close")))
        );
        tcp.install(FaultSpec::Common(CommonFault::Close { count: Some(2) }))
            .unwrap_or(());
        assert!(tcp.take_close(&applied));
        assert!(!tcp.take_no_reply(&applied), "close is not no_reply");
        assert!(tcp.take_close(&applied));
        assert!(!tcp.take_close(&applied), "count used up");
        assert_eq!(applied.close.get(), 2);
        let rtu_over_tcp = Faults::new(Framing::RtuOverTcp);
        assert!(rtu_over_tcp
            .install(FaultSpec::Common(CommonFault::Close { count: None }))
            .is_ok());
    }

    #[test]
    fn config_form_deserializes_through_the_same_parser() {
        let v = serde_json::json!([{"fault": "no_reply", "count": 2}]);
        let specs: Result<Vec<FaultSpec>, _> = serde_json::from_value(v);
        assert_eq!(
            specs.ok(),
            Some(vec![FaultSpec::Common(CommonFault::NoReply {
                count: Some(2)
            })])
        );
        let v = serde_json::json!([{"fault": "no_reply", "cuont": 2}]);
        let e = serde_json::from_value::<Vec<FaultSpec>>(v)
            .err()
            .map(|e| e.to_string());
        assert!(e.is_some_and(|m| m.contains("cuont")));
        let round =
            serde_json::to_value(FaultSpec::Common(CommonFault::Delay { ms: 3, count: None }))
                .unwrap_or_default();
        assert_eq!(round, serde_json::json!({"fault": "delay", "ms": 3}));
    }
}
