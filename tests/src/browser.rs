//! The dashboard's browser tests: `node tests/web/dashboard.mjs SCENARIO BASE ARG`, which drives
//! Debian's headless chromium with playwright-core (both installed by `scripts/setup`).

use std::path::PathBuf;
use std::process::{Command, Output};
use std::time::Duration;

use crate::{output_report, require_tool, run_with_timeout, workspace_root};

/// How long one scenario may take (chromium's start included).
const BROWSER_TIMEOUT: Duration = Duration::from_secs(240);
/// Where Debian's `chromium` package puts the browser.
pub const CHROMIUM: &str = "/usr/bin/chromium";

/// Run `scenario` of `tests/web/dashboard.mjs` against the control listener at `base`
/// (`http://127.0.0.1:PORT`); panics with the script's output unless every check passed.
/// Returns its output (one `ok: …` line per check).
pub fn run_dashboard_scenario(scenario: &str, base: &str, arg: &str) -> String {
    let web = workspace_root().join("tests/web");
    let module = web.join("node_modules/playwright-core/package.json");
    assert!(
        module.is_file(),
        "{} is missing: run scripts/setup (npm ci in tests/web)",
        module.display()
    );
    assert!(
        PathBuf::from(CHROMIUM).is_file(),
        "{CHROMIUM} is missing: run scripts/setup (apt-get install chromium)"
    );
    let mut command = Command::new(require_tool("node"));
    command
        .current_dir(&web)
        .args(["dashboard.mjs", scenario, base, arg]);
    let out: Output = run_with_timeout(command, b"", BROWSER_TIMEOUT);
    let report = output_report(&format!("dashboard.mjs {scenario}"), &out);
    assert!(out.status.success(), "{report}");
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// Run the dashboard's JavaScript unit tests `tests/web/NAME` with `node --test`; panics with
/// their output unless every test passed. Returns the output (TAP).
pub fn run_web_unit_tests(name: &str) -> String {
    let mut command = Command::new(require_tool("node"));
    command
        .current_dir(workspace_root().join("tests/web"))
        .args(["--test", name]);
    let out: Output = run_with_timeout(command, b"", BROWSER_TIMEOUT);
    let report = output_report(&format!("node --test {name}"), &out);
    assert!(out.status.success(), "{report}");
    String::from_utf8_lossy(&out.stdout).into_owned()
}
