//! The names of digest 001 Appendix A that real programs use: each the handler of the name it
//! misspells.

use mcemu_nmc::table::{self, Function};

use super::io;
use crate::nmc::service::Handler;

pub const HANDLERS: &[(Function, Handler)] = &[
    (table::SET_DOG_GROUP, io::set_do_group),
    (table::GET_DOG_GROUP, io::get_do_group),
];
