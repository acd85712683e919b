//! One pass over a parsed file: sections sorted into descriptive ones, object lists and object
//! sections; objects read; the whole checked (CiA 306 §4).

use std::collections::BTreeMap;

use super::error::{EdsError, Place, Reason};
use super::fields::Fields;
use super::info::{read_comments, Commissioning, DeviceInfo, DummyUsage, FileInfo};
use super::ini::{Document, Section};
use super::objects::{Object, ObjectList, ObjectSections};
use super::pdo;
use super::Eds;

/// CiA 301 §7.5.1: every device has these.
const MANDATORY: [u16; 3] = [0x1000, 0x1001, 0x1018];

/// What an object-related section name says.
enum Kind {
    Object(u16),
    Sub(u16, u8),
    Names(u16),
    Values(u16),
    /// `[xxxxDenotation]` of a DCF: names for a tool, nothing a device uses.
    Denotations,
    /// Not about an object (or a section this loader does not use, such as modules).
    Other,
}

fn classify(name: &str) -> Result<Kind, Reason> {
    let Some(head) = name.get(..4) else {
        return Ok(Kind::Other);
    };
    let Ok(index) = u16::from_str_radix(head, 16) else {
        return Ok(Kind::Other);
    };
    if !head.bytes().all(|b| b.is_ascii_hexdigit()) {
        return Ok(Kind::Other);
    }
    let rest = name.get(4..).unwrap_or_default();
    let lower = rest.to_ascii_lowercase();
    if index == 0 && (rest.is_empty() || lower.starts_with("sub")) {
        return Err(Reason::IndexZero);
    }
    Ok(match lower.as_str() {
        "" => Kind::Object(index),
        "name" => Kind::Names(index),
        "value" => Kind::Values(index),
        "denotation" => Kind::Denotations,
        _ => match lower.strip_prefix("sub") {
            Some(digits) if (1..=2).contains(&digits.len()) => {
                let sub =
                    u8::from_str_radix(digits, 16).map_err(|_| Reason::BadObjectSectionName)?;
                if !digits.bytes().all(|b| b.is_ascii_hexdigit()) {
                    return Err(Reason::BadObjectSectionName);
                }
                Kind::Sub(index, sub)
            }
            Some(_) => return Err(Reason::BadObjectSectionName),
            None => Kind::Other,
        },
    })
}

pub(crate) fn load(file: &str, text: &str) -> Result<Eds, EdsError> {
    let doc = Document::parse(file, text)?;
    let mut warnings = Vec::new();
    let warn_missing = |name: &str, warnings: &mut Vec<EdsError>| {
        warnings.push(
            Place {
                section: Some(name),
                ..Place::default()
            }
            .error(file, Reason::MissingSection),
        );
    };

    let file_info = match doc.section("fileinfo") {
        Some(s) => FileInfo::read(Fields::new(file, s)),
        None => {
            warn_missing("FileInfo", &mut warnings);
            FileInfo::default()
        }
    };
    let device_info = match doc.section("deviceinfo") {
        Some(s) => DeviceInfo::read(Fields::new(file, s))?,
        None => {
            warn_missing("DeviceInfo", &mut warnings);
            DeviceInfo::default()
        }
    };
    let dummy_usage = match doc.section("dummyusage") {
        Some(s) => DummyUsage::read(Fields::new(file, s))?,
        None => DummyUsage::default(),
    };
    let commissioning = doc
        .section("devicecomissioning")
        .or_else(|| doc.section("devicecommissioning"))
        .map(|s| Commissioning::read(Fields::new(file, s)))
        .transpose()?;
    let comments = doc
        .section("comments")
        .map(read_comments)
        .unwrap_or_default();

    let listed = read_object_lists(&doc, file, &mut warnings)?;
    let objects = gather_object_sections(&doc, file)?;

    for (&index, (_, place)) in &listed {
        if !objects.contains_key(&index) {
            return Err(place.error(file, Reason::ListedObjectMissing { index }));
        }
    }
    let mut model = BTreeMap::new();
    for (&index, sections) in &objects {
        let list = listed.get(&index).map(|(list, _)| *list);
        if list.is_none() && !listed.is_empty() {
            warnings.push(sections.main.place().error(file, Reason::Unlisted));
        }
        model.insert(index, sections.read(file, list)?);
    }
    for index in MANDATORY {
        if !model.contains_key(&index) {
            return Err(Place {
                section: Some(ObjectList::Mandatory.section()),
                ..Place::default()
            }
            .error(file, Reason::MandatoryObjectMissing { index }));
        }
    }

    let mut eds = Eds {
        file_name: file.to_string(),
        file_info,
        device_info,
        dummy_usage,
        commissioning,
        comments,
        objects: model,
        warnings,
    };
    pdo::check(&eds)?;
    eds.warnings.extend(pdo_count_warnings(&eds, &doc));
    Ok(eds)
}

/// [MandatoryObjects], [OptionalObjects], [ManufacturerObjects]: index → list and the place of
/// its entry.
fn read_object_lists<'d>(
    doc: &'d Document<'_>,
    file: &str,
    warnings: &mut Vec<EdsError>,
) -> Result<BTreeMap<u16, (ObjectList, Place<'d>)>, EdsError> {
    let mut listed = BTreeMap::new();
    for list in ObjectList::ALL {
        let Some(section) = doc.section(&list.section().to_ascii_lowercase()) else {
            continue;
        };
        let f = Fields::new(file, section);
        let count_item = f.required("SupportedObjects")?;
        let count: u16 = f.parse_unsigned(count_item, "0–65535")?;
        for n in 1..=count {
            let item = f.required(&n.to_string())?;
            let index: u16 = f.parse_unsigned(item, "an object index 0x0001–0xFFFF")?;
            if index == 0 {
                return Err(f.error(item, Reason::IndexZero));
            }
            if listed.contains_key(&index) {
                return Err(f.error(item, Reason::ListedTwice { index }));
            }
            listed.insert(index, (list, item.place(section)));
        }
        let extra = section.items.iter().find(|item| {
            item.key
                .parse::<u32>()
                .is_ok_and(|n| n == 0 || n > u32::from(count))
        });
        if let Some(item) = extra {
            warnings.push(f.error(item, Reason::ListEntryBeyond { count }));
        }
    }
    Ok(listed)
}

/// The sections of each object: its own, its sub-indices, and a compact array's names and values.
fn gather_object_sections<'d, 'a>(
    doc: &'d Document<'a>,
    file: &str,
) -> Result<BTreeMap<u16, ObjectSections<'d, 'a>>, EdsError> {
    let mut objects: BTreeMap<u16, ObjectSections<'_, '_>> = BTreeMap::new();
    let mut subs: Vec<(u16, u8, &Section<'_>)> = Vec::new();
    let mut names: Vec<(u16, &Section<'_>)> = Vec::new();
    let mut values: Vec<(u16, &Section<'_>)> = Vec::new();
    for section in &doc.sections {
        match classify(section.name).map_err(|reason| section.place().error(file, reason))? {
            Kind::Object(index) => {
                objects.insert(
                    index,
                    ObjectSections {
                        index,
                        main: section,
                        subs: BTreeMap::new(),
                        names: None,
                        values: None,
                    },
                );
            }
            Kind::Sub(index, sub) => subs.push((index, sub, section)),
            Kind::Names(index) => names.push((index, section)),
            Kind::Values(index) => values.push((index, section)),
            Kind::Denotations | Kind::Other => {}
        }
    }
    for (index, sub, section) in subs {
        let Some(object) = objects.get_mut(&index) else {
            return Err(section
                .place()
                .error(file, Reason::SubWithoutObject { index }));
        };
        // Two spellings of one sub-index (`sub1`, `sub01`) are one section defined twice.
        if let Some(first) = object.subs.insert(sub, section) {
            return Err(section.place().error(
                file,
                Reason::DuplicateSection {
                    first_line: first.line,
                },
            ));
        }
    }
    for (index, section) in names {
        if let Some(object) = objects.get_mut(&index) {
            object.names = Some(section);
        }
    }
    for (index, section) in values {
        if let Some(object) = objects.get_mut(&index) {
            object.values = Some(section);
        }
    }

    Ok(objects)
}

/// `NrOfRXPDO` / `NrOfTXPDO` against the PDO objects present.
fn pdo_count_warnings(eds: &Eds, doc: &Document<'_>) -> Vec<EdsError> {
    let Some(section) = doc.section("deviceinfo") else {
        return Vec::new();
    };
    let f = Fields::new(&eds.file_name, section);
    let count = |range: std::ops::RangeInclusive<u16>| {
        eds.objects
            .range(range)
            .filter(|(_, o): &(&u16, &Object)| o.sub(1).is_some())
            .count()
    };
    let mut warnings = Vec::new();
    for (key, declared, found) in [
        (
            "NrOfRXPDO",
            eds.device_info.nr_of_rx_pdo,
            count(0x1400..=0x15FF),
        ),
        (
            "NrOfTXPDO",
            eds.device_info.nr_of_tx_pdo,
            count(0x1800..=0x19FF),
        ),
    ] {
        if usize::from(declared) != found {
            let reason = Reason::PdoCount { declared, found };
            warnings.push(match f.item(key) {
                Some(item) => f.error(item, reason),
                None => f.section_error(reason),
            });
        }
    }
    warnings
}
