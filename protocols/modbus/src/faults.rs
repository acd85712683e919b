//! Fault injection: deterministic changes to what the server answers, configured at start
//! (`faults = [...]` in a transport's config) and changed at run time through the control API
//! (`POST /faults` with `{"frontend": NAME, "fault": KIND, ...}`).
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
//! | `clear` | `kind` | remove every fault, or those of one kind |

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Mutex, MutexGuard};
use std::time::Duration;

use serde::{Deserialize, Serialize};
use serde_json::{Map, Value};

use crate::counters::FaultsApplied;
use crate::pdu::Exception;
use crate::state::Framing;

/// Longest `delay`: longer than any client's timeout, short enough to stay a delay.
pub const MAX_DELAY_MS: u64 = 60_000;

/// One fault. `count: None` means until cleared; in the active list it is what remains.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
#[serde(tag = "fault", rename_all = "snake_case")]
pub enum FaultSpec {
    Delay {
        ms: u64,
        #[serde(skip_serializing_if = "Option::is_none")]
        count: Option<u32>,
    },
    NoReply {
        #[serde(skip_serializing_if = "Option::is_none")]
        count: Option<u32>,
    },
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
    Corrupt {
        /// Index into the reply frame (0 = the address byte); default the last PDU byte.
        #[serde(skip_serializing_if = "Option::is_none")]
        byte: Option<u16>,
        bit: u8,
        #[serde(skip_serializing_if = "Option::is_none")]
        count: Option<u32>,
    },
}

/// The kinds, for `{"fault": "clear", "kind": ...}`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FaultKind {
    Delay,
    NoReply,
    Exception,
    DropBytes,
    Corrupt,
}

impl FaultKind {
    const NAMES: [(&'static str, FaultKind); 5] = [
        ("delay", FaultKind::Delay),
        ("no_reply", FaultKind::NoReply),
        ("exception", FaultKind::Exception),
        ("drop_bytes", FaultKind::DropBytes),
        ("corrupt", FaultKind::Corrupt),
    ];

    fn from_name(name: &str) -> Option<FaultKind> {
        Self::NAMES
            .iter()
            .find(|(n, _)| *n == name)
            .map(|(_, k)| *k)
    }

    pub fn name(self) -> &'static str {
        Self::NAMES
            .iter()
            .find(|(_, k)| *k == self)
            .map_or("", |(n, _)| n)
    }
}

impl FaultSpec {
    pub fn kind(&self) -> FaultKind {
        match self {
            FaultSpec::Delay { .. } => FaultKind::Delay,
            FaultSpec::NoReply { .. } => FaultKind::NoReply,
            FaultSpec::Exception { .. } => FaultKind::Exception,
            FaultSpec::DropBytes { .. } => FaultKind::DropBytes,
            FaultSpec::Corrupt { .. } => FaultKind::Corrupt,
        }
    }

    fn count_mut(&mut self) -> &mut Option<u32> {
        match self {
            FaultSpec::Delay { count, .. }
            | FaultSpec::NoReply { count }
            | FaultSpec::Exception { count, .. }
            | FaultSpec::DropBytes { count, .. }
            | FaultSpec::Corrupt { count, .. } => count,
        }
    }

    /// Whether `other` takes this one's place when installed: same kind, and for exceptions
    /// the same filter (exceptions for different functions or addresses coexist).
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

/// A fault request that cannot be taken, naming the field at fault.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{message}")]
pub struct FaultError {
    /// The offending key, when one is to blame.
    pub field: Option<String>,
    pub message: String,
}

impl FaultError {
    fn field(field: &str, message: impl Into<String>) -> FaultError {
        FaultError {
            field: Some(field.to_owned()),
            message: message.into(),
        }
    }
}

/// A run-time request: install a fault or clear some.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum FaultRequest {
    Set(FaultSpec),
    /// `None`: every fault.
    Clear(Option<FaultKind>),
}

impl FaultRequest {
    /// Parse `{"fault": KIND, ...}` (the control API's body without `frontend`).
    pub fn from_json(map: &Map<String, Value>) -> Result<FaultRequest, FaultError> {
        let kind = match map.get("fault") {
            Some(Value::String(s)) => s.as_str(),
            Some(other) => {
                return Err(FaultError::field(
                    "fault",
                    format!("`fault` must be a string naming the fault, not {other}"),
                ))
            }
            None => {
                return Err(FaultError::field(
                    "fault",
                    "missing field `fault`: one of delay, no_reply, exception, drop_bytes, \
                     corrupt, clear",
                ))
            }
        };
        let allowed: &[&str] = match kind {
            "delay" => &["ms", "count"],
            "no_reply" => &["count"],
            "exception" => &["code", "function", "address", "count"],
            "drop_bytes" => &["bytes", "count"],
            "corrupt" => &["byte", "bit", "count"],
            "clear" => &["kind"],
            other => {
                return Err(FaultError::field(
                    "fault",
                    format!(
                        "unknown fault `{other}`: expected one of delay, no_reply, exception, \
                         drop_bytes, corrupt, clear"
                    ),
                ))
            }
        };
        if let Some(key) = map
            .keys()
            .find(|k| *k != "fault" && !allowed.contains(&k.as_str()))
        {
            return Err(FaultError::field(
                key,
                format!(
                    "unknown field `{key}` for fault `{kind}`; expected {}",
                    allowed.join(", ")
                ),
            ));
        }
        let count = || -> Result<Option<u32>, FaultError> {
            uint(map, "count", 1, u64::from(u32::MAX))
                .map(|c| c.map(|c| u32::try_from(c).unwrap_or(u32::MAX)))
        };
        let spec = match kind {
            "delay" => FaultSpec::Delay {
                ms: required(map, "ms", 0, MAX_DELAY_MS)?,
                count: count()?,
            },
            "no_reply" => FaultSpec::NoReply { count: count()? },
            "exception" => {
                let code = required(map, "code", 1, 255)?;
                if Exception::from_code(code as u8).is_none() {
                    return Err(FaultError::field(
                        "code",
                        format!(
                            "`code` {code} is not an exception code: 1, 2, 3, 4, 5, 6, 10 or 11"
                        ),
                    ));
                }
                FaultSpec::Exception {
                    code: code as u8,
                    function: uint(map, "function", 1, 127)?.map(|f| f as u8),
                    address: uint(map, "address", 0, 0xFFFF)?.map(|a| a as u16),
                    count: count()?,
                }
            }
            "drop_bytes" => FaultSpec::DropBytes {
                bytes: required(map, "bytes", 1, 255)? as u8,
                count: count()?,
            },
            "corrupt" => FaultSpec::Corrupt {
                byte: uint(map, "byte", 0, 255)?.map(|b| b as u16),
                bit: uint(map, "bit", 0, 7)?.unwrap_or(0) as u8,
                count: count()?,
            },
            _ => {
                // "clear"
                return match map.get("kind") {
                    None | Some(Value::Null) => Ok(FaultRequest::Clear(None)),
                    Some(Value::String(k)) => match FaultKind::from_name(k) {
                        Some(kind) => Ok(FaultRequest::Clear(Some(kind))),
                        None => Err(FaultError::field(
                            "kind",
                            format!(
                                "unknown fault kind `{k}`: expected one of delay, no_reply, \
                                 exception, drop_bytes, corrupt"
                            ),
                        )),
                    },
                    Some(other) => Err(FaultError::field(
                        "kind",
                        format!("`kind` must be a fault name, not {other}"),
                    )),
                };
            }
        };
        Ok(FaultRequest::Set(spec))
    }
}

/// An optional unsigned integer field in `min..=max`; `null` counts as absent.
fn uint(
    map: &Map<String, Value>,
    key: &str,
    min: u64,
    max: u64,
) -> Result<Option<u64>, FaultError> {
    match map.get(key) {
        None | Some(Value::Null) => Ok(None),
        Some(v) => match v.as_u64() {
            Some(n) if (min..=max).contains(&n) => Ok(Some(n)),
            _ => Err(FaultError::field(
                key,
                format!("`{key}` must be an integer from {min} to {max}, not {v}"),
            )),
        },
    }
}

fn required(map: &Map<String, Value>, key: &str, min: u64, max: u64) -> Result<u64, FaultError> {
    uint(map, key, min, max)?.ok_or_else(|| {
        FaultError::field(
            key,
            format!("missing field `{key}` (an integer from {min} to {max})"),
        )
    })
}

/// Config form: the same objects as the run-time requests (`clear` excluded), e.g.
/// `faults = [{ fault = "delay", ms = 100 }]`.
impl<'de> Deserialize<'de> for FaultSpec {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let map = Map::<String, Value>::deserialize(deserializer)?;
        match FaultRequest::from_json(&map) {
            Ok(FaultRequest::Set(spec)) => Ok(spec),
            Ok(FaultRequest::Clear(_)) => Err(serde::de::Error::custom(
                "`clear` is a run-time request, not a fault to configure",
            )),
            Err(e) => Err(serde::de::Error::custom(e.message)),
        }
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
                count}`, `{fault = \"exception\", code, function, address, count}`, and on RTU \
                framing `{fault = \"drop_bytes\", bytes, count}`, `{fault = \"corrupt\", byte, \
                bit, count}`; without `count` a fault lasts until cleared.",
            "required": ["fault"],
            "properties": {
                "fault": {
                    "type": "string",
                    "enum": ["delay", "no_reply", "exception", "drop_bytes", "corrupt"]
                }
            }
        })
    }
}

/// The active faults of one front-end.
#[derive(Debug)]
pub struct Faults {
    framing: Framing,
    /// Whether `active` is non-empty: the request path's only cost when nothing is injected.
    armed: AtomicBool,
    active: Mutex<Vec<FaultSpec>>,
}

impl Faults {
    pub fn new(framing: Framing) -> Faults {
        Faults {
            framing,
            armed: AtomicBool::new(false),
            active: Mutex::new(Vec::new()),
        }
    }

    fn lock(&self) -> MutexGuard<'_, Vec<FaultSpec>> {
        // A panic elsewhere cannot leave the list half-updated (every change is one push,
        // remove or assignment), so a poisoned lock is still good.
        self.active.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Install a fault, replacing one of the same kind (and, for exceptions, the same filter).
    pub fn install(&self, spec: FaultSpec) -> Result<(), FaultError> {
        if matches!(spec.kind(), FaultKind::DropBytes | FaultKind::Corrupt)
            && !self.framing.is_rtu()
        {
            return Err(FaultError::field(
                "fault",
                format!(
                    "`{}` changes RTU frames; this front-end uses {} framing",
                    spec.kind().name(),
                    self.framing.name()
                ),
            ));
        }
        let mut list = self.lock();
        list.retain(|f| !f.replaced_by(&spec));
        list.push(spec);
        self.armed.store(true, Ordering::Release);
        Ok(())
    }

    /// Remove every fault, or those of one kind.
    pub fn clear(&self, kind: Option<FaultKind>) {
        let mut list = self.lock();
        list.retain(|f| kind.is_some_and(|k| f.kind() != k));
        self.armed.store(!list.is_empty(), Ordering::Release);
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
        if !self.armed.load(Ordering::Acquire) {
            return Vec::new();
        }
        self.lock().clone()
    }

    /// Use up one application of the first fault for which `pick` says what to do.
    fn take<R>(&self, mut pick: impl FnMut(&FaultSpec) -> Option<R>) -> Option<R> {
        if !self.armed.load(Ordering::Acquire) {
            return None;
        }
        let mut list = self.lock();
        let (i, r) = list
            .iter()
            .enumerate()
            .find_map(|(i, f)| pick(f).map(|r| (i, r)))?;
        let count = list.get_mut(i)?.count_mut();
        match count {
            Some(n) if *n > 1 => *n -= 1,
            Some(_) => {
                list.remove(i);
            }
            None => {}
        }
        self.armed.store(!list.is_empty(), Ordering::Release);
        Some(r)
    }

    /// A `no_reply` fault swallows this request.
    pub(crate) fn take_no_reply(&self, applied: &FaultsApplied) -> bool {
        let hit = self
            .take(|f| matches!(f, FaultSpec::NoReply { .. }).then_some(()))
            .is_some();
        if hit {
            applied.no_reply.inc();
        }
        hit
    }

    /// The exception an `exception` fault forces on a request with `function` whose address
    /// range `covers` an address.
    pub(crate) fn take_exception(
        &self,
        function: u8,
        covers: impl Fn(u16) -> bool,
        applied: &FaultsApplied,
    ) -> Option<Exception> {
        let e = self.take(|f| match f {
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
        let d = self.take(|f| match f {
            FaultSpec::Delay { ms, .. } => Some(Duration::from_millis(*ms)),
            _ => None,
        })?;
        applied.delay.inc();
        Some(d)
    }

    /// Damage an RTU reply frame (address … CRC) as `corrupt` and `drop_bytes` say.
    pub(crate) fn mangle_rtu_reply(&self, frame: &mut Vec<u8>, applied: &FaultsApplied) {
        if let Some((byte, bit)) = self.take(|f| match f {
            FaultSpec::Corrupt { byte, bit, .. } => Some((*byte, *bit)),
            _ => None,
        }) {
            let last = frame.len().saturating_sub(1);
            let at = byte
                .map_or(frame.len().saturating_sub(3), usize::from)
                .min(last);
            if let Some(b) = frame.get_mut(at) {
                *b ^= 1 << (bit & 7);
            }
            applied.corrupt.inc();
        }
        if let Some(n) = self.take(|f| match f {
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
            Value::Object(map) => FaultRequest::from_json(&map),
            _ => panic!("not an object: {json}"),
        }
    }

    fn field(json: &str) -> Option<String> {
        parse(json).err().and_then(|e| e.field)
    }

    #[test]
    fn requests_parse_and_errors_name_the_field() {
        assert_eq!(
            parse(r#"{"fault":"delay","ms":200,"count":3}"#),
            Ok(FaultRequest::Set(FaultSpec::Delay {
                ms: 200,
                count: Some(3)
            }))
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
            Ok(FaultRequest::Clear(Some(FaultKind::NoReply)))
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
        f.install(FaultSpec::Delay {
            ms: 5,
            count: Some(2),
        })
        .unwrap_or(());
        f.install(FaultSpec::Delay {
            ms: 7,
            count: Some(2),
        })
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
        f.clear(Some(FaultKind::Exception));
        assert_eq!(f.take_exception(3, |_| false, &applied), None);
    }

    #[test]
    fn rtu_replies_are_damaged_and_tcp_refuses_rtu_faults() {
        let f = Faults::new(Framing::RtuOverTcp);
        let applied = FaultsApplied::default();
        f.install(FaultSpec::Corrupt {
            byte: None,
            bit: 0,
            count: Some(1),
        })
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
    fn config_form_deserializes_through_the_same_parser() {
        let v = serde_json::json!([{"fault": "no_reply", "count": 2}]);
        let specs: Result<Vec<FaultSpec>, _> = serde_json::from_value(v);
        assert_eq!(
            specs.ok(),
            Some(vec![FaultSpec::NoReply { count: Some(2) }])
        );
        let v = serde_json::json!([{"fault": "no_reply", "cuont": 2}]);
        let e = serde_json::from_value::<Vec<FaultSpec>>(v)
            .err()
            .map(|e| e.to_string());
        assert!(e.is_some_and(|m| m.contains("cuont")));
        let round =
            serde_json::to_value(FaultSpec::Delay { ms: 3, count: None }).unwrap_or_default();
        assert_eq!(round, serde_json::json!({"fault": "delay", "ms": 3}));
    }
}
