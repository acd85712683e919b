//! Modbus RTU on a serial line (Modbus over Serial Line V1.02): a pseudo-terminal this process
//! creates, or a tty device it opens and configures (baud, parity, stop bits; 8 data bits).
//!
//! A frame ends after 3.5 characters of silence (§2.5.1.1). To keep latency low where the line
//! is a pty (which delivers a whole write at once), a frame also ends as soon as its length,
//! predicted from the function code, is complete *and* its CRC checks; otherwise the silence
//! decides. A reply is sent as soon as it is ready: the master is waiting for it, so the line is
//! idle.

use std::fs::OpenOptions;
use std::future::Future;
use std::io;
use std::os::fd::{AsFd, OwnedFd};
use std::os::unix::fs::OpenOptionsExt;
use std::sync::Arc;
use std::time::Duration;

use nix::fcntl::{fcntl, FcntlArg, OFlag};
use nix::sys::termios::{
    cfmakeraw, cfsetspeed, tcflush, tcgetattr, tcsetattr, BaudRate, ControlFlags, FlushArg, SetArg,
    SpecialCharacterIndices,
};
use tokio::io::unix::AsyncFd;
use tokio::time::Instant;
use tracing::Instrument;

use super::{sleep_until, transient};
use crate::config::{Parity, RtuConfig};
use crate::frame::rtu::{self, Decoded, Length, MAX_ADU};
use crate::model::{DataModel, Peer};
use crate::server::{Outcome, Server};
use crate::state::FrontendState;

/// A reply the line cannot take in this time (nobody reads the pty) is dropped.
const WRITE_TIMEOUT: Duration = Duration::from_secs(1);

/// What became of one RTU frame.
pub(crate) enum Verdict {
    /// The reply frame, CRC included, after any `corrupt`/`drop_bytes` fault.
    Reply(Vec<u8>),
    /// A good frame that gets no reply (another unit, broadcast, listen-only …).
    Silent,
    /// A bad frame (CRC, too short, too long): dropped and counted, never answered.
    Dropped,
    /// No reply, and the connection closes (a `close` fault; never on a serial line, which
    /// refuses it).
    Close,
}

/// Check one RTU frame and answer it.
pub(crate) async fn answer<D: DataModel>(server: &Server<D>, frame: &[u8], peer: &Peer) -> Verdict {
    let state = server.state();
    let c = &state.counters;
    match rtu::decode(frame) {
        Decoded::Frame { unit, pdu } => match server.handle(unit, pdu, peer).await {
            Outcome::Reply(reply) => {
                let mut out = Vec::with_capacity(reply.len() + 3);
                rtu::encode(unit, &reply, &mut out);
                state.faults.mangle_rtu_reply(&mut out, &c.faults_applied);
                Verdict::Reply(out)
            }
            Outcome::Silent => Verdict::Silent,
            Outcome::Close => Verdict::Close,
        },
        Decoded::BadCrc => {
            c.crc_errors.inc();
            c.diagnostics.bus_communication_error.inc();
            tracing::debug!(len = frame.len(), "frame with a bad CRC dropped");
            Verdict::Dropped
        }
        Decoded::TooShort => {
            // Serial Line §6.1.1: a frame too short for a CRC is a communication error too.
            c.too_short.inc();
            c.diagnostics.bus_communication_error.inc();
            tracing::debug!(len = frame.len(), "frame too short dropped");
            Verdict::Dropped
        }
        Decoded::TooLong => {
            c.too_long.inc();
            c.diagnostics.bus_character_overrun.inc();
            tracing::debug!(len = frame.len(), "frame too long dropped");
            Verdict::Dropped
        }
    }
}

/// A serial line that cannot be opened or configured.
#[derive(Debug, thiserror::Error)]
#[error("modbus_rtu device {device}: {reason}")]
pub struct LineError {
    pub device: String,
    pub reason: String,
}

/// An open, configured serial line, not yet served.
#[derive(Debug)]
pub struct RtuLine {
    /// The side this server reads and writes: the pty master, or the device.
    fd: OwnedFd,
    /// A pty's slave side, held open so the line (and its settings) survives clients that
    /// close and reopen it.
    _slave: Option<OwnedFd>,
    path: String,
    silence: Duration,
}

impl RtuLine {
    /// Create the pty (`device = "pty"`) or open the device, and configure it. Needs no
    /// runtime; [`serve_rtu`] does.
    pub fn open(config: &RtuConfig) -> Result<RtuLine, LineError> {
        let fail = |device: &str, reason: String| LineError {
            device: device.to_owned(),
            reason,
        };
        let device = config.device.as_str();
        let baud = baud_rate(config.baud).ok_or_else(|| {
            fail(
                device,
                format!(
                    "baud {} is not a standard rate: {}",
                    config.baud,
                    BAUDS
                        .iter()
                        .map(|(b, _)| b.to_string())
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            )
        })?;
        if !(1..=2).contains(&config.stop_bits) {
            return Err(fail(
                device,
                format!("stop_bits must be 1 or 2, not {}", config.stop_bits),
            ));
        }
        let (fd, slave, path) = if device == "pty" {
            let pty = nix::pty::openpty(None, None)
                .map_err(|e| fail(device, format!("cannot create a pty: {e}")))?;
            let path = nix::unistd::ttyname(&pty.slave)
                .map_err(|e| fail(device, format!("cannot name the new pty: {e}")))?
                .to_string_lossy()
                .into_owned();
            configure(&pty.slave, baud, config)
                .map_err(|e| fail(&path, format!("cannot set up the pty: {e}")))?;
            (pty.master, Some(pty.slave), path)
        } else {
            let file = OpenOptions::new()
                .read(true)
                .write(true)
                // Not our controlling terminal; never block in open (modem lines).
                .custom_flags(nix::libc::O_NOCTTY | nix::libc::O_NONBLOCK)
                .open(device)
                .map_err(|e| fail(device, format!("cannot open it: {e}")))?;
            let fd = OwnedFd::from(file);
            configure(&fd, baud, config).map_err(|e| fail(device, e))?;
            // Whatever was queued before we came is no request of this session.
            let _ = tcflush(&fd, FlushArg::TCIOFLUSH);
            (fd, None, device.to_owned())
        };
        set_nonblocking(&fd)
            .map_err(|e| fail(&path, format!("cannot make it non-blocking: {e}")))?;
        Ok(RtuLine {
            fd,
            _slave: slave,
            path,
            silence: rtu::inter_frame_silence(config.baud),
        })
    }

    /// The device path clients open: the pty's `/dev/pts/N`, or the configured device.
    pub fn path(&self) -> &str {
        &self.path
    }

    /// The silence that ends a frame at this line's baud.
    pub fn silence(&self) -> Duration {
        self.silence
    }
}

/// Raw 8-bit mode with the configured speed, parity and stop bits (Serial Line §2.5.1).
fn configure(fd: &OwnedFd, baud: BaudRate, config: &RtuConfig) -> Result<(), String> {
    let mut t = tcgetattr(fd).map_err(|e| format!("not a terminal ({e})"))?;
    cfmakeraw(&mut t);
    t.control_flags &= !(ControlFlags::CSIZE
        | ControlFlags::PARENB
        | ControlFlags::PARODD
        | ControlFlags::CSTOPB
        | ControlFlags::CRTSCTS);
    t.control_flags |= ControlFlags::CS8 | ControlFlags::CREAD | ControlFlags::CLOCAL;
    match config.parity {
        Parity::None => {}
        Parity::Even => t.control_flags |= ControlFlags::PARENB,
        Parity::Odd => t.control_flags |= ControlFlags::PARENB | ControlFlags::PARODD,
    }
    if config.stop_bits == 2 {
        t.control_flags |= ControlFlags::CSTOPB;
    }
    t.control_chars[SpecialCharacterIndices::VMIN as usize] = 1;
    t.control_chars[SpecialCharacterIndices::VTIME as usize] = 0;
    cfsetspeed(&mut t, baud).map_err(|e| format!("cannot set baud: {e}"))?;
    tcsetattr(fd, SetArg::TCSANOW, &t).map_err(|e| format!("cannot configure: {e}"))
}

fn set_nonblocking(fd: &OwnedFd) -> nix::Result<()> {
    let flags = OFlag::from_bits_truncate(fcntl(fd, FcntlArg::F_GETFL)?);
    fcntl(fd, FcntlArg::F_SETFL(flags | OFlag::O_NONBLOCK)).map(|_| ())
}

const BAUDS: [(u32, BaudRate); 15] = [
    (1200, BaudRate::B1200),
    (2400, BaudRate::B2400),
    (4800, BaudRate::B4800),
    (9600, BaudRate::B9600),
    (19_200, BaudRate::B19200),
    (38_400, BaudRate::B38400),
    (57_600, BaudRate::B57600),
    (115_200, BaudRate::B115200),
    (230_400, BaudRate::B230400),
    (460_800, BaudRate::B460800),
    (500_000, BaudRate::B500000),
    (576_000, BaudRate::B576000),
    (921_600, BaudRate::B921600),
    (1_000_000, BaudRate::B1000000),
    (2_000_000, BaudRate::B2000000),
];

fn baud_rate(baud: u32) -> Option<BaudRate> {
    BAUDS.iter().find(|(b, _)| *b == baud).map(|(_, r)| *r)
}

/// Serve Modbus RTU on `line` until `shutdown` resolves. Returns an error when the line fails
/// (a device that hangs up or goes away). `state` should have
/// [`Framing::Rtu`](crate::state::Framing::Rtu).
pub async fn serve_rtu<D: DataModel>(
    line: RtuLine,
    model: Arc<D>,
    state: Arc<FrontendState>,
    shutdown: impl Future<Output = ()>,
) -> io::Result<()> {
    let RtuLine {
        fd,
        _slave,
        path,
        silence,
    } = line;
    let span = tracing::info_span!("modbus_rtu", frontend = %state.name(), device = %path);
    // `AsyncFd::new` is deprecated because a generic `T` may close or swap its fd while
    // registered; an `OwnedFd` owns its fd, which stays open and the same until the `AsyncFd`
    // drops, so the replacement's safety contract (`unsafe fn register`) holds here without
    // `unsafe`, which this workspace denies.
    #[allow(deprecated)]
    let fd = AsyncFd::new(fd)?;
    let server = Server::new(model, state);
    let peer = Peer::Serial(Arc::from(path.as_str()));
    let result = serve_line(&fd, &server, &peer, silence, shutdown)
        .instrument(span)
        .await;
    drop(_slave);
    result
}

async fn serve_line<D: DataModel>(
    fd: &AsyncFd<OwnedFd>,
    server: &Server<D>,
    peer: &Peer,
    silence: Duration,
    shutdown: impl Future<Output = ()>,
) -> io::Result<()> {
    let counters = &server.state().counters;
    let mut buf: Vec<u8> = Vec::with_capacity(2 * MAX_ADU);
    let mut chunk = [0u8; 512];
    let mut last_rx = Instant::now();
    // After an overlong frame: drop bytes until the line falls silent.
    let mut discarding = false;
    tokio::pin!(shutdown);
    loop {
        let silence_end = (!buf.is_empty() || discarding).then_some(last_rx + silence);
        tokio::select! {
            () = &mut shutdown => return Ok(()),
            ready = fd.readable() => {
                let mut guard = ready?;
                let n = match guard.try_io(|fd| {
                    nix::unistd::read(fd.get_ref(), &mut chunk).map_err(io::Error::from)
                }) {
                    Err(_would_block) => continue,
                    Ok(Ok(0)) => {
                        return Err(io::Error::new(
                            io::ErrorKind::UnexpectedEof,
                            "the serial line hung up",
                        ))
                    }
                    Ok(Ok(n)) => n,
                    Ok(Err(e)) if transient(&e) => continue,
                    Ok(Err(e)) => return Err(e),
                };
                counters.bytes_in.add(n as u64);
                last_rx = Instant::now();
                if discarding {
                    continue;
                }
                buf.extend_from_slice(chunk.get(..n).unwrap_or_default());
                if buf.len() > MAX_ADU {
                    counters.too_long.inc();
                    counters.diagnostics.bus_character_overrun.inc();
                    tracing::debug!("frame longer than 256 bytes dropped");
                    buf.clear();
                    discarding = true;
                    continue;
                }
                // Early end: the predicted length is here and its CRC checks.
                while let Length::Known(len) = rtu::request_length(&buf) {
                    let Some(frame) = buf.get(..len) else { break };
                    if !matches!(rtu::decode(frame), Decoded::Frame { .. }) {
                        break;
                    }
                    let frame: Vec<u8> = buf.drain(..len).collect();
                    tokio::select! {
                        r = respond(fd, server, &frame, peer) => r?,
                        () = &mut shutdown => return Ok(()),
                    }
                }
            }
            () = sleep_until(silence_end) => {
                // 3.5 characters of silence: what arrived is one frame.
                discarding = false;
                let frame = std::mem::take(&mut buf);
                if !frame.is_empty() {
                    tokio::select! {
                        r = respond(fd, server, &frame, peer) => r?,
                        () = &mut shutdown => return Ok(()),
                    }
                }
            }
        }
    }
}

async fn respond<D: DataModel>(
    fd: &AsyncFd<OwnedFd>,
    server: &Server<D>,
    frame: &[u8],
    peer: &Peer,
) -> io::Result<()> {
    let Verdict::Reply(reply) = answer(server, frame, peer).await else {
        return Ok(());
    };
    match tokio::time::timeout(WRITE_TIMEOUT, write_all(fd, &reply)).await {
        Ok(Ok(())) => {
            server.state().counters.bytes_out.add(reply.len() as u64);
            Ok(())
        }
        Ok(Err(e)) => Err(e),
        Err(_) => {
            tracing::warn!("reply dropped: the line did not take it within 1 s");
            Ok(())
        }
    }
}

async fn write_all(fd: &AsyncFd<OwnedFd>, mut bytes: &[u8]) -> io::Result<()> {
    while !bytes.is_empty() {
        let mut guard = fd.writable().await?;
        match guard
            .try_io(|fd| nix::unistd::write(fd.get_ref().as_fd(), bytes).map_err(io::Error::from))
        {
            Ok(Ok(n)) => bytes = bytes.get(n..).unwrap_or_default(),
            Ok(Err(e)) if transient(&e) => {}
            Ok(Err(e)) => return Err(e),
            Err(_would_block) => {}
        }
    }
    Ok(())
}
