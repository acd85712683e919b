//! `GET /api/v1/stream`: every servo tick's values of the chosen channels, batched, as
//! server-sent events (the dashboard's data path, issue 15 item 5).
//!
//! Like the trace recorder, a runtime observer copies each tick into a buffer on the servo
//! thread; when the buffer holds `batch` ticks it is handed to the client's task with
//! `try_send` on a bounded queue. A client that does not keep up loses whole batches (counted,
//! and the count is in every batch it does get); the servo thread never waits for it. Buffers
//! come back through a recycling queue, so a steady stream allocates nothing on the servo
//! thread. The observer removes itself once the client is gone.
//!
//! Query: `axes=0,1` (default: all), `channels=cmd_pos,act_pos` (default: all of
//! [`CHANNELS`]) for the same channels of every axis, or instead `series=0:cmd_pos,0:act_pos,
//! 1:following_error` for channels chosen per axis (axes in order of first mention);
//! `io=false` (default true: DI/DO bit masks each tick), `batch=N` ticks (default: 50 ms worth,
//! at least 1).
//!
//! Events: first `hello` (`{period, tick, axes, channels, axis_channels, io, batch,
//! max_clients, flag_bits}`: `axis_channels[a]` are axis `axes[a]`'s channels, `channels` their
//! union), then `samples` (`{first_tick, ticks, dropped, data: [[[value per tick] per channel of
//! axis_channels[a]] per axis a], di, do, changes: [{tick, axis, state, flags}]}`); `changes`
//! lists each state or flag change of a streamed axis at the tick it happened.

use std::convert::Infallible;
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use std::sync::Arc;

use axes::status::{AxisFlags, AxisState, AxisStatus};
use axes::Engine;
use axum::extract::{RawQuery, State};
use axum::response::sse::{Event, KeepAlive, Sse};
use axum::response::{IntoResponse, Response};
use serde::Serialize;
use serde_json::{json, Value};
use tokio::sync::mpsc;

use super::error::ApiError;
use super::names::{flag_names, FLAG_NAMES};
use super::ControlState;

/// Batches queued for one client; beyond it, batches are dropped: 3.2 s of data at the default
/// 50 ms batch (a 1 s advance of the virtual clock arrives whole), at most about 1.5 MB for 8
/// axes × 7 channels.
pub const CLIENT_QUEUE: usize = 64;
/// Largest `batch` a client may ask for (ticks).
pub const MAX_BATCH_TICKS: u32 = 10_000;
/// Batch length when the query gives none, seconds of engine time.
const DEFAULT_BATCH_SECONDS: f64 = 0.05;

/// A per-axis channel: one value per tick.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Channel {
    CmdPos,
    ActPos,
    CmdVel,
    ActVel,
    CmdAcc,
    FollowingError,
    /// The axis's flag bits (`AxisFlags`, names as `/state` lists them).
    Flags,
}

/// Every channel, by its name (the trace CSV column names where one exists).
pub const CHANNELS: [(&str, Channel); 7] = [
    ("cmd_pos", Channel::CmdPos),
    ("act_pos", Channel::ActPos),
    ("cmd_vel", Channel::CmdVel),
    ("act_vel", Channel::ActVel),
    ("cmd_acc", Channel::CmdAcc),
    ("following_error", Channel::FollowingError),
    ("flags", Channel::Flags),
];

impl Channel {
    fn name(self) -> &'static str {
        CHANNELS
            .iter()
            .find(|(_, c)| *c == self)
            .map_or("?", |(n, _)| n)
    }

    fn value(self, s: &AxisStatus) -> f64 {
        match self {
            Channel::CmdPos => s.cmd_pos,
            Channel::ActPos => s.act_pos,
            Channel::CmdVel => s.cmd_vel,
            Channel::ActVel => s.act_vel,
            Channel::CmdAcc => s.cmd_acc,
            Channel::FollowingError => s.following_error,
            Channel::Flags => f64::from(s.flags.bits()),
        }
    }
}

/// What one client asked for, checked.
#[derive(Clone, Debug, PartialEq)]
pub struct StreamRequest {
    pub axes: Vec<u16>,
    /// `axis_channels[a]`: the channels of `axes[a]`, in the order they are sent.
    pub axis_channels: Vec<Vec<Channel>>,
    pub io: bool,
    pub batch: u32,
}

/// `cmd_pos` → its channel, or the error naming the choices.
fn channel_named(key: &str, item: &str) -> Result<Channel, ApiError> {
    CHANNELS
        .iter()
        .find(|(n, _)| *n == item)
        .map(|(_, c)| *c)
        .ok_or_else(|| {
            ApiError::InvalidRequest(format!(
                "{key}: no channel `{item}` (one of {})",
                CHANNELS.map(|(n, _)| n).join(", ")
            ))
        })
}

/// `2` → axis 2 if the machine has it.
fn axis_numbered(key: &str, item: &str, axis_count: usize) -> Result<u16, ApiError> {
    item.parse::<u16>()
        .ok()
        .filter(|&a| usize::from(a) < axis_count)
        .ok_or_else(|| {
            ApiError::InvalidRequest(format!(
                "{key}: `{item}` is not an axis (the machine has {axis_count})"
            ))
        })
}

impl StreamRequest {
    /// Parse the query against a machine of `axis_count` axes and servo `period`.
    pub fn parse(query: Option<&str>, axis_count: usize, period: f64) -> Result<Self, ApiError> {
        let mut axes = None;
        let mut channels = None;
        let mut series: Option<Vec<(u16, Vec<Channel>)>> = None;
        let mut io = true;
        let mut batch = None;
        for pair in query.unwrap_or("").split('&').filter(|p| !p.is_empty()) {
            let (key, value) = pair.split_once('=').unwrap_or((pair, ""));
            // Browsers encode the lists' commas (`%2C`).
            let value = &value.replace("%2C", ",").replace("%2c", ",");
            match key {
                "axes" => {
                    let mut list = Vec::new();
                    for item in value.split(',').filter(|v| !v.is_empty()) {
                        let axis = axis_numbered("axes", item, axis_count)?;
                        if list.contains(&axis) {
                            return Err(ApiError::InvalidRequest(format!(
                                "axes: {axis} is listed twice"
                            )));
                        }
                        list.push(axis);
                    }
                    axes = Some(list);
                }
                "channels" => {
                    let mut list = Vec::new();
                    for item in value.split(',').filter(|v| !v.is_empty()) {
                        let channel = channel_named("channels", item)?;
                        if !list.contains(&channel) {
                            list.push(channel);
                        }
                    }
                    channels = Some(list);
                }
                "series" => {
                    let value = value.replace("%3A", ":").replace("%3a", ":");
                    let mut list: Vec<(u16, Vec<Channel>)> = Vec::new();
                    for item in value.split(',').filter(|v| !v.is_empty()) {
                        let (axis, channel) = item.split_once(':').ok_or_else(|| {
                            ApiError::InvalidRequest(format!(
                                "series: `{item}` is not AXIS:CHANNEL (`0:cmd_pos`)"
                            ))
                        })?;
                        let axis = axis_numbered("series", axis, axis_count)?;
                        let channel = channel_named("series", channel)?;
                        match list.iter_mut().find(|(a, _)| *a == axis) {
                            Some((_, chosen)) if chosen.contains(&channel) => {}
                            Some((_, chosen)) => chosen.push(channel),
                            None => list.push((axis, vec![channel])),
                        }
                    }
                    if list.is_empty() {
                        return Err(ApiError::InvalidRequest(
                            "series: empty; list AXIS:CHANNEL pairs (`0:cmd_pos,1:act_pos`)".into(),
                        ));
                    }
                    series = Some(list);
                }
                "io" => {
                    io = match value.as_str() {
                        "true" => true,
                        "false" => false,
                        other => {
                            return Err(ApiError::InvalidRequest(format!(
                                "io: `{other}`; true or false"
                            )))
                        }
                    }
                }
                "batch" => {
                    batch = Some(
                        value
                            .parse::<u32>()
                            .ok()
                            .filter(|b| (1..=MAX_BATCH_TICKS).contains(b))
                            .ok_or_else(|| {
                                ApiError::InvalidRequest(format!(
                                    "batch: `{value}`; 1 … {MAX_BATCH_TICKS} ticks"
                                ))
                            })?,
                    )
                }
                // The token travels in the query for EventSource, which cannot set headers.
                "token" => {}
                other => {
                    return Err(ApiError::InvalidRequest(format!(
                        "unknown query parameter `{other}` (axes, channels, series, io, batch)"
                    )))
                }
            }
        }
        if series.is_some() && (axes.is_some() || channels.is_some()) {
            return Err(ApiError::InvalidRequest(
                "series chooses axes and channels itself: give it without axes or channels".into(),
            ));
        }
        let default_batch = if period.is_finite() && period > 0.0 {
            (DEFAULT_BATCH_SECONDS / period).round().clamp(1.0, 1000.0) as u32
        } else {
            1
        };
        let (axes, axis_channels) = match series {
            Some(series) => series.into_iter().unzip(),
            None => {
                let axes: Vec<u16> = axes.unwrap_or_else(|| {
                    (0..axis_count)
                        .map(|a| u16::try_from(a).unwrap_or(u16::MAX))
                        .collect()
                });
                let channels = channels.unwrap_or_else(|| CHANNELS.map(|(_, c)| c).to_vec());
                let per_axis = vec![channels; axes.len()];
                (axes, per_axis)
            }
        };
        Ok(StreamRequest {
            axes,
            axis_channels,
            io,
            batch: batch.unwrap_or(default_batch),
        })
    }

    /// Values one tick adds to a batch.
    fn values_per_tick(&self) -> usize {
        self.axis_channels.iter().map(Vec::len).sum()
    }

    /// Every channel streamed for some axis, in order of first appearance.
    fn channel_union(&self) -> Vec<Channel> {
        let mut union: Vec<Channel> = Vec::new();
        for c in self.axis_channels.iter().flatten() {
            if !union.contains(c) {
                union.push(*c);
            }
        }
        union
    }
}

/// A state or flag change of a streamed axis.
#[derive(Clone, Copy, Debug)]
struct Change {
    tick: u64,
    axis: u16,
    state: AxisState,
    flags: AxisFlags,
}

/// One batch as the servo thread fills it: `values` is tick-major (`[tick][axis][channel]`).
#[derive(Debug, Default)]
struct Batch {
    first_tick: u64,
    ticks: u32,
    values: Vec<f64>,
    di: Vec<u64>,
    do_: Vec<u64>,
    changes: Vec<Change>,
    /// Batches this client had lost when this one was sent.
    dropped: u64,
}

impl Batch {
    fn with_capacity(request: &StreamRequest) -> Batch {
        let ticks = request.batch as usize;
        Batch {
            values: Vec::with_capacity(ticks * request.values_per_tick()),
            di: Vec::with_capacity(if request.io { ticks } else { 0 }),
            do_: Vec::with_capacity(if request.io { ticks } else { 0 }),
            changes: Vec::with_capacity(request.axes.len() * 4),
            ..Batch::default()
        }
    }

    fn clear(&mut self) {
        self.ticks = 0;
        self.values.clear();
        self.di.clear();
        self.do_.clear();
        self.changes.clear();
    }
}

/// The first 64 bits of an I/O image as a mask (bit n: channel n).
fn mask(bits: &[bool]) -> u64 {
    bits.iter()
        .take(64)
        .enumerate()
        .fold(0, |m, (i, &b)| if b { m | (1 << i) } else { m })
}

/// The servo thread's half of one client.
struct Sampler {
    request: Arc<StreamRequest>,
    batch: Batch,
    last: Vec<Option<(AxisState, AxisFlags)>>,
    tx: mpsc::Sender<Batch>,
    recycled: mpsc::UnboundedReceiver<Batch>,
    dropped: Arc<AtomicU64>,
    /// Every client's losses, for `/state`.
    clients: Arc<StreamClients>,
}

impl Sampler {
    /// Record one tick; `false` (the client is gone) ends the observer.
    fn sample(&mut self, engine: &Engine) -> bool {
        if self.tx.is_closed() {
            return false;
        }
        let tick = engine.tick();
        if self.batch.ticks == 0 {
            self.batch.first_tick = tick;
        }
        for (i, &axis) in self.request.axes.iter().enumerate() {
            let Some(status) = engine.axis_status(usize::from(axis)) else {
                continue;
            };
            for channel in self.request.axis_channels.get(i).into_iter().flatten() {
                self.batch.values.push(channel.value(&status));
            }
            let now = (status.state, status.flags);
            if let Some(last) = self.last.get_mut(i) {
                if *last != Some(now) {
                    *last = Some(now);
                    self.batch.changes.push(Change {
                        tick,
                        axis,
                        state: now.0,
                        flags: now.1,
                    });
                }
            }
        }
        if self.request.io {
            let io = engine.io();
            self.batch.di.push(mask(&io.di));
            self.batch.do_.push(mask(&io.do_));
        }
        self.batch.ticks += 1;
        if self.batch.ticks >= self.request.batch {
            let mut next = self
                .recycled
                .try_recv()
                .unwrap_or_else(|_| Batch::with_capacity(&self.request));
            next.clear();
            let mut full = std::mem::replace(&mut self.batch, next);
            full.dropped = self.dropped.load(Ordering::Relaxed);
            match self.tx.try_send(full) {
                Ok(()) => {}
                Err(mpsc::error::TrySendError::Full(lost)) => {
                    self.dropped.fetch_add(1, Ordering::Relaxed);
                    self.clients.dropped.fetch_add(1, Ordering::Relaxed);
                    self.batch = lost;
                    self.batch.clear();
                }
                Err(mpsc::error::TrySendError::Closed(_)) => return false,
            }
        }
        true
    }
}

/// Open streams, for the `stream_max_clients` bound and `/state`.
#[derive(Debug, Default)]
pub struct StreamClients {
    open: AtomicUsize,
    /// Batches lost by every client since start.
    dropped: AtomicU64,
}

/// What `/state` says about the streams.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct StreamStatus {
    pub clients: usize,
    pub max_clients: usize,
    pub dropped_batches: u64,
}

impl StreamClients {
    pub fn status(&self, max_clients: usize) -> StreamStatus {
        StreamStatus {
            clients: self.open.load(Ordering::Relaxed),
            max_clients,
            dropped_batches: self.dropped.load(Ordering::Relaxed),
        }
    }
}

/// A place among the open streams; dropping it (the client went away) frees it.
struct Place {
    clients: Arc<StreamClients>,
    /// This client's lost batches.
    dropped: Arc<AtomicU64>,
}

impl Place {
    fn take(clients: &Arc<StreamClients>, max: usize) -> Option<Place> {
        clients
            .open
            .fetch_update(Ordering::AcqRel, Ordering::Acquire, |n| {
                (n < max).then_some(n + 1)
            })
            .ok()?;
        Some(Place {
            clients: Arc::clone(clients),
            dropped: Arc::default(),
        })
    }
}

impl Drop for Place {
    fn drop(&mut self) {
        self.clients.open.fetch_sub(1, Ordering::AcqRel);
    }
}

/// The `samples` event of one batch, transposed per axis and channel for the plots.
fn samples_json(request: &StreamRequest, batch: &Batch) -> Value {
    let per_tick = request.values_per_tick();
    let mut offset = 0;
    let data: Vec<Vec<Vec<f64>>> = request
        .axis_channels
        .iter()
        .map(|channels| {
            let first = offset;
            offset += channels.len();
            (0..channels.len())
                .map(|c| {
                    batch
                        .values
                        .iter()
                        .skip(first + c)
                        .step_by(per_tick.max(1))
                        .copied()
                        .collect()
                })
                .collect()
        })
        .collect();
    let changes: Vec<Value> = batch
        .changes
        .iter()
        .map(|c| {
            json!({
                "tick": c.tick,
                "axis": c.axis,
                "state": c.state,
                "flags": flag_names(c.flags),
            })
        })
        .collect();
    json!({
        "first_tick": batch.first_tick,
        "ticks": batch.ticks,
        "dropped": batch.dropped,
        "data": data,
        "di": batch.di,
        "do": batch.do_,
        "changes": changes,
    })
}

/// One client's end of its stream: the events still to send, and its place.
struct Feed {
    first: Option<Event>,
    rx: mpsc::Receiver<Batch>,
    recycle: mpsc::UnboundedSender<Batch>,
    request: Arc<StreamRequest>,
    _place: Place,
}

pub async fn get_stream(State(state): State<ControlState>, RawQuery(query): RawQuery) -> Response {
    let snapshot = state.handle.snapshot();
    let request = match StreamRequest::parse(query.as_deref(), snapshot.axes.len(), snapshot.period)
    {
        Ok(r) => Arc::new(r),
        Err(e) => return e.into_response(),
    };
    let max = state.stream_max_clients;
    let Some(place) = Place::take(&state.streams, max) else {
        return ApiError::TooManyStreams { limit: max }.into_response();
    };
    let (tx, rx) = mpsc::channel::<Batch>(CLIENT_QUEUE);
    let (recycle, recycled) = mpsc::unbounded_channel::<Batch>();
    let mut sampler = Sampler {
        request: Arc::clone(&request),
        batch: Batch::with_capacity(&request),
        last: vec![None; request.axes.len()],
        tx,
        recycled,
        dropped: Arc::clone(&place.dropped),
        clients: Arc::clone(&state.streams),
    };
    if let Err(e) = state
        .handle
        .add_observer_async(move |engine: &Engine| sampler.sample(engine))
        .await
    {
        return ApiError::from(e).into_response();
    }
    let hello = json!({
        "period": snapshot.period,
        "tick": snapshot.tick,
        "axes": request.axes,
        "channels": request.channel_union().iter().map(|c| c.name()).collect::<Vec<_>>(),
        "axis_channels": request
            .axis_channels
            .iter()
            .map(|cs| cs.iter().map(|c| c.name()).collect::<Vec<_>>())
            .collect::<Vec<_>>(),
        "io": request.io,
        "batch": request.batch,
        "max_clients": max,
        // Bit of each flag in the `flags` channel.
        "flag_bits": FLAG_NAMES
            .iter()
            .map(|(flag, name)| (name.to_string(), json!(flag.bits())))
            .collect::<serde_json::Map<_, _>>(),
    });
    let first = Event::default().event("hello").data(hello.to_string());
    let feed = Feed {
        first: Some(first),
        rx,
        recycle,
        request,
        _place: place,
    };
    let events = futures_util::stream::unfold(feed, |mut feed| async move {
        if let Some(event) = feed.first.take() {
            return Some((event, feed));
        }
        let batch = feed.rx.recv().await?;
        let event = Event::default()
            .event("samples")
            .data(samples_json(&feed.request, &batch).to_string());
        // Back to the servo thread for reuse; it is gone if the observer ended.
        let _ = feed.recycle.send(batch);
        Some((event, feed))
    });
    let events = futures_util::StreamExt::map(events, Ok::<Event, Infallible>);
    Sse::new(events)
        .keep_alive(KeepAlive::default())
        .into_response()
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

    use super::*;
    use axes::command::{Command, Enable};
    use axes::config::{AxisConfig, EngineConfig};
    use axes::runtime::{ClockMode, Runtime, RuntimeOptions};

    #[test]
    fn queries_are_checked() {
        let r = StreamRequest::parse(None, 3, 1e-3).unwrap();
        assert_eq!((r.axes, r.io, r.batch), (vec![0, 1, 2], true, 50));
        assert!(r.axis_channels.iter().all(|cs| cs.len() == 7));
        let r = StreamRequest::parse(
            Some("axes=2,0&channels=act_pos&io=false&batch=3&token=x"),
            3,
            1e-3,
        )
        .unwrap();
        assert_eq!(r.axes, vec![2, 0]);
        assert_eq!(r.axis_channels, vec![vec![Channel::ActPos]; 2]);
        assert_eq!((r.io, r.batch), (false, 3));
        // Channels chosen per axis: axes in order of first mention, repeats ignored.
        let r = StreamRequest::parse(
            Some("series=2:act_pos,0:cmd_pos,2:following_error%2C0%3Acmd_pos"),
            3,
            1e-3,
        )
        .unwrap();
        assert_eq!(r.axes, vec![2, 0]);
        assert_eq!(
            r.axis_channels,
            vec![
                vec![Channel::ActPos, Channel::FollowingError],
                vec![Channel::CmdPos]
            ]
        );
        assert_eq!(
            r.channel_union(),
            vec![Channel::ActPos, Channel::FollowingError, Channel::CmdPos]
        );
        for bad in [
            "axes=3",
            "axes=1,1",
            "axes=-1",
            "channels=speed",
            "io=1",
            "batch=0",
            "batch=99999",
            "rate=1",
            "series=",
            "series=0",
            "series=3:cmd_pos",
            "series=0:speed",
            "series=0:cmd_pos&axes=0",
            "channels=cmd_pos&series=0:cmd_pos",
        ] {
            assert!(
                matches!(
                    StreamRequest::parse(Some(bad), 3, 1e-3),
                    Err(ApiError::InvalidRequest(_))
                ),
                "{bad}"
            );
        }
    }

    #[test]
    fn every_tick_is_batched_and_a_slow_client_loses_whole_batches() {
        let config = EngineConfig {
            axes: vec![AxisConfig::default(); 2],
            ..EngineConfig::default()
        };
        let engine = Engine::new(&config).unwrap();
        let (handle, _guard) =
            Runtime::start(engine, RuntimeOptions::with_clock(ClockMode::Virtual)).unwrap();
        let request = Arc::new(
            StreamRequest::parse(Some("axes=1&channels=cmd_pos,flags&batch=4"), 2, 1e-3).unwrap(),
        );
        let (tx, mut rx) = mpsc::channel(2);
        let (_recycle, recycled) = mpsc::unbounded_channel();
        let dropped = Arc::new(AtomicU64::new(0));
        let mut sampler = Sampler {
            request: Arc::clone(&request),
            batch: Batch::with_capacity(&request),
            last: vec![None],
            tx,
            recycled,
            dropped: Arc::clone(&dropped),
            clients: Arc::default(),
        };
        handle
            .add_observer(move |e: &Engine| sampler.sample(e))
            .unwrap();
        handle.call(Command::from(Enable { axis: 1 })).unwrap();
        let move_to: Command = serde_json::from_str(
            r#"{"type":"move_absolute","axis":1,"position":1.0,"velocity":10.0}"#,
        )
        .unwrap();
        handle.call(move_to).unwrap();
        // 16 ticks: four batches, the queue holds two, two are lost.
        handle.advance(16).unwrap();
        let first = rx.try_recv().unwrap();
        let second = rx.try_recv().unwrap();
        assert!(rx.try_recv().is_err());
        assert_eq!(dropped.load(Ordering::Relaxed), 2);
        assert_eq!((first.ticks, second.first_tick), (4, first.first_tick + 4));
        let json = samples_json(&request, &second);
        let cmd_pos = json["data"][0][0].as_array().unwrap();
        assert_eq!(cmd_pos.len(), 4);
        // Moving: the commanded position grows tick by tick.
        let values: Vec<f64> = cmd_pos.iter().map(|v| v.as_f64().unwrap()).collect();
        assert!(values.windows(2).all(|w| w[1] > w[0]), "{values:?}");
        assert_eq!(json["di"].as_array().unwrap().len(), 4);
        // The first batch saw the axis's first state (and the enable).
        let changes = samples_json(&request, &first)["changes"].clone();
        assert!(!changes.as_array().unwrap().is_empty(), "{changes}");
        // The client goes: the observer removes itself at its next tick.
        drop(rx);
        handle.advance(1).unwrap();
    }

    #[test]
    fn channels_chosen_per_axis_arrive_per_axis() {
        let config = EngineConfig {
            axes: vec![AxisConfig::default(); 2],
            ..EngineConfig::default()
        };
        let engine = Engine::new(&config).unwrap();
        let (handle, _guard) =
            Runtime::start(engine, RuntimeOptions::with_clock(ClockMode::Virtual)).unwrap();
        let request = Arc::new(
            StreamRequest::parse(Some("series=1:cmd_pos,0:flags,1:cmd_vel&batch=5"), 2, 1e-3)
                .unwrap(),
        );
        let (tx, mut rx) = mpsc::channel(4);
        let (_recycle, recycled) = mpsc::unbounded_channel();
        let mut sampler = Sampler {
            request: Arc::clone(&request),
            batch: Batch::with_capacity(&request),
            last: vec![None; 2],
            tx,
            recycled,
            dropped: Arc::default(),
            clients: Arc::default(),
        };
        handle
            .add_observer(move |e: &Engine| sampler.sample(e))
            .unwrap();
        handle.call(Command::from(Enable { axis: 1 })).unwrap();
        let move_to: Command = serde_json::from_str(
            r#"{"type":"move_absolute","axis":1,"position":1.0,"velocity":10.0}"#,
        )
        .unwrap();
        handle.call(move_to).unwrap();
        handle.advance(5).unwrap();
        let json = samples_json(&request, &rx.try_recv().unwrap());
        let series = |a: usize, c: usize| -> Vec<f64> {
            json["data"][a][c]
                .as_array()
                .unwrap()
                .iter()
                .map(|v| v.as_f64().unwrap())
                .collect()
        };
        // Axis 1 first (first mentioned): its position grows, its velocity is positive.
        let (pos, vel) = (series(0, 0), series(0, 1));
        assert_eq!((pos.len(), vel.len()), (5, 5));
        assert!(pos.windows(2).all(|w| w[1] > w[0]), "{pos:?}");
        assert!(vel.iter().all(|&v| v > 0.0), "{vel:?}");
        // Axis 0: its flags only, the same each tick (it is not moving).
        let flags = series(1, 0);
        assert_eq!(flags.len(), 5);
        assert!(flags.windows(2).all(|w| w[0] == w[1]), "{flags:?}");
        assert!(json["data"][1].as_array().unwrap().len() == 1);
    }
}
