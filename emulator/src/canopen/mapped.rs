//! A CANopen node whose manufacturer objects are a Modbus register map's holding registers: the
//! CT E10 servo (CPU 226H §10.2, digest 003 §6) on CANopen with the parameter semantics of
//! `fixtures/modbus/ct-e10-servo.toml`, written once (decisions.md, "CT E10 on CANopen").
//!
//! Object 0x2000 + n is holding register n of the map for the node's axis. A master's write is
//! the map's table write (which issues the engine commands: P282 bit 0 → enable …); the
//! objects are refreshed from the map's reads before each call into the node, so SDO uploads
//! and TPDOs show live values (R204, R216 …). The objects the EDS marks `rw` are the drive's
//! stored parameters (P95 … P102, P113, P290): 0x1010 stores them with the communication
//! parameters, and their power-on values (stored, else the map's at start) are written into the
//! map at power-on and at NMT reset node, as a drive loads its saved parameters when it boots.

use std::ops::RangeInclusive;
use std::sync::Arc;

use axes::od::{DataType, ObjectDictionary, OdError, Value};
use axes::Snapshot;
use mcemu_canopen::Device;
use mcemu_modbus::map::value::{decode, encode, PointType, WordOrder};
use mcemu_modbus::map::{UnitMap, UnitService};
use mcemu_modbus::model::ExecError;
use mcemu_modbus::tables::{Table, TableAccess};

/// The manufacturer objects backed by holding registers: 0x2000 + n for register n.
pub const BACKED: RangeInclusive<u16> = 0x2000..=0x23FF;

/// How a backed object's value lies in the registers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Words {
    /// An 8- or 16-bit object: register n.
    One,
    /// A 32-bit object over a 32-bit point of the map at n: the point's word order (P290, R216:
    /// high word first in the CT E10 map).
    Point(WordOrder),
    /// A 32-bit object over two 16-bit registers n, n + 1: bits 0–15 are register n, bits
    /// 16–31 register n + 1 — CANopen's little-endian order of the two words (P113 =
    /// acceleration time P113 | deceleration time P114 << 16, decisions.md "EDS/DCF files").
    LowFirst,
}

impl Words {
    pub fn count(self) -> u16 {
        match self {
            Words::One => 1,
            Words::Point(_) | Words::LowFirst => 2,
        }
    }

    /// The registers holding `raw` (the object's bit pattern).
    pub fn encode(self, raw: u32) -> Vec<u16> {
        match self {
            Words::One => vec![raw as u16],
            Words::LowFirst => vec![raw as u16, (raw >> 16) as u16],
            Words::Point(order) => {
                let mut out = [0u16; 2];
                encode(f64::from(raw), PointType::U32, order, &mut out);
                out.to_vec()
            }
        }
    }

    /// The bit pattern the registers hold (`None`: not as many words as the layout needs).
    pub fn decode(self, words: &[u16]) -> Option<u32> {
        match (self, words) {
            (Words::One, [w]) => Some(u32::from(*w)),
            (Words::LowFirst, [lo, hi]) => Some(u32::from(*lo) | u32::from(*hi) << 16),
            (Words::Point(order), [_, _]) => decode(words, PointType::U32, order).map(|v| v as u32),
            _ => None,
        }
    }
}

/// One object backed by registers.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Backed {
    pub index: u16,
    pub register: u16,
    pub data_type: DataType,
    pub words: Words,
    /// Its registers issue engine commands when written (`on_write`): within one RPDO such
    /// objects are written after the set-points (P282 after P290).
    pub commands: bool,
    /// A stored parameter: an entry 0x1010 stores (`rw` in the EDS; process data — `rww`, as
    /// P281/P282 — and monitors are not), whose power-on value goes into the map.
    pub stored: bool,
}

/// The backed objects of `od` over `map`: every entry in [`BACKED`] must be an 8/16/32-bit
/// integer (or BOOLEAN) VAR whose registers the map has. An error names the object and why.
pub fn backed_objects(od: &ObjectDictionary, map: &UnitMap) -> Result<Vec<Backed>, String> {
    let holding: Vec<_> = map
        .tables
        .get(&Table::HoldingRegisters)
        .map(|points| points.iter().filter_map(|&i| map.points.get(i)).collect())
        .unwrap_or_default();
    let covered = |address: u16| {
        holding
            .iter()
            .any(|p| (p.address..p.address.saturating_add(p.width)).contains(&address))
            || map.areas.iter().any(|a| {
                a.table == Table::HoldingRegisters
                    && (a.start..a.start.saturating_add(a.count)).contains(&address)
            })
    };
    let mut out = Vec::new();
    for entry in od.entries().filter(|e| BACKED.contains(&e.def.index)) {
        let (index, sub) = (entry.def.index, entry.def.subindex);
        let what = format!("object {index:#06x}:{sub} ({})", entry.def.name);
        if sub != 0 {
            return Err(format!(
                "{what}: only VARs (sub-index 0) map to a holding register"
            ));
        }
        let register = index - BACKED.start();
        let data_type = entry.def.data_type;
        let words = match data_type.size() {
            Some(1 | 2) => Words::One,
            Some(4) if is_integer(data_type) => {
                match holding.iter().find(|p| p.address == register) {
                    Some(p) if p.width == 2 => Words::Point(p.order),
                    _ => Words::LowFirst,
                }
            }
            _ => {
                return Err(format!(
                    "{what}: {data_type} cannot be a holding register (8, 16 or 32-bit integers)"
                ))
            }
        };
        if !is_integer(data_type) && data_type != DataType::Boolean {
            return Err(format!(
                "{what}: {data_type} cannot be a holding register (8, 16 or 32-bit integers)"
            ));
        }
        if let Some(missing) = (register..register + words.count()).find(|&a| !covered(a)) {
            return Err(format!(
                "{what} is holding register {missing}, which map `{}` does not have",
                map.name
            ));
        }
        let span = register..register + words.count();
        let commands = holding.iter().any(|p| {
            !p.actions.is_empty()
                && (p.address..p.address.saturating_add(p.width)).any(|a| span.contains(&a))
        });
        out.push(Backed {
            index,
            register,
            data_type,
            words,
            commands,
            stored: mcemu_canopen::store::storable(entry),
        });
    }
    Ok(out)
}

fn is_integer(t: DataType) -> bool {
    matches!(
        t,
        DataType::Integer8
            | DataType::Integer16
            | DataType::Integer32
            | DataType::Unsigned8
            | DataType::Unsigned16
            | DataType::Unsigned32
    )
}

/// A value's bit pattern, zero-extended to 32 bits.
pub fn raw_bits(value: &Value) -> Option<u32> {
    Some(match *value {
        Value::Bool(b) => u32::from(b),
        Value::I8(v) => u32::from(v as u8),
        Value::I16(v) => u32::from(v as u16),
        Value::I32(v) => v as u32,
        Value::U8(v) => u32::from(v),
        Value::U16(v) => u32::from(v),
        Value::U32(v) => v,
        _ => return None,
    })
}

/// The value of `data_type` whose bit pattern is the low bits of `raw`.
pub fn from_bits(data_type: DataType, raw: u32) -> Option<Value> {
    Some(match data_type {
        DataType::Boolean => Value::Bool(raw & 1 != 0),
        DataType::Integer8 => Value::I8(raw as u8 as i8),
        DataType::Integer16 => Value::I16(raw as u16 as i16),
        DataType::Integer32 => Value::I32(raw as i32),
        DataType::Unsigned8 => Value::U8(raw as u8),
        DataType::Unsigned16 => Value::U16(raw as u16),
        DataType::Unsigned32 => Value::U32(raw),
        _ => return None,
    })
}

/// Why a register write did not happen.
#[derive(Clone, Debug, PartialEq)]
pub enum WriteError {
    /// The map refused it, with its Modbus exception (the value, the engine's state …).
    Refused(ExecError),
    /// The map could not run at all: no runtime for its write, or the engine it commands has
    /// stopped. The device failed inside; no Modbus exception says more than that.
    Failed(String),
}

impl WriteError {
    pub fn reason(&self) -> &str {
        match self {
            WriteError::Refused(e) => &e.reason,
            WriteError::Failed(why) => why,
        }
    }
}

impl From<ExecError> for WriteError {
    fn from(e: ExecError) -> WriteError {
        WriteError::Refused(e)
    }
}

/// A failed register write as the SDO abort a master gets (decisions.md, "CT E10 on CANopen"):
/// a refusal by its Modbus exception, the E10's table in
/// [`mcemu_dialects::cpu226h::od_error_for_exception`] (02 → 0x06020000, 03 → 0x06090030,
/// others → 0x08000022). A map that could not run at all → 0x08000000, general error (CiA 301
/// Table 22: no more specific code fits an internal failure).
pub fn od_error(index: u16, subindex: u8, e: &WriteError) -> OdError {
    let e = match e {
        WriteError::Refused(e) => e,
        WriteError::Failed(why) => {
            return OdError::DeviceFailure {
                index,
                subindex,
                detail: why.clone(),
            }
        }
    };
    mcemu_dialects::cpu226h::od_error_for_exception(e.exception.code(), index, subindex, &e.reason)
}

/// Word access to the holding registers behind the objects.
pub trait Registers {
    /// The registers with the engine's values of the latest published snapshot.
    fn read(&self, address: u16, count: u16) -> Result<Vec<u16>, ExecError>;
    /// The registers with the engine's values of `snapshot` (inside the servo tick: that tick's).
    fn read_in(
        &self,
        _snapshot: &Snapshot,
        address: u16,
        count: u16,
    ) -> Result<Vec<u16>, ExecError> {
        self.read(address, count)
    }
    fn write(&self, address: u16, words: &[u16]) -> Result<(), WriteError>;
}

/// The map service of the node's axis.
pub struct ServiceRegisters(pub Arc<UnitService>);

impl Registers for ServiceRegisters {
    fn read(&self, address: u16, count: u16) -> Result<Vec<u16>, ExecError> {
        TableAccess::read(&*self.0, Table::HoldingRegisters, address, count)
    }

    fn read_in(
        &self,
        snapshot: &Snapshot,
        address: u16,
        count: u16,
    ) -> Result<Vec<u16>, ExecError> {
        self.0
            .read_in(snapshot, Table::HoldingRegisters, address, count)
    }

    /// `Device::write` is synchronous (the node answers an SDO in the same call) while the
    /// map's write awaits the engine's reply to its commands. The node task runs on the
    /// multi-threaded front-end runtime, so it blocks in place: tokio moves the worker's other
    /// tasks away meanwhile. The engine never waits on this task, so the wait ends (one servo
    /// tick on a paced clock; at once on a virtual one, which applies commands without
    /// advancing). Deferring the write until after the node call would answer the SDO before
    /// knowing whether the map accepted the value, losing the abort.
    fn write(&self, address: u16, words: &[u16]) -> Result<(), WriteError> {
        let fail = |why: &str| Err(WriteError::Failed(why.to_string()));
        let Ok(runtime) = tokio::runtime::Handle::try_current() else {
            return fail("no async runtime to run the map's write on");
        };
        if runtime.runtime_flavor() != tokio::runtime::RuntimeFlavor::MultiThread {
            return fail("the map's write needs the multi-threaded runtime");
        }
        let service = &*self.0;
        let written = tokio::task::block_in_place(|| {
            runtime.block_on(TableAccess::write(
                service,
                Table::HoldingRegisters,
                address,
                words,
            ))
        });
        match written {
            Ok(()) => Ok(()),
            // The map says 04 both for the engine's refusals and for an engine that is gone;
            // only the latter is a failure of the device.
            Err(e) if !service.handle().is_running() => Err(WriteError::Failed(format!(
                "the engine has stopped ({})",
                e.reason
            ))),
            Err(e) => Err(WriteError::Refused(e)),
        }
    }
}

/// The node's device: the EDS's dictionary, its manufacturer objects over the registers.
pub struct MapDevice<R: Registers> {
    od: ObjectDictionary,
    registers: R,
    backed: Vec<Backed>,
    /// Set while the node handles an RPDO (see [`MapDevice::begin_rpdo`]).
    in_rpdo: bool,
    /// An RPDO's changed objects, written by [`MapDevice::finish_rpdo`]: (backed, raw).
    pending: Vec<(usize, u32)>,
    /// Reads the map refused during refreshes (the object keeps its last value).
    pub refresh_errors: u64,
    /// RPDO values the map refused (an RPDO has no answer; the object returns to the map's
    /// value at the next refresh).
    pub rpdo_write_errors: u64,
    /// Power-on values of stored parameters the map refused (the map keeps its value).
    pub parameter_errors: u64,
}

impl<R: Registers> MapDevice<R> {
    /// `backed` from [`backed_objects`] on the same dictionary.
    pub fn new(od: ObjectDictionary, registers: R, backed: Vec<Backed>) -> MapDevice<R> {
        MapDevice {
            od,
            registers,
            backed,
            in_rpdo: false,
            pending: Vec::new(),
            refresh_errors: 0,
            rpdo_write_errors: 0,
            parameter_errors: 0,
        }
    }

    /// Whether `cob_id` is one of the node's valid RPDOs (0x1400–0x15FF sub-index 1).
    pub fn is_rpdo(&self, cob_id: u16) -> bool {
        self.od
            .entries()
            .filter(|e| (0x1400..=0x15FF).contains(&e.def.index) && e.def.subindex == 1)
            .filter_map(|e| e.value.as_u64())
            .any(|v| v & 1 << 31 == 0 && v & 0x7FF == u64::from(cob_id))
    }

    /// The next writes come from an RPDO: the master's process image, sent whole every time.
    /// Only an object whose value changed is an action for the map (P281 = 0 in every RPDO1
    /// must not stop the drive each time, P282 bit 0 not re-enable it), and the changed ones
    /// are written at [`finish_rpdo`](Self::finish_rpdo), set-points before command registers,
    /// so "P290 and P282 bit 1" in one RPDO positions to the new P290.
    pub fn begin_rpdo(&mut self) {
        self.in_rpdo = true;
        self.pending.clear();
    }

    /// Write what the RPDO changed; returns how many writes the map refused.
    pub fn finish_rpdo(&mut self) -> u64 {
        self.in_rpdo = false;
        let mut pending = std::mem::take(&mut self.pending);
        pending.sort_by_key(|(b, _)| self.backed.get(*b).is_some_and(|b| b.commands));
        let mut refused = 0;
        for (b, raw) in pending {
            let Some(b) = self.backed.get(b) else {
                continue;
            };
            if let Err(e) = self.registers.write(b.register, &b.words.encode(raw)) {
                tracing::debug!(index = b.index, reason = %e.reason(), "RPDO value refused by the map");
                refused += 1;
            }
        }
        self.rpdo_write_errors += refused;
        refused
    }

    pub fn backed(&self) -> &[Backed] {
        &self.backed
    }

    /// Every backed object from its registers, with device access (read-only monitors
    /// included), so uploads and TPDOs see the map's current values.
    pub fn refresh(&mut self) {
        self.refresh_with(None);
    }

    /// [`refresh`](Self::refresh) with the engine's values of `snapshot` (the servo tick's).
    pub fn refresh_in(&mut self, snapshot: &Snapshot) {
        self.refresh_with(Some(snapshot));
    }

    fn refresh_with(&mut self, snapshot: Option<&Snapshot>) {
        for b in &self.backed {
            let words = match snapshot {
                Some(s) => self.registers.read_in(s, b.register, b.words.count()),
                None => self.registers.read(b.register, b.words.count()),
            };
            let value = words
                .ok()
                .and_then(|w| b.words.decode(&w))
                .and_then(|raw| from_bits(b.data_type, raw));
            match value {
                Some(v) => {
                    if self.od.set(b.index, 0, v).is_err() {
                        self.refresh_errors += 1;
                    }
                }
                None => self.refresh_errors += 1,
            }
        }
    }
}

impl<R: Registers> MapDevice<R> {
    /// The stored parameters' power-on values, which NMT reset node and 0x1011 (restore
    /// defaults) return to: the map's current values — the machine's configuration (P113 = the
    /// axis's accel_time …), not the EDS's placeholders — except for the objects of
    /// `configured`, whose DCF `ParameterValue` is the power-on value. Each stored parameter is
    /// set to its power-on value. Call after [`refresh`](Self::refresh), before any stored image
    /// is applied. A map value outside the EDS's limits keeps the EDS default.
    pub fn adopt_power_on_defaults(&mut self, configured: &[u16]) {
        let stored: Vec<u16> = self
            .backed
            .iter()
            .filter(|b| b.stored)
            .map(|b| b.index)
            .collect();
        let entries: Vec<(axes::od::EntryDef, Value)> = self
            .od
            .entries()
            .map(|e| {
                let mut def = e.def.clone();
                if def.subindex != 0 || !stored.contains(&def.index) {
                    return (def, e.value.clone());
                }
                if !configured.contains(&def.index) && def.default != e.value {
                    let candidate = axes::od::EntryDef {
                        default: e.value.clone(),
                        ..def.clone()
                    };
                    if ObjectDictionary::from_defs([candidate.clone()]).is_ok() {
                        def = candidate;
                    }
                }
                let value = def.default.clone();
                (def, value)
            })
            .collect();
        match ObjectDictionary::from_defs(entries.iter().map(|(d, _)| d.clone())) {
            Ok(mut od) => {
                for (d, v) in entries {
                    let _ = od.set(d.index, d.subindex, v);
                }
                self.od = od;
            }
            Err(e) => {
                tracing::warn!(error = %e, "the map's power-on values stay out of the defaults")
            }
        }
    }

    /// Write the stored parameters' dictionary values (their power-on values, after a start or
    /// an NMT reset node) into the map where it holds something else, through the map's writes
    /// and their commands (P113 sets the axis's ramp times). Returns how many the map refused;
    /// a refused one keeps the map's value (the next refresh shows it).
    pub fn load_parameters(&mut self) -> u64 {
        self.load_where(|_, b| b.stored)
    }

    /// NMT reset node: the stored parameters' power-on values as [`load_parameters`], and the
    /// process outputs' too (P281 command 0, P282 control word 0), as a drive that reboots comes
    /// up disabled and idle rather than running as it was. Monitors (R registers) are the
    /// drive's to say, never written.
    ///
    /// [`load_parameters`]: Self::load_parameters
    pub fn load_reset_values(&mut self) -> u64 {
        self.load_where(|od, b| {
            let output = od
                .entry(b.index, 0)
                .is_ok_and(|e| e.def.access == axes::od::Access::Rww);
            b.stored || output
        })
    }

    fn load_where(&mut self, wanted: impl Fn(&ObjectDictionary, &Backed) -> bool) -> u64 {
        let mut refused = 0;
        for b in self.backed.iter().filter(|b| wanted(&self.od, b)) {
            let Some(raw) = self.od.get(b.index, 0).and_then(raw_bits) else {
                continue;
            };
            let held = self
                .registers
                .read(b.register, b.words.count())
                .ok()
                .and_then(|w| b.words.decode(&w));
            if held == Some(raw) {
                continue;
            }
            if let Err(e) = self.registers.write(b.register, &b.words.encode(raw)) {
                tracing::warn!(
                    index = b.index,
                    reason = %e.reason(),
                    "a stored parameter's power-on value was refused by the map"
                );
                refused += 1;
            }
        }
        self.parameter_errors += refused;
        refused
    }
}

impl<R: Registers> Device for MapDevice<R> {
    fn od(&self) -> &ObjectDictionary {
        &self.od
    }

    fn od_mut(&mut self) -> &mut ObjectDictionary {
        &mut self.od
    }

    /// The dictionary's checks (access, type, limits), then the map's write for a backed
    /// object (its checks and commands), then the store. Within an RPDO the map's write waits
    /// for [`MapDevice::finish_rpdo`].
    fn write(&mut self, index: u16, subindex: u8, value: Value) -> Result<(), OdError> {
        self.od.validate(index, subindex, &value)?;
        let found = self
            .backed
            .iter()
            .enumerate()
            .find(|(_, b)| b.index == index && subindex == 0);
        if let Some((k, b)) = found {
            let raw = raw_bits(&value).ok_or_else(|| OdError::WrongType {
                index,
                subindex,
                expected: b.data_type,
                found: value.data_type(),
            })?;
            if self.in_rpdo {
                if self.od.get(index, subindex) != Some(&value) {
                    self.pending.retain(|(p, _)| *p != k);
                    self.pending.push((k, raw));
                }
                return self.od.write(index, subindex, value);
            }
            self.registers
                .write(b.register, &b.words.encode(raw))
                .map_err(|e| od_error(index, subindex, &e))?;
        }
        self.od.write(index, subindex, value)
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
mod tests {
    use std::cell::RefCell;
    use std::collections::BTreeMap;

    use mcemu_canopen::eds::Eds;
    use mcemu_modbus::map::{self, Binding, MachineShape};
    use mcemu_modbus::pdu::Exception;

    use super::*;

    fn e10_map() -> UnitMap {
        let shape = MachineShape {
            axes: 1,
            ..MachineShape::default()
        };
        let binding = Binding { axes: vec![0] };
        map::load(
            map::shipped("ct-e10-servo").unwrap(),
            "ct-e10-servo",
            &shape,
            &binding,
        )
        .unwrap()
    }

    fn e10_od() -> ObjectDictionary {
        let text = include_str!("../../../fixtures/canopen/ct-e10.eds");
        Eds::parse("ct-e10.eds", text)
            .unwrap()
            .dictionary(2)
            .unwrap()
    }

    /// Registers in memory; a write to `refuse` fails with that exception; the others are
    /// logged in `writes`.
    #[derive(Default)]
    struct Fake {
        words: RefCell<BTreeMap<u16, u16>>,
        refuse: Option<(u16, Exception)>,
        writes: RefCell<Vec<(u16, Vec<u16>)>>,
    }

    impl Registers for Fake {
        fn read(&self, address: u16, count: u16) -> Result<Vec<u16>, ExecError> {
            let w = self.words.borrow();
            Ok((address..address + count)
                .map(|a| w.get(&a).copied().unwrap_or(0))
                .collect())
        }

        fn write(&self, address: u16, words: &[u16]) -> Result<(), WriteError> {
            if let Some((a, e)) = self.refuse.filter(|(a, _)| *a == address) {
                return Err(ExecError::new(e, format!("register {a} refused")).into());
            }
            self.writes.borrow_mut().push((address, words.to_vec()));
            let mut w = self.words.borrow_mut();
            for (i, v) in words.iter().enumerate() {
                w.insert(address + i as u16, *v);
            }
            Ok(())
        }
    }

    fn device(fake: Fake) -> MapDevice<Fake> {
        let od = e10_od();
        let backed = backed_objects(&od, &e10_map()).unwrap();
        MapDevice::new(od, fake, backed)
    }

    #[test]
    fn every_e10_object_is_a_register_of_the_e10_map() {
        let backed = backed_objects(&e10_od(), &e10_map()).unwrap();
        let find = |i: u16| backed.iter().find(|b| b.index == i).unwrap().clone();
        assert_eq!(find(0x211A).register, 282);
        assert_eq!(find(0x211A).words, Words::One);
        assert_eq!(find(0x20CC).register, 204);
        // P290 and R216 are 32-bit points of the map: its word order (high word first).
        assert_eq!(find(0x2122).words, Words::Point(WordOrder::Abcd));
        assert_eq!(find(0x20D8).words, Words::Point(WordOrder::Abcd));
        // P113 is two 16-bit registers P113/P114.
        assert_eq!(find(0x2071).words, Words::LowFirst);
        assert_eq!(find(0x2071).data_type, DataType::Unsigned32);
    }

    #[test]
    fn an_object_without_its_register_is_refused() {
        let mut od = e10_od();
        od.insert(axes::od::EntryDef::new(
            0x2190,
            0,
            "P400",
            axes::od::Access::Rww,
            Value::U16(0),
        ))
        .unwrap();
        let e = backed_objects(&od, &e10_map()).unwrap_err();
        assert!(
            e.contains("0x2190") && e.contains("holding register 400"),
            "{e}"
        );
    }

    #[test]
    fn words_encode_as_the_decisions_say() {
        // P113 = accel 100 ms (bits 0–15) | decel 200 ms (bits 16–31) → HR 113 = 100, HR 114 = 200.
        assert_eq!(Words::LowFirst.encode(100 | 200 << 16), vec![100, 200]);
        assert_eq!(Words::LowFirst.decode(&[100, 200]), Some(100 | 200 << 16));
        // P290 = −2 as an i32 point, high word first.
        let raw = raw_bits(&Value::I32(-2)).unwrap();
        let w = Words::Point(WordOrder::Abcd).encode(raw);
        assert_eq!(w, vec![0xFFFF, 0xFFFE]);
        let back = Words::Point(WordOrder::Abcd).decode(&w).unwrap();
        assert_eq!(from_bits(DataType::Integer32, back), Some(Value::I32(-2)));
        assert_eq!(
            Words::Point(WordOrder::Cdab).encode(0x0001_0002),
            vec![2, 1]
        );
        // 16-bit signed: the register holds the bit pattern.
        let raw = raw_bits(&Value::I16(-300)).unwrap();
        assert_eq!(Words::One.encode(raw), vec![(-300i16) as u16]);
        assert_eq!(from_bits(DataType::Integer16, raw), Some(Value::I16(-300)));
        assert_eq!(Words::One.decode(&[1, 2]), None);
    }

    #[test]
    fn writes_reach_the_registers_and_refreshes_come_back() {
        let mut d = device(Fake::default());
        d.write(0x2071, 0, Value::U32(100 | 200 << 16)).unwrap();
        d.write(0x2122, 0, Value::I32(123_456)).unwrap();
        {
            let w = d.registers.words.borrow();
            assert_eq!((w[&113], w[&114]), (100, 200));
            assert_eq!((w[&290], w[&291]), (1, 57_920));
        }
        d.registers.words.borrow_mut().insert(204, 0b11);
        d.registers.words.borrow_mut().insert(216, 0xFFFF);
        d.registers.words.borrow_mut().insert(217, 0xFFF6);
        d.refresh();
        assert_eq!(d.od().get(0x20CC, 0), Some(&Value::U16(3)));
        assert_eq!(d.od().get(0x20D8, 0), Some(&Value::I32(-10)));
        assert_eq!(d.refresh_errors, 0);
        // A read-only monitor stays read-only for a master.
        let e = d.write(0x20CC, 0, Value::U16(1)).unwrap_err();
        assert_eq!(e.sdo_abort_code(), 0x0601_0002);
    }

    #[test]
    fn map_exceptions_become_sdo_aborts() {
        for (exception, abort) in [
            (Exception::IllegalDataAddress, 0x0602_0000),
            (Exception::IllegalDataValue, 0x0609_0030),
            (Exception::ServerDeviceFailure, 0x0800_0022),
            (Exception::ServerDeviceBusy, 0x0800_0022),
        ] {
            let mut d = device(Fake {
                refuse: Some((113, exception)),
                ..Fake::default()
            });
            let e = d.write(0x2071, 0, Value::U32(5)).unwrap_err();
            assert_eq!(e.sdo_abort_code(), abort, "{exception:?}");
            // Refused: the object keeps its value.
            assert_eq!(d.od().get(0x2071, 0), Some(&Value::U32(0)));
        }
    }

    /// The real path: a map service over a running engine, its write awaited in place on the
    /// multi-threaded runtime; the engine's value check (03) and its state refusal (04) come
    /// back as SDO aborts, and an accepted write reaches the axis.
    #[tokio::test(flavor = "multi_thread", worker_threads = 2)]
    async fn a_real_map_service_answers_through_the_device() {
        use axes::config::{AxisConfig, EngineConfig};
        use axes::runtime::{ClockMode, Runtime, RuntimeOptions};
        use axes::Engine;

        let config = EngineConfig {
            axes: vec![AxisConfig::default()],
            ..EngineConfig::default()
        };
        let engine = Engine::new(&config).unwrap();
        let (handle, guard) =
            Runtime::start(engine, RuntimeOptions::with_clock(ClockMode::Virtual)).unwrap();
        let text = r#"
[map]
name = "test"
[[point]]
table = "holding_registers"
address = 5
name = "speed"
type = "i16"
read = "axis.param.speed"
write = "axis.param.speed"
[[point]]
table = "holding_registers"
address = 6
name = "run"
write = "memory"
on_write = [{ when = "=1", command = "move_velocity", args = { velocity = 10 } }]
"#;
        let shape = MachineShape {
            axes: 1,
            ..MachineShape::default()
        };
        let unit = map::load(text, "test", &shape, &Binding { axes: vec![0] }).unwrap();
        let mut od = ObjectDictionary::default();
        for (index, default) in [(0x2005, Value::I16(0)), (0x2006, Value::U16(0))] {
            od.insert(axes::od::EntryDef::new(index, 0, "p", axes::od::Access::Rww, default).pdo())
                .unwrap();
        }
        let backed = backed_objects(&od, &unit).unwrap();
        let service = Arc::new(UnitService::new(unit, handle.clone()));
        let mut d = MapDevice::new(od, ServiceRegisters(service), backed);

        d.write(0x2005, 0, Value::I16(1234)).unwrap();
        let speed = handle
            .snapshot()
            .params
            .first()
            .map(|p| p.get(axes::ParamId::Speed));
        assert_eq!(speed, Some(1234.0));
        d.refresh();
        assert_eq!(d.od().get(0x2005, 0), Some(&Value::I16(1234)));
        // A negative speed: the engine's parameter range, exception 03.
        let e = d.write(0x2005, 0, Value::I16(-1)).unwrap_err();
        assert_eq!(e.sdo_abort_code(), 0x0609_0030, "{e}");
        assert_eq!(d.od().get(0x2005, 0), Some(&Value::I16(1234)));
        // A move of a disabled axis: refused in the engine's state, exception 04.
        let e = d.write(0x2006, 0, Value::U16(1)).unwrap_err();
        assert_eq!(e.sdo_abort_code(), 0x0800_0022, "{e}");
        // The engine gone (the map answers 04 here too): a failure of the device, 0x08000000.
        guard.stop().unwrap();
        let e = d.write(0x2005, 0, Value::I16(100)).unwrap_err();
        assert_eq!(e.sdo_abort_code(), 0x0800_0000, "{e}");
        assert_eq!(d.od().get(0x2005, 0), Some(&Value::I16(1234)));
    }

    /// Outside a multi-threaded runtime the map's write cannot run at all: general error.
    #[test]
    fn a_map_service_without_its_runtime_is_a_device_failure() {
        use axes::config::{AxisConfig, EngineConfig};
        use axes::runtime::{ClockMode, Runtime, RuntimeOptions};
        use axes::Engine;

        let config = EngineConfig {
            axes: vec![AxisConfig::default()],
            ..EngineConfig::default()
        };
        let engine = Engine::new(&config).unwrap();
        let (handle, _guard) =
            Runtime::start(engine, RuntimeOptions::with_clock(ClockMode::Virtual)).unwrap();
        let service = Arc::new(UnitService::new(e10_map(), handle));
        let od = e10_od();
        let backed = backed_objects(&od, service.map()).unwrap();
        let mut d = MapDevice::new(od, ServiceRegisters(service), backed);
        let e = d.write(0x2071, 0, Value::U32(5)).unwrap_err();
        assert_eq!(e.sdo_abort_code(), 0x0800_0000, "{e}");
        assert!(matches!(e, OdError::DeviceFailure { .. }), "{e:?}");
    }

    #[test]
    fn the_e10_settings_are_its_stored_parameters_and_commands_are_not() {
        let backed = backed_objects(&e10_od(), &e10_map()).unwrap();
        let stored: Vec<u16> = backed
            .iter()
            .filter(|b| b.stored)
            .map(|b| b.index)
            .collect();
        // P95–P102 internal speeds, P113 ramps, P290 given position.
        assert_eq!(
            stored,
            [0x205F, 0x2060, 0x2061, 0x2062, 0x2063, 0x2064, 0x2065, 0x2066, 0x2071, 0x2122]
        );
    }

    /// Power-on: the map's values at start become the defaults; a stored image's values (applied
    /// to the dictionary by the node) go into the map, only where the map holds something else;
    /// a value the map refuses is counted and the map keeps its own.
    #[test]
    fn power_on_values_go_into_the_map() {
        let od = e10_od();
        let backed = backed_objects(&od, &e10_map()).unwrap();
        let log = Fake {
            refuse: Some((97, Exception::IllegalDataValue)),
            ..Fake::default()
        };
        // The machine's ramps: 100 ms / 100 ms; R204 = 1 (a monitor: not a parameter).
        log.words
            .borrow_mut()
            .extend([(113, 100), (114, 100), (204, 1)]);
        let mut d = MapDevice::new(od, log, backed);
        d.refresh();
        d.adopt_power_on_defaults(&[]);
        let default = |d: &MapDevice<Fake>, i| d.od().entry(i, 0).unwrap().def.default.clone();
        assert_eq!(default(&d, 0x2071), Value::U32(100 | 100 << 16));
        assert_eq!(
            default(&d, 0x20CC),
            Value::U16(0),
            "monitors keep the EDS default"
        );
        assert_eq!(d.load_parameters(), 0);
        assert!(d.registers.writes.borrow().is_empty(), "nothing differs");
        // What a stored image puts in the dictionary (device access).
        d.od_mut()
            .set(0x2071, 0, Value::U32(100 | 200 << 16))
            .unwrap();
        d.od_mut().set(0x2122, 0, Value::I32(-5)).unwrap();
        d.od_mut().set(0x2061, 0, Value::I16(30)).unwrap();
        d.od_mut().set(0x211A, 0, Value::U16(1)).unwrap();
        assert_eq!(d.load_parameters(), 1, "P97 refused");
        assert_eq!(
            *d.registers.writes.borrow(),
            [(113, vec![100, 200]), (290, vec![0xFFFF, 0xFFFB])],
            "P113 and P290 written; P282 (process data) not"
        );
        assert_eq!(d.parameter_errors, 1);
        assert_eq!(
            d.load_parameters(),
            1,
            "again: only the refused one differs"
        );
        assert_eq!(d.registers.writes.borrow().len(), 2);
    }

    /// NMT reset node: the process outputs' power-on values go into the map too (the drive
    /// comes back disabled and idle); monitors are never written.
    #[test]
    fn reset_node_disables_the_drive_through_the_map() {
        let od = e10_od();
        let backed = backed_objects(&od, &e10_map()).unwrap();
        let fake = Fake::default();
        // Running: P281 = 3 (a command), P282 = 1 (enabled); R204 = 1 (ready, a monitor).
        fake.words
            .borrow_mut()
            .extend([(281, 3), (282, 1), (204, 1)]);
        let mut d = MapDevice::new(od, fake, backed);
        d.refresh();
        d.adopt_power_on_defaults(&[]);
        // What reset node leaves in the dictionary: the power-on values (0 for both outputs).
        for index in [0x2119u16, 0x211A] {
            let value = d.od().entry(index, 0).unwrap().def.default.clone();
            d.od_mut().set(index, 0, value).unwrap();
        }
        assert_eq!(d.load_parameters(), 0);
        assert!(
            d.registers.writes.borrow().is_empty(),
            "parameters alone: no output"
        );
        assert_eq!(d.load_reset_values(), 0);
        let mut written = d.registers.writes.borrow().clone();
        written.sort();
        assert_eq!(written, [(281, vec![0]), (282, vec![0])]);
        assert_eq!(
            d.registers.words.borrow()[&204],
            1,
            "the monitor is untouched"
        );
    }

    /// A DCF's `ParameterValue` for a stored parameter is its power-on value: written into the
    /// map at power-on instead of taking the map's.
    #[test]
    fn a_dcf_value_is_the_power_on_value() {
        let text = include_str!("../../../fixtures/canopen/ct-e10.eds").replace(
            "ParameterName=P95 1st internal speed\nObjectType=0x7\nDataType=0x0003\nAccessType=rw\nDefaultValue=0\n",
            "ParameterName=P95 1st internal speed\nObjectType=0x7\nDataType=0x0003\nAccessType=rw\nDefaultValue=0\nParameterValue=-1500\n",
        );
        let od = Eds::parse("e10.dcf", &text).unwrap().dictionary(2).unwrap();
        let backed = backed_objects(&od, &e10_map()).unwrap();
        let mut d = MapDevice::new(od, Fake::default(), backed);
        d.refresh();
        assert_eq!(
            d.od().get(0x205F, 0),
            Some(&Value::I16(0)),
            "the map's value"
        );
        d.adopt_power_on_defaults(&[0x205F]);
        assert_eq!(d.od().get(0x205F, 0), Some(&Value::I16(-1500)));
        assert_eq!(d.load_parameters(), 0);
        assert_eq!(d.registers.words.borrow()[&95], (-1500i16) as u16);
    }

    #[test]
    fn an_rpdo_writes_changed_values_set_points_first() {
        #[derive(Default)]
        struct Log(RefCell<Vec<(u16, Vec<u16>)>>);
        impl Registers for Log {
            fn read(&self, _: u16, count: u16) -> Result<Vec<u16>, ExecError> {
                Ok(vec![0; usize::from(count)])
            }
            fn write(&self, address: u16, words: &[u16]) -> Result<(), WriteError> {
                self.0.borrow_mut().push((address, words.to_vec()));
                Ok(())
            }
        }
        let od = e10_od();
        let backed = backed_objects(&od, &e10_map()).unwrap();
        let mut d = MapDevice::new(od, Log::default(), backed);
        assert!(d.is_rpdo(0x202) && d.is_rpdo(0x302) && !d.is_rpdo(0x182));
        // RPDO1 in mapping order: P282 = 3 (enable, start), P281 = 0 (unchanged), P290 = 5000.
        d.begin_rpdo();
        d.write(0x211A, 0, Value::U16(3)).unwrap();
        d.write(0x2119, 0, Value::U16(0)).unwrap();
        d.write(0x2122, 0, Value::I32(5000)).unwrap();
        assert!(
            d.registers.0.borrow().is_empty(),
            "nothing before the RPDO ends"
        );
        assert_eq!(d.finish_rpdo(), 0);
        assert_eq!(
            *d.registers.0.borrow(),
            [(290, vec![0, 5000]), (282, vec![3])],
            "P290 first, P282 (commands) after, P281 unchanged: not written"
        );
        // The same image again: no action.
        d.begin_rpdo();
        d.write(0x211A, 0, Value::U16(3)).unwrap();
        d.write(0x2122, 0, Value::I32(5000)).unwrap();
        d.finish_rpdo();
        assert_eq!(d.registers.0.borrow().len(), 2);
        // An SDO write always acts, changed or not.
        d.write(0x211A, 0, Value::U16(3)).unwrap();
        assert_eq!(d.registers.0.borrow().len(), 3);
    }
}
