//! Object sections (`[6040]`, `[1018]` + `[1018sub0]` …, compact arrays with `[xxxxName]` and
//! `[xxxxValue]`) → [`Object`]s with their [`SubObject`]s (CiA 306 §4.6).

use std::cmp::Ordering;
use std::collections::BTreeMap;
use std::fmt;

use axes::od::{Access, DataType, EntryDef, Value};

use super::error::{EdsError, Reason};
use super::fields::Fields;
use super::ini::{Item, Section};
use super::value::{format_value, parse_integer, parse_value, zero, EdsValue, NODE_IDS};

/// CiA 306 `ObjectType` (CiA 301 Table 42 object codes). NULL (0) has no use in a file.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ObjectType {
    /// 0x2: one variable of type DOMAIN.
    Domain,
    /// 0x5: a data type definition (its value is the type's size).
    DefType,
    /// 0x6: a record type definition.
    DefStruct,
    /// 0x7: one variable (the default when `ObjectType` is absent).
    Var,
    /// 0x8: sub-indices of one type.
    Array,
    /// 0x9: sub-indices of different types.
    Record,
}

impl ObjectType {
    pub const fn code(self) -> u8 {
        match self {
            ObjectType::Domain => 0x2,
            ObjectType::DefType => 0x5,
            ObjectType::DefStruct => 0x6,
            ObjectType::Var => 0x7,
            ObjectType::Array => 0x8,
            ObjectType::Record => 0x9,
        }
    }

    pub const fn from_code(code: u32) -> Option<ObjectType> {
        Some(match code {
            0x2 => ObjectType::Domain,
            0x5 => ObjectType::DefType,
            0x6 => ObjectType::DefStruct,
            0x7 => ObjectType::Var,
            0x8 => ObjectType::Array,
            0x9 => ObjectType::Record,
            _ => return None,
        })
    }

    pub const fn name(self) -> &'static str {
        match self {
            ObjectType::Domain => "DOMAIN",
            ObjectType::DefType => "DEFTYPE",
            ObjectType::DefStruct => "DEFSTRUCT",
            ObjectType::Var => "VAR",
            ObjectType::Array => "ARRAY",
            ObjectType::Record => "RECORD",
        }
    }

    /// Whether the object has sub-index sections (or a compact sub-object list).
    pub const fn has_sub_indices(self) -> bool {
        matches!(
            self,
            ObjectType::Array | ObjectType::Record | ObjectType::DefStruct
        )
    }
}

impl fmt::Display for ObjectType {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Which object list of the file names an object.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ObjectList {
    Mandatory,
    Optional,
    Manufacturer,
}

impl ObjectList {
    pub const ALL: [ObjectList; 3] = [
        ObjectList::Mandatory,
        ObjectList::Optional,
        ObjectList::Manufacturer,
    ];

    /// The section name as CiA 306 spells it.
    pub const fn section(self) -> &'static str {
        match self {
            ObjectList::Mandatory => "MandatoryObjects",
            ObjectList::Optional => "OptionalObjects",
            ObjectList::Manufacturer => "ManufacturerObjects",
        }
    }
}

/// One object: a VAR/DOMAIN/DEFTYPE has one sub-object (sub-index 0), an ARRAY/RECORD/DEFSTRUCT
/// one per sub-index.
#[derive(Clone, Debug, PartialEq)]
pub struct Object {
    pub index: u16,
    pub name: String,
    pub object_type: ObjectType,
    /// The list that names it; `None` for a section no list names (see [`Eds::warnings`]).
    ///
    /// [`Eds::warnings`]: super::Eds::warnings
    pub list: Option<ObjectList>,
    pub sub_objects: BTreeMap<u8, SubObject>,
    /// The object's section name as the file spells it, for errors.
    pub section: String,
}

impl Object {
    pub fn sub(&self, subindex: u8) -> Option<&SubObject> {
        self.sub_objects.get(&subindex)
    }
}

/// One sub-index: everything a dictionary entry needs, with values still relative to the node id
/// where the file says `$NODEID`.
#[derive(Clone, Debug, PartialEq)]
pub struct SubObject {
    pub index: u16,
    pub subindex: u8,
    pub name: String,
    pub data_type: DataType,
    pub access: Access,
    pub pdo_mappable: bool,
    /// `DefaultValue` (the type's zero when absent or empty).
    pub default: EdsValue,
    /// `ParameterValue` of a DCF: the configured value, which replaces the default as the
    /// entry's initial value.
    pub parameter_value: Option<EdsValue>,
    pub low: Option<EdsValue>,
    pub high: Option<EdsValue>,
    /// `ObjFlags` (bit 0: refuse read on scan, bit 1: refuse write on download).
    pub obj_flags: u32,
    /// The section that defines it (`1018sub2`, or `1003` for a compact array), for errors.
    pub section: String,
}

impl SubObject {
    /// The value an entry starts with: `ParameterValue`, else `DefaultValue`.
    pub fn initial(&self) -> &EdsValue {
        self.parameter_value.as_ref().unwrap_or(&self.default)
    }

    /// The dictionary row for `node_id` (1–127; other ids resolve `$NODEID` values to the zero
    /// of their type rather than fail).
    pub fn entry_def(&self, node_id: u8) -> EntryDef {
        let resolve = |v: &EdsValue| v.resolve(node_id).unwrap_or_else(|| zero(self.data_type));
        EntryDef {
            index: self.index,
            subindex: self.subindex,
            name: self.name.clone().into(),
            data_type: self.data_type,
            access: self.access,
            pdo_mappable: self.pdo_mappable,
            default: resolve(self.initial()),
            low: self.low.as_ref().map(resolve),
            high: self.high.as_ref().map(resolve),
        }
    }
}

/// CiA 301 data type codes mcemu does not store, for a clearer error than "unknown".
fn unsupported_type_name(code: u32) -> Option<&'static str> {
    Some(match code {
        0x000B => "UNICODE_STRING",
        0x000C => "TIME_OF_DAY",
        0x000D => "TIME_DIFFERENCE",
        0x0010 => "INTEGER24",
        0x0012 => "INTEGER40",
        0x0013 => "INTEGER48",
        0x0014 => "INTEGER56",
        0x0016 => "UNSIGNED24",
        0x0018 => "UNSIGNED40",
        0x0019 => "UNSIGNED48",
        0x001A => "UNSIGNED56",
        _ => return None,
    })
}

/// The sections of one object, gathered by the loader.
pub(crate) struct ObjectSections<'d, 'a> {
    pub index: u16,
    pub main: &'d Section<'a>,
    /// `[xxxxsubN]` sections, by sub-index.
    pub subs: BTreeMap<u8, &'d Section<'a>>,
    /// `[xxxxName]` of a compact array.
    pub names: Option<&'d Section<'a>>,
    /// `[xxxxValue]` of a compact array in a DCF.
    pub values: Option<&'d Section<'a>>,
}

impl ObjectSections<'_, '_> {
    pub fn read(&self, file: &str, list: Option<ObjectList>) -> Result<Object, EdsError> {
        let f = Fields::new(file, self.main);
        let name = f.required("ParameterName")?.value.to_string();
        let object_type = match f.item("ObjectType") {
            None => ObjectType::Var,
            Some(item) => {
                let code: u32 = f.parse_unsigned(item, "an object code")?;
                ObjectType::from_code(code)
                    .ok_or_else(|| f.error(item, Reason::UnknownObjectType { code }))?
            }
        };
        let mut sub_objects = BTreeMap::new();
        if !object_type.has_sub_indices() {
            if let Some(sub) = self.subs.values().next() {
                return Err(sub.place().error(
                    file,
                    Reason::SubOfVar {
                        index: self.index,
                        object_type: object_type.name(),
                    },
                ));
            }
            let fallback = (object_type == ObjectType::Domain).then_some(DataType::Domain);
            sub_objects.insert(0, read_sub_object(f, self.index, 0, fallback)?);
        } else if let Some(count) = compact_count(f)? {
            sub_objects = self.read_compact(f, &name, count)?;
        } else {
            if let Some(item) = f.item("SubNumber") {
                let declared: u32 = f.parse_unsigned(item, "0–256")?;
                if usize::try_from(declared).ok() != Some(self.subs.len()) {
                    return Err(f.error(
                        item,
                        Reason::SubNumberMismatch {
                            declared,
                            found: self.subs.len(),
                        },
                    ));
                }
            }
            for (&subindex, section) in &self.subs {
                let sub = read_sub_object(Fields::new(file, section), self.index, subindex, None)?;
                sub_objects.insert(subindex, sub);
            }
            let Some(sub0) = sub_objects.get(&0) else {
                return Err(f.section_error(Reason::NoSubIndexZero { index: self.index }));
            };
            if sub0.data_type != DataType::Unsigned8 {
                let section = self.subs.get(&0).copied().unwrap_or(self.main);
                let f0 = Fields::new(file, section);
                let reason = Reason::SubIndexZeroType {
                    data_type: sub0.data_type,
                };
                return Err(match f0.item("DataType") {
                    Some(item) => f0.error(item, reason),
                    None => f0.section_error(reason),
                });
            }
        }
        Ok(Object {
            index: self.index,
            name,
            object_type,
            list,
            sub_objects,
            section: self.main.name.to_string(),
        })
    }

    /// `CompactSubObj=n`: sub-index 0 (UNSIGNED8, ro, = n) and sub-indices 1–n with the object
    /// section's type, access, mapping, default and limits; names from `[xxxxName]`, DCF values
    /// from `[xxxxValue]` (CiA 306 §4.6.4).
    fn read_compact(
        &self,
        f: Fields<'_, '_>,
        name: &str,
        count: u8,
    ) -> Result<BTreeMap<u8, SubObject>, EdsError> {
        if let Some(sub) = self.subs.values().next() {
            return Err(f.error(
                f.required("CompactSubObj")?,
                Reason::CompactWithSubs {
                    section: sub.name.to_string(),
                },
            ));
        }
        let template = read_sub_object(f, self.index, 1, None)?;
        let mut subs = BTreeMap::new();
        subs.insert(
            0,
            SubObject {
                subindex: 0,
                name: "Highest sub-index supported".to_string(),
                data_type: DataType::Unsigned8,
                access: Access::Ro,
                pdo_mappable: false,
                default: EdsValue::Fixed(Value::U8(count)),
                parameter_value: None,
                low: None,
                high: None,
                ..template.clone()
            },
        );
        for subindex in 1..=count {
            subs.insert(
                subindex,
                SubObject {
                    subindex,
                    name: format!("{name} {subindex}"),
                    ..template.clone()
                },
            );
        }
        if let Some(names) = self.names {
            let names = Fields::new(f.file, names);
            for (subindex, item) in numbered_entries(names, count)? {
                if let Some(sub) = subs.get_mut(&subindex) {
                    sub.name = item.value.to_string();
                }
            }
        }
        if let Some(values) = self.values {
            let values = Fields::new(f.file, values);
            for (subindex, item) in numbered_entries(values, count)? {
                if let Some(sub) = subs.get_mut(&subindex) {
                    let value = parse_value(item.value, sub.data_type)
                        .map_err(|reason| values.error(item, reason))?;
                    check_limits(values, Some(item), item.key, sub, &value)?;
                    sub.parameter_value = Some(value);
                }
            }
        }
        Ok(subs)
    }
}

/// `CompactSubObj`: 0 or absent = sub-index sections; 1–254 (sub-index 255 is reserved).
fn compact_count(f: Fields<'_, '_>) -> Result<Option<u8>, EdsError> {
    let Some(item) = f.item("CompactSubObj") else {
        return Ok(None);
    };
    match f.parse_unsigned::<u8>(item, "0–254")? {
        0 => Ok(None),
        255 => Err(f.error(
            item,
            Reason::OutOfRangeFor {
                text: item.value.to_string(),
                range: "0–254",
            },
        )),
        n => Ok(Some(n)),
    }
}

/// `n=…` entries of a `[xxxxName]` / `[xxxxValue]` section: sub-indices 1 to the compact count;
/// `NrOfEntries`, where given, counts them.
fn numbered_entries<'d, 'a>(
    f: Fields<'d, 'a>,
    count: u8,
) -> Result<Vec<(u8, &'d Item<'a>)>, EdsError> {
    let mut entries = Vec::new();
    for item in &f.section.items {
        if item.key.eq_ignore_ascii_case("NrOfEntries") {
            continue;
        }
        let entry = parse_integer(item.key)
            .ok()
            .and_then(|l| u32::try_from(l.value).ok())
            .ok_or_else(|| {
                f.error(
                    item,
                    Reason::NotANumber {
                        text: item.key.to_string(),
                        why: "keys are entry numbers 1–254 or NrOfEntries",
                    },
                )
            })?;
        match u8::try_from(entry) {
            Ok(subindex) if (1..=count).contains(&subindex) => entries.push((subindex, item)),
            _ => {
                return Err(f.error(
                    item,
                    Reason::CompactEntryBeyond {
                        entry,
                        count: u32::from(count),
                    },
                ))
            }
        }
    }
    if let Some(item) = f.item("NrOfEntries") {
        let declared: u32 = f.parse_unsigned(item, "0–254")?;
        if usize::try_from(declared).ok() != Some(entries.len()) {
            return Err(f.error(
                item,
                Reason::EntryCountMismatch {
                    declared,
                    found: entries.len(),
                },
            ));
        }
    }
    Ok(entries)
}

/// The keys of one variable: the section of a VAR, of a sub-index, or of a compact array.
fn read_sub_object(
    f: Fields<'_, '_>,
    index: u16,
    subindex: u8,
    fallback_type: Option<DataType>,
) -> Result<SubObject, EdsError> {
    let name = f.required("ParameterName")?.value.to_string();
    let data_type = match (f.item("DataType"), fallback_type) {
        (Some(item), _) => {
            let code: u32 = f.parse_unsigned(item, "a data type code")?;
            let known = u16::try_from(code).ok().and_then(DataType::from_code);
            match (known, unsupported_type_name(code)) {
                (Some(data_type), _) => data_type,
                (None, Some(name)) => {
                    return Err(f.error(item, Reason::UnsupportedDataType { code, name }))
                }
                (None, None) => return Err(f.error(item, Reason::UnknownDataType { code })),
            }
        }
        (None, Some(data_type)) => data_type,
        (None, None) => return Err(f.missing("DataType")),
    };
    let access_item = f.required("AccessType")?;
    let access = Access::from_eds(access_item.value).ok_or_else(|| {
        f.error(
            access_item,
            Reason::UnknownAccessType {
                text: access_item.value.to_string(),
            },
        )
    })?;
    let value_of = |key: &str| -> Result<Option<EdsValue>, EdsError> {
        match f.item(key) {
            None => Ok(None),
            Some(item) => parse_value(item.value, data_type)
                .map(Some)
                .map_err(|reason| f.error(item, reason)),
        }
    };
    let limit_of = |key: &str| -> Result<Option<EdsValue>, EdsError> {
        match f.item(key) {
            Some(item) if !item.value.is_empty() => {
                if !is_numeric(data_type) {
                    return Err(f.error(item, Reason::LimitsNotNumeric { data_type }));
                }
                value_of(key)
            }
            _ => Ok(None),
        }
    };
    let mut sub = SubObject {
        index,
        subindex,
        name,
        data_type,
        access,
        pdo_mappable: f.flag("PDOMapping")?.unwrap_or(false),
        default: value_of("DefaultValue")?.unwrap_or(EdsValue::Fixed(zero(data_type))),
        parameter_value: None,
        low: limit_of("LowLimit")?,
        high: limit_of("HighLimit")?,
        obj_flags: f.unsigned("ObjFlags", "UNSIGNED32")?.unwrap_or(0),
        section: f.section.name.to_string(),
    };
    if let (Some(low), Some(high)) = (&sub.low, &sub.high) {
        for node_id in [*NODE_IDS.start(), *NODE_IDS.end()] {
            let (l, h) = (low.resolve(node_id), high.resolve(node_id));
            if let (Some(l), Some(h)) = (l, h) {
                if l.compare(&h) == Some(Ordering::Greater) {
                    let item = f.item("HighLimit").unwrap_or(access_item);
                    return Err(f.error(
                        item,
                        Reason::LimitsCrossed {
                            low: format_value(&l),
                            high: format_value(&h),
                        },
                    ));
                }
            }
        }
    }
    // An absent DefaultValue is the type's zero, which must lie within the limits too.
    check_limits(
        f,
        f.item("DefaultValue"),
        "DefaultValue",
        &sub,
        &sub.default,
    )?;
    if let Some(item) = f.item("ParameterValue") {
        let value = parse_value(item.value, data_type).map_err(|reason| f.error(item, reason))?;
        check_limits(f, Some(item), "ParameterValue", &sub, &value)?;
        sub.parameter_value = Some(value);
    }
    Ok(sub)
}

fn is_numeric(data_type: DataType) -> bool {
    !matches!(
        data_type,
        DataType::Boolean | DataType::VisibleString | DataType::OctetString | DataType::Domain
    )
}

/// A value must lie within the limits for every node id (checked at the extremes: values and
/// limits move with the node id by a constant). The error names `item`, or `key` of the section
/// when the value was not written.
fn check_limits(
    f: Fields<'_, '_>,
    item: Option<&Item<'_>>,
    key: &str,
    sub: &SubObject,
    value: &EdsValue,
) -> Result<(), EdsError> {
    let error = |reason| match item {
        Some(item) => f.error(item, reason),
        None => {
            let mut e = f.section_error(reason);
            e.key = Some(key.into());
            e
        }
    };
    for node_id in [*NODE_IDS.start(), *NODE_IDS.end()] {
        let Some(v) = value.resolve(node_id) else {
            continue;
        };
        let shown = if value.depends_on_node_id() {
            format!("{value} = {} for node id {node_id},", format_value(&v))
        } else {
            format_value(&v)
        };
        let limit = |l: &Option<EdsValue>| l.as_ref().and_then(|l| l.resolve(node_id));
        // A NaN is outside every limit, as the dictionary treats it.
        if let Some(low) = limit(&sub.low) {
            if v.compare(&low).is_none_or(|o| o == Ordering::Less) {
                return Err(error(Reason::BelowLowLimit {
                    value: shown,
                    low: format_value(&low),
                }));
            }
        }
        if let Some(high) = limit(&sub.high) {
            if v.compare(&high).is_none_or(|o| o == Ordering::Greater) {
                return Err(error(Reason::AboveHighLimit {
                    value: shown,
                    high: format_value(&high),
                }));
            }
        }
    }
    Ok(())
}
