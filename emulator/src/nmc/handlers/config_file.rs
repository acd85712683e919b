//! The configuration as text (digest 001 §1.5, §2.2 (9), §2.20 (14)): what
//! `NMC_SaveConfigToFile` writes and `NMC_LoadConfigFromFile` reads. The file lives on the host
//! ("文件在当前工程目录下", the program's directory), so the library does the file I/O and
//! carries the text with these two mcemu rows (`mtn_lib20_ext.h`). The text is
//! `NMC_SaveMotionConfig`'s (`saved_config.rs`): alarm, limits, home level, soft limits,
//! safety, following error, in-position band, pulse mode, filters, encoder modes. The GCS
//! tool's `.cfg` format is not described (§1.5) and is refused with `RTN_FILE`.

use mcemu_nmc::errors::{RTN_FILE, RTN_UNSUPPORTED};
use mcemu_nmc::sys::CONFIG_TEXT_MAX;
use mcemu_nmc::table::{self, Function};

use crate::nmc::saved_config;
use crate::nmc::service::{Call, Handler, Refusal};

pub const HANDLERS: &[(Function, Handler)] = &[
    (table::DEV_GET_CONFIG_TEXT, dev_get_config_text),
    (table::DEV_SET_CONFIG_TEXT, dev_set_config_text),
];

fn dev_get_config_text(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let text =
        saved_config::text(c.service, &c.snapshot).map_err(|e| Refusal::new(RTN_UNSUPPORTED, e))?;
    if text.len() > CONFIG_TEXT_MAX {
        return Err(Refusal::new(
            RTN_UNSUPPORTED,
            format!(
                "the configuration is {} bytes, more than the {CONFIG_TEXT_MAX} one reply carries",
                text.len()
            ),
        ));
    }
    c.output.str(text.as_bytes());
    Ok(())
}

/// Parsed and checked whole (format, axis count, known finite parameters) before anything is
/// applied: a text that fails changes nothing.
fn dev_set_config_text(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let text = c.input.str()?.to_vec();
    let saved =
        saved_config::parse(&text, c.snapshot.axes.len()).map_err(|e| Refusal::new(RTN_FILE, e))?;
    for command in saved_config::apply(c.service, saved) {
        c.command(command);
    }
    Ok(())
}
