// Tests fail loudly.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

//! The CiA 301 objects of the shipped EDS files are the ones the node implements
//! (`communication_objects`): every communication-area object of a file is either the node's or
//! the device's (0x1009, 0x100A), and where both define a sub-index, data type and access agree —
//! so a master reading the EDS is told what the node answers.

use axes::cia402::{object_table, DriveConfig};
use mcemu_canopen::eds::Eds;
use mcemu_canopen::{communication_objects, NodeConfig};

fn check(file: &str) {
    let path = format!(
        "{}/../../fixtures/canopen/{file}",
        env!("CARGO_MANIFEST_DIR")
    );
    let eds = Eds::load(path).unwrap();
    let node = communication_objects(&NodeConfig::default(), 1);
    let device = object_table(&DriveConfig::default());
    let mut problems = Vec::new();
    for sub in eds.sub_objects().filter(|s| s.index < 0x2000) {
        let (index, subindex) = (sub.index, sub.subindex);
        let node_object = node.iter().any(|d| d.index == index);
        let device_object = device.iter().any(|d| d.index == index);
        if !node_object && !device_object {
            problems.push(format!(
                "{index:#06x} is neither the node's nor the device's"
            ));
            continue;
        }
        let Some(def) = node
            .iter()
            .find(|d| d.index == index && d.subindex == subindex)
        else {
            continue;
        };
        if (def.data_type, def.access) != (sub.data_type, sub.access) {
            problems.push(format!(
                "{index:#06x}:{subindex}: node {} {}, {file} {} {}",
                def.data_type,
                def.access.eds_name(),
                sub.data_type,
                sub.access.eds_name()
            ));
        }
    }
    assert!(problems.is_empty(), "{file}:\n{}", problems.join("\n"));
}

#[test]
fn the_drive_eds_describes_the_nodes_communication_objects() {
    check("cia402-drive.eds");
}

#[test]
fn the_e10_eds_describes_the_nodes_communication_objects() {
    check("ct-e10.eds");
}
