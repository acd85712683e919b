//! Users (digest 001 §2.20 (22)–(24), §4.9): the one user the manual names, "USER1", its
//! password (≤ 15 characters, like the system password of `dev_services.rs`) and its login.
//! The manual names no function a login unlocks, so none is gated: the login is kept and
//! `NMC_UserLogout` refuses when nobody is logged in (docs/decisions.md).

use axes::command::ErrorKind;
use mcemu_dialects::nmc::code_for_kind;
use mcemu_nmc::errors::RTN_PASSWORD;
use mcemu_nmc::table::{self, Function};

use crate::nmc::service::{Call, Handler, Refusal};

pub const HANDLERS: &[(Function, Handler)] = &[
    (table::USER_SET_PASSWORD, user_set_password),
    (table::USER_LOGIN, user_login),
    (table::USER_LOGOUT, user_logout),
];

/// The only user (digest 001 §2.20: "目前只支持 USER1").
const USER: &[u8] = b"USER1";

fn user(name: &[u8]) -> Result<(), Refusal> {
    if name == USER {
        Ok(())
    } else {
        Err(Refusal::range(
            "pUserName",
            String::from_utf8_lossy(name),
            "{\"USER1\"} (the only user)",
        ))
    }
}

fn check(c: &Call<'_>, given: &[u8]) -> Result<(), Refusal> {
    if c.service.sys().user_password.as_bytes() == given {
        Ok(())
    } else {
        Err(Refusal::new(RTN_PASSWORD, "wrong password of USER1"))
    }
}

fn user_set_password(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let (name, old, new) = (
        c.input.str()?.to_vec(),
        c.input.str()?.to_vec(),
        c.input.str()?.to_vec(),
    );
    user(&name)?;
    if new.is_empty() || new.len() > 15 {
        return Err(Refusal::range(
            "pPasswordNew",
            format!("{} bytes", new.len()),
            "1 to 15 bytes",
        ));
    }
    check(c, &old)?;
    c.service.sys().user_password = String::from_utf8_lossy(&new).into_owned();
    Ok(())
}

fn user_login(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let (name, password) = (c.input.str()?.to_vec(), c.input.str()?.to_vec());
    user(&name)?;
    check(c, &password)?;
    c.service.sys().user_logged_in = true;
    Ok(())
}

fn user_logout(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let name = c.input.str()?.to_vec();
    user(&name)?;
    let mut sys = c.service.sys();
    if !sys.user_logged_in {
        return Err(Refusal::new(
            code_for_kind(ErrorKind::InvalidState),
            "USER1 is not logged in",
        ));
    }
    sys.user_logged_in = false;
    Ok(())
}
