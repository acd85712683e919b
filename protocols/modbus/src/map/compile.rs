//! From a map file to the tables the service runs on, for one unit: blocks repeated for the
//! unit's axes, paths resolved, overlaps, missing sources and bad types refused with the key
//! and the reason.

use std::collections::BTreeMap;

use axes::Command;
use serde_json::{Map, Value};

use super::schema::{
    ActionFile, ArgFile, ChannelKind, ChannelsFile, CodeFile, Gaps, InitValue, MapFile, PointFile,
    ReadFile, Table,
};
use super::source::{
    parse_bits, parse_select, parse_source, parse_target, MachineShape, Scope, Source, Target,
};
use super::value::{encode, encode_string, PointType, WordOrder};
use crate::model::DeviceIdentity;

/// A map that cannot be used: the key path inside the map file and why.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CompileError {
    /// e.g. `block[0].point[3].read`.
    pub key: String,
    pub reason: String,
}

/// What the unit serves: the machine axes its blocks repeat for, in order. Outside blocks,
/// `axis.` means the first.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Binding {
    pub axes: Vec<usize>,
}

/// When an action fires, judged on the written raw value.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum When {
    Always,
    Nonzero,
    Zero,
    BitSet(u8),
    BitClear(u8),
    /// Bit set now and clear in the previous write.
    RisingBit(u8),
    /// The written value equals N (a command code register).
    Equals(i64),
}

/// A command argument filled in at write time.
#[derive(Clone, Debug, PartialEq)]
pub enum Arg {
    /// The written value (scaled).
    Written,
    /// The current value of another point, by index into the unit's points; `negate` for
    /// `-@name`.
    Point { index: usize, negate: bool },
}

/// A command a write issues: a JSON template of `axes::Command` with holes.
#[derive(Clone, Debug, PartialEq)]
pub struct IssuedCommand {
    pub when: When,
    pub template: Map<String, Value>,
    pub holes: Vec<(String, Arg)>,
}

/// Where a point's reads come from after compilation.
#[derive(Clone, Debug, PartialEq)]
pub enum Read {
    Source(Source),
    /// The point's memory cell.
    Memory,
}

/// One compiled point.
#[derive(Clone, Debug, PartialEq)]
pub struct Point {
    /// `name` (fixed points) or `name@axisN` (block copies), for logs and errors.
    pub name: String,
    pub table: Table,
    pub address: u16,
    pub ty: PointType,
    /// Registers (1 for bits).
    pub width: u16,
    pub order: WordOrder,
    pub scale: f64,
    pub read: Read,
    /// Lookup of the read datum: by name first, then by number.
    pub names: Vec<(String, f64)>,
    pub numbers: Vec<(f64, f64)>,
    pub default: Option<f64>,
    /// `code << 24 | axis << 16 | value` for nonzero values (HIMC axis error codes).
    pub axis_code: Option<u8>,
    /// Writes: where the value goes, `None` with no actions = read-only.
    pub write: Option<Target>,
    pub actions: Vec<IssuedCommand>,
    /// First word of the point's memory cell in [`UnitMap::initial_memory`], if it has one.
    pub cell: Option<usize>,
}

impl Point {
    pub fn writable(&self) -> bool {
        self.write.is_some() || !self.actions.is_empty()
    }
}

/// A compiled map for one unit.
#[derive(Clone, Debug, PartialEq)]
pub struct UnitMap {
    pub name: String,
    pub identity: DeviceIdentity,
    pub gaps: Gaps,
    pub lenient_parameters: bool,
    pub points: Vec<Point>,
    /// Point indices per table, sorted by address.
    pub tables: BTreeMap<Table, Vec<usize>>,
    /// Memory areas: table, first address, words, persisted, first memory word.
    pub areas: Vec<Area>,
    /// Initial contents of all memory cells and areas (registers as words, bits as 0/1).
    pub initial_memory: Vec<u16>,
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Area {
    pub name: String,
    pub table: Table,
    pub start: u16,
    pub count: u16,
    pub persist: bool,
    pub cell: usize,
}

fn err(key: impl Into<String>, reason: impl Into<String>) -> CompileError {
    CompileError {
        key: key.into(),
        reason: reason.into(),
    }
}

/// A point file placed at its address for one axis, before compilation.
struct Placed<'f> {
    file: &'f PointFile,
    key: String,
    table: Table,
    address: u16,
    axis: Option<usize>,
    name: String,
}

/// Compile `file` for a unit serving `binding` on `machine`.
pub fn compile(
    file: &MapFile,
    machine: &MachineShape,
    binding: &Binding,
) -> Result<UnitMap, CompileError> {
    if let Some(&bad) = binding.axes.iter().find(|&&a| a >= machine.axes) {
        return Err(err(
            "",
            format!("the unit serves axis {bad}, which the machine does not have"),
        ));
    }
    let mut unit = UnitMap {
        name: file.map.name.clone(),
        identity: identity(file),
        gaps: file.map.gaps,
        lenient_parameters: file.map.lenient_parameters,
        points: Vec::new(),
        tables: BTreeMap::new(),
        areas: Vec::new(),
        initial_memory: Vec::new(),
    };
    // Keys of the points as written, for overlap messages and `@name` references.
    let mut keys: Vec<String> = Vec::new();
    // Point files with their scope, compiled in two passes so that actions can refer to points
    // defined after them.
    let mut pending: Vec<Placed<'_>> = Vec::new();
    for (i, p) in file.point.iter().enumerate() {
        let key = format!("point[{i}]");
        let table = p.table.ok_or_else(|| {
            err(
                format!("{key}.table"),
                "a point outside a block needs `table`",
            )
        })?;
        let address = p.address.ok_or_else(|| {
            err(
                format!("{key}.address"),
                "a point outside a block needs `address` (`offset` is for block points)",
            )
        })?;
        if p.offset.is_some() {
            return Err(err(
                format!("{key}.offset"),
                "`offset` is for block points; use `address`",
            ));
        }
        pending.push(Placed {
            file: p,
            key,
            table,
            address,
            axis: binding.axes.first().copied(),
            name: p.name.clone(),
        });
    }
    for (b, block) in file.block.iter().enumerate() {
        let served = block.max_axes.map_or(binding.axes.len(), |m| {
            binding.axes.len().min(usize::from(m))
        });
        for (k, &axis) in binding.axes.iter().take(served).enumerate() {
            for (i, p) in block.point.iter().enumerate() {
                let key = format!("block[{b}].point[{i}]");
                if p.table.is_some_and(|t| t != block.table) {
                    return Err(err(
                        format!("{key}.table"),
                        "a block point is in its block's table; use another block for another table",
                    ));
                }
                if p.address.is_some() {
                    return Err(err(
                        format!("{key}.address"),
                        "block points take `offset`, not `address`",
                    ));
                }
                let offset = p
                    .offset
                    .ok_or_else(|| err(format!("{key}.offset"), "a block point needs `offset`"))?;
                let address =
                    u32::from(block.base) + u32::from(block.stride) * k as u32 + u32::from(offset);
                let address = u16::try_from(address).map_err(|_| {
                    err(
                        format!("block[{b}].stride"),
                        format!(
                            "axis {axis} (the unit's axis #{k}) puts `{}` at {address}, beyond \
                             the last address 65535",
                            p.name
                        ),
                    )
                })?;
                pending.push(Placed {
                    file: p,
                    key,
                    table: block.table,
                    address,
                    axis: Some(axis),
                    name: format!("{}@axis{axis}", p.name),
                });
            }
        }
    }
    // Pass 1: layout, types, reads, writes; memory cells.
    for pl in &pending {
        let point = point(
            pl.file,
            &pl.key,
            pl.table,
            pl.address,
            pl.axis,
            &pl.name,
            file,
            machine,
            &binding.axes,
            &mut unit.initial_memory,
        )?;
        unit.points.push(point);
        keys.push(pl.key.clone());
    }
    // Pass 2: actions, which may name other points.
    for (i, pl) in pending.iter().enumerate() {
        let (p, key, axis) = (pl.file, &pl.key, pl.axis);
        let mut actions = Vec::new();
        for (j, a) in p.on_write.iter().enumerate() {
            let key = format!("{key}.on_write[{j}]");
            actions.push(action(a, &key, axis, i, &pending, &unit.points)?);
        }
        if !actions.is_empty() && !unit.points[i].table.is_writable() {
            return Err(err(
                format!("{key}.on_write"),
                format!(
                    "{} cannot be written over Modbus",
                    unit.points[i].table.name()
                ),
            ));
        }
        unit.points[i].actions = actions;
    }
    for (i, m) in file.memory.iter().enumerate() {
        let key = format!("memory[{i}]");
        if m.count == 0 {
            return Err(err(
                format!("{key}.count"),
                "a memory area needs at least one address",
            ));
        }
        if u32::from(m.start) + u32::from(m.count) > 65536 {
            return Err(err(
                format!("{key}.count"),
                "the area runs past address 65535",
            ));
        }
        let cell = unit.initial_memory.len();
        unit.initial_memory.resize(cell + usize::from(m.count), 0);
        unit.areas.push(Area {
            name: m.name.clone(),
            table: m.table,
            start: m.start,
            count: m.count,
            persist: m.persist,
            cell,
        });
    }
    for (i, c) in file.channels.iter().enumerate() {
        channels(
            c,
            &format!("channels[{i}]"),
            file,
            machine,
            &mut unit,
            &mut keys,
        )?;
    }
    check_overlaps(&unit, &keys, file)?;
    for (i, p) in unit.points.iter().enumerate() {
        unit.tables.entry(p.table).or_default().push(i);
    }
    for list in unit.tables.values_mut() {
        list.sort_by_key(|&i| unit.points[i].address);
    }
    Ok(unit)
}

/// Expand a `[[channels]]` table into one point per channel.
fn channels(
    c: &ChannelsFile,
    key: &str,
    file: &MapFile,
    machine: &MachineShape,
    unit: &mut UnitMap,
    keys: &mut Vec<String>,
) -> Result<(), CompileError> {
    let (count, analog, output) = match c.kind {
        ChannelKind::Di => (machine.digital_inputs, false, false),
        ChannelKind::Do => (machine.digital_outputs, false, true),
        ChannelKind::Ai => (machine.analog_inputs, true, false),
        ChannelKind::Ao => (machine.analog_outputs, true, true),
    };
    let ty = match (c.table.is_bits(), analog, c.ty) {
        (true, true, _) => {
            return Err(err(
                format!("{key}.table"),
                "analog channels need a register table",
            ))
        }
        (true, false, _) => PointType::Bool,
        (false, _, Some(PointType::String)) => {
            return Err(err(format!("{key}.type"), "channels are numbers, not text"))
        }
        (false, _, Some(t)) => t,
        (false, true, None) => PointType::F32,
        (false, false, None) => PointType::U16,
    };
    let width = ty.registers(0);
    let name = match c.kind {
        ChannelKind::Di => "di",
        ChannelKind::Do => "do",
        ChannelKind::Ai => "ai",
        ChannelKind::Ao => "ao",
    };
    for n in 0..count {
        let address = u32::from(c.base) + n as u32 * u32::from(width);
        let address = u16::try_from(address)
            .ok()
            .filter(|a| u32::from(*a) + u32::from(width) <= 65536)
            .ok_or_else(|| {
                err(
                    format!("{key}.base"),
                    format!("{name}.{n} runs past address 65535"),
                )
            })?;
        let read = match c.kind {
            ChannelKind::Di => Source::DigitalInput(n),
            ChannelKind::Do => Source::DigitalOutput(n),
            ChannelKind::Ai => Source::AnalogInput(n),
            ChannelKind::Ao => Source::AnalogOutput(n),
        };
        let write = match (output && c.table.is_writable(), analog) {
            (false, _) => None,
            (true, false) => Some(Target::DigitalOutput(n)),
            (true, true) => Some(Target::AnalogOutput(n)),
        };
        unit.points.push(Point {
            name: format!("{name}.{n}"),
            table: c.table,
            address,
            ty,
            width,
            order: file.map.word_order,
            scale: c.scale.unwrap_or(1.0),
            read: Read::Source(read),
            names: Vec::new(),
            numbers: Vec::new(),
            default: None,
            axis_code: None,
            write,
            actions: Vec::new(),
            cell: None,
        });
        keys.push(key.to_string());
    }
    Ok(())
}

fn identity(file: &MapFile) -> DeviceIdentity {
    let f = &file.identity;
    DeviceIdentity {
        server_id: f.server_id.clone(),
        vendor_name: f.vendor_name.clone(),
        product_code: f.product_code.clone(),
        revision: f.revision.clone(),
        vendor_url: f.vendor_url.clone(),
        product_name: f.product_name.clone(),
        model_name: f.model_name.clone(),
        user_application_name: f.user_application_name.clone(),
    }
}

#[allow(clippy::too_many_arguments)]
fn point(
    p: &PointFile,
    key: &str,
    table: Table,
    address: u16,
    axis: Option<usize>,
    name: &str,
    file: &MapFile,
    machine: &MachineShape,
    binding_axes: &[usize],
    memory: &mut Vec<u16>,
) -> Result<Point, CompileError> {
    let scope = Scope { machine, axis };
    let ty = match (table.is_bits(), p.ty) {
        (true, None | Some(PointType::Bool)) => PointType::Bool,
        (true, Some(t)) => {
            return Err(err(
                format!("{key}.type"),
                format!(
                    "{} hold single bits: the type is `bool`, not `{t:?}`",
                    table.name()
                )
                .to_lowercase(),
            ))
        }
        (false, None) => PointType::U16,
        (false, Some(t)) => t,
    };
    let width = match (ty, p.length) {
        (PointType::String, Some(n)) if (1..=123).contains(&n) => n,
        (PointType::String, _) => {
            return Err(err(
                format!("{key}.length"),
                "a string needs `length`, 1 … 123 registers",
            ))
        }
        (_, Some(_)) => return Err(err(format!("{key}.length"), "`length` is for strings")),
        (t, None) => t.registers(0),
    };
    if u32::from(address) + u32::from(width) > 65536 {
        return Err(err(
            format!("{key}.address"),
            "the point runs past address 65535",
        ));
    }
    let scale = p.scale.unwrap_or(1.0);
    if !scale.is_finite() || scale == 0.0 {
        return Err(err(
            format!("{key}.scale"),
            "the scale must be a finite number other than 0",
        ));
    }
    let read = match &p.read {
        None => Read::Memory,
        Some(ReadFile::Path(path)) => match parse_source(path, &scope) {
            Ok(Source::Memory) => Read::Memory,
            Ok(s) => Read::Source(s),
            Err(reason) => return Err(err(format!("{key}.read"), reason)),
        },
        Some(ReadFile::Select { first, all_axes }) => {
            if !ty.is_integer() {
                return Err(err(
                    format!("{key}.type"),
                    "a `first` table gives codes: use an integer type",
                ));
            }
            let axes = match (*all_axes, axis) {
                (true, _) => binding_axes.to_vec(),
                (false, Some(a)) => vec![a],
                (false, None) => Vec::new(),
            };
            let mut cases = Vec::with_capacity(first.len());
            for (i, c) in first.iter().enumerate() {
                let value = code_value(&c.value)
                    .map_err(|r| err(format!("{key}.read.first[{i}].value"), r))?;
                cases.push((c.when.as_str(), value));
            }
            Read::Source(parse_select(cases, axes).map_err(|r| err(format!("{key}.read"), r))?)
        }
        Some(ReadFile::Bits { bits }) => {
            let w = u8::try_from(16 * width).unwrap_or(64).min(64);
            if ty.is_integer() || ty == PointType::Bool {
                Read::Source(
                    parse_bits(bits, w, &scope).map_err(|r| err(format!("{key}.read"), r))?,
                )
            } else {
                return Err(err(
                    format!("{key}.read"),
                    "a bit table needs an integer type (u16, u32 …)",
                ));
            }
        }
    };
    let write = match &p.write {
        None => None,
        Some(path) => Some(parse_target(path, &scope).map_err(|r| err(format!("{key}.write"), r))?),
    };
    if write.is_some() && !table.is_writable() {
        return Err(err(
            format!("{key}.write"),
            format!("{} cannot be written over Modbus", table.name()),
        ));
    }
    if write == Some(Target::Memory) && read != Read::Memory {
        return Err(err(
            format!("{key}.write"),
            "`write = \"memory\"` holds the value for reads; drop `read`, or write somewhere else",
        ));
    }
    if ty == PointType::String && matches!(read, Read::Source(_)) {
        return Err(err(
            format!("{key}.type"),
            "a string is text held in memory; it cannot read a source",
        ));
    }
    let (mut names, mut numbers) = (Vec::new(), Vec::new());
    for (k, v) in &p.values {
        match parse_number(k) {
            Some(n) => numbers.push((n, *v)),
            None => names.push((k.clone(), *v)),
        }
    }
    // Memory cell: points that read their own memory (constants included).
    let cell = if read == Read::Memory {
        let at = memory.len();
        memory.resize(at + usize::from(width), 0);
        let order = p.word_order.unwrap_or(file.map.word_order);
        match &p.init {
            None => {}
            Some(InitValue::Number(v)) if ty != PointType::String => {
                encode(v * scale, ty, order, &mut memory[at..]);
            }
            Some(InitValue::Text(t)) if ty == PointType::String => {
                encode_string(t, &mut memory[at..]);
            }
            Some(_) => {
                return Err(err(
                    format!("{key}.init"),
                    "`init` is a number, or text for a string point",
                ))
            }
        }
        Some(at)
    } else {
        if p.init.is_some() {
            return Err(err(
                format!("{key}.init"),
                "`init` is for points that read their own memory",
            ));
        }
        None
    };
    Ok(Point {
        name: name.to_string(),
        table,
        address,
        ty,
        width,
        order: p.word_order.unwrap_or(file.map.word_order),
        scale,
        read,
        names,
        numbers,
        default: p.default,
        axis_code: p.axis_code,
        write,
        actions: Vec::new(),
        cell,
    })
}

/// A `first` case's value: the number, or the number a vendor's code name stands for.
fn code_value(value: &CodeFile) -> Result<f64, String> {
    match value {
        CodeFile::Number(n) => Ok(*n),
        CodeFile::Name(name) => mcemu_dialects::code_by_name(name)
            .map(f64::from)
            .ok_or_else(|| format!("`{name}` is not a code any dialect names")),
    }
}

fn parse_number(text: &str) -> Option<f64> {
    if let Some(hex) = text.strip_prefix("0x") {
        return u64::from_str_radix(hex, 16).ok().map(|v| v as f64);
    }
    text.parse().ok()
}

fn parse_when(text: &str) -> Option<When> {
    let bit = |t: &str| t.parse::<u8>().ok().filter(|&n| n < 64);
    Some(match text {
        "always" => When::Always,
        "nonzero" => When::Nonzero,
        "zero" => When::Zero,
        _ => {
            if let Some(n) = text.strip_prefix('=') {
                When::Equals(n.trim().parse().ok()?)
            } else if let Some(n) = text.strip_prefix("rising_bit") {
                When::RisingBit(bit(n)?)
            } else if let Some(n) = text.strip_prefix("!bit") {
                When::BitClear(bit(n)?)
            } else if let Some(n) = text.strip_prefix("bit") {
                When::BitSet(bit(n)?)
            } else {
                return None;
            }
        }
    })
}

fn action(
    a: &ActionFile,
    key: &str,
    axis: Option<usize>,
    own: usize,
    pending: &[Placed<'_>],
    points: &[Point],
) -> Result<IssuedCommand, CompileError> {
    let when = parse_when(&a.when).ok_or_else(|| {
        err(
            format!("{key}.when"),
            format!(
                "`{}`: expected always, nonzero, zero, =N, bitN, !bitN or rising_bitN",
                a.when
            ),
        )
    })?;
    let mut template = Map::new();
    template.insert("type".into(), Value::String(a.command.clone()));
    let mut holes = Vec::new();
    for (field, arg) in &a.args {
        let value = match arg {
            ArgFile::Bool(b) => Value::Bool(*b),
            ArgFile::Number(n) => serde_json::Number::from_f64(*n)
                .map(Value::Number)
                .ok_or_else(|| err(format!("{key}.args.{field}"), "not a finite number"))?,
            ArgFile::Text(t) if t == "value" => {
                holes.push((field.clone(), Arg::Written));
                Value::from(0.0)
            }
            ArgFile::Text(t) => match t
                .strip_prefix('@')
                .map(|n| (n, false))
                .or_else(|| t.strip_prefix("-@").map(|n| (n, true)))
            {
                Some((name, negate)) => {
                    let target = resolve(name, axis, pending).ok_or_else(|| {
                        err(
                            format!("{key}.args.{field}"),
                            format!(
                                "no point `{name}` in this block or among the map's fixed points"
                            ),
                        )
                    })?;
                    if target == own || points[target].ty == PointType::String {
                        return Err(err(
                            format!("{key}.args.{field}"),
                            format!("`{name}` cannot be an argument (the point itself, or text)"),
                        ));
                    }
                    holes.push((
                        field.clone(),
                        Arg::Point {
                            index: target,
                            negate,
                        },
                    ));
                    Value::from(0.0)
                }
                None => Value::String(t.clone()),
            },
        };
        template.insert(field.clone(), value);
    }
    if !template.contains_key("axis") {
        if let Some(axis) = axis {
            template.insert("axis".into(), Value::from(axis));
        }
    }
    // Holes hold 0 here: what cannot become a command with zeros cannot with other numbers.
    serde_json::from_value::<Command>(Value::Object(template.clone()))
        .map_err(|e| err(format!("{key}.command"), format!("`{}`: {e}", a.command)))?;
    Ok(IssuedCommand {
        when,
        template,
        holes,
    })
}

/// A point named in an argument: in the same block copy (same axis) first, then a fixed point.
fn resolve(name: &str, axis: Option<usize>, pending: &[Placed<'_>]) -> Option<usize> {
    let block_key = |k: &str| k.starts_with("block[");
    pending
        .iter()
        .position(|pl| block_key(&pl.key) && pl.axis == axis && pl.file.name == name)
        .or_else(|| {
            pending
                .iter()
                .position(|pl| !block_key(&pl.key) && pl.file.name == name)
        })
}

fn check_overlaps(unit: &UnitMap, keys: &[String], file: &MapFile) -> Result<(), CompileError> {
    // (table, start, end, what) for points and areas.
    let mut spans: Vec<(Table, u32, u32, String, String)> = unit
        .points
        .iter()
        .zip(keys)
        .map(|(p, k)| {
            (
                p.table,
                u32::from(p.address),
                u32::from(p.address) + u32::from(p.width),
                k.clone(),
                p.name.clone(),
            )
        })
        .collect();
    for (i, a) in unit.areas.iter().enumerate() {
        spans.push((
            a.table,
            u32::from(a.start),
            u32::from(a.start) + u32::from(a.count),
            format!("memory[{i}]"),
            file.memory[i].name.clone(),
        ));
    }
    spans.sort_by_key(|s| (s.0, s.1));
    for pair in spans.windows(2) {
        let (a, b) = (&pair[0], &pair[1]);
        if a.0 == b.0 && b.1 < a.2 {
            return Err(err(
                b.3.clone(),
                format!(
                    "`{}` at {} overlaps `{}` ({}, {} … {})",
                    b.4,
                    b.1,
                    a.4,
                    a.3,
                    a.1,
                    a.2 - 1
                ),
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn machine() -> MachineShape {
        MachineShape {
            axes: 4,
            digital_inputs: 8,
            digital_outputs: 8,
            analog_inputs: 2,
            analog_outputs: 2,
            slaves: vec![],
        }
    }

    fn build(text: &str, axes: &[usize]) -> Result<UnitMap, CompileError> {
        let file: MapFile = toml::from_str(text).unwrap();
        compile(
            &file,
            &machine(),
            &Binding {
                axes: axes.to_vec(),
            },
        )
    }

    const BLOCK: &str = r#"
[map]
name = "t"
word_order = "cdab"
[[point]]
table = "holding_registers"
address = 1000
name = "status"
read = "machine.error"
values = { "0" = 2, "1" = 4 }
[[point]]
table = "coils"
address = 0
name = "out0"
read = "do.0"
write = "do.0"
[[block]]
table = "holding_registers"
base = 0
stride = 10
[[block.point]]
offset = 0
name = "position"
type = "f32"
read = "axis.act_pos"
[[block.point]]
offset = 2
name = "target"
type = "f32"
write = "memory"
[[block.point]]
offset = 4
name = "start"
write = "memory"
on_write = [{ when = "rising_bit0", command = "move_absolute", args = { position = "@target" } }]
"#;

    #[test]
    fn blocks_repeat_per_axis_and_actions_find_their_block_points() {
        let unit = build(BLOCK, &[0, 2]).unwrap();
        let names: Vec<(&str, u16)> = unit
            .points
            .iter()
            .map(|p| (p.name.as_str(), p.address))
            .collect();
        assert_eq!(
            names,
            [
                ("status", 1000),
                ("out0", 0),
                ("position@axis0", 0),
                ("target@axis0", 2),
                ("start@axis0", 4),
                ("position@axis2", 10),
                ("target@axis2", 12),
                ("start@axis2", 14),
            ]
        );
        let start = &unit.points[7];
        assert_eq!(start.actions[0].when, When::RisingBit(0));
        assert_eq!(
            start.actions[0].holes,
            [(
                "position".into(),
                Arg::Point {
                    index: 6,
                    negate: false
                }
            )]
        );
        assert_eq!(start.actions[0].template["axis"], 2);
        assert_eq!(unit.points[0].numbers, [(0.0, 2.0), (1.0, 4.0)]);
        assert_eq!(unit.points[3].order, WordOrder::Cdab);
        let holding = &unit.tables[&Table::HoldingRegisters];
        let addresses: Vec<u16> = holding.iter().map(|&i| unit.points[i].address).collect();
        assert_eq!(addresses, [0, 2, 4, 10, 12, 14, 1000]);
        // Memory: target and start of two axes (2 + 1 words each), status has a source.
        assert_eq!(unit.initial_memory.len(), 6);
    }

    #[test]
    fn what_cannot_work_is_refused_with_key_and_reason() {
        let cases = [
            // The stride is smaller than the block: axis 2's position runs into axis 0's start.
            (
                BLOCK.replace("stride = 10", "stride = 4"),
                "block[0].point[0]",
                "overlaps",
            ),
            (
                BLOCK.replace("\"axis.act_pos\"", "\"axis.act_position\""),
                "block[0].point[0].read",
                "not an axis field",
            ),
            (
                BLOCK.replace("\"do.0\"\nwrite", "\"do.9\"\nwrite"),
                "point[1].read",
                "digital output 9 does not exist",
            ),
            (
                BLOCK.replace("type = \"f32\"\nread", "type = \"f31\"\nread"),
                "",
                "",
            ),
            (
                BLOCK.replace("\"@target\"", "\"@nowhere\""),
                "block[0].point[2].on_write[0].args.position",
                "no point `nowhere`",
            ),
            (
                BLOCK.replace(
                    "command = \"move_absolute\"",
                    "command = \"move_absolutely\"",
                ),
                "block[0].point[2].on_write[0].command",
                "move_absolutely",
            ),
            (
                BLOCK.replace("rising_bit0", "rising_edge"),
                "block[0].point[2].on_write[0].when",
                "expected always",
            ),
            (
                BLOCK.replace(
                    "table = \"coils\"\naddress = 0\nname = \"out0\"",
                    "table = \"discrete_inputs\"\naddress = 0\nname = \"out0\"",
                ),
                "point[1].write",
                "cannot be written",
            ),
            (
                BLOCK.replace(
                    "offset = 2\nname = \"target\"\ntype = \"f32\"\nwrite",
                    "offset = 2\nname = \"target\"\ntype = \"f32\"\nread = \"axis.cmd_pos\"\nwrite",
                ),
                "block[0].point[1].write",
                "holds the value",
            ),
        ];
        for (text, key, reason) in cases {
            let Ok(file) = toml::from_str::<MapFile>(&text) else {
                // A bad type name is serde's to refuse (the loader reports its key).
                assert_eq!(key, "");
                continue;
            };
            let e = compile(&file, &machine(), &Binding { axes: vec![0, 2] }).unwrap_err();
            assert_eq!(e.key, key, "{e:?}");
            assert!(e.reason.contains(reason), "{e:?}");
        }
        let e = build(BLOCK, &[4]).unwrap_err();
        assert!(e.reason.contains("axis 4"), "{e:?}");
    }

    const CODES: &str = r#"
[map]
name = "codes"
[[point]]
table = "holding_registers"
address = 0
name = "err"
type = "u32"
read = { first = [
  { when = "latched.drive_alarm", value = "eERR_AXIS_DRIVE_FAULT" },
  { when = "fe_fault", value = 0x083e },
] }
"#;

    #[test]
    fn a_case_value_may_name_a_dialect_code() {
        let unit = build(CODES, &[0]).unwrap();
        let Read::Source(Source::Select { cases, .. }) = &unit.points[0].read else {
            panic!(
                "a `first` table is a select source: {:?}",
                unit.points[0].read
            );
        };
        let values: Vec<f64> = cases.iter().map(|(_, v)| *v).collect();
        assert_eq!(values, [f64::from(0x03f2), f64::from(0x083e)]);

        let e = build(&CODES.replace("_DRIVE_FAULT", "_DRIVE_FAUL"), &[0]).unwrap_err();
        assert_eq!(e.key, "point[0].read.first[0].value", "{e:?}");
        assert!(e.reason.contains("eERR_AXIS_DRIVE_FAUL"), "{e:?}");
    }

    /// The HIMC map names its codes; they are the numbers it had before it did (and
    /// eERR_AXIS_COMP_LIMIT 0x0802, added since).
    #[test]
    fn the_himc_map_names_the_codes_it_had_as_numbers() {
        let text = crate::map::SHIPPED
            .iter()
            .find(|(name, _)| *name == "himc")
            .map(|(_, text)| *text)
            .unwrap();
        let unit = build(text, &[0]).unwrap();
        let codes = |name: &str| -> Vec<f64> {
            let point = unit.points.iter().find(|p| p.name == name).unwrap();
            let Read::Source(Source::Select { cases, .. }) = &point.read else {
                panic!("{name} is a `first` table: {:?}", point.read);
            };
            cases.iter().map(|(_, v)| *v).collect()
        };
        let faults = [
            0x03f2, 0x083e, 0x0802, 0x042e, 0x07ee, 0x07ee, 0x07f8, 0x07f8, 0x07da, 0x07da, 0x07e4,
            0x07e4,
        ];
        let refusals = [0x001e, 0x0078, 0x0096, 0x0064, 0x012c, 0x012c, 0x000a];
        let last_err: Vec<f64> = faults
            .iter()
            .chain(&refusals)
            .map(|&v| f64::from(v))
            .collect();
        assert_eq!(codes("last_err@axis0"), last_err);
        let latest: Vec<f64> = faults.iter().map(|&v| f64::from(v)).collect();
        assert_eq!(codes("latest_error"), latest);
    }
}
