//! The tokio task that joins a SocketCAN interface and a hub.

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use std::time::Duration;

use tokio::sync::watch;

use crate::hub::{EndpointOptions, FrameReceiver, FrameSender, Hub};
use crate::socketcan::convert::{from_socketcan, to_socketcan};
use crate::socketcan::open::{check_sysfs, open, SocketCanError};

/// How the bridge runs.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SocketCanConfig {
    /// `vcan0` by default.
    pub interface: String,
    /// While the interface is down or gone, try to reopen it this often; while it is up,
    /// look at its link state (sysfs) this often.
    pub retry: Duration,
    /// A write that the interface does not take within this time is dropped (a bus-off
    /// controller must not stall the bridge).
    pub write_timeout: Duration,
}

impl Default for SocketCanConfig {
    fn default() -> Self {
        Self {
            interface: "vcan0".to_string(),
            retry: Duration::from_millis(500),
            write_timeout: Duration::from_millis(100),
        }
    }
}

/// Whether the interface is usable.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum LinkState {
    Up,
    /// Why not, naming the interface; the bridge keeps retrying.
    Down(String),
}

/// The bridge's counters.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SocketCanStats {
    /// Frames read from the interface and put on the hub (error frames included).
    pub frames_in: u64,
    /// Error frames among them.
    pub error_frames_in: u64,
    /// Frames from the hub written to the interface.
    pub frames_out: u64,
    /// Frames from the hub not written: the interface was down, its queue full, or the write
    /// timed out.
    pub dropped_out: u64,
    /// Error frames from the hub, which are not written out (they are reports, not traffic).
    pub error_frames_not_sent: u64,
    /// Frames read from the interface that the hub refused (bit-rate model's queue full) or
    /// that could not be converted.
    pub dropped_in: u64,
    /// Times the interface went down or away.
    pub link_losses: u64,
}

#[derive(Default)]
struct Stats {
    frames_in: AtomicU64,
    error_frames_in: AtomicU64,
    frames_out: AtomicU64,
    dropped_out: AtomicU64,
    error_frames_not_sent: AtomicU64,
    dropped_in: AtomicU64,
    link_losses: AtomicU64,
}

fn bump(counter: &AtomicU64) {
    counter.fetch_add(1, Ordering::Relaxed);
}

/// A running bridge between an interface and a hub.
pub struct SocketCanBridge {
    interface: String,
    state: watch::Receiver<LinkState>,
    stats: Arc<Stats>,
    stop: watch::Sender<bool>,
    task: tokio::task::JoinHandle<()>,
}

impl SocketCanBridge {
    /// Open `config.interface` (failing with the reason if it cannot be opened now), attach to
    /// `hub` as `socketcan IFACE`, and bridge on a spawned task.
    pub async fn start(hub: &Hub, config: SocketCanConfig) -> Result<Self, SocketCanError> {
        let socket = open(&config.interface)?;
        let endpoint = hub.attach(EndpointOptions::new(format!(
            "socketcan {}",
            config.interface
        )));
        let (sender, receiver) = endpoint.split();
        let stats = Arc::new(Stats::default());
        let (state_tx, state) = watch::channel(LinkState::Up);
        let (stop, stop_rx) = watch::channel(false);
        let interface = config.interface.clone();
        let task = tokio::spawn(
            Bridge {
                config,
                sender,
                receiver,
                stats: Arc::clone(&stats),
                state: state_tx,
            }
            .run(socket, stop_rx),
        );
        Ok(Self {
            interface,
            state,
            stats,
            stop,
            task,
        })
    }

    pub fn interface(&self) -> &str {
        &self.interface
    }

    pub fn state(&self) -> LinkState {
        self.state.borrow().clone()
    }

    /// A receiver that sees each change of [`LinkState`].
    pub fn watch_state(&self) -> watch::Receiver<LinkState> {
        self.state.clone()
    }

    pub fn stats(&self) -> SocketCanStats {
        let get = |c: &AtomicU64| c.load(Ordering::Relaxed);
        let s = &self.stats;
        SocketCanStats {
            frames_in: get(&s.frames_in),
            error_frames_in: get(&s.error_frames_in),
            frames_out: get(&s.frames_out),
            dropped_out: get(&s.dropped_out),
            error_frames_not_sent: get(&s.error_frames_not_sent),
            dropped_in: get(&s.dropped_in),
            link_losses: get(&s.link_losses),
        }
    }

    /// Stop the bridge; its endpoint detaches from the hub.
    pub async fn stop(self) {
        let _ = self.stop.send(true);
        let _ = self.task.await;
    }
}

struct Bridge {
    config: SocketCanConfig,
    sender: FrameSender,
    receiver: FrameReceiver,
    stats: Arc<Stats>,
    state: watch::Sender<LinkState>,
}

impl Bridge {
    async fn run(mut self, socket: socketcan::tokio::CanSocket, mut stop: watch::Receiver<bool>) {
        let mut socket = Some(socket);
        loop {
            let keep_going = match socket.take() {
                Some(up) => match self.serve(&up, &mut stop).await {
                    Served::Stop => false,
                    Served::Lost(error) => {
                        tracing::warn!("SocketCAN {error}; retrying every {:?}", self.config.retry);
                        bump(&self.stats.link_losses);
                        let _ = self.state.send(LinkState::Down(error.to_string()));
                        true
                    }
                },
                None => match self.wait_for_link(&mut stop).await {
                    Some(up) => {
                        tracing::info!("SocketCAN {}: up again", self.config.interface);
                        let _ = self.state.send(LinkState::Up);
                        socket = Some(up);
                        true
                    }
                    None => false,
                },
            };
            if !keep_going {
                return;
            }
        }
    }

    /// Bridge until the link fails or the bridge stops.
    async fn serve(
        &mut self,
        socket: &socketcan::tokio::CanSocket,
        stop: &mut watch::Receiver<bool>,
    ) -> Served {
        let interface = self.config.interface.clone();
        // A raw socket learns of its interface going down as a socket error (EPOLLERR without
        // EPOLLIN), which does not wake a tokio reader: look at the link as well.
        let mut health = tokio::time::interval(self.config.retry);
        health.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Delay);
        loop {
            tokio::select! {
                _ = stop.changed() => return Served::Stop,
                _ = health.tick() => {
                    if let Err(error) = check_sysfs(&interface) {
                        return Served::Lost(error);
                    }
                }
                read = socket.read_frame() => match read {
                    Ok(native) => self.frame_in(&native),
                    Err(e) => return Served::Lost(SocketCanError::from_io(&interface, "read", e)),
                },
                delivery = self.receiver.recv() => {
                    let Some(delivery) = delivery else { return Served::Stop };
                    if delivery.frame.is_error() {
                        bump(&self.stats.error_frames_not_sent);
                        continue;
                    }
                    let Some(native) = to_socketcan(&delivery.frame) else {
                        bump(&self.stats.dropped_out);
                        continue;
                    };
                    let write = socket.write_frame(native);
                    match tokio::time::timeout(self.config.write_timeout, write).await {
                        Ok(Ok(())) => bump(&self.stats.frames_out),
                        // The controller's queue is full: that frame is lost, the link is fine.
                        Ok(Err(e)) if e.raw_os_error() == Some(libc::ENOBUFS) => {
                            bump(&self.stats.dropped_out)
                        }
                        Ok(Err(e)) => {
                            bump(&self.stats.dropped_out);
                            return Served::Lost(SocketCanError::from_io(&interface, "write", e));
                        }
                        Err(_) => bump(&self.stats.dropped_out),
                    }
                }
            }
        }
    }

    fn frame_in(&self, native: &socketcan::CanFrame) {
        match from_socketcan(native) {
            Ok(frame) => {
                bump(&self.stats.frames_in);
                if frame.is_error() {
                    bump(&self.stats.error_frames_in);
                }
                if self.sender.send(frame).is_err() {
                    bump(&self.stats.dropped_in);
                }
            }
            Err(_) => bump(&self.stats.dropped_in),
        }
    }

    /// While the link is down: drop (and count) the hub's frames, retry opening. `None` when
    /// the bridge stops.
    async fn wait_for_link(
        &mut self,
        stop: &mut watch::Receiver<bool>,
    ) -> Option<socketcan::tokio::CanSocket> {
        let mut retry = tokio::time::interval(self.config.retry);
        retry.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Delay);
        retry.tick().await; // the first tick is immediate: wait one period first
        loop {
            tokio::select! {
                _ = stop.changed() => return None,
                delivery = self.receiver.recv() => {
                    delivery.as_ref()?;
                    bump(&self.stats.dropped_out);
                }
                _ = retry.tick() => match open(&self.config.interface) {
                    Ok(socket) => return Some(socket),
                    Err(error) => {
                        let down = LinkState::Down(error.to_string());
                        self.state.send_if_modified(|state| {
                            let changed = *state != down;
                            *state = down;
                            changed
                        });
                    }
                },
            }
        }
    }
}

enum Served {
    Stop,
    Lost(SocketCanError),
}
