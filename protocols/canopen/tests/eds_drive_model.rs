// Tests fail loudly.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

//! `fixtures/canopen/cia402-drive.eds` describes the drive that `axes::cia402` implements: every
//! object of the drive model's table is in the EDS with the same data type, access, PDO
//! mappability, default and limits, and every manufacturer (0x2000–0x5FFF) and device-profile
//! (0x6000–0x9FFF) object of the EDS is in the drive model. Change one, and this test says what
//! to change in the other.

use axes::cia402::{object_table, DriveConfig};
use axes::od::EntryDef;
use mcemu_canopen::eds::Eds;

const EDS: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../fixtures/canopen/cia402-drive.eds"
);

fn eds_entries() -> Vec<EntryDef> {
    Eds::load(EDS).unwrap().entry_defs(1).unwrap()
}

#[test]
fn every_drive_model_object_is_in_the_eds_unchanged() {
    let eds = eds_entries();
    let mut problems = Vec::new();
    for model in object_table(&DriveConfig::default()) {
        let (index, sub) = (model.index, model.subindex);
        let Some(file) = eds.iter().find(|e| e.index == index && e.subindex == sub) else {
            problems.push(format!("{index:#06x}:{sub} {:?} is missing", model.name));
            continue;
        };
        let mut differs = |what: &str, model: String, file: String| {
            if model != file {
                problems.push(format!(
                    "{index:#06x}:{sub} {what}: drive model {model}, EDS {file}"
                ));
            }
        };
        differs(
            "data type",
            model.data_type.to_string(),
            file.data_type.to_string(),
        );
        differs(
            "access",
            model.access.eds_name().into(),
            file.access.eds_name().into(),
        );
        differs(
            "PDO mapping",
            model.pdo_mappable.to_string(),
            file.pdo_mappable.to_string(),
        );
        // 0x100A carries the crate version (DriveConfig's default): the EDS cannot follow it.
        if index != 0x100A {
            differs(
                "default",
                format!("{:?}", model.default),
                format!("{:?}", file.default),
            );
        }
        differs(
            "low limit",
            format!("{:?}", model.low),
            format!("{:?}", file.low),
        );
        differs(
            "high limit",
            format!("{:?}", model.high),
            format!("{:?}", file.high),
        );
    }
    assert!(
        problems.is_empty(),
        "the EDS and the drive model disagree:\n{}",
        problems.join("\n")
    );
}

#[test]
fn every_manufacturer_and_device_profile_object_of_the_eds_is_in_the_drive_model() {
    let model = object_table(&DriveConfig::default());
    let extra: Vec<String> = eds_entries()
        .iter()
        .filter(|e| (0x2000..=0x9FFF).contains(&e.index))
        .filter(|e| {
            !model
                .iter()
                .any(|m| m.index == e.index && m.subindex == e.subindex)
        })
        .map(|e| format!("{:#06x}:{} {:?}", e.index, e.subindex, e.name))
        .collect();
    assert!(
        extra.is_empty(),
        "in the EDS but not in the drive model (axes/src/cia402/objects.rs):\n{}",
        extra.join("\n")
    );
}

#[test]
fn the_eds_identity_is_the_default_drive_config() {
    let config = DriveConfig::default();
    let eds = Eds::load(EDS).unwrap();
    let info = &eds.device_info;
    assert_eq!(info.vendor_number, Some(config.vendor_id));
    assert_eq!(info.product_number, Some(config.product_code));
    assert_eq!(info.revision_number, Some(config.revision));
    assert_eq!(info.product_name.as_deref(), Some(config.name.as_str()));
}
