//! RTU frames (address, PDU, CRC) over TCP, as serial-to-Ethernet converters carry them. TCP
//! has no silence between frames, so a frame's length is predicted from its function code
//! (`frame::rtu::request_length`); only when the function code does not tell is a frame ended
//! by silence. Connection bound and timeouts as for Modbus TCP.

use std::future::Future;
use std::sync::Arc;
use std::time::Duration;

use mcemu_frontend::bound::Connection;
use tokio::net::TcpListener;
use tokio::time::Instant;

use super::rtu::{answer, Verdict};
use super::{
    accept_loop, closed_by_fault, earliest, expired, unless_stopping, wait_for_bytes, write_reply,
    Close, Deadlines, Wait,
};
use crate::config::{ConnectionLimits, RtuOverTcpConfig};
use crate::frame::rtu::{self, Length, MAX_ADU};
use crate::model::{DataModel, Peer};
use crate::server::Server;

use crate::state::FrontendState;

/// Serve RTU over TCP on `listener` until `shutdown` resolves. `state` should have
/// [`Framing::RtuOverTcp`](crate::state::Framing::RtuOverTcp).
pub async fn serve_rtu_over_tcp<D: DataModel>(
    listener: TcpListener,
    model: Arc<D>,
    config: &RtuOverTcpConfig,
    state: Arc<FrontendState>,
    shutdown: impl Future<Output = ()>,
) {
    let limits = config.limits();
    let silence = Duration::from_millis(config.silence_ms.max(1));
    let server = Server::new(model, Arc::clone(&state));
    accept_loop(listener, limits, state, shutdown, move |c| {
        connection(server.clone(), c, limits, silence)
    })
    .await;
}

async fn connection<D: DataModel>(
    server: Server<D>,
    mut c: Connection,
    limits: ConnectionLimits,
    silence: Duration,
) {
    let why = run(&server, &mut c, limits, silence).await;
    tracing::debug!(?why, "connection ends");
}

async fn run<D: DataModel>(
    server: &Server<D>,
    c: &mut Connection,
    limits: ConnectionLimits,
    silence: Duration,
) -> Close {
    let counters = &server.state().counters;
    let peer_id = Peer::Tcp(c.peer);
    let mut buf: Vec<u8> = Vec::with_capacity(2 * MAX_ADU);
    let mut deadlines = Deadlines::new(limits);
    let mut last_rx = Instant::now();
    loop {
        let mut consumed = false;
        // Set when the buffer's frame can only be delimited by silence.
        let mut by_silence = false;
        while !buf.is_empty() {
            let n = match rtu::request_length(&buf) {
                Length::Known(n) if buf.len() >= n => n,
                Length::Known(_) | Length::NeedMore => break,
                Length::Unknown => {
                    by_silence = true;
                    break;
                }
            };
            let frame = buf.get(..n).unwrap_or_default();
            if matches!(rtu::decode(frame), rtu::Decoded::BadCrc) {
                // The frame's own length fields may be wrong (CPU 226H §10.1 network 5 as
                // printed: 4 registers, byte count 0, 4 data bytes, a CRC over all 13): let
                // silence end it, as on a serial line. Its CRC then decides; a bad one drops
                // everything buffered, as before.
                by_silence = true;
                break;
            }
            // Not evicted while it is answered (a `delay` fault may hold it long).
            let _request = c.activity.request();
            let Some(verdict) = unless_stopping(answer(server, frame, &peer_id), &mut c.stop).await
            else {
                return Close::Shutdown;
            };
            match verdict {
                Verdict::Reply(reply) => {
                    if let Err(close) =
                        write_reply(&mut c.stream, &reply, counters, &limits, &mut c.stop).await
                    {
                        return close;
                    }
                    buf.drain(..n);
                }
                Verdict::Silent => {
                    buf.drain(..n);
                }
                Verdict::Close => return closed_by_fault(),
                Verdict::Dropped => {
                    // A bad CRC means the length prediction may be off too: resynchronise by
                    // dropping everything received so far.
                    buf.clear();
                }
            }
            consumed = true;
        }
        if by_silence && buf.len() > MAX_ADU {
            // No frame is that long: drop the lot (counted) and wait for a clean start.
            counters.too_long.inc();
            counters.diagnostics.bus_character_overrun.inc();
            buf.clear();
            by_silence = false;
        }
        deadlines.framed(consumed, !buf.is_empty());
        let next = deadlines.next();
        let silence_end = by_silence.then_some(last_rx + silence);
        let deadline = earliest(next.as_ref().map(|(t, _)| *t), silence_end);
        match wait_for_bytes(c, &mut buf, counters, &mut deadlines, deadline).await {
            Ok(Wait::Received) => last_rx = Instant::now(),
            Ok(Wait::Deadline) => {
                if silence_end.is_some_and(|s| Instant::now() >= s) {
                    // Silence ends the frame (Serial Line §2.5.1.1): whatever arrived is one.
                    let frame = std::mem::take(&mut buf);
                    let _request = c.activity.request();
                    let Some(verdict) =
                        unless_stopping(answer(server, &frame, &peer_id), &mut c.stop).await
                    else {
                        return Close::Shutdown;
                    };
                    match verdict {
                        Verdict::Reply(reply) => {
                            if let Err(close) =
                                write_reply(&mut c.stream, &reply, counters, &limits, &mut c.stop)
                                    .await
                            {
                                return close;
                            }
                        }
                        Verdict::Close => return closed_by_fault(),
                        Verdict::Silent | Verdict::Dropped => {}
                    }
                    deadlines.framed(true, false);
                    continue;
                }
                if let Some((_, which)) = next {
                    expired(counters, &which, &limits);
                }
                return Close::Ours;
            }
            Err(close) => return close,
        }
    }
}
