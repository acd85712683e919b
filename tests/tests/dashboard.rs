//! The dashboard (issue 15) against `mcemu run`: the page in headless chromium
//! (`tests/web/dashboard.mjs`), the stream read by a plain HTTP client, and the control port's
//! access rules (token off loopback, cross-origin and form posts refused).

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::io::{BufRead, BufReader};
use std::path::PathBuf;
use std::time::Duration;

use mcemu_tests::{fresh_dir, run_dashboard_scenario, run_web_unit_tests, Mcemu};
use serde_json::{json, Value};

const VIRTUAL: [&str; 2] = ["--set", "machine.clock=virtual"];

fn base(mcemu: &Mcemu) -> String {
    mcemu.api.trim_end_matches("/api/v1").to_string()
}

fn agent() -> ureq::Agent {
    ureq::Agent::config_builder()
        .http_status_as_error(false)
        .timeout_global(Some(Duration::from_secs(60)))
        .build()
        .into()
}

#[test]
fn the_page_shows_and_drives_the_default_machine() {
    let mcemu = Mcemu::start(None, &VIRTUAL);
    // Under target/, for the README (docs/dashboard.png is a copy).
    let shot = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .parent()
        .expect("the target directory")
        .join("dashboard.png");
    let _ = std::fs::remove_file(&shot);
    let out = run_dashboard_scenario("machine", &base(&mcemu), shot.to_str().unwrap());
    assert!(
        out.contains("ok: the exported CSV contains the trigger point"),
        "{out}"
    );
    assert!(shot.is_file(), "no screenshot at {}", shot.display());
    assert!(
        out.contains("ok: the stream carries the channels chosen per axis (0.act_pos,1.following_error,di,do)"),
        "{out}"
    );
    // The front-ends view showed the listeners (`/state`'s `listeners`).
    assert!(
        out.contains("ok: the modbus-tcp front-end shows it listens on 127.0.0.1:"),
        "{out}"
    );
    assert!(
        out.contains("ok: the thinned plot keeps the extremes and both ends of the window"),
        "{out}"
    );
    // What the page did, seen through the API: axis 0 stopped short at the forced limit,
    // axis 1 went to 20; the cross-origin form did not enable axis 2 (the page checked it
    // before enabling it itself for the handwheel and gear it then showed).
    assert!(
        out.contains("ok: and axis 2 stayed disabled")
            && out.contains("ok: the couplings and handwheels tables show them"),
        "{out}"
    );
    let state = mcemu.state();
    assert!(state["axes"][0]["act_pos"].as_f64().unwrap() < 400.0);
    assert_eq!(state["axes"][1]["act_pos"], 20.0);
    assert_eq!(state["handwheels"][0]["axis"], 2);
    assert_eq!(state["couplings"][0]["slave"], 3);
}

/// What the plot draws: min and max per pixel column (`decimate.js`), a spike kept, a ring's
/// wrap read in order, gaps kept, a zoomed region whole.
#[test]
fn the_plot_thins_to_min_and_max_per_pixel_column() {
    let out = run_web_unit_tests("decimate.test.mjs");
    assert!(
        out.contains("# pass 4") && out.contains("# fail 0"),
        "{out}"
    );
}

#[test]
fn sixty_four_axes_render() {
    let dir = fresh_dir(env!("CARGO_TARGET_TMPDIR"), "dashboard64");
    let mut config = String::from("[machine]\nname = \"wide\"\nclock = \"virtual\"\n");
    for n in 0..64 {
        config.push_str(&format!("\n[[axes]]\nname = \"a{n}\"\n"));
    }
    let path = dir.join("wide.toml");
    std::fs::write(&path, config).unwrap();
    let mcemu = Mcemu::start(Some(&path), &[]);
    run_dashboard_scenario("axes64", &base(&mcemu), "64");
    assert_eq!(mcemu.axis(63)["state"], "standstill");
}

#[test]
fn off_loopback_the_token_is_required() {
    let args = [
        "--set",
        "frontends.control.bind=127.0.0.2:0",
        "--set",
        "machine.clock=virtual",
    ];
    let mcemu = Mcemu::start(None, &args);
    let token = mcemu
        .stdout_text()
        .lines()
        .find_map(|l| l.strip_prefix("control token: ").map(str::to_string))
        .expect("a generated token printed at start");
    let agent = agent();
    let state = format!("{}/state", mcemu.api);
    let reply = agent.get(&state).call().unwrap();
    assert_eq!(reply.status(), 401);
    let reply = agent
        .post(format!("{}/commands", mcemu.api))
        .header("content-type", "application/json")
        .send(json!({"type": "enable", "axis": 0}).to_string())
        .unwrap();
    assert_eq!(reply.status(), 401);
    let reply = agent
        .get(&state)
        .header("authorization", &format!("Bearer {token}"))
        .call()
        .unwrap();
    assert_eq!(reply.status(), 200);
    // The page itself needs no token; the browser asks for it.
    assert_eq!(agent.get(base(&mcemu) + "/").call().unwrap().status(), 200);
    run_dashboard_scenario("token", &base(&mcemu), &token);
}

#[test]
fn cross_origin_requests_and_form_bodies_are_refused() {
    let mcemu = Mcemu::start(None, &VIRTUAL);
    let agent = agent();
    let commands = format!("{}/commands", mcemu.api);
    let enable = json!({"type": "enable", "axis": 0}).to_string();
    let send = |content_type: &str, origin: Option<&str>, body: &str| {
        let mut request = agent.post(&commands).header("content-type", content_type);
        if let Some(origin) = origin {
            request = request.header("origin", origin);
        }
        let mut reply = request.send(body.to_string()).unwrap();
        let status = reply.status().as_u16();
        let body: Value = serde_json::from_str(&reply.body_mut().read_to_string().unwrap())
            .unwrap_or(Value::Null);
        (status, body)
    };
    let (status, body) = send("application/json", Some("http://evil.example"), &enable);
    assert_eq!(
        (status, body["error"].as_str()),
        (403, Some("cross_origin"))
    );
    let (status, body) = send(
        "application/x-www-form-urlencoded",
        None,
        "type=enable&axis=0",
    );
    assert_eq!(
        (status, body["error"].as_str()),
        (415, Some("unsupported_media_type"))
    );
    let (status, body) = send("text/plain", None, &enable);
    assert_eq!(
        (status, body["error"].as_str()),
        (415, Some("unsupported_media_type"))
    );
    assert_eq!(mcemu.axis(0)["state"], "disabled");
    // The page's own origin passes.
    let (status, _) = send("application/json", Some(&base(&mcemu)), &enable);
    assert_eq!(status, 200);
    let reply = agent
        .get(format!("{}/stream", mcemu.api))
        .header("origin", "http://evil.example")
        .call()
        .unwrap();
    assert_eq!(reply.status(), 403);
}

/// The next server-sent event: (name, data as JSON).
fn next_event(lines: &mut impl BufRead) -> (String, Value) {
    let (mut name, mut data) = (String::new(), String::new());
    loop {
        let mut line = String::new();
        assert!(lines.read_line(&mut line).unwrap() > 0, "the stream ended");
        let line = line.trim_end();
        if line.is_empty() && !data.is_empty() {
            return (name, serde_json::from_str(&data).unwrap());
        }
        if let Some(n) = line.strip_prefix("event: ") {
            name = n.to_string();
        } else if let Some(d) = line.strip_prefix("data: ") {
            data.push_str(d);
        }
    }
}

#[test]
fn the_stream_carries_every_tick_batched_and_is_bounded() {
    let mcemu = Mcemu::start(
        None,
        &[
            "--set",
            "machine.clock=virtual",
            "--set",
            "frontends.control.stream_max_clients=1",
        ],
    );
    let agent = agent();
    let url = format!(
        "{}/stream?axes=1&channels=cmd_pos,flags&batch=10",
        mcemu.api
    );
    let reply = agent.get(&url).call().unwrap();
    assert_eq!(reply.status(), 200);
    let mut events = BufReader::new(reply.into_body().into_reader());
    let (name, hello) = next_event(&mut events);
    assert_eq!(name, "hello");
    assert_eq!(hello["channels"], json!(["cmd_pos", "flags"]));
    assert_eq!(hello["batch"], 10);
    // One stream at most: the second is refused with the typed error.
    let mut second = agent.get(&url).call().unwrap();
    assert_eq!(second.status(), 503);
    let body: Value = serde_json::from_str(&second.body_mut().read_to_string().unwrap()).unwrap();
    assert_eq!(body["error"], "too_many_streams");

    mcemu.post_ok("/commands", &json!({"type": "enable", "axis": 1}));
    mcemu.post_ok(
        "/commands",
        &json!({"type": "move_absolute", "axis": 1, "position": 1.0}),
    );
    let reached = mcemu.advance(&json!({"ticks": 200}))["tick"]
        .as_u64()
        .unwrap();
    let mut next_tick = None;
    let mut positions = Vec::new();
    while positions.len() < 200 {
        let (name, batch) = next_event(&mut events);
        assert_eq!(name, "samples");
        assert_eq!(batch["ticks"], 10);
        assert_eq!(batch["dropped"], 0);
        let first = batch["first_tick"].as_u64().unwrap();
        // Contiguous: every tick, none skipped or repeated.
        assert!(
            next_tick.is_none_or(|n| n == first),
            "{next_tick:?} then {first}"
        );
        next_tick = Some(first + 10);
        let values = batch["data"][0][0].as_array().unwrap();
        positions.extend(values.iter().map(|v| v.as_f64().unwrap()));
    }
    assert_eq!(next_tick, Some(reached + 1));
    assert!(positions.windows(2).all(|w| w[1] >= w[0]), "{positions:?}");
    assert_eq!(positions.last(), Some(&1.0));
    assert_eq!(mcemu.state()["stream"]["clients"], 1);

    // A burst of 300 batches at once: the client's queue (64) takes what it can, the rest is
    // lost whole and counted; what arrives plus what was lost is every tick.
    let reached = mcemu.advance(&json!({"ticks": 3000}))["tick"]
        .as_u64()
        .unwrap();
    let reached = mcemu.advance(&json!({"ticks": 10}))["tick"]
        .as_u64()
        .unwrap()
        .max(reached);
    let mut received = 0;
    let mut expected = next_tick.unwrap();
    let dropped = loop {
        let (_, batch) = next_event(&mut events);
        let first = batch["first_tick"].as_u64().unwrap();
        assert_eq!((first - expected) % 10, 0, "whole batches only");
        expected = first + 10;
        received += 10;
        if expected == reached + 1 {
            break batch["dropped"].as_u64().unwrap();
        }
    };
    assert_eq!(
        received + dropped * 10,
        3010,
        "{received} received, {dropped} lost"
    );
    assert_eq!(mcemu.state()["stream"]["dropped_batches"], dropped);
}
