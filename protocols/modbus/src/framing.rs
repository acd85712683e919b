//! How requests reach a Modbus front-end: a leaf type that the state, the faults and the
//! transports all name.

use serde::{Deserialize, Serialize};

/// How requests are framed, which decides unit-id semantics: on RTU framing unit 0 is a
/// broadcast and unserved units are ignored; on TCP every unit id is answered.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Framing {
    Tcp,
    Rtu,
    RtuOverTcp,
}

impl Framing {
    pub fn is_rtu(self) -> bool {
        matches!(self, Framing::Rtu | Framing::RtuOverTcp)
    }

    pub fn name(self) -> &'static str {
        match self {
            Framing::Tcp => "tcp",
            Framing::Rtu => "rtu",
            Framing::RtuOverTcp => "rtu_over_tcp",
        }
    }
}
