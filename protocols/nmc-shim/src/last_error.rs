//! `NMC_GetLastErr`, `NMC_GetErrDesc`, `NMC_SetErrCodeMode`: the last failure of the calling
//! thread (calls from other threads do not overwrite it), and the mode codes are returned in.

use std::cell::RefCell;
use std::sync::atomic::{AtomicI16, Ordering};

use mcemu_nmc::errors;

use crate::connection::CallError;

thread_local! {
    static LAST: RefCell<(i16, String)> = const { RefCell::new((0, String::new())) };
}

/// 0 detailed codes (the default), 1 categories only.
static MODE: AtomicI16 = AtomicI16::new(0);

pub fn set_mode(mode: i16) {
    MODE.store(mode, Ordering::Relaxed);
}

/// The return code of a call that ended with `result`; a failure is remembered.
pub fn report(result: Result<(), CallError>) -> i16 {
    let code = match result {
        Ok(()) => 0,
        Err(e) => {
            let code = e.code;
            LAST.with(|l| *l.borrow_mut() = (e.code, e.description));
            code
        }
    };
    if MODE.load(Ordering::Relaxed) == 1 {
        errors::category_code(code)
    } else {
        code
    }
}

/// The calling thread's last failure code (0 if none).
pub fn last_code() -> i16 {
    LAST.with(|l| l.borrow().0)
}

/// The description of `code`: the last failure's own text if it was `code`, else the table's.
pub fn description(code: i16) -> String {
    let own = LAST.with(|l| {
        let l = l.borrow();
        (l.0 == code && !l.1.is_empty()).then(|| l.1.clone())
    });
    own.or_else(|| errors::lookup(code).map(|c| c.description.to_string()))
        .unwrap_or_else(|| match code {
            0 => "success".to_string(),
            _ => format!("unknown error code {code}"),
        })
}
