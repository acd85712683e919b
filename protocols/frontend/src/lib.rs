//! The front-end kit: what every protocol front-end of mcemu shares, so that a new front-end
//! writes only its codec and its service (ARCHITECTURE §5).
//!
//! - [`artefact`]: artefacts a config names (register maps, EDS files): shipped by name, or a
//!   file relative to the config file's directory;
//! - [`axis_ref`]: axis references (`0`, `"x"`) resolved against the machine's axes;
//! - [`bound`]: the bounded accept loop, with eviction of the connection idle longest at the
//!   limit ([`bound::AtLimit`]), and one tracing span per connection;
//! - [`counter`]: counts for `GET /state`, among them a TCP front-end's connection counts;
//! - [`fault`]: the fault list of a request/response front-end (`delay`, `no_reply`, `close`,
//!   `corrupt`, and the protocol's own kinds such as a forced error), with counts, matching,
//!   clearing and parsing from JSON;
//! - [`refusal`]: the last request the engine refused, for `GET /state`.

pub mod artefact;
pub mod axis_ref;
pub mod bound;
pub mod counter;
pub mod fault;
pub mod refusal;

pub use artefact::{Artefact, ArtefactError, Artefacts, Located};
pub use axis_ref::{AxisRef, AxisRefError};
