//! Modbus TCP server (Messaging on TCP/IP Implementation Guide V1.0b): MBAP framing, one task
//! per connection, pipelined requests answered in order.

use std::future::Future;
use std::sync::Arc;

use mcemu_frontend::bound::Connection;
use tokio::net::TcpListener;

use super::{
    accept_loop, closed_by_fault, expired, unless_stopping, wait_for_bytes, write_reply, Close,
    Deadlines, Wait,
};
use crate::config::{ConnectionLimits, TcpConfig};
use crate::frame::tcp::{self, Decoded};
use crate::model::{DataModel, Peer};
use crate::server::{Outcome, Server};
use crate::state::FrontendState;

/// Serve Modbus TCP on `listener` until `shutdown` resolves; then stop accepting, close every
/// connection and return. `state` should have [`Framing::Tcp`](crate::state::Framing::Tcp).
pub async fn serve_tcp<D: DataModel>(
    listener: TcpListener,
    model: Arc<D>,
    config: &TcpConfig,
    state: Arc<FrontendState>,
    shutdown: impl Future<Output = ()>,
) {
    let limits = config.limits();
    let server = Server::new(model, Arc::clone(&state));
    accept_loop(listener, limits, state, shutdown, move |c| {
        connection(server.clone(), c, limits)
    })
    .await;
}

async fn connection<D: DataModel>(server: Server<D>, mut c: Connection, limits: ConnectionLimits) {
    let why = run(&server, &mut c, limits).await;
    tracing::debug!(?why, "connection ends");
}

async fn run<D: DataModel>(
    server: &Server<D>,
    c: &mut Connection,
    limits: ConnectionLimits,
) -> Close {
    let counters = &server.state().counters;
    let peer_id = Peer::Tcp(c.peer);
    let mut buf: Vec<u8> = Vec::with_capacity(2 * tcp::MAX_ADU);
    let mut out = Vec::with_capacity(tcp::MAX_ADU);
    let mut deadlines = Deadlines::new(limits);
    loop {
        // Answer every complete frame in the buffer, in order.
        let mut consumed = false;
        loop {
            match tcp::decode(&buf) {
                Decoded::Frame {
                    header,
                    pdu,
                    consumed: n,
                } => {
                    // Not evicted while it is answered (a `delay` fault may hold it long).
                    let _request = c.activity.request();
                    let Some(outcome) =
                        unless_stopping(server.handle(header.unit, pdu, &peer_id), &mut c.stop)
                            .await
                    else {
                        return Close::Shutdown;
                    };
                    match outcome {
                        Outcome::Reply(reply) => {
                            out.clear();
                            // The reply echoes the transaction and unit ids (§3.1.3).
                            tcp::encode(header, &reply, &mut out);
                            if let Err(close) =
                                write_reply(&mut c.stream, &out, counters, &limits, &mut c.stop)
                                    .await
                            {
                                return close;
                            }
                        }
                        Outcome::Close => return closed_by_fault(),
                        Outcome::Silent => {}
                    }
                    buf.drain(..n);
                    consumed = true;
                }
                Decoded::Discard {
                    consumed: n,
                    protocol,
                } => {
                    // Not Modbus, but well delimited: skip it, keep the connection.
                    counters.not_modbus.inc();
                    counters.diagnostics.bus_communication_error.inc();
                    tracing::debug!(protocol, "frame with a non-Modbus protocol id skipped");
                    buf.drain(..n);
                    consumed = true;
                }
                Decoded::Close { length } => {
                    // The length cannot be trusted, so neither can any later byte.
                    counters.bad_length.inc();
                    counters.diagnostics.bus_communication_error.inc();
                    tracing::info!(length, "closing connection: impossible MBAP length");
                    return Close::Ours;
                }
                Decoded::NeedMore => break,
            }
        }
        deadlines.framed(consumed, !buf.is_empty());
        let next = deadlines.next();
        let deadline = next.as_ref().map(|(t, _)| *t);
        match wait_for_bytes(c, &mut buf, counters, &mut deadlines, deadline).await {
            Ok(Wait::Received) => {}
            Ok(Wait::Deadline) => {
                if let Some((_, which)) = next {
                    expired(counters, &which, &limits);
                }
                return Close::Ours;
            }
            Err(close) => return close,
        }
    }
}
