//! The exception matrix of issue 4 item 2 (anchors §26), end to end: raw MBAP requests over TCP
//! to the real `mcemu` serving each shipped map, so no client library filters what is sent.
//!
//! For every function code 1, 2, 3, 4, 5, 6, 15, 16, 22 and 23 and every table of each map, the
//! map's edges come from the map the binary compiles (the same config and `--set` overrides,
//! compiled through `mcemu::config`): the first and the last mapped address of each table
//! answer normally (a write covering a writable point, of its current value; a read-only point
//! or a write cutting a wide point is exception 02), the address just outside each edge and a
//! request straddling it get 02 and change nothing; a table the map does not have is 02
//! everywhere. Then, per function code: the quantity limits 2000/1968/125/123/121 (the largest
//! quantity is decoded, and then refused only by its address; one more is 03), quantity 0 and
//! byte-count mismatches (03, before the address check), FC 5 values other than 0xFF00/0x0000
//! (03), unknown function codes (01), a value the point or the engine refuses (03), an engine
//! refusal (04, its reason in `GET /state`'s `last_error`), FC 8 echo and counters, FC 17 and
//! FC 43/14 from the map's identity. Finally the front-end's `exceptions_by_code` must count
//! exactly the exceptions the matrix expected.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::collections::BTreeMap;
use std::path::PathBuf;

use mcemu::config::Config;
use mcemu_modbus::map::schema::Table;
use mcemu_modbus::map::UnitMap;
use mcemu_modbus::model::DeviceIdentity;
use mcemu_tests::{to_hex, workspace_root, MbapClient, Mcemu};

// ---- requests ------------------------------------------------------------------------------

fn be(v: u16) -> [u8; 2] {
    v.to_be_bytes()
}

fn read(function: u8, address: u16, quantity: u16) -> Vec<u8> {
    [&[function][..], &be(address), &be(quantity)].concat()
}

fn fc5(address: u16, value: u16) -> Vec<u8> {
    [&[5][..], &be(address), &be(value)].concat()
}

fn fc6(address: u16, value: u16) -> Vec<u8> {
    [&[6][..], &be(address), &be(value)].concat()
}

fn pack_bits(bits: &[bool]) -> Vec<u8> {
    let mut bytes = vec![0u8; bits.len().div_ceil(8)];
    for (i, &b) in bits.iter().enumerate() {
        if b {
            bytes[i / 8] |= 1 << (i % 8);
        }
    }
    bytes
}

/// FC 15 with an explicit quantity and byte count (mismatches on purpose allowed).
fn fc15_raw(address: u16, quantity: u16, count: u8, data: &[u8]) -> Vec<u8> {
    [&[15][..], &be(address), &be(quantity), &[count], data].concat()
}

fn fc15(address: u16, bits: &[bool]) -> Vec<u8> {
    let data = pack_bits(bits);
    fc15_raw(address, bits.len() as u16, data.len() as u8, &data)
}

fn words_bytes(words: &[u16]) -> Vec<u8> {
    words.iter().flat_map(|w| w.to_be_bytes()).collect()
}

fn fc16_raw(address: u16, quantity: u16, count: u8, data: &[u8]) -> Vec<u8> {
    [&[16][..], &be(address), &be(quantity), &[count], data].concat()
}

fn fc16(address: u16, words: &[u16]) -> Vec<u8> {
    let data = words_bytes(words);
    fc16_raw(address, words.len() as u16, data.len() as u8, &data)
}

fn fc22(address: u16, and: u16, or: u16) -> Vec<u8> {
    [&[22][..], &be(address), &be(and), &be(or)].concat()
}

fn fc23_raw(ra: u16, rq: u16, wa: u16, wq: u16, count: u8, data: &[u8]) -> Vec<u8> {
    [
        &[23][..],
        &be(ra),
        &be(rq),
        &be(wa),
        &be(wq),
        &[count],
        data,
    ]
    .concat()
}

fn fc23(ra: u16, rq: u16, wa: u16, words: &[u16]) -> Vec<u8> {
    let data = words_bytes(words);
    fc23_raw(ra, rq, wa, words.len() as u16, data.len() as u8, &data)
}

fn fc8(sub: u16, data: &[u8]) -> Vec<u8> {
    [&[8][..], &be(sub), data].concat()
}

// ---- the map as the binary compiles it -----------------------------------------------------

/// A covered stretch of a table: a point (written whole) or a memory area (any part).
#[derive(Clone, Copy, Debug)]
struct Span {
    start: u16,
    width: u16,
    writable: bool,
    area: bool,
}

impl Span {
    fn end(&self) -> u32 {
        u32::from(self.start) + u32::from(self.width) - 1
    }

    /// The stretch a write touching `address` must cover: the whole point, or one register
    /// of an area.
    fn write_unit(&self, address: u16) -> (u16, u16) {
        if self.area {
            (address, 1)
        } else {
            (self.start, self.width)
        }
    }
}

const TABLES: [Table; 4] = [
    Table::Coils,
    Table::DiscreteInputs,
    Table::InputRegisters,
    Table::HoldingRegisters,
];

fn spans(map: &UnitMap, table: Table) -> Vec<Span> {
    let mut out: Vec<Span> = map
        .tables
        .get(&table)
        .into_iter()
        .flatten()
        .map(|&i| {
            let p = &map.points[i];
            Span {
                start: p.address,
                width: p.width,
                writable: p.writable(),
                area: false,
            }
        })
        .chain(map.areas.iter().filter(|a| a.table == table).map(|a| Span {
            start: a.start,
            width: a.count,
            writable: table.is_writable(),
            area: true,
        }))
        .collect();
    out.sort_by_key(|s| s.start);
    out
}

/// The unit map `modbus_tcp` serves with this config and these overrides.
fn compiled_map(config: &Option<PathBuf>, overrides: &[String]) -> UnitMap {
    let (text, file) = match config {
        Some(p) => (std::fs::read_to_string(p).unwrap(), p.display().to_string()),
        None => (
            std::fs::read_to_string(workspace_root().join("fixtures/default.toml")).unwrap(),
            "default".to_string(),
        ),
    };
    let config = Config::parse_with(&text, &file, overrides).unwrap();
    let mut sections = config.modbus_units(&file).unwrap();
    let (_, units) = sections
        .drain(..)
        .find(|(s, _)| *s == "modbus_tcp")
        .expect("a modbus_tcp section");
    assert_eq!(units.len(), 1, "one unit on the TCP front-end");
    units.into_iter().next().unwrap().map
}

// ---- the matrix runner ---------------------------------------------------------------------

struct Matrix {
    client: MbapClient,
    /// Exceptions the rows expect, by code.
    expected: BTreeMap<u8, u64>,
    failures: Vec<String>,
    rows: usize,
}

impl Matrix {
    fn send(&mut self, pdu: &[u8]) -> Vec<u8> {
        self.client.request(1, pdu)
    }

    fn fail(&mut self, what: &str, pdu: &[u8], got: &[u8], want: &str) {
        self.failures.push(format!(
            "{what}: request {} answered {}, expected {want}",
            to_hex(pdu),
            to_hex(got)
        ));
    }

    fn exception(&mut self, what: &str, pdu: &[u8], code: u8) {
        self.rows += 1;
        *self.expected.entry(code).or_default() += 1;
        let got = self.send(pdu);
        let function = pdu.first().copied().unwrap_or(0);
        if got != [function | 0x80, code] {
            self.fail(
                what,
                pdu,
                &got,
                &format!("exception {code:02}: {:02X} {code:02X}", function | 0x80),
            );
        }
    }

    /// A normal answer, checked for its shape; returns it.
    fn ok(&mut self, what: &str, pdu: &[u8]) -> Vec<u8> {
        self.rows += 1;
        let got = self.send(pdu);
        let q = |at: usize| usize::from(u16::from_be_bytes([pdu[at], pdu[at + 1]]));
        let right = match pdu[0] {
            1 | 2 => {
                got.len() >= 2
                    && got[0] == pdu[0]
                    && usize::from(got[1]) == q(3).div_ceil(8)
                    && got.len() == 2 + usize::from(got[1])
            }
            3 | 4 => {
                got.len() == 2 + 2 * q(3) && got[0] == pdu[0] && usize::from(got[1]) == 2 * q(3)
            }
            5 | 6 | 22 => got == pdu,
            15 | 16 => got == pdu[..5],
            23 => got.len() == 2 + 2 * q(3) && got[0] == 23 && usize::from(got[1]) == 2 * q(3),
            _ => !got.is_empty() && got[0] == pdu[0],
        };
        if !right {
            self.fail(what, pdu, &got, "a normal answer");
        }
        got
    }

    /// Bits or registers `[start, start + n)` of a table, read with FC 1 or FC 3.
    fn current_bits(&mut self, start: u16, n: u16) -> Vec<bool> {
        let got = self.ok("read current coils", &read(1, start, n));
        (0..usize::from(n))
            .map(|i| got.get(2 + i / 8).is_some_and(|b| b >> (i % 8) & 1 == 1))
            .collect()
    }

    fn current_words(&mut self, start: u16, n: u16) -> Vec<u16> {
        let got = self.ok("read current registers", &read(3, start, n));
        got.get(2..)
            .unwrap_or_default()
            .chunks_exact(2)
            .map(|c| u16::from_be_bytes([c[0], c[1]]))
            .collect()
    }

    fn check_eq<T: PartialEq + std::fmt::Debug>(&mut self, what: &str, got: T, want: T) {
        if got != want {
            self.failures
                .push(format!("{what}: {got:?}, expected {want:?}"));
        }
    }
}

/// What each map needs beyond its edges: a write the engine refuses (04, with a fragment of
/// the reason) and writes whose value is refused (03).
struct Fixture {
    name: &'static str,
    config: Option<PathBuf>,
    /// `--set` overrides of both the binary and the compiled map.
    overrides: Vec<String>,
    /// FC 16 (address, words) that the engine refuses, and part of its reason.
    refusal: (u16, Vec<u16>, &'static str),
    /// FC 16 (address, words) whose values are refused with 03.
    bad_values: Vec<(u16, Vec<u16>)>,
}

fn edge_rows(m: &mut Matrix, table: Table, spans: &[Span]) {
    let t = table.name();
    let read_fc = match table {
        Table::Coils => 1,
        Table::DiscreteInputs => 2,
        Table::InputRegisters => 4,
        Table::HoldingRegisters => 3,
    };
    let Some(first) = spans.first().copied() else {
        // A table the map does not have: 02 everywhere.
        for a in [0u16, 1, 0xFFFF] {
            m.exception(
                &format!("{t} (not in map) read {a}"),
                &read(read_fc, a, 1),
                2,
            );
            match table {
                Table::Coils => {
                    m.exception(&format!("{t} (not in map) FC 5 {a}"), &fc5(a, 0xFF00), 2);
                    m.exception(&format!("{t} (not in map) FC 15 {a}"), &fc15(a, &[true]), 2);
                }
                Table::HoldingRegisters => {
                    m.exception(&format!("{t} (not in map) FC 6 {a}"), &fc6(a, 1), 2);
                    m.exception(&format!("{t} (not in map) FC 16 {a}"), &fc16(a, &[1]), 2);
                    m.exception(&format!("{t} (not in map) FC 22 {a}"), &fc22(a, 0, 1), 2);
                    m.exception(
                        &format!("{t} (not in map) FC 23 {a}"),
                        &fc23(a, 1, a, &[1]),
                        2,
                    );
                }
                _ => {}
            }
        }
        return;
    };
    let last = *spans.iter().max_by_key(|s| s.end()).unwrap();
    let lo = first.start;
    let hi = last.end() as u16;
    eprintln!("{t}: mapped {lo} … {hi}");
    for (side, edge, span) in [("first", lo, first), ("last", hi, last)] {
        let what = format!("{t} {side} address {edge}");
        // Just inside: reads answer.
        m.ok(&format!("{what}: read"), &read(read_fc, edge, 1));
        if !table.is_writable() {
            continue;
        }
        let (start, width) = span.write_unit(edge);
        if table == Table::Coils {
            let cur = m.current_bits(start, width);
            let single = fc5(
                edge,
                if cur[usize::from(edge - start)] {
                    0xFF00
                } else {
                    0
                },
            );
            let multi = fc15(start, &cur);
            if span.writable {
                m.ok(&format!("{what}: FC 5 of its value"), &single);
                m.ok(&format!("{what}: FC 15 of its value"), &multi);
            } else {
                m.exception(&format!("{what}: FC 5 (read-only)"), &single, 2);
                m.exception(&format!("{what}: FC 15 (read-only)"), &multi, 2);
            }
            let after = m.current_bits(start, width);
            m.check_eq(&format!("{what}: unchanged"), after, cur);
        } else {
            let cur = m.current_words(start, width);
            let own = cur[usize::from(edge - start)];
            let writable = span.writable;
            let whole = width == 1;
            let rows: [(&str, Vec<u8>, bool); 4] = [
                ("FC 6 of its value", fc6(edge, own), writable && whole),
                ("FC 16 of its value", fc16(start, &cur), writable),
                (
                    "FC 22 keeping its value",
                    fc22(edge, 0xFFFF, 0),
                    writable && whole,
                ),
                (
                    "FC 23 reading it, writing its value",
                    fc23(edge, 1, start, &cur),
                    writable,
                ),
            ];
            for (name, pdu, answers) in rows {
                if answers {
                    m.ok(&format!("{what}: {name}"), &pdu);
                } else {
                    let why = if writable {
                        "cuts a wide point"
                    } else {
                        "read-only"
                    };
                    m.exception(&format!("{what}: {name} ({why})"), &pdu, 2);
                }
            }
            let after = m.current_words(start, width);
            m.check_eq(&format!("{what}: unchanged"), after, cur);
        }
    }
    // Just outside, and straddling each edge: 02, nothing written.
    let mut outside = Vec::new();
    if lo > 0 {
        outside.push((format!("{t} below the first address"), lo - 1, lo - 1));
    }
    if hi < 0xFFFF {
        outside.push((format!("{t} after the last address"), hi + 1, hi));
    }
    for (what, out, straddle) in outside {
        m.exception(&format!("{what}: read {out}"), &read(read_fc, out, 1), 2);
        m.exception(
            &format!("{what}: read {straddle} … {}", straddle + 1),
            &read(read_fc, straddle, 2),
            2,
        );
        let inside = if straddle == out { out + 1 } else { straddle };
        match table {
            Table::Coils => {
                let before = m.current_bits(inside, 1);
                m.exception(&format!("{what}: FC 5 {out}"), &fc5(out, 0xFF00), 2);
                m.exception(&format!("{what}: FC 15 {out}"), &fc15(out, &[true]), 2);
                m.exception(
                    &format!("{what}: FC 15 {straddle} … {}", straddle + 1),
                    &fc15(straddle, &[!before[0], !before[0]]),
                    2,
                );
                let after = m.current_bits(inside, 1);
                m.check_eq(&format!("{what}: coil {inside} unchanged"), after, before);
            }
            Table::HoldingRegisters => {
                let before = m.current_words(inside, 1);
                let other = before[0] ^ 0x5A5A;
                m.exception(&format!("{what}: FC 6 {out}"), &fc6(out, 1), 2);
                m.exception(&format!("{what}: FC 16 {out}"), &fc16(out, &[1]), 2);
                m.exception(
                    &format!("{what}: FC 16 {straddle} … {}", straddle + 1),
                    &fc16(straddle, &[other, other]),
                    2,
                );
                m.exception(&format!("{what}: FC 22 {out}"), &fc22(out, 0, 1), 2);
                m.exception(
                    &format!("{what}: FC 23 reading {out}"),
                    &fc23(out, 1, inside, &[before[0]]),
                    2,
                );
                m.exception(
                    &format!("{what}: FC 23 writing {out}"),
                    &fc23(inside, 1, out, &[1]),
                    2,
                );
                let after = m.current_words(inside, 1);
                m.check_eq(
                    &format!("{what}: register {inside} unchanged"),
                    after,
                    before,
                );
            }
            _ => {}
        }
    }
}

/// The first address of a run of `n` addresses all covered by memory areas (writes there have
/// no side effects), if the table has one.
fn memory_run(spans: &[Span], n: u16) -> Option<u16> {
    spans
        .iter()
        .find(|s| s.area && s.width >= n)
        .map(|s| s.start)
}

/// An address of `table` outside the map with room for `n` addresses after it.
fn unmapped(spans: &[Span], n: u16) -> u16 {
    let after = spans.iter().map(|s| s.end() + 1).max().unwrap_or(0);
    assert!(after + u32::from(n) <= 0x1_0000, "no room after the map");
    after as u16
}

fn quantity_rows(m: &mut Matrix, map: &UnitMap) {
    let coils = spans(map, Table::Coils);
    let hr = spans(map, Table::HoldingRegisters);
    // The largest quantities decode, and are refused by address only; one more is 03, also
    // at an unmapped address (quantity is checked before address); quantity 0 is 03.
    for (function, table, max) in [
        (1u8, Table::Coils, 2000u16),
        (2, Table::DiscreteInputs, 2000),
        (3, Table::HoldingRegisters, 125),
        (4, Table::InputRegisters, 125),
    ] {
        let out = unmapped(&spans(map, table), max + 1);
        m.exception(
            &format!("FC {function} quantity {max}"),
            &read(function, out, max),
            2,
        );
        m.exception(
            &format!("FC {function} quantity {}", max + 1),
            &read(function, out, max + 1),
            3,
        );
        m.exception(
            &format!("FC {function} quantity 0"),
            &read(function, out, 0),
            3,
        );
        m.exception(
            &format!("FC {function} quantity 0xFFFF"),
            &read(function, out, 0xFFFF),
            3,
        );
        m.exception(
            &format!("FC {function} short request"),
            &read(function, out, 1)[..4],
            3,
        );
    }
    let out = unmapped(&coils, 1969);
    m.exception(
        "FC 15 quantity 1968",
        &fc15_raw(out, 1968, 246, &[0; 246]),
        2,
    );
    m.exception(
        "FC 15 quantity 1969",
        &fc15_raw(out, 1969, 247, &[0; 247]),
        3,
    );
    m.exception("FC 15 quantity 0", &fc15_raw(out, 0, 0, &[]), 3);
    m.exception(
        "FC 15 byte count 1 for 9 coils",
        &fc15_raw(out, 9, 1, &[0]),
        3,
    );
    m.exception(
        "FC 15 byte count 2, 1 byte sent",
        &fc15_raw(out, 9, 2, &[0]),
        3,
    );
    m.exception(
        "FC 15 byte count 1, 2 bytes sent",
        &fc15_raw(out, 8, 1, &[0, 0]),
        3,
    );
    m.exception("FC 5 value 0x1234", &fc5(out, 0x1234), 3);
    m.exception("FC 5 value 0x00FF", &fc5(out, 0x00FF), 3);
    m.exception("FC 5 value 0xFFFF", &fc5(out, 0xFFFF), 3);
    m.exception("FC 5 short request", &fc5(out, 0xFF00)[..4], 3);
    let out = unmapped(&hr, 125);
    m.exception("FC 6 short request", &fc6(out, 1)[..4], 3);
    m.exception("FC 16 quantity 123", &fc16(out, &[0; 123]), 2);
    // 124 registers do not fit in a PDU: the quantity alone is refused.
    m.exception("FC 16 quantity 124", &fc16_raw(out, 124, 0, &[]), 3);
    m.exception("FC 16 quantity 0", &fc16_raw(out, 0, 0, &[]), 3);
    m.exception(
        "FC 16 byte count 3 for 2 registers",
        &fc16_raw(out, 2, 3, &[0; 3]),
        3,
    );
    m.exception(
        "FC 16 byte count 4, 2 bytes sent",
        &fc16_raw(out, 2, 4, &[0; 2]),
        3,
    );
    m.exception(
        "FC 16 byte count 2, 4 bytes sent",
        &fc16_raw(out, 1, 2, &[0; 4]),
        3,
    );
    m.exception("FC 22 short request", &fc22(out, 0, 0)[..6], 3);
    m.exception(
        "FC 22 long request",
        &[fc22(out, 0, 0), vec![0]].concat(),
        3,
    );
    m.exception(
        "FC 23 read 125, write 121",
        &fc23(out, 125, out, &[0; 121]),
        2,
    );
    m.exception("FC 23 read 126", &fc23(out, 126, out, &[0]), 3);
    m.exception("FC 23 write 122", &fc23_raw(out, 1, out, 122, 0, &[]), 3);
    m.exception("FC 23 read 0", &fc23(out, 0, out, &[0]), 3);
    m.exception("FC 23 write 0", &fc23_raw(out, 1, out, 0, 0, &[]), 3);
    m.exception(
        "FC 23 byte count 3 for 2 registers",
        &fc23_raw(out, 1, out, 2, 3, &[0; 3]),
        3,
    );
    m.exception(
        "FC 23 byte count 4, 2 bytes sent",
        &fc23_raw(out, 1, out, 2, 4, &[0; 2]),
        3,
    );
    // The largest quantities where the map has that much memory in one stretch: answered.
    if let Some(a) = memory_run(&hr, 125) {
        m.ok("FC 3 quantity 125 in memory", &read(3, a, 125));
        let words = m.current_words(a, 123);
        m.ok("FC 16 quantity 123 in memory", &fc16(a, &words));
        let words = m.current_words(a, 121);
        m.ok(
            "FC 23 read 125, write 121 in memory",
            &fc23(a, 125, a, &words),
        );
    }
    if let Some(a) = memory_run(&coils, 2000) {
        m.ok("FC 1 quantity 2000 in memory", &read(1, a, 2000));
    }
}

fn function_rows(m: &mut Matrix, identity: &DeviceIdentity, out: u16) {
    // Unknown or unimplemented function codes: 01, whatever follows them.
    for pdu in [
        vec![0x42],
        vec![0x42, 0, 0, 0, 1],
        vec![0x07],
        vec![0x0B],
        vec![0x0C],
        vec![0x14, 0],
        vec![0x18, 0, 0],
        vec![0x2B, 0x0D, 0, 0],
        vec![0x7F],
    ] {
        m.exception(&format!("unknown function {:02X}", pdu[0]), &pdu, 1);
    }
    // FC 8: echo, counters (a query counts itself), bad data 03, unknown sub-function 01.
    let echo = fc8(0, &[0xA5, 0x5A, 0x12]);
    let got = m.ok("FC 8 echo", &echo);
    m.check_eq("FC 8 echo", to_hex(&got), to_hex(&echo));
    let clear = fc8(0x0A, &[0, 0]);
    let got = m.ok("FC 8 clear counters", &clear);
    m.check_eq("FC 8 clear counters", to_hex(&got), to_hex(&clear));
    let got = m.ok("FC 8 bus message count", &fc8(0x0B, &[0, 0]));
    m.check_eq(
        "FC 8 bus message count",
        to_hex(&got),
        "08 00 0B 00 01".into(),
    );
    m.exception("read outside the map", &read(3, out, 1), 2);
    let got = m.ok("FC 8 exception count", &fc8(0x0D, &[0, 0]));
    m.check_eq(
        "FC 8 exception count",
        to_hex(&got),
        "08 00 0D 00 01".into(),
    );
    let got = m.ok("FC 8 server message count", &fc8(0x0E, &[0, 0]));
    m.check_eq(
        "FC 8 server message count",
        to_hex(&got),
        "08 00 0E 00 04".into(),
    );
    m.exception("FC 8 counter with data 0001", &fc8(0x0B, &[0, 1]), 3);
    m.exception("FC 8 sub-function 0003", &fc8(0x03, &[0, 0]), 1);
    m.exception("FC 8 without a sub-function", &[8, 0], 3);

    // FC 17: byte count, the map's server id, run indicator FF.
    let mut want = vec![0x11, identity.server_id.len() as u8 + 1];
    want.extend_from_slice(&identity.server_id);
    want.push(0xFF);
    let got = m.ok("FC 17", &[0x11]);
    m.check_eq("FC 17", to_hex(&got), to_hex(&want));
    m.exception("FC 17 with data", &[0x11, 0], 3);

    // FC 43/14 basic stream: objects 0–2 of the map's identity.
    let mut want = vec![0x2B, 0x0E, 0x01, 0x82, 0x00, 0x00, 3];
    for (id, text) in [
        &identity.vendor_name,
        &identity.product_code,
        &identity.revision,
    ]
    .into_iter()
    .enumerate()
    {
        want.extend_from_slice(&[id as u8, text.len() as u8]);
        want.extend_from_slice(text.as_bytes());
    }
    let got = m.ok("FC 43/14 basic", &[0x2B, 0x0E, 0x01, 0x00]);
    m.check_eq("FC 43/14 basic", to_hex(&got), to_hex(&want));
    // Individual access to the vendor name.
    let mut want = vec![0x2B, 0x0E, 0x04, 0x82, 0x00, 0x00, 1, 0];
    want.push(identity.vendor_name.len() as u8);
    want.extend_from_slice(identity.vendor_name.as_bytes());
    let got = m.ok("FC 43/14 object 0", &[0x2B, 0x0E, 0x04, 0x00]);
    m.check_eq("FC 43/14 object 0", to_hex(&got), to_hex(&want));
    m.exception("FC 43/14 object 0x80 (none)", &[0x2B, 0x0E, 0x04, 0x80], 2);
    m.exception("FC 43/14 read code 5", &[0x2B, 0x0E, 0x05, 0x00], 3);
    m.exception("FC 43/14 read code 0", &[0x2B, 0x0E, 0x00, 0x00], 3);
}

fn run(fixture: Fixture) {
    let map = compiled_map(&fixture.config, &fixture.overrides);
    let mut args: Vec<&str> = vec!["--clock", "virtual"];
    for o in &fixture.overrides {
        args.extend(["--set", o]);
    }
    let mcemu = Mcemu::start(fixture.config.as_deref(), &args);
    let mut m = Matrix {
        client: MbapClient::connect(mcemu.address("modbus-tcp")),
        expected: BTreeMap::new(),
        failures: Vec::new(),
        rows: 0,
    };
    for table in TABLES {
        edge_rows(&mut m, table, &spans(&map, table));
    }
    quantity_rows(&mut m, &map);

    // Values refused: 03, nothing executed.
    for (address, words) in &fixture.bad_values {
        m.exception(
            &format!("FC 16 bad value {words:04X?} at {address}"),
            &fc16(*address, words),
            3,
        );
    }
    // The engine refuses: 04, with its reason in the control API.
    let (address, words, reason) = &fixture.refusal;
    let pdu = fc16(*address, words);
    m.exception(
        &format!("FC 16 refused by the engine at {address}"),
        &pdu,
        4,
    );
    let last = mcemu.frontend("modbus_tcp")["last_error"].clone();
    m.check_eq("last_error.exception", last["exception"].clone(), 4.into());
    m.check_eq("last_error.function", last["function"].clone(), 16.into());
    if !last["reason"].as_str().unwrap_or("").contains(reason) {
        m.failures
            .push(format!("last_error names no `{reason}`: {last}"));
    }

    let out = unmapped(&spans(&map, Table::HoldingRegisters), 1);
    function_rows(&mut m, &map.identity, out);

    // The front-end counted exactly the exceptions the rows expected.
    let counted = &mcemu.frontend("modbus_tcp")["counters"]["exceptions_by_code"];
    let counted: BTreeMap<u8, u64> = counted
        .as_object()
        .unwrap()
        .iter()
        .map(|(k, v)| (k.parse().unwrap(), v.as_u64().unwrap()))
        .collect();
    m.check_eq("exceptions_by_code", counted, m.expected.clone());
    eprintln!("{}: {} rows", fixture.name, m.rows);
    assert!(
        m.failures.is_empty(),
        "{}: {} of {} rows failed:\n{}",
        fixture.name,
        m.failures.len(),
        m.rows,
        m.failures.join("\n")
    );
}

fn f64_words(v: f64) -> Vec<u16> {
    v.to_be_bytes()
        .chunks(2)
        .map(|c| u16::from_be_bytes([c[0], c[1]]))
        .collect()
}

/// Low word first (HIMC, `cdab`).
fn f32_cdab(v: f32) -> Vec<u16> {
    let b = v.to_be_bytes();
    vec![
        u16::from_be_bytes([b[2], b[3]]),
        u16::from_be_bytes([b[0], b[1]]),
    ]
}

#[test]
fn generic_map_on_the_default_machine() {
    run(Fixture {
        name: "generic",
        config: None,
        overrides: Vec::new(),
        // Command register of axis 0: move absolute, axis disabled.
        refusal: (8, vec![1], "axis 0 is disabled"),
        bad_values: vec![
            // A NaN target (f64) is no value of the point's type.
            (0, vec![0x7FF8, 0, 0, 0]),
            // A negative speed is refused by the engine's parameter check.
            (10, f64_words(-1.0)),
        ],
    });
}

#[test]
fn himc_map_on_the_himc_fixture() {
    run(Fixture {
        name: "himc",
        config: Some(workspace_root().join("fixtures/himc.toml")),
        overrides: Vec::new(),
        // Motion command 1 (move absolute) of axis 0, disabled.
        refusal: (48, vec![1], "axis 0 is disabled"),
        bad_values: vec![
            // Smoothing time 600 ms (0 … 500).
            (28, f32_cdab(600.0)),
            // Infinite max velocity.
            (16, vec![0, 0, 0, 0x7FF0]),
        ],
    });
}

#[test]
fn hollysys_map_on_the_hollysys_fixture() {
    run(Fixture {
        name: "hollysys-mc",
        config: Some(workspace_root().join("fixtures/hollysys-mc.toml")),
        overrides: Vec::new(),
        // HMC_MoveAbs of axis 0, disabled.
        refusal: (198, vec![14], "axis 0 is disabled"),
        bad_values: vec![
            // RepMode 99 and CmdStopMode 99 are no modes (lenient parameters fix signs and
            // zeros, not these).
            (29, vec![99]),
            (77, vec![99]),
        ],
    });
}

#[test]
fn ct_e10_servo_map_on_the_cpu226h_fixture() {
    // The fixture serves the E10 over RTU and RTU over TCP; a Modbus TCP section with the same
    // map and axis gives the matrix raw MBAP access to it.
    run(Fixture {
        name: "ct-e10-servo",
        config: Some(workspace_root().join("fixtures/cpu226h.toml")),
        overrides: vec![
            "frontends.modbus_tcp.bind=127.0.0.1:0".into(),
            "frontends.modbus_tcp.map=\"ct-e10-servo\"".into(),
            "frontends.modbus_tcp.axes=[\"e10_rtu\"]".into(),
        ],
        // P281 = 1: run at internal speed 1, drive disabled.
        refusal: (281, vec![1], "axis 4 is disabled"),
        // Every E10 register is a plain integer that takes any value: 03 comes from the codec
        // rows only (the misprinted CPU 226H frame is in modbus_cpu226h_frames.rs).
        bad_values: Vec::new(),
    });
}
