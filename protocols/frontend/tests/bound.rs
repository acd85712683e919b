//! The bounded accept loop on real loopback sockets, with a toy line protocol: each byte is
//! echoed, except `w`, which starts a request that is answered (`W`) only when the test says.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::sync::Arc;
use std::time::Duration;

use mcemu_frontend::bound::{serve, AtLimit, Bound, Connection, ConnectionTable};
use mcemu_frontend::counter::ConnectionCounters;
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::{TcpListener, TcpStream};
use tokio::sync::{mpsc, oneshot, Semaphore};

struct Server {
    addr: std::net::SocketAddr,
    counters: Arc<ConnectionCounters>,
    /// One permit answers one pending `w`.
    answers: Arc<Semaphore>,
    /// One message per `w` whose request has started.
    started: mpsc::UnboundedReceiver<()>,
    stop: Option<oneshot::Sender<()>>,
    task: tokio::task::JoinHandle<()>,
}

async fn start(max_connections: usize, at_limit: AtLimit) -> Server {
    let listener = TcpListener::bind("127.0.0.1:0").await.unwrap();
    let addr = listener.local_addr().unwrap();
    let counters = Arc::new(ConnectionCounters::default());
    let table = ConnectionTable::new(
        Bound {
            max_connections,
            at_limit,
        },
        Arc::clone(&counters),
    );
    let answers = Arc::new(Semaphore::new(0));
    let (stop, stopped) = oneshot::channel::<()>();
    let service_answers = Arc::clone(&answers);
    let (start_tx, started) = mpsc::unbounded_channel();
    let task = tokio::spawn(async move {
        serve(
            listener,
            table,
            "toy",
            async move {
                let _ = stopped.await;
            },
            move |c| echo(c, Arc::clone(&service_answers), start_tx.clone()),
            |mut stream, _| async move {
                let _ = stream.write_all(b"full").await;
            },
        )
        .await;
    });
    Server {
        addr,
        counters,
        answers,
        started,
        stop: Some(stop),
        task,
    }
}

async fn echo(mut c: Connection, answers: Arc<Semaphore>, started: mpsc::UnboundedSender<()>) {
    let mut buf = [0u8; 64];
    loop {
        let n = tokio::select! {
            r = c.stream.read(&mut buf) => match r {
                Ok(0) | Err(_) => return,
                Ok(n) => n,
            },
            _ = c.stop.changed() => return,
        };
        c.activity.received();
        for &b in &buf[..n] {
            if b == b'w' {
                let _busy = c.activity.request();
                let _ = started.send(());
                let Ok(permit) = answers.acquire().await else {
                    return;
                };
                permit.forget();
                let _ = c.stream.write_all(b"W").await;
            } else {
                let _ = c.stream.write_all(&[b]).await;
            }
        }
    }
}

impl Server {
    async fn shutdown(mut self) {
        let _ = self.stop.take().map(|s| s.send(()));
        self.answers.add_permits(100);
        self.task.await.unwrap();
    }
}

/// A client that is served: its byte comes back.
async fn echoes(stream: &mut TcpStream, byte: u8) -> bool {
    if stream.write_all(&[byte]).await.is_err() {
        return false;
    }
    let mut b = [0u8; 1];
    matches!(
        tokio::time::timeout(Duration::from_secs(5), stream.read_exact(&mut b)).await,
        Ok(Ok(_)) if b[0] == byte
    )
}

/// Whether the server closed `stream` (end of stream or reset), waiting up to 5 s.
async fn closed(stream: &mut TcpStream) -> Option<Vec<u8>> {
    let mut got = Vec::new();
    let mut b = [0u8; 16];
    loop {
        match tokio::time::timeout(Duration::from_secs(5), stream.read(&mut b)).await {
            Ok(Ok(0)) | Ok(Err(_)) => return Some(got),
            Ok(Ok(n)) => got.extend_from_slice(&b[..n]),
            Err(_) => return None,
        }
    }
}

async fn eventually(what: &str, mut cond: impl FnMut() -> bool) {
    let deadline = tokio::time::Instant::now() + Duration::from_secs(5);
    while !cond() {
        assert!(tokio::time::Instant::now() < deadline, "{what}");
        tokio::time::sleep(Duration::from_millis(5)).await;
    }
}

#[tokio::test]
async fn at_the_limit_the_connection_idle_longest_makes_room() {
    let server = start(3, AtLimit::EvictIdle).await;
    let mut clients = Vec::new();
    for _ in 0..3 {
        let mut c = TcpStream::connect(server.addr).await.unwrap();
        assert!(echoes(&mut c, b'a').await);
        clients.push(c);
    }
    // The first connected, but the second has been idle longest since.
    assert!(echoes(&mut clients[0], b'b').await);
    assert!(echoes(&mut clients[2], b'c').await);
    let mut newcomer = TcpStream::connect(server.addr).await.unwrap();
    assert!(echoes(&mut newcomer, b'n').await, "the newcomer is served");
    assert_eq!(closed(&mut clients[1]).await, Some(vec![]), "idle longest");
    assert!(echoes(&mut clients[0], b'd').await);
    assert!(echoes(&mut clients[2], b'e').await);
    let c = &server.counters;
    assert_eq!(
        (
            c.evicted_idle.get(),
            c.refused_at_limit.get(),
            c.opened.get()
        ),
        (1, 0, 4)
    );
    eventually("the evicted one counted closed", || c.open() == 3).await;
    server.shutdown().await;
}

#[tokio::test]
async fn a_connection_in_a_request_is_evicted_after_an_idle_one_and_never_refused_for() {
    let mut server = start(2, AtLimit::EvictIdle).await;
    let mut busy = TcpStream::connect(server.addr).await.unwrap();
    assert!(echoes(&mut busy, b'a').await);
    let mut idle = TcpStream::connect(server.addr).await.unwrap();
    assert!(echoes(&mut idle, b'a').await);
    // `busy` received bytes last, but its request is still being answered.
    busy.write_all(b"w").await.unwrap();
    server.started.recv().await.unwrap();
    let mut newcomer = TcpStream::connect(server.addr).await.unwrap();
    assert!(echoes(&mut newcomer, b'n').await);
    assert_eq!(closed(&mut idle).await, Some(vec![]));
    assert_eq!(server.counters.evicted_idle.get(), 1);
    // Now both open connections are in a request: the next newcomer is refused.
    newcomer.write_all(b"w").await.unwrap();
    server.started.recv().await.unwrap();
    let mut third = TcpStream::connect(server.addr).await.unwrap();
    assert_eq!(closed(&mut third).await, Some(b"full".to_vec()));
    assert_eq!(server.counters.refused_at_limit.get(), 1);
    server.answers.add_permits(2);
    let mut w = [0u8; 1];
    busy.read_exact(&mut w).await.unwrap();
    assert_eq!(&w, b"W", "the request survived");
    newcomer.read_exact(&mut w).await.unwrap();
    assert_eq!(&w, b"W");
    server.shutdown().await;
}

#[tokio::test]
async fn refuse_closes_the_newcomer_with_the_protocols_refusal() {
    let server = start(1, AtLimit::Refuse).await;
    let mut first = TcpStream::connect(server.addr).await.unwrap();
    assert!(echoes(&mut first, b'a').await);
    let mut second = TcpStream::connect(server.addr).await.unwrap();
    assert_eq!(closed(&mut second).await, Some(b"full".to_vec()));
    assert!(echoes(&mut first, b'b').await, "the open one is kept");
    assert_eq!(server.counters.refused_at_limit.get(), 1);
    assert_eq!(server.counters.evicted_idle.get(), 0);
    drop(first);
    let c = Arc::clone(&server.counters);
    eventually("the place freed", || c.open() == 0).await;
    let mut third = TcpStream::connect(server.addr).await.unwrap();
    assert!(echoes(&mut third, b'c').await);
    server.shutdown().await;
}

#[tokio::test]
async fn admit_waiting_waits_for_a_place() {
    let counters = Arc::new(ConnectionCounters::default());
    let table = ConnectionTable::new(
        Bound {
            max_connections: 1,
            at_limit: AtLimit::EvictIdle,
        },
        Arc::clone(&counters),
    );
    let first = table.admit_waiting().await;
    let second = table.admit_waiting();
    tokio::pin!(second);
    // Were the bound broken the wait would be ready at once; a slow machine can only make
    // this pass wrongly, never fail wrongly.
    let waited = tokio::time::timeout(Duration::from_millis(100), second.as_mut()).await;
    assert!(waited.is_err(), "admitted past the bound");
    drop(first);
    let _second = second.await;
    assert_eq!((counters.opened.get(), counters.closed.get()), (2, 1));
    assert_eq!(counters.evicted_idle.get(), 0, "waiting never evicts");
}
