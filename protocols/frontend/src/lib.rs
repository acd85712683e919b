//! The front-end kit: what every protocol front-end of mcemu shares, so that a new front-end
//! writes only its codec and its service (ARCHITECTURE §5).
//!
//! - [`bound`]: the bounded accept loop, with eviction of the connection idle longest at the
//!   limit ([`bound::AtLimit`]), and one tracing span per connection;
//! - [`counter`]: counts for `GET /state`, among them a TCP front-end's connection counts.

pub mod bound;
pub mod counter;
