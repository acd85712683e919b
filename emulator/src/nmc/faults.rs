//! The NMC front-end's faults (issue 13 "server-side faults"), installed at run time through
//! the control API (`POST /api/v1/faults {"frontend": "nmc", "fault": KIND, …}`) on the kit's
//! `FaultList`: the common `delay`, `no_reply`, `close` and `corrupt` (a bit of the reply
//! frame flipped; by default in the magic, which makes it a garbage frame), and
//! `wrong_sequence` (the reply carries the next sequence number, so the library never sees its
//! own). Each applies to the next `count` requests, or until cleared; the library answers every
//! one with the communication error (−1) after its timeout or at once, and reconnects.

use std::time::Duration;

use mcemu_frontend::counter::Counter;
use mcemu_frontend::fault::{
    self, parse_request, Common, CommonFault, Fault, FaultError, FaultList, FaultRequest, Parsed,
};
use serde::Serialize;
use serde_json::{Map, Value};

#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
#[serde(tag = "fault", rename_all = "snake_case")]
pub enum NmcFault {
    WrongSequence {
        #[serde(skip_serializing_if = "Option::is_none")]
        count: Option<u32>,
    },
    /// `delay`, `no_reply`, `close`, `corrupt`.
    #[serde(untagged)]
    Common(CommonFault),
}

const KINDS: [(&str, &[&str]); 5] = [
    fault::DELAY,
    fault::NO_REPLY,
    fault::CLOSE,
    fault::CORRUPT,
    ("wrong_sequence", &["count"]),
];

impl Fault for NmcFault {
    fn kind(&self) -> &'static str {
        match self {
            NmcFault::WrongSequence { .. } => "wrong_sequence",
            NmcFault::Common(c) => c.kind(),
        }
    }

    fn count_mut(&mut self) -> &mut Option<u32> {
        match self {
            NmcFault::WrongSequence { count } => count,
            NmcFault::Common(c) => c.count_mut(),
        }
    }

    fn common(&self) -> Option<Common> {
        match self {
            NmcFault::WrongSequence { .. } => None,
            NmcFault::Common(c) => Some(c.effect()),
        }
    }
}

/// Parse `{"fault": KIND, ...}` (the control API's body without `frontend`).
pub fn parse(map: &Map<String, Value>) -> Result<FaultRequest<NmcFault>, FaultError> {
    let (kind, f) = match parse_request(map, &KINDS)? {
        Parsed::Clear(kind) => return Ok(FaultRequest::Clear(kind)),
        Parsed::Set { kind, fields } => (kind, fields),
    };
    let spec = match f.common(kind)? {
        Some(c) => NmcFault::Common(c),
        None => NmcFault::WrongSequence { count: f.count()? },
    };
    Ok(FaultRequest::Set(spec))
}

/// The section's faults and how often each kind applied.
#[derive(Debug, Default)]
pub struct NmcFaults {
    pub list: FaultList<NmcFault>,
    pub delayed: Counter,
    pub swallowed: Counter,
    pub closed: Counter,
    pub corrupted: Counter,
    pub wrong_sequence: Counter,
}

/// What the faults do to one request.
#[derive(Debug, Default, PartialEq)]
pub struct Applied {
    /// Close the connection instead of serving the request.
    pub close: bool,
    /// Serve it but send nothing.
    pub no_reply: bool,
    pub delay: Option<Duration>,
    /// Flip this bit of the reply frame: (byte, bit).
    pub corrupt: Option<(Option<u16>, u8)>,
    /// Answer with the next sequence number.
    pub wrong_sequence: bool,
}

impl NmcFaults {
    /// The faults that apply to the next request (each used up once).
    pub fn take(&self) -> Applied {
        if self.list.take_close(&self.closed) {
            return Applied {
                close: true,
                ..Applied::default()
            };
        }
        if self.list.take_no_reply(&self.swallowed) {
            return Applied {
                no_reply: true,
                ..Applied::default()
            };
        }
        let wrong_sequence = self
            .list
            .take(|f| matches!(f, NmcFault::WrongSequence { .. }).then_some(()))
            .is_some();
        if wrong_sequence {
            self.wrong_sequence.inc();
        }
        Applied {
            close: false,
            no_reply: false,
            delay: self.list.take_delay(&self.delayed),
            corrupt: self.list.take_corrupt(&self.corrupted),
            wrong_sequence,
        }
    }

    /// How often each kind applied, for `GET /state`.
    pub fn applied(&self) -> Value {
        serde_json::json!({
            "delay": self.delayed.get(),
            "no_reply": self.swallowed.get(),
            "close": self.closed.get(),
            "corrupt": self.corrupted.get(),
            "wrong_sequence": self.wrong_sequence.get(),
        })
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn request(v: Value) -> FaultRequest<NmcFault> {
        parse(v.as_object().unwrap()).unwrap()
    }

    #[test]
    fn faults_parse_apply_and_count_down() {
        let f = NmcFaults::default();
        f.list.apply(request(
            serde_json::json!({"fault": "wrong_sequence", "count": 1}),
        ));
        f.list
            .apply(request(serde_json::json!({"fault": "delay", "ms": 5})));
        assert_eq!(
            serde_json::to_value(f.list.active()).unwrap(),
            serde_json::json!([
                {"fault": "wrong_sequence", "count": 1},
                {"fault": "delay", "ms": 5},
            ]),
            "each kind's own JSON"
        );
        let a = f.take();
        assert!(a.wrong_sequence);
        assert_eq!(a.delay, Some(Duration::from_millis(5)));
        let b = f.take();
        assert!(!b.wrong_sequence, "count 1 is used up");
        f.list.apply(request(serde_json::json!({"fault": "clear"})));
        assert_eq!(f.take(), Applied::default());
        f.list
            .apply(request(serde_json::json!({"fault": "close", "count": 1})));
        assert!(f.take().close);
        assert_eq!(f.closed.get(), 1);
        assert!(parse(
            serde_json::json!({"fault": "exception"})
                .as_object()
                .unwrap()
        )
        .is_err());
    }
}
