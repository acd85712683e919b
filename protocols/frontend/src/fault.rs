//! Fault injection for request/response front-ends: a list of faults, each for the next `count`
//! matching events or until cleared, configured at start (`faults = [...]`) and changed at run
//! time through the control API (`POST /faults` with `{"frontend": NAME, "fault": KIND, ...}`).
//! Nothing is random. The list is checked only while it is non-empty (one atomic load
//! otherwise), so an unfaulted front-end takes no lock per request.
//!
//! The kit knows the kinds every request/response protocol has ([`Common`]: `delay`,
//! `no_reply`, `close`, `corrupt`), parses requests ([`parse_request`], [`Fields`]) and keeps
//! the list ([`FaultList`]); a protocol's own enum of faults (its forced error's payload, its
//! framing's faults) implements [`Fault`], so its JSON stays its own.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Mutex, MutexGuard};
use std::time::Duration;

use serde_json::{Map, Value};

use crate::counter::Counter;

/// Longest `delay`: longer than any client's timeout, short enough to stay a delay.
pub const MAX_DELAY_MS: u64 = 60_000;

/// The fields of the common kinds, for [`parse_request`]'s table.
pub const DELAY: (&str, &[&str]) = ("delay", &["ms", "count"]);
pub const NO_REPLY: (&str, &[&str]) = ("no_reply", &["count"]);
pub const CLOSE: (&str, &[&str]) = ("close", &["count"]);
pub const CORRUPT: (&str, &[&str]) = ("corrupt", &["byte", "bit", "count"]);

/// What a fault of a common kind does, whatever the protocol.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Common {
    /// The reply waits this long before it is sent.
    Delay(Duration),
    /// The request is swallowed: not executed, not answered.
    NoReply,
    /// The connection is closed instead of answering; the request is not executed.
    Close,
    /// One bit of the reply is flipped: bit `bit` of byte `byte` (the protocol's default byte
    /// when `None`).
    Corrupt { byte: Option<u16>, bit: u8 },
}

/// A fault of a common kind with its count, which a protocol's enum of faults carries as its
/// last variant, `#[serde(untagged)] Common(CommonFault)`: its JSON is the kind's own
/// (`{"fault": "delay", "ms": 100, "count": 2}`), and [`Fields::common`] parses it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(tag = "fault", rename_all = "snake_case")]
pub enum CommonFault {
    Delay {
        ms: u64,
        #[serde(skip_serializing_if = "Option::is_none")]
        count: Option<u32>,
    },
    NoReply {
        #[serde(skip_serializing_if = "Option::is_none")]
        count: Option<u32>,
    },
    Close {
        #[serde(skip_serializing_if = "Option::is_none")]
        count: Option<u32>,
    },
    Corrupt {
        /// Index into the reply frame; `None`: the protocol's default byte.
        #[serde(skip_serializing_if = "Option::is_none")]
        byte: Option<u16>,
        bit: u8,
        #[serde(skip_serializing_if = "Option::is_none")]
        count: Option<u32>,
    },
}

impl CommonFault {
    /// For [`Fault::kind`].
    pub fn kind(&self) -> &'static str {
        match self {
            CommonFault::Delay { .. } => "delay",
            CommonFault::NoReply { .. } => "no_reply",
            CommonFault::Close { .. } => "close",
            CommonFault::Corrupt { .. } => "corrupt",
        }
    }

    /// For [`Fault::count_mut`].
    pub fn count_mut(&mut self) -> &mut Option<u32> {
        match self {
            CommonFault::Delay { count, .. }
            | CommonFault::NoReply { count }
            | CommonFault::Close { count }
            | CommonFault::Corrupt { count, .. } => count,
        }
    }

    /// For [`Fault::common`]: what it does.
    pub fn effect(&self) -> Common {
        match *self {
            CommonFault::Delay { ms, .. } => Common::Delay(Duration::from_millis(ms)),
            CommonFault::NoReply { .. } => Common::NoReply,
            CommonFault::Close { .. } => Common::Close,
            CommonFault::Corrupt { byte, bit, .. } => Common::Corrupt { byte, bit },
        }
    }
}

/// One kind of fault of a protocol, as its front-end lists it.
pub trait Fault: Clone {
    /// The kind's name, as `fault` (and `clear`'s `kind`) names it.
    fn kind(&self) -> &'static str;
    /// How many more times it applies; `None`: until cleared.
    fn count_mut(&mut self) -> &mut Option<u32>;
    /// What it does, when it is of a common kind.
    fn common(&self) -> Option<Common>;
    /// Whether `other` takes this one's place when installed; by default, one of each kind.
    fn replaced_by(&self, other: &Self) -> bool {
        self.kind() == other.kind()
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
    pub fn field(field: &str, message: impl Into<String>) -> FaultError {
        FaultError {
            field: Some(field.to_owned()),
            message: message.into(),
        }
    }
}

/// A run-time request: install a fault or clear some.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum FaultRequest<F> {
    Set(F),
    /// Clear faults of this kind; `None`: every fault.
    Clear(Option<&'static str>),
}

/// The fields of a request for one kind, checked against the kind's list.
pub struct Fields<'a> {
    map: &'a Map<String, Value>,
}

/// What [`parse_request`] found.
pub enum Parsed<'a> {
    /// Install a fault of `kind` (one of the table's names) with these fields.
    Set {
        kind: &'static str,
        fields: Fields<'a>,
    },
    Clear(Option<&'static str>),
}

/// Parse `{"fault": KIND, ...}` (the control API's body without `frontend`) against `kinds`
/// (name, allowed fields): the kind is known and no field is foreign to it; `clear` (with an
/// optional `kind`) is always known.
pub fn parse_request<'a>(
    map: &'a Map<String, Value>,
    kinds: &[(&'static str, &'static [&'static str])],
) -> Result<Parsed<'a>, FaultError> {
    let names: Vec<&str> = kinds.iter().map(|(n, _)| *n).collect();
    let names = names.join(", ");
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
                format!("missing field `fault`: one of {names}, clear"),
            ))
        }
    };
    let (kind, allowed): (&'static str, &[&str]) = match kinds.iter().find(|(n, _)| *n == kind) {
        Some((name, fields)) => (name, fields),
        None if kind == "clear" => ("clear", &["kind"]),
        None => {
            return Err(FaultError::field(
                "fault",
                format!("unknown fault `{kind}`: expected one of {names}, clear"),
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
    if kind != "clear" {
        return Ok(Parsed::Set {
            kind,
            fields: Fields { map },
        });
    }
    match map.get("kind") {
        None | Some(Value::Null) => Ok(Parsed::Clear(None)),
        Some(Value::String(k)) => match kinds.iter().find(|(n, _)| n == k) {
            Some((name, _)) => Ok(Parsed::Clear(Some(name))),
            None => Err(FaultError::field(
                "kind",
                format!("unknown fault kind `{k}`: expected one of {names}"),
            )),
        },
        Some(other) => Err(FaultError::field(
            "kind",
            format!("`kind` must be a fault name, not {other}"),
        )),
    }
}

impl Fields<'_> {
    /// An optional unsigned integer field in `min..=max`; `null` counts as absent.
    pub fn uint(&self, key: &str, min: u64, max: u64) -> Result<Option<u64>, FaultError> {
        match self.map.get(key) {
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

    /// A required unsigned integer field in `min..=max`.
    pub fn required(&self, key: &str, min: u64, max: u64) -> Result<u64, FaultError> {
        self.uint(key, min, max)?.ok_or_else(|| {
            FaultError::field(
                key,
                format!("missing field `{key}` (an integer from {min} to {max})"),
            )
        })
    }

    /// `count`: how many times the fault applies (absent: until cleared).
    pub fn count(&self) -> Result<Option<u32>, FaultError> {
        self.uint("count", 1, u64::from(u32::MAX))
            .map(|c| c.map(|c| u32::try_from(c).unwrap_or(u32::MAX)))
    }

    /// `delay`'s `ms`.
    pub fn delay_ms(&self) -> Result<u64, FaultError> {
        self.required("ms", 0, MAX_DELAY_MS)
    }

    /// `corrupt`'s `byte` (absent: the protocol's default) and `bit` (default 0).
    pub fn corrupt_at(&self) -> Result<(Option<u16>, u8), FaultError> {
        let byte = self.uint("byte", 0, 255)?.map(|b| b as u16);
        let bit = self.uint("bit", 0, 7)?.unwrap_or(0) as u8;
        Ok((byte, bit))
    }

    /// The fault of `kind` when it is a common kind (`None`: one of the protocol's own).
    pub fn common(&self, kind: &str) -> Result<Option<CommonFault>, FaultError> {
        let count = || self.count();
        Ok(Some(match kind {
            "delay" => CommonFault::Delay {
                ms: self.delay_ms()?,
                count: count()?,
            },
            "no_reply" => CommonFault::NoReply { count: count()? },
            "close" => CommonFault::Close { count: count()? },
            "corrupt" => {
                let (byte, bit) = self.corrupt_at()?;
                CommonFault::Corrupt {
                    byte,
                    bit,
                    count: count()?,
                }
            }
            _ => return Ok(None),
        }))
    }
}

/// The config form of a protocol's faults: the same objects as the run-time requests, `clear`
/// excluded (`faults = [{ fault = "delay", ms = 100 }]`); for its `Deserialize`.
pub fn deserialize_config<'de, D, F>(
    deserializer: D,
    parse: impl FnOnce(&Map<String, Value>) -> Result<FaultRequest<F>, FaultError>,
) -> Result<F, D::Error>
where
    D: serde::Deserializer<'de>,
{
    use serde::de::Error as _;
    use serde::Deserialize as _;
    let map = Map::<String, Value>::deserialize(deserializer)?;
    match parse(&map) {
        Ok(FaultRequest::Set(spec)) => Ok(spec),
        Ok(FaultRequest::Clear(_)) => Err(D::Error::custom(
            "`clear` is a run-time request, not a fault to configure",
        )),
        Err(e) => Err(D::Error::custom(e.message)),
    }
}

/// The active faults of one front-end.
///
/// Inputs: [`FaultList::install`] / [`FaultList::clear`] (or [`FaultList::apply`] of a parsed
/// request) from the control API or the config, any time; [`FaultList::take`] (or one of the
/// `take_*` of the common kinds) from the request path, once per event a fault could change.
/// Outputs: what the taken fault says to do, and [`FaultList::active`] for `GET /state`.
#[derive(Debug)]
pub struct FaultList<F> {
    /// Whether `active` is non-empty: the request path's only cost when nothing is injected.
    armed: AtomicBool,
    active: Mutex<Vec<F>>,
}

impl<F> Default for FaultList<F> {
    fn default() -> Self {
        FaultList {
            armed: AtomicBool::new(false),
            active: Mutex::new(Vec::new()),
        }
    }
}

impl<F: Fault> FaultList<F> {
    fn lock(&self) -> MutexGuard<'_, Vec<F>> {
        // A panic elsewhere cannot leave the list half-updated (every change is one push,
        // remove or assignment), so a poisoned lock is still good.
        self.active.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Install a fault, replacing those it replaces ([`Fault::replaced_by`]).
    pub fn install(&self, spec: F) {
        let mut list = self.lock();
        list.retain(|f| !f.replaced_by(&spec));
        list.push(spec);
        self.armed.store(true, Ordering::Release);
    }

    /// Remove every fault, or those of one kind.
    pub fn clear(&self, kind: Option<&str>) {
        let mut list = self.lock();
        list.retain(|f| kind.is_some_and(|k| f.kind() != k));
        self.armed.store(!list.is_empty(), Ordering::Release);
    }

    /// Apply a run-time request (already checked by the protocol); the answer is the list of
    /// active faults.
    pub fn apply(&self, request: FaultRequest<F>) -> Vec<F> {
        match request {
            FaultRequest::Set(spec) => self.install(spec),
            FaultRequest::Clear(kind) => self.clear(kind),
        }
        self.active()
    }

    pub fn active(&self) -> Vec<F> {
        if !self.armed.load(Ordering::Acquire) {
            return Vec::new();
        }
        self.lock().clone()
    }

    /// Use up one application of the first fault for which `pick` says what to do.
    pub fn take<R>(&self, mut pick: impl FnMut(&F) -> Option<R>) -> Option<R> {
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

    /// Use up one application of the first fault of a common kind for which `pick` says what
    /// to do, counting it in `applied`.
    fn take_common<R>(&self, applied: &Counter, pick: impl Fn(Common) -> Option<R>) -> Option<R> {
        let r = self.take(|f| f.common().and_then(&pick))?;
        applied.inc();
        Some(r)
    }

    /// How long this reply waits (`delay`).
    pub fn take_delay(&self, applied: &Counter) -> Option<Duration> {
        self.take_common(applied, |c| match c {
            Common::Delay(d) => Some(d),
            _ => None,
        })
    }

    /// Whether a `no_reply` fault swallows this request.
    pub fn take_no_reply(&self, applied: &Counter) -> bool {
        self.take_common(applied, |c| (c == Common::NoReply).then_some(()))
            .is_some()
    }

    /// Whether a `close` fault closes the connection instead of answering this request.
    pub fn take_close(&self, applied: &Counter) -> bool {
        self.take_common(applied, |c| (c == Common::Close).then_some(()))
            .is_some()
    }

    /// Where a `corrupt` fault flips a bit of this reply: (byte, bit).
    pub fn take_corrupt(&self, applied: &Counter) -> Option<(Option<u16>, u8)> {
        self.take_common(applied, |c| match c {
            Common::Corrupt { byte, bit } => Some((byte, bit)),
            _ => None,
        })
    }
}

/// Flip bit `bit` of byte `byte` of `reply` (clamped to its last byte); `byte` `None`:
/// `default_byte`.
pub fn flip_bit(reply: &mut [u8], byte: Option<u16>, bit: u8, default_byte: usize) {
    let last = reply.len().saturating_sub(1);
    let at = byte.map_or(default_byte, usize::from).min(last);
    if let Some(b) = reply.get_mut(at) {
        *b ^= 1 << (bit & 7);
    }
}
