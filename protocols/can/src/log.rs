//! A `candump -L` log of every frame on a bus: `(1700000000.123456) vcan0 123#DEADBEEF`, one
//! line a frame, in the compact form of can-utils (see [`crate::WireFrame`]'s `Display`), so
//! `canplayer` and `log2asc` read it.
//!
//! The bus must never wait for a disk: frames go through a bounded queue to a writer thread,
//! and a frame that finds the queue full is dropped from the log and counted. The writer
//! flushes whenever the queue runs empty, so a quiet bus leaves a complete file.

use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::Path;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::{sync_channel, Receiver, SyncSender, TrySendError};
use std::sync::Arc;
use std::thread::{self, JoinHandle};

use crate::clock::Timestamp;
use crate::frame::WireFrame;

/// Frames the log queue holds by default before it drops (about 1 s of a saturated 1 Mbit/s
/// bus).
pub const DEFAULT_LOG_QUEUE: usize = 8192;

/// One `candump -L` line, without the newline.
pub fn format_line(stamp: Timestamp, interface: &str, frame: &WireFrame) -> String {
    format!("({stamp}) {interface} {frame}")
}

/// What a finished log wrote and lost.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LogSummary {
    pub lines: u64,
    /// Frames dropped because the queue was full.
    pub dropped: u64,
}

/// A running log: a bounded queue to its writer thread.
#[derive(Debug)]
pub struct CandumpLog {
    queue: SyncSender<(Timestamp, WireFrame)>,
    writer: JoinHandle<io::Result<u64>>,
    dropped: Arc<AtomicU64>,
}

impl CandumpLog {
    /// Create (truncate) `path` and log frames of bus `interface` to it.
    pub fn create(path: &Path, interface: &str, queue: usize) -> io::Result<Self> {
        let file = File::create(path).map_err(|e| {
            io::Error::new(e.kind(), format!("candump log {}: {e}", path.display()))
        })?;
        Self::to_writer(file, interface, queue)
    }

    /// Log to any writer (buffered here).
    pub fn to_writer<W: Write + Send + 'static>(
        writer: W,
        interface: &str,
        queue: usize,
    ) -> io::Result<Self> {
        let (tx, rx) = sync_channel(queue.max(1));
        let interface = interface.to_string();
        let writer = thread::Builder::new()
            .name(format!("candump-log {interface}"))
            .spawn(move || write_lines(rx, BufWriter::new(writer), &interface))?;
        Ok(Self {
            queue: tx,
            writer,
            dropped: Arc::new(AtomicU64::new(0)),
        })
    }

    /// Queue one frame; never blocks. Returns `false` when it was dropped (queue full, or the
    /// writer stopped on an I/O error).
    pub fn record(&self, stamp: Timestamp, frame: &WireFrame) -> bool {
        match self.queue.try_send((stamp, *frame)) {
            Ok(()) => true,
            Err(TrySendError::Full(_) | TrySendError::Disconnected(_)) => {
                self.dropped.fetch_add(1, Ordering::Relaxed);
                false
            }
        }
    }

    pub fn dropped(&self) -> u64 {
        self.dropped.load(Ordering::Relaxed)
    }

    /// Stop: the writer writes what is queued, flushes and ends. Returns what it wrote, or its
    /// first I/O error.
    pub fn finish(self) -> io::Result<LogSummary> {
        let dropped = self.dropped();
        drop(self.queue);
        let lines = self
            .writer
            .join()
            .map_err(|_| io::Error::other("the candump log writer panicked"))??;
        Ok(LogSummary { lines, dropped })
    }
}

fn write_lines<W: Write>(
    rx: Receiver<(Timestamp, WireFrame)>,
    mut out: W,
    interface: &str,
) -> io::Result<u64> {
    let mut lines = 0;
    // Blocks until a frame or the end; then writes whatever else is already queued before
    // flushing, so a busy bus gets large writes and a quiet one a flushed file.
    while let Ok((stamp, frame)) = rx.recv() {
        writeln!(out, "{}", format_line(stamp, interface, &frame))?;
        lines += 1;
        while let Ok((stamp, frame)) = rx.try_recv() {
            writeln!(out, "{}", format_line(stamp, interface, &frame))?;
            lines += 1;
        }
        out.flush()?;
    }
    out.flush()?;
    Ok(lines)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use super::*;
    use crate::frame::CanId;
    use std::sync::Mutex;

    #[derive(Clone, Default)]
    struct Shared(Arc<Mutex<Vec<u8>>>);
    impl Write for Shared {
        fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
            self.0.lock().unwrap().extend_from_slice(buf);
            Ok(buf.len())
        }
        fn flush(&mut self) -> io::Result<()> {
            Ok(())
        }
    }

    #[test]
    fn lines_in_candump_l_form() {
        let stamp = Timestamp {
            secs: 1_700_000_000,
            micros: 123_456,
        };
        let frames = [
            WireFrame::standard(0x123, &[0xDE, 0xAD, 0xBE, 0xEF]).unwrap(),
            WireFrame::remote(CanId::standard(0x123).unwrap(), 0).unwrap(),
            WireFrame::remote(CanId::standard(0x123).unwrap(), 4).unwrap(),
            WireFrame::extended(0x1234_5678, &[1]).unwrap(),
            WireFrame::error(0x80, &[]).unwrap(),
        ];
        let sink = Shared::default();
        let log = CandumpLog::to_writer(sink.clone(), "vcan0", 16).unwrap();
        for f in &frames {
            assert!(log.record(stamp, f));
        }
        assert_eq!(
            log.finish().unwrap(),
            LogSummary {
                lines: 5,
                dropped: 0
            }
        );
        let text = String::from_utf8(sink.0.lock().unwrap().clone()).unwrap();
        assert_eq!(
            text,
            "(1700000000.123456) vcan0 123#DEADBEEF\n\
             (1700000000.123456) vcan0 123#R\n\
             (1700000000.123456) vcan0 123#R4\n\
             (1700000000.123456) vcan0 12345678#01\n\
             (1700000000.123456) vcan0 20000080#0000000000000000\n"
        );
    }

    /// A writer that blocks until released: the bus side must not wait for it.
    struct Stuck(Arc<(Mutex<bool>, std::sync::Condvar)>);
    impl Write for Stuck {
        fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
            let (lock, cv) = &*self.0;
            let mut go = lock.lock().unwrap();
            while !*go {
                go = cv.wait(go).unwrap();
            }
            Ok(buf.len())
        }
        fn flush(&mut self) -> io::Result<()> {
            Ok(())
        }
    }

    #[test]
    fn a_stuck_disk_drops_frames_instead_of_blocking() {
        let gate = Arc::new((Mutex::new(false), std::sync::Condvar::new()));
        let log = CandumpLog::to_writer(Stuck(gate.clone()), "vcan0", 4).unwrap();
        let frame = WireFrame::standard(1, &[]).unwrap();
        let stamp = Timestamp { secs: 0, micros: 0 };
        let accepted = (0..1000).filter(|_| log.record(stamp, &frame)).count();
        // The queue (4) plus what the writer buffered before it stuck; the rest dropped at once.
        assert!(accepted < 1000 / 2, "{accepted}");
        assert_eq!(log.dropped(), 1000 - accepted as u64);
        *gate.0.lock().unwrap() = true;
        gate.1.notify_all();
        let summary = log.finish().unwrap();
        assert_eq!(summary.lines + summary.dropped, 1000);
    }
}
