//! The control API's TCP listener, bounded by the front-end kit's [`ConnectionTable`]
//! (ARCHITECTURE §8): a connection holds a slot for its lifetime; at the bound, `accept` waits
//! until one closes, so the kernel's backlog absorbs the excess instead of this process. (It
//! does not evict: hyper owns the connections, and an idle keep-alive connection cannot be told
//! from one whose long request is running; docs/decisions.md "Front-end kit: connections".)

use std::io;
use std::net::SocketAddr;
use std::pin::Pin;
use std::sync::Arc;
use std::task::{Context, Poll};

use mcemu_frontend::bound::{AtLimit, Bound, ConnectionTable, Slot};
use mcemu_frontend::counter::ConnectionCounters;
use tokio::io::{AsyncRead, AsyncWrite, ReadBuf};
use tokio::net::{TcpListener, TcpStream};

pub struct BoundedListener {
    inner: TcpListener,
    table: Arc<ConnectionTable>,
}

impl BoundedListener {
    pub fn new(inner: TcpListener, max_connections: usize) -> BoundedListener {
        let bound = Bound {
            max_connections,
            // Not consulted: `admit_waiting` waits at the bound.
            at_limit: AtLimit::Refuse,
        };
        BoundedListener {
            inner,
            table: ConnectionTable::new(bound, Arc::new(ConnectionCounters::default())),
        }
    }
}

/// A connection and its slot: dropping it frees a place.
pub struct BoundedStream {
    stream: TcpStream,
    _slot: Slot,
}

impl axum::serve::Listener for BoundedListener {
    type Io = BoundedStream;
    type Addr = SocketAddr;

    async fn accept(&mut self) -> (Self::Io, Self::Addr) {
        let admitted = self.table.admit_waiting().await;
        // axum's own accept retries transient errors (EMFILE …) with a back-off.
        let (stream, addr) = axum::serve::Listener::accept(&mut self.inner).await;
        (
            BoundedStream {
                stream,
                _slot: admitted.slot,
            },
            addr,
        )
    }

    fn local_addr(&self) -> io::Result<Self::Addr> {
        self.inner.local_addr()
    }
}

impl AsyncRead for BoundedStream {
    fn poll_read(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        buf: &mut ReadBuf<'_>,
    ) -> Poll<io::Result<()>> {
        Pin::new(&mut self.stream).poll_read(cx, buf)
    }
}

impl AsyncWrite for BoundedStream {
    fn poll_write(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        buf: &[u8],
    ) -> Poll<io::Result<usize>> {
        Pin::new(&mut self.stream).poll_write(cx, buf)
    }

    fn poll_flush(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<io::Result<()>> {
        Pin::new(&mut self.stream).poll_flush(cx)
    }

    fn poll_shutdown(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<io::Result<()>> {
        Pin::new(&mut self.stream).poll_shutdown(cx)
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use axum::serve::Listener;
    use std::time::Duration;

    #[tokio::test]
    async fn a_connection_at_the_bound_waits_until_one_closes() {
        let mut listener = BoundedListener::new(TcpListener::bind("127.0.0.1:0").await.unwrap(), 1);
        let address = listener.local_addr().unwrap();
        let _first_client = TcpStream::connect(address).await.unwrap();
        let (first, _) = listener.accept().await;
        // The second client's handshake completes in the kernel's backlog …
        let second_client = TcpStream::connect(address).await.unwrap();
        let accept = listener.accept();
        tokio::pin!(accept);
        // … but it is not taken while the first holds the only place. (Were the bound broken,
        // the accept would be ready at once; a slow machine can only make this pass wrongly,
        // never fail wrongly.)
        let waited = tokio::time::timeout(Duration::from_millis(200), accept.as_mut()).await;
        assert!(waited.is_err(), "accepted past the bound");
        drop(first);
        let (second, _) = accept.await;
        assert_eq!(
            second.stream.peer_addr().unwrap(),
            second_client.local_addr().unwrap()
        );
    }
}
