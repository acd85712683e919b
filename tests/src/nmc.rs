//! The NMC library under test: `libnmc_lib20.so` built in this build's target directory and
//! profile, C programs of `tests/nmc/` compiled against its headers with gcc and linked with
//! it, and run with `MCEMU_NMC` pointing at an mcemu.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::OnceLock;
use std::time::Duration;

use crate::mcemu::{cargo_in_profile, profile_dir};
use crate::{output_report, require_tool, run_with_timeout, workspace_root};

/// How long one example program may run.
pub const PROGRAM_TIMEOUT: Duration = Duration::from_secs(120);

/// The directory holding `libnmc_lib20.so`, built first (once per process) with `cargo build
/// -p nmc-shim --lib` in this build's profile.
pub fn nmc_library_dir() -> PathBuf {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let dir = profile_dir();
        let out = cargo_in_profile(&dir, &["build", "-p", "nmc-shim", "--lib"])
            .output()
            .expect("cargo runs");
        assert!(
            out.status.success(),
            "{}",
            output_report("cargo build -p nmc-shim", &out)
        );
        assert!(dir.join("libnmc_lib20.so").is_file());
        dir
    })
    .clone()
}

/// The headers' directory, `protocols/nmc-shim/include`.
pub fn nmc_include_dir() -> PathBuf {
    workspace_root().join("protocols/nmc-shim/include")
}

/// Compile `tests/nmc/NAME` (C, or C++ for `.cpp`) with `-Wall -Wextra -Werror` and `extra`
/// flags into `out_dir`, linked with the library (and libm); the executable's path.
pub fn compile_example(name: &str, out_dir: &Path, extra: &[&str]) -> PathBuf {
    let source = workspace_root().join("tests/nmc").join(name);
    let cpp = extra.contains(&"-xc++");
    let compiler = require_tool(if cpp { "g++" } else { "gcc" });
    let lib = nmc_library_dir();
    let exe = out_dir.join(Path::new(name).with_extension(if cpp { "cpp.bin" } else { "bin" }));
    let mut command = Command::new(compiler);
    command
        .args(["-Wall", "-Wextra", "-Werror"])
        .args(extra)
        .arg("-I")
        .arg(nmc_include_dir())
        .arg(&source)
        .arg("-o")
        .arg(&exe)
        .arg("-L")
        .arg(&lib)
        .arg(format!("-Wl,-rpath,{}", lib.display()))
        .args(["-lnmc_lib20", "-lpthread", "-lm"]);
    let out = command.output().expect("the compiler runs");
    assert!(out.status.success(), "{}", output_report(name, &out));
    exe
}

/// Run an example with `MCEMU_NMC=address`; its output (panics on timeout).
pub fn run_example(exe: &Path, address: &str) -> Output {
    let mut command = Command::new(exe);
    command.env("MCEMU_NMC", address);
    run_with_timeout(command, b"", PROGRAM_TIMEOUT)
}
