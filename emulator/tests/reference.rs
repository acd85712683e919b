//! The checked-in configuration reference is what the generator prints: it cannot drift from the
//! config types and the parameter table. Regenerate it with
//! `cargo run -p mcemu -- reference > docs/configuration.md`.

// Tests fail loudly.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::path::Path;
use std::process::Command;

fn checked_in() -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/configuration.md");
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

#[test]
fn docs_configuration_md_is_the_generated_reference() {
    let generated = mcemu::reference::markdown();
    let file = checked_in();
    if file != generated {
        let line = file
            .lines()
            .zip(generated.lines())
            .position(|(a, b)| a != b)
            .unwrap_or_else(|| file.lines().count().min(generated.lines().count()));
        panic!(
            "docs/configuration.md differs from the generator from line {}: regenerate it with\n    {}",
            line + 1,
            mcemu::reference::REGENERATE
        );
    }
}

#[test]
fn mcemu_reference_prints_it() {
    let out = Command::new(env!("CARGO_BIN_EXE_mcemu"))
        .arg("reference")
        .output()
        .unwrap();
    assert!(out.status.success());
    assert_eq!(String::from_utf8(out.stdout).unwrap(), checked_in());
}

#[test]
fn the_readme_links_the_reference() {
    let readme =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("../README.md"))
            .unwrap();
    assert!(readme.contains("docs/configuration.md"));
}
