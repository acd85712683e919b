//! Arbitrary bytes through the Native ASCII core as a connection feeds them: split into lines
//! in two chunks at every split point the input chooses, each line parsed and handled against
//! an empty machine. Never panics; the splitter holds at most 512 bytes; every line gets
//! exactly one reply, ending in CRLF; the same bytes in one chunk give the same lines.

#![no_main]

use std::sync::Arc;

use libfuzzer_sys::fuzz_target;
use mcemu_ascii::counters::Counters;
use mcemu_ascii::line::LineSplitter;
use mcemu_ascii::native::{Native, Options, Step};
use mcemu_ascii::parse::parse_call;
use mcemu_ascii::registers::Registers;

fuzz_target!(|data: &[u8]| {
    let Some((&cut, bytes)) = data.split_first() else {
        return;
    };
    let cut = usize::from(cut).min(bytes.len());
    let (a, b) = bytes.split_at(cut);
    let mut split = LineSplitter::new(512);
    let mut lines = Vec::new();
    split.push(a, &mut lines);
    assert!(split.pending() <= 512);
    split.push(b, &mut lines);
    assert!(split.pending() <= 512);
    let mut whole = LineSplitter::new(512);
    let mut again = Vec::new();
    whole.push(bytes, &mut again);
    assert_eq!(lines, again);

    let native = Native::new(Options::default(), Arc::new(Counters::default()));
    let snapshot = axes::Snapshot::default();
    let mut registers = Registers::default();
    for line in &lines {
        if let mcemu_ascii::line::Line::Text(t) = line {
            let _ = parse_call(t);
        }
        match native.line(line, &snapshot, &mut registers) {
            Step::Reply(r) => {
                assert!(r.ends_with("\r\n"));
                assert_eq!(r.matches("\r\n").count(), 1);
            }
            Step::Engine(commands, _) => assert!(!commands.is_empty()),
        }
    }
});
