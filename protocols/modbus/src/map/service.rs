//! A compiled map at work: Modbus reads answered from the latest snapshot (no round trip to the
//! servo thread), writes turned into engine commands.
//!
//! Check order (anchors §26): the codec has checked the function, quantities and byte counts
//! (01, 03); here every address of the request must belong to a point or memory area, and a
//! write must cover whole points that take writes (02); written words must be values of their
//! point's type (03); only then is anything executed, in address order, and an engine refusal
//! ends the request with 04 (the writes before it stay done: Modbus has no transactions). The
//! engine's own value checks (a parameter's range, a command's arguments) answer 03.

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex, MutexGuard, PoisonError};

use axes::command::{EngineError, SetParameter, WriteAnalogOutput, WriteDigitalOutput};
use axes::runtime::{CallError, EngineHandle, SubmitError};
use axes::{Command, Snapshot};
use serde_json::Value;

use super::compile::{Arg, IssuedCommand, Point, Read, UnitMap, When};
use super::schema::{Gaps, Table};
use super::source::Target;
use super::value::{decode, encode, PointType};
use crate::model::{DataModel, DeviceIdentity, ExecError, RequestContext};
use crate::pdu::{Exception, Request, Response};
use crate::tables::{self, TableAccess};

/// One unit's map over the engine.
pub struct UnitService {
    map: UnitMap,
    handle: EngineHandle,
    /// Memory cells and areas, as laid out by the compiler.
    memory: Mutex<Vec<u16>>,
    /// The last raw value written to each point, for `rising_bitN`.
    previous: Mutex<Vec<u64>>,
    /// Bumped by every write to memory, so a saver knows when persisted areas may have changed.
    memory_writes: AtomicU64,
}

fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    // Plain data updated without panicking: a poisoned lock still holds consistent contents.
    m.lock().unwrap_or_else(PoisonError::into_inner)
}

/// One checked part of a write.
enum Step {
    Point {
        index: usize,
        at: usize,
        value: Option<f64>,
    },
    Area {
        cell: usize,
        at: usize,
        width: usize,
    },
}

/// A covered stretch of a table: a point, or part of a memory area.
enum Item<'a> {
    Point(usize, &'a Point),
    Area { cell: usize, count: u16 },
}

impl UnitService {
    pub fn new(map: UnitMap, handle: EngineHandle) -> UnitService {
        let memory = Mutex::new(map.initial_memory.clone());
        let previous = Mutex::new(vec![0; map.points.len()]);
        UnitService {
            map,
            handle,
            memory,
            previous,
            memory_writes: AtomicU64::new(0),
        }
    }

    pub fn map(&self) -> &UnitMap {
        &self.map
    }

    /// The engine the unit's commands and parameter writes go to.
    pub fn handle(&self) -> &EngineHandle {
        &self.handle
    }

    /// How many writes to memory this unit has taken; a saver compares it with the count at its
    /// last save.
    pub fn memory_writes(&self) -> u64 {
        self.memory_writes.load(Ordering::Acquire)
    }

    /// Contents of the persisted memory areas, by name.
    pub fn persisted(&self) -> Vec<(String, Vec<u16>)> {
        let memory = lock(&self.memory);
        self.map
            .areas
            .iter()
            .filter(|a| a.persist)
            .map(|a| {
                let words = memory[a.cell..a.cell + usize::from(a.count)].to_vec();
                (a.name.clone(), words)
            })
            .collect()
    }

    /// Restore a persisted area; a length that no longer matches the map is refused.
    pub fn restore(&self, name: &str, words: &[u16]) -> Result<(), String> {
        let area = self
            .map
            .areas
            .iter()
            .find(|a| a.persist && a.name == name)
            .ok_or_else(|| format!("the map has no persisted area `{name}`"))?;
        if words.len() != usize::from(area.count) {
            return Err(format!(
                "area `{name}` has {} addresses, the saved state {}",
                area.count,
                words.len()
            ));
        }
        lock(&self.memory)[area.cell..area.cell + words.len()].copy_from_slice(words);
        Ok(())
    }

    /// The items covering `[start, start + count)` of `table`, in address order, or the first
    /// uncovered address.
    fn cover(&self, table: Table, start: u16, count: u16) -> Result<Vec<Item<'_>>, u16> {
        let end = u32::from(start) + u32::from(count);
        let mut items = Vec::new();
        let points = self.map.tables.get(&table).map_or(&[][..], |v| &v[..]);
        // First point that ends after `start`.
        let first = points.partition_point(|&i| {
            let p = &self.map.points[i];
            u32::from(p.address) + u32::from(p.width) <= u32::from(start)
        });
        let mut next_point = first;
        let mut at = u32::from(start);
        while at < end {
            if let Some(&i) = points.get(next_point) {
                let p = &self.map.points[i];
                if u32::from(p.address) <= at {
                    items.push(Item::Point(i, p));
                    at = u32::from(p.address) + u32::from(p.width);
                    next_point += 1;
                    continue;
                }
            }
            let area = self.map.areas.iter().find(|a| {
                a.table == table
                    && u32::from(a.start) <= at
                    && at < u32::from(a.start) + u32::from(a.count)
            });
            match area {
                Some(a) => {
                    let area_end = u32::from(a.start) + u32::from(a.count);
                    let stop = area_end.min(end);
                    items.push(Item::Area {
                        cell: a.cell + (at - u32::from(a.start)) as usize,
                        count: (stop - at) as u16,
                    });
                    at = stop;
                }
                None => return Err(at as u16),
            }
        }
        Ok(items)
    }

    /// A point's current engineering value (after lookup, before scale) or `None` for text.
    fn value_of(&self, point: &Point, snapshot: &Snapshot) -> Option<f64> {
        match &point.read {
            Read::Memory => {
                let cell = point.cell?;
                let memory = lock(&self.memory);
                let words = &memory[cell..cell + usize::from(point.width)];
                decode(words, point.ty, point.order).map(|raw| raw / point.scale)
            }
            Read::Source(source) => {
                let datum = source.read(snapshot)?;
                let by_name = datum
                    .name
                    .and_then(|n| point.names.iter().find(|(k, _)| k == n));
                let by_number = || point.numbers.iter().find(|(k, _)| *k == datum.number);
                let looked_up = by_name
                    .map(|(_, v)| *v)
                    .or_else(|| by_number().map(|(_, v)| *v));
                let value = looked_up.unwrap_or(point.default.unwrap_or(datum.number));
                Some(match (point.axis_code, datum.axis) {
                    (Some(code), Some(axis)) if value != 0.0 => {
                        let low = (value as i64 as u64) & 0xFFFF;
                        ((u64::from(code) << 24) | ((axis as u64 & 0xFF) << 16) | low) as f64
                    }
                    _ => value,
                })
            }
        }
    }

    /// A point's registers (or its bit as 0/1).
    fn words_of(&self, point: &Point, snapshot: &Snapshot, out: &mut Vec<u16>) {
        let at = out.len();
        out.resize(at + usize::from(point.width), 0);
        match (&point.read, point.cell) {
            (Read::Memory, Some(cell)) => {
                let memory = lock(&self.memory);
                out[at..].copy_from_slice(&memory[cell..cell + usize::from(point.width)]);
            }
            _ => {
                let value = self.value_of(point, snapshot).unwrap_or(0.0);
                encode(value * point.scale, point.ty, point.order, &mut out[at..]);
            }
        }
    }

    fn read_table(&self, table: Table, start: u16, count: u16) -> Result<Vec<u16>, ExecError> {
        self.read_in(&self.handle.snapshot(), table, start, count)
    }

    /// A read with the engine's values taken from `snapshot` rather than the latest published
    /// one: for a caller inside the servo tick, which has the engine of that tick (a CANopen node
    /// over this map sampling its TPDO data) and would otherwise see the tick before.
    pub fn read_in(
        &self,
        snapshot: &Snapshot,
        table: Table,
        start: u16,
        count: u16,
    ) -> Result<Vec<u16>, ExecError> {
        let mut words = Vec::with_capacity(usize::from(count));
        let mut at = start;
        let push_range = |words: &mut Vec<u16>, from: u16, all: &[u16], item_start: u16| {
            // The part of the item inside the request (a read may cut a wide point).
            let skip = usize::from(from - item_start);
            let take = (usize::from(count) - words.len()).min(all.len() - skip);
            words.extend_from_slice(&all[skip..skip + take]);
        };
        let items = match self.cover(table, start, count) {
            Ok(items) => items,
            Err(missing) if self.map.gaps == Gaps::Error => {
                return Err(ExecError::new(
                    Exception::IllegalDataAddress,
                    format!(
                        "{} {missing} is not in map `{}`",
                        table.name(),
                        self.map.name
                    ),
                ))
            }
            Err(_) => return Ok(self.read_with_gaps(table, start, count, snapshot)),
        };
        let mut scratch = Vec::new();
        for item in items {
            match item {
                Item::Point(_, p) => {
                    scratch.clear();
                    self.words_of(p, snapshot, &mut scratch);
                    push_range(&mut words, at, &scratch, p.address);
                    at = at.saturating_add(p.width - (at - p.address));
                }
                Item::Area { cell, count: n, .. } => {
                    let memory = lock(&self.memory);
                    words.extend_from_slice(&memory[cell..cell + usize::from(n)]);
                    at = at.saturating_add(n);
                }
            }
        }
        Ok(words)
    }

    /// `gaps = "zero"`: address by address, zeros where nothing is.
    fn read_with_gaps(
        &self,
        table: Table,
        start: u16,
        count: u16,
        snapshot: &Snapshot,
    ) -> Vec<u16> {
        let mut words = Vec::with_capacity(usize::from(count));
        let mut scratch = Vec::new();
        for a in 0..count {
            let address = start + a;
            match self.cover(table, address, 1).ok().and_then(|mut v| v.pop()) {
                Some(Item::Point(_, p)) => {
                    scratch.clear();
                    self.words_of(p, snapshot, &mut scratch);
                    words.push(scratch[usize::from(address - p.address)]);
                }
                Some(Item::Area { cell, .. }) => words.push(lock(&self.memory)[cell]),
                None => words.push(0),
            }
        }
        words
    }

    /// Check a write of `words` at `start`, then execute it.
    async fn write_table(&self, table: Table, start: u16, words: &[u16]) -> Result<(), ExecError> {
        let count = u16::try_from(words.len()).unwrap_or(u16::MAX);
        let items = self.cover(table, start, count).map_err(|missing| {
            ExecError::new(
                Exception::IllegalDataAddress,
                format!(
                    "{} {missing} is not in map `{}`",
                    table.name(),
                    self.map.name
                ),
            )
        })?;
        // Check everything first: whole points, writable, values of their type.
        let mut plan: Vec<Step> = Vec::new();
        let mut offset = 0usize;
        for item in &items {
            match item {
                Item::Point(i, p) => {
                    if p.address < start
                        || usize::from(p.address - start) + usize::from(p.width) > words.len()
                    {
                        return Err(ExecError::new(
                            Exception::IllegalDataAddress,
                            format!(
                                "`{}` spans {} … {}: a write must cover all of it",
                                p.name,
                                p.address,
                                p.address + p.width - 1
                            ),
                        ));
                    }
                    if !p.writable() {
                        return Err(ExecError::new(
                            Exception::IllegalDataAddress,
                            format!("`{}` at {} is read-only", p.name, p.address),
                        ));
                    }
                    let raw = &words[offset..offset + usize::from(p.width)];
                    let value = if p.ty == PointType::String {
                        None
                    } else {
                        let v = decode(raw, p.ty, p.order).ok_or_else(|| {
                            ExecError::new(
                                Exception::IllegalDataValue,
                                format!("{raw:04X?} is not a {:?} value for `{}`", p.ty, p.name),
                            )
                        })?;
                        Some(v / p.scale)
                    };
                    plan.push(Step::Point {
                        index: *i,
                        at: offset,
                        value,
                    });
                    offset += usize::from(p.width);
                }
                Item::Area { cell, count, .. } => {
                    plan.push(Step::Area {
                        cell: *cell,
                        at: offset,
                        width: usize::from(*count),
                    });
                    offset += usize::from(*count);
                }
            }
        }
        // Execute in address order.
        for step in plan {
            match step {
                Step::Area { cell, at, width } => {
                    lock(&self.memory)[cell..cell + width].copy_from_slice(&words[at..at + width]);
                    self.memory_writes.fetch_add(1, Ordering::Release);
                }
                Step::Point { index, at, value } => {
                    let p = &self.map.points[index];
                    let raw = &words[at..at + usize::from(p.width)];
                    self.apply(index, p, raw, value).await?;
                }
            }
        }
        Ok(())
    }

    /// One point's write: store or apply the value, then fire its actions.
    async fn apply(
        &self,
        i: usize,
        p: &Point,
        raw: &[u16],
        value: Option<f64>,
    ) -> Result<(), ExecError> {
        let v = value.unwrap_or(0.0);
        match &p.write {
            None => {}
            Some(Target::Memory) => {
                if let Some(cell) = p.cell {
                    lock(&self.memory)[cell..cell + raw.len()].copy_from_slice(raw);
                    self.memory_writes.fetch_add(1, Ordering::Release);
                }
            }
            Some(Target::Param { axis, id }) => {
                self.call(
                    p,
                    Command::from(SetParameter {
                        axis: *axis as axes::AxisIndex,
                        name: *id,
                        value: v,
                        lenient: self.map.lenient_parameters,
                    }),
                )
                .await?;
            }
            Some(Target::DigitalOutput(n)) => {
                self.call(
                    p,
                    Command::from(WriteDigitalOutput {
                        channel: *n as u16,
                        value: v != 0.0,
                    }),
                )
                .await?;
            }
            Some(Target::AnalogOutput(n)) => {
                self.call(
                    p,
                    Command::from(WriteAnalogOutput {
                        channel: *n as u16,
                        value: v,
                    }),
                )
                .await?;
            }
        }
        if p.actions.is_empty() {
            return Ok(());
        }
        let bits = raw_bits(raw, p);
        let before = std::mem::replace(&mut lock(&self.previous)[i], bits);
        for action in &p.actions {
            if fires(action.when, bits, before) {
                let command = self.command(action, v)?;
                self.call(p, command).await?;
            }
        }
        Ok(())
    }

    fn command(&self, action: &IssuedCommand, written: f64) -> Result<Command, ExecError> {
        let snapshot = self.handle.snapshot();
        let mut template = action.template.clone();
        for (field, arg) in &action.holes {
            let value = match arg {
                Arg::Written => written,
                Arg::Point { index, negate } => {
                    let q = &self.map.points[*index];
                    let v = self.value_of(q, &snapshot).unwrap_or(0.0);
                    if *negate {
                        -v
                    } else {
                        v
                    }
                }
            };
            // A limit left at 0 in a setpoint register means "the axis's own parameter".
            let optional = OPTIONAL_LIMITS.contains(&field.as_str())
                && template.get("type").and_then(Value::as_str) != Some("move_velocity");
            if matches!(arg, Arg::Point { .. }) && value == 0.0 && optional {
                template.remove(field);
                continue;
            }
            let number = serde_json::Number::from_f64(value).ok_or_else(|| {
                ExecError::new(
                    Exception::IllegalDataValue,
                    format!("`{field}` is not a number"),
                )
            })?;
            template.insert(field.clone(), Value::Number(number));
        }
        serde_json::from_value(Value::Object(template))
            .map_err(|e| ExecError::new(Exception::IllegalDataValue, format!("command: {e}")))
    }

    async fn call(&self, p: &Point, command: Command) -> Result<(), ExecError> {
        match self.handle.call_async(command).await {
            Ok(_) => Ok(()),
            Err(CallError::Engine(e)) => Err(engine_refusal(p, &e)),
            Err(CallError::Submit(SubmitError::QueueFull { .. })) => Err(ExecError::new(
                Exception::ServerDeviceBusy,
                "the engine's command queue is full",
            )),
            Err(e) => Err(ExecError::new(
                Exception::ServerDeviceFailure,
                e.to_string(),
            )),
        }
    }
}

/// Command fields that may be absent (the axis parameter applies); see [`Command`].
const OPTIONAL_LIMITS: [&str; 4] = ["velocity", "acceleration", "deceleration", "jerk"];

/// The exception of an engine refusal: the dialects' table (03 for a refused value, else 04).
fn engine_refusal(p: &Point, e: &EngineError) -> ExecError {
    let exception = Exception::from_code(mcemu_dialects::modbus::exception_for(e))
        .unwrap_or(Exception::ServerDeviceFailure);
    ExecError::new(exception, format!("`{}`: {e}", p.name))
}

/// The written raw value (before the scale) as bits for `when`: integers as two's complement,
/// other types as their words.
fn raw_bits(raw: &[u16], p: &Point) -> u64 {
    match decode(raw, p.ty, p.order) {
        Some(v) if p.ty.is_integer() || p.ty == PointType::Bool => (v as i64) as u64,
        _ => raw.iter().fold(0u64, |acc, &w| acc << 16 | u64::from(w)),
    }
}

fn fires(when: When, now: u64, before: u64) -> bool {
    let bit = |v: u64, n: u8| v >> n & 1 == 1;
    match when {
        When::Always => true,
        When::Nonzero => now != 0,
        When::Zero => now == 0,
        When::BitSet(n) => bit(now, n),
        When::BitClear(n) => !bit(now, n),
        When::RisingBit(n) => bit(now, n) && !bit(before, n),
        When::Equals(n) => now == n as u64,
    }
}

impl UnitService {
    /// Execute a data request (see [`DataModel::execute`]).
    pub async fn execute(&self, request: &Request<'_>) -> Result<Response, ExecError> {
        tables::execute(self, request).await
    }
}

impl TableAccess for UnitService {
    fn read(&self, table: Table, address: u16, count: u16) -> Result<Vec<u16>, ExecError> {
        self.read_table(table, address, count)
    }

    fn check_read(&self, table: Table, address: u16, count: u16) -> Result<(), ExecError> {
        match self.cover(table, address, count) {
            Ok(_) => Ok(()),
            Err(_) if self.map.gaps == Gaps::Zero => Ok(()),
            Err(missing) => Err(ExecError::new(
                Exception::IllegalDataAddress,
                format!(
                    "{} {missing} is not in map `{}`",
                    table.name(),
                    self.map.name
                ),
            )),
        }
    }

    async fn write(&self, table: Table, address: u16, words: &[u16]) -> Result<(), ExecError> {
        self.write_table(table, address, words).await
    }
}

/// The units of one front-end: a map per unit id, or one map for any unit.
pub struct MapModel {
    units: Vec<(Option<u8>, Arc<UnitService>)>,
}

impl MapModel {
    /// `None` as a unit id serves every id no other entry claims.
    pub fn new(units: Vec<(Option<u8>, Arc<UnitService>)>) -> MapModel {
        MapModel { units }
    }

    pub fn unit(&self, unit: u8) -> Option<&Arc<UnitService>> {
        self.units
            .iter()
            .find(|(id, _)| *id == Some(unit))
            .or_else(|| self.units.iter().find(|(id, _)| id.is_none()))
            .map(|(_, s)| s)
    }

    pub fn units(&self) -> impl Iterator<Item = &(Option<u8>, Arc<UnitService>)> {
        self.units.iter()
    }
}

impl DataModel for MapModel {
    fn serves(&self, unit: u8) -> bool {
        self.unit(unit).is_some()
    }

    fn identity(&self, unit: u8) -> Option<&DeviceIdentity> {
        self.unit(unit).map(|s| &s.map.identity)
    }

    async fn execute<'a>(
        &'a self,
        context: &'a RequestContext,
        request: &'a Request<'a>,
    ) -> Result<Response, ExecError> {
        if context.broadcast {
            // An RTU broadcast (address 0) is a write to every unit on the line; nothing is
            // answered, so the first failure is only counted and logged by the server.
            let (mut first_error, mut answered) = (None, None);
            for (_, service) in &self.units {
                match service.execute(request).await {
                    Ok(r) => answered = Some(r),
                    Err(e) => {
                        first_error.get_or_insert(e);
                    }
                }
            }
            return match (first_error, answered) {
                (Some(e), _) => Err(e),
                (None, Some(r)) => Ok(r),
                (None, None) => Err(ExecError::new(
                    Exception::GatewayTargetFailed,
                    "no unit to broadcast to",
                )),
            };
        }
        match self.unit(context.unit) {
            Some(service) => service.execute(request).await,
            None => Err(ExecError::new(
                Exception::GatewayTargetFailed,
                format!("unit {} is not served", context.unit),
            )),
        }
    }
}
