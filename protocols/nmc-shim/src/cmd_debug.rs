//! `NMC_SetCmdDebug` and `NMC_UserPrint` (digest 001 §2.20 (12), (32)): the library's debug
//! output. Mode 1 (communication debug output), 3 (GCS) and 4 (DebugView) print to stderr, the
//! host's one debug channel here; mode 2 appends to a file; 0 (the default) is off. Each call
//! that reaches mcemu writes one line: the function, the handle and the return code.

use std::fs::{File, OpenOptions};
use std::io::Write;
use std::sync::{Mutex, PoisonError};

enum Sink {
    Stderr,
    File(File),
}

static SINK: Mutex<Option<Sink>> = Mutex::new(None);

/// Set the mode; `path` is mode 2's file (appended to, created if missing). A file that cannot
/// be opened is an `Err` with the reason, and the mode is unchanged.
pub fn set(mode: i16, path: &[u8]) -> Result<(), String> {
    let sink = match mode {
        0 => None,
        1 | 3 | 4 => Some(Sink::Stderr),
        2 => {
            let name = std::str::from_utf8(path)
                .map_err(|_| "debugOutputFile is not UTF-8".to_string())?;
            if name.is_empty() {
                return Err("debugOutputFile is empty (mode 2 writes to a file)".into());
            }
            let file = OpenOptions::new()
                .create(true)
                .append(true)
                .open(name)
                .map_err(|e| format!("cannot open {name}: {e}"))?;
            Some(Sink::File(file))
        }
        _ => return Err(format!("enable = {mode} is outside [0, 4]")),
    };
    *SINK.lock().unwrap_or_else(PoisonError::into_inner) = sink;
    Ok(())
}

/// Write `line` and a newline to the debug output if one is on; with `always`, to stderr when
/// none is (`NMC_UserPrint`).
pub fn write_line(line: &str, always: bool) {
    let mut sink = SINK.lock().unwrap_or_else(PoisonError::into_inner);
    // A debug line that cannot be written is dropped: debugging never fails a call.
    match sink.as_mut() {
        Some(Sink::File(f)) => {
            let _ = writeln!(f, "{line}");
        }
        Some(Sink::Stderr) => eprintln!("{line}"),
        None if always => eprintln!("{line}"),
        None => {}
    }
}

/// Whether a debug output is on (calls skip formatting their line otherwise).
pub fn on() -> bool {
    SINK.lock()
        .unwrap_or_else(PoisonError::into_inner)
        .is_some()
}
