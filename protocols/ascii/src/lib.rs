//! HIWIN HIMC Native ASCII front-end (issue 14, digest 004 §1.6, §7.1): HMPL calls as text
//! lines, `MoveAbs(0, 100)` → `0`, over TCP (the controller's port 3999).
//!
//! Sans-IO core, in the order a line goes through it:
//! - [`line`]: bytes → lines (CR, LF, CRLF; 512 characters; bounded memory);
//! - [`parse`]: a line → a call (`Name(arg, …)`);
//! - [`table`]: the function table's types; [`functions`]: its rows, one module per chapter;
//! - [`native`]: a call → a reply, or engine commands and then a reply; errors latched in
//!   [`registers`];
//! - [`reply`]: return values as text.
//!
//! [`user`] is the User ASCII core (port 4000): a grammar declared in the config in place of the
//! user's HMPL parser (digest 004 §1.7).
//!
//! [`transport`] holds the thin tokio servers over both, sharing one connection loop; [`config`]
//! the Native config section; [`counters`] what `GET /api/v1/state` shows.

pub mod config;
pub mod counters;
pub mod estop;
pub mod functions;
pub mod line;
pub mod native;
pub mod parse;
pub mod registers;
pub mod reply;
pub mod table;
pub mod transport;
pub mod user;
