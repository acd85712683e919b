//! HIMC User ASCII end to end (issue 14 item 4, digest 004 §1.7): `mcemu run` with a grammar
//! from the config, real TCP clients (OpenBSD `nc`, a plain Python socket, a `TcpStream`): the
//! manual's two shipped grammars, a grammar of the test's own, the broadcast to every client
//! through the control API, an unmatched line, and a bad grammar refused at start.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

use mcemu_tests::{mcemu_bin, workspace_root, AsciiClient, Mcemu, TempDir};
use serde_json::json;

fn himc(args: &[&str]) -> Mcemu {
    let mut all = vec!["--clock", "virtual"];
    all.extend_from_slice(args);
    Mcemu::start(Some(&workspace_root().join("fixtures/himc.toml")), &all)
}

fn count(m: &Mcemu, name: &str) -> u64 {
    let counters = m.frontend("ascii_user")["counters"].clone();
    counters[name]
        .as_u64()
        .unwrap_or_else(|| panic!("no counter {name} in {counters}"))
}

/// Lines sent through OpenBSD `nc -N` (it closes after its input; the server after the last
/// reply), the replies as one string.
fn nc(m: &Mcemu, input: &[u8]) -> String {
    let mut nc = Command::new("nc")
        .args(["-N", "127.0.0.1", &m.port("ascii-user")])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .unwrap_or_else(|e| panic!("nc (netcat-openbsd, scripts/setup): {e}"));
    nc.stdin.take().unwrap().write_all(input).unwrap();
    let out = nc.wait_with_output().unwrap();
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// The default machine's config with `extra` appended (more keys of `[frontends.ascii_user]`
/// come as `[[frontends.ascii_user.commands]]` tables, which TOML allows anywhere after).
fn config_with(dir: &Path, extra: &str) -> PathBuf {
    let base = std::fs::read_to_string(workspace_root().join("fixtures/default.toml")).unwrap();
    let path = dir.join("user.toml");
    std::fs::write(&path, format!("{base}\n{extra}")).unwrap();
    path
}

fn position(m: &Mcemu, axis: usize) -> f64 {
    m.axis(axis)["act_pos"].as_f64().unwrap()
}

#[test]
fn example2_moves_the_axis_over_nc() {
    let m = himc(&[]);
    // The manual's commands (two spaces included); each answers an empty line.
    assert_eq!(nc(&m, b"ENABLE 0\r\n"), "\r\n");
    m.advance(&json!({"seconds": 0.5}));
    assert_eq!(nc(&m, b"MOVEABS 0  10\r\n"), "\r\n");
    m.advance(&json!({"seconds": 5}));
    assert!((position(&m, 0) - 10.0).abs() < 1e-6, "{}", position(&m, 0));
    // CR, LF and CRLF end a line; himc.toml's own `POS? %d` reads the state.
    assert_eq!(
        nc(&m, b"MOVEREL 0 -2.5\rSTOP 9\nPOS? 0\r\nHELLO\r\n"),
        "\r\n\r\n10\r\nERR unknown command\r\n"
    );
    m.advance(&json!({"seconds": 5}));
    assert!((position(&m, 0) - 7.5).abs() < 1e-6, "{}", position(&m, 0));
    assert_eq!(count(&m, "matched"), 5);
    assert_eq!(count(&m, "unmatched"), 1);
    // STOP 9: the engine has no axis 9; Example 2 ignores what its calls return.
    assert_eq!(count(&m, "engine_refusals"), 1);
}

#[test]
fn example1_answers_each_character_plus_one_to_a_python_socket_tv79() {
    let m = himc(&["--set", "frontends.ascii_user.grammar=\"example1\""]);
    let script = r#"
import socket, sys
host, port = sys.argv[1].rsplit(":", 1)
s = socket.create_connection((host, int(port)), timeout=20)
f = s.makefile("rb")
for line in ["hello", "asdf"]:
    s.sendall(line.encode() + b"\n")
    print(f.readline().decode().rstrip("\r\n"))
"#;
    let out = Command::new("python3")
        .args(["-c", script, m.address("ascii-user")])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(String::from_utf8_lossy(&out.stdout), "ifmmp\nbteg\n");
}

#[test]
fn a_grammar_of_the_tests_own_with_regex_captures_state_and_errors() {
    let dir = TempDir::new("ascii-user");
    let config = config_with(
        dir.path(),
        r#"
[[frontends.ascii_user.commands]]
regex = 'GO (?P<axis>\d+) TO (\S+)'
captures = ["int", "float"]
engine = [{ type = "move_absolute", axis = "$axis", position = "$2", velocity = 50.0 }]
reply = "OK {axis} -> {2}"
error_reply = "NAK {error}"

[[frontends.ascii_user.commands]]
pattern = "WHERE %d"
reply = "AT {axis[$1].position} {axis[$1].state}"
error_reply = "NAK {error}"
"#,
    );
    let m = Mcemu::start(
        Some(&config),
        &[
            "--clock",
            "virtual",
            "--set",
            "frontends.ascii_user.unmatched=\"WHAT? {line}\"",
        ],
    );
    let mut c = AsciiClient::connect(m.address("ascii-user"));
    m.post_ok("/commands", &json!({"type": "enable", "axis": 1}));
    m.advance(&json!({"seconds": 0.5}));
    assert_eq!(c.call("GO 1 TO 2.5"), "OK 1 -> 2.5");
    m.advance(&json!({"seconds": 2}));
    assert_eq!(c.call("WHERE 1"), "AT 2.5 standstill");
    // Axis 2 is not enabled: the engine's refusal, in the command's error reply.
    assert!(c.call("GO 2 TO 1").starts_with("NAK "));
    assert_eq!(c.call("WHERE 9"), "NAK no axes[9] on this machine");
    assert_eq!(c.call("where 1"), "WHAT? where 1");
    // The shipped Example 2 is still served after the config's commands.
    assert_eq!(c.call("STOP 1"), "");
}

#[test]
fn broadcast_reaches_every_client_and_an_overlong_one_is_refused() {
    let m = himc(&[]);
    let mut a = AsciiClient::connect(m.address("ascii-user"));
    let mut b = AsciiClient::connect(m.address("ascii-user"));
    // A reply each: both connections are served, so both hear broadcasts.
    assert_eq!(a.call("STOP 0"), "");
    assert_eq!(b.call("STOP 1"), "");
    let sent = m.post_ok(
        "/frontends/ascii_user/broadcast",
        &json!({"message": "test\n\r"}),
    );
    assert_eq!(sent, json!({"bytes": 6, "clients": 2}));
    // The message as given: `ASCII_ServerBroadcast` adds no terminator (digest 004 §1.7).
    assert_eq!(a.read_reply(), "test\n");
    assert_eq!(b.read_reply(), "test\n");
    // The `\r` left over starts the next reply's line.
    assert_eq!(a.call("POS? 0"), "\r0");
    let (status, e) = m.post(
        "/frontends/ascii_user/broadcast",
        &json!({"message": "x".repeat(129)}),
    );
    assert_eq!(
        (status, &e["error"]),
        (422, &json!("broadcast_too_long")),
        "{e}"
    );
    let (status, e) = m.post(
        "/frontends/ascii_native/broadcast",
        &json!({"message": "x"}),
    );
    assert_eq!((status, &e["error"]), (400, &json!("no_broadcast")), "{e}");
    assert_eq!(count(&m, "broadcasts"), 1);
    assert_eq!(count(&m, "connections_open"), 2);
}

#[test]
fn a_bad_grammar_is_a_config_error_naming_file_key_and_reason() {
    let dir = TempDir::new("ascii-user-bad");
    let config = config_with(
        dir.path(),
        "[[frontends.ascii_user.commands]]\nregex = 'GO (\\d+'\nreply = \"{1}\"\n",
    );
    let out = Command::new(mcemu_bin())
        .args(["run", "--any-port", "--config", config.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("user.toml")
            && err.contains("frontends.ascii_user.commands[0].regex")
            && err.contains("unclosed group"),
        "{err}"
    );
}
