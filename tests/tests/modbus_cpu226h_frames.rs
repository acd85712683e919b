//! The CPU 226H's Modbus RTU example (manual §10.1 networks 3–6, digest 003 §5 and its test
//! vectors TV-01 … TV-06) byte for byte, CRC included, against `mcemu run --config
//! fixtures/cpu226h.toml` playing the CT E10 drive at address 2: on the fixture's own pty (raw
//! bytes written to and read from `/dev/pts/N`) and over its RTU-over-TCP listener. Every frame
//! the digest gives is sent; each answer must be exactly the digest's frame and nothing more,
//! and the engine must have done what the frames ask (TV-02: P282 bit 0 enables the drive).

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::net::TcpStream;
use std::path::Path;
use std::time::Duration;

use mcemu_tests::{crc16, hex, rtu_frame, workspace_root, ByteLink, Mcemu, RawSerial};

/// After each answer the line must stay silent this long (a pty or loopback delivers an answer
/// in well under a millisecond; a stray byte would come at once).
const QUIET: Duration = Duration::from_millis(150);

fn start() -> Mcemu {
    Mcemu::start(
        Some(&workspace_root().join("fixtures/cpu226h.toml")),
        &["--clock", "virtual"],
    )
}

/// Every frame of networks 3–6, in an order that keeps each expected answer exact: network 6
/// first, while the drive is disabled at rest (its 60 zero bytes), then networks 3, 4 and 5.
fn exchange_the_manuals_frames(m: &Mcemu, frontend: &str, link: &mut dyn ByteLink) {
    let e10 = 4; // axis e10_rtu
    assert_eq!(m.axis(e10)["state"], "disabled");

    // TV-06, network 6: read R200 … R229 (30 words at 40201).
    let mut zeros = hex("02 03 3C");
    zeros.extend([0u8; 60]);
    zeros.extend(hex("B9 D7"));
    link.exchange(&hex("02 03 00 C8 00 1E 44 0F"), &zeros, QUIET);

    // TV-01, network 3: 40282 (P281) = 0, 40283 (P282) = 1.
    link.exchange(
        &hex("02 10 01 19 00 02 04 00 00 00 01 F1 DD"),
        &hex("02 10 01 19 00 02 91 C0"),
        QUIET,
    );
    // TV-02: P282 bit 0 = 1 enabled the drive.
    let axis = m.axis(e10);
    assert_ne!(axis["state"], "disabled", "{axis}");
    assert!(
        axis["flags"]
            .as_array()
            .unwrap()
            .contains(&"enabled".into()),
        "{axis}"
    );

    // TV-03, network 4: 40325 (P324) = 100, the answer is the echo.
    link.exchange(
        &hex("02 06 01 44 00 64 C9 FB"),
        &hex("02 06 01 44 00 64 C9 FB"),
        QUIET,
    );

    // TV-04, network 5 as corrected: 40114 (P113) = 100, 40115 (P114) = 200.
    link.exchange(
        &hex("02 10 00 71 00 02 04 00 64 00 C8 7A 4A"),
        &hex("02 10 00 71 00 02 11 E0"),
        QUIET,
    );

    // TV-05, network 5 as printed: 4 registers, byte count 0 → exception 03.
    link.exchange(
        &hex("02 10 00 71 00 04 00 00 64 00 C8 8B EC"),
        &hex("02 90 03 FC 01"),
        QUIET,
    );

    // What the writes left, read back (P113/P114, P281/P282, P324), CRCs computed here.
    link.exchange(
        &rtu_frame(2, &hex("03 00 71 00 02")),
        &rtu_frame(2, &hex("03 04 00 64 00 C8")),
        QUIET,
    );
    link.exchange(
        &rtu_frame(2, &hex("03 01 19 00 02")),
        &rtu_frame(2, &hex("03 04 00 00 00 01")),
        QUIET,
    );
    link.exchange(
        &rtu_frame(2, &hex("03 01 44 00 01")),
        &rtu_frame(2, &hex("03 02 00 64")),
        QUIET,
    );

    // Network 6 again, the drive now enabled at rest: R204 bit 0 "servo ready" (§10.2), bit 1
    // in position, as the engine's flags say; every other monitor still 0 (R202 no error,
    // R216 position 0, R221 speed 0).
    let axis = m.axis(e10);
    let flags = axis["flags"].as_array().unwrap();
    let has = |f: &str| flags.contains(&f.into());
    let r204 = u8::from(has("enabled"))
        | u8::from(has("in_position")) << 1
        | u8::from(has("moving")) << 2
        | u8::from(axis["state"] == "error_stop") << 3;
    assert_eq!(r204 & 1, 1, "{axis}");
    let mut image = hex("02 03 3C");
    image.extend([0u8; 60]);
    image[3 + 2 * 4 + 1] = r204; // R204, low byte
    let crc = crc16(&image);
    image.extend(crc.to_le_bytes());
    link.exchange(&hex("02 03 00 C8 00 1E 44 0F"), &image, QUIET);

    // The front-end saw the one exception and no bad frame.
    let name = frontend;
    let c = m.frontend(name)["counters"].clone();
    assert_eq!(c["requests"], 9, "{name}: {c}");
    assert_eq!(c["replies"], 9, "{name}: {c}");
    assert_eq!(c["exceptions_by_code"]["3"], 1, "{name}: {c}");
    assert_eq!(c["crc_errors"], 0, "{name}: {c}");
}

#[test]
fn cpu226h_frames_byte_for_byte_on_the_fixtures_pty() {
    let m = start();
    let device = m.address("modbus-rtu").to_string();
    let mut line = RawSerial::open(Path::new(&device));
    exchange_the_manuals_frames(&m, "modbus_rtu", &mut line);
}

#[test]
fn cpu226h_frames_byte_for_byte_over_rtu_over_tcp() {
    let m = start();
    let mut socket = TcpStream::connect(m.address("modbus-rtu-over-tcp")).unwrap();
    socket.set_nodelay(true).unwrap();
    exchange_the_manuals_frames(&m, "modbus_rtu_over_tcp", &mut socket);
}
