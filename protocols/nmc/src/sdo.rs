//! How an SDO abort travels (`NMC_EcatSdoRead`/`Write`'s `abort_code`, digest 001 §2.1): a
//! refused call's reply carries only its code and text, so the server's text starts with the
//! CiA 301 abort code in a fixed form and the library reads it back from there.

const PREFIX: &str = "SDO abort 0x";

/// The refusal text of an SDO the slave aborted with `code` (`detail` says why).
pub fn abort_text(code: u32, detail: &str) -> String {
    format!("{PREFIX}{code:08X}: {detail}")
}

/// The abort code in a refusal's text, if it names one (the function's name may precede it).
pub fn abort_in(text: &str) -> Option<u32> {
    let at = text.find(PREFIX)? + PREFIX.len();
    let hex = text.get(at..at + 8)?;
    u32::from_str_radix(hex, 16).ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_code_survives_the_text() {
        let t = format!(
            "NMC_EcatSdoRead: {}",
            abort_text(0x0602_0000, "no object 0x1234")
        );
        assert_eq!(abort_in(&t), Some(0x0602_0000));
        assert_eq!(abort_in("devId 5: no such slave"), None);
        assert_eq!(abort_in("SDO abort 0x12"), None);
    }
}
