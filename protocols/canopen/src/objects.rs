//! The CiA 301 communication objects the node serves (CiA 301 §7.5.2) and the table that adds
//! those a device's own table lacks.

use std::time::Duration;

use axes::od::{Access, EntryDef, ObjectDictionary, Value, MAX_VARIABLE_LEN};

/// Object indices of the communication profile area.
pub mod idx {
    pub const DEVICE_TYPE: u16 = 0x1000;
    pub const ERROR_REGISTER: u16 = 0x1001;
    pub const ERROR_HISTORY: u16 = 0x1003;
    pub const COB_ID_SYNC: u16 = 0x1005;
    pub const SYNC_PERIOD: u16 = 0x1006;
    pub const DEVICE_NAME: u16 = 0x1008;
    pub const GUARD_TIME: u16 = 0x100C;
    pub const LIFE_TIME_FACTOR: u16 = 0x100D;
    pub const STORE: u16 = 0x1010;
    pub const RESTORE: u16 = 0x1011;
    pub const COB_ID_EMCY: u16 = 0x1014;
    pub const EMCY_INHIBIT: u16 = 0x1015;
    pub const CONSUMER_HEARTBEAT: u16 = 0x1016;
    pub const PRODUCER_HEARTBEAT: u16 = 0x1017;
    pub const IDENTITY: u16 = 0x1018;
    pub const SYNC_OVERFLOW: u16 = 0x1019;
    pub const ERROR_BEHAVIOUR: u16 = 0x1029;
    pub const SDO_SERVER: u16 = 0x1200;
    pub const RPDO_COMM: u16 = 0x1400;
    pub const RPDO_MAP: u16 = 0x1600;
    pub const TPDO_COMM: u16 = 0x1800;
    pub const TPDO_MAP: u16 = 0x1A00;
    /// Number of PDOs of each kind CiA 301 allows (0x1400–0x15FF …).
    pub const PDO_RANGE: u16 = 0x200;
}

/// Identity object 0x1018 (and the LSS address, CiA 305).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Identity {
    pub vendor_id: u32,
    pub product_code: u32,
    pub revision: u32,
    pub serial: u32,
}

/// What the node does to its NMT state on a communication error (heartbeat consumer timeout,
/// life guarding): CiA 301 §7.5.2.32, object 0x1029:01, whose value this is.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ErrorBehaviour {
    /// 0: Operational → Pre-operational (CiA 301 default).
    #[default]
    PreOperational,
    /// 1: no change.
    NoChange,
    /// 2: → Stopped.
    Stopped,
}

impl ErrorBehaviour {
    pub const fn code(self) -> u8 {
        match self {
            ErrorBehaviour::PreOperational => 0,
            ErrorBehaviour::NoChange => 1,
            ErrorBehaviour::Stopped => 2,
        }
    }

    pub const fn from_code(code: u8) -> Option<ErrorBehaviour> {
        match code {
            0 => Some(ErrorBehaviour::PreOperational),
            1 => Some(ErrorBehaviour::NoChange),
            2 => Some(ErrorBehaviour::Stopped),
            _ => None,
        }
    }
}

/// Configuration of a node. Values that live in the dictionary (heartbeat times, PDO
/// parameters …) are the defaults of the objects the node adds; a device table that defines
/// the object itself wins.
#[derive(Clone, Debug, PartialEq)]
pub struct NodeConfig {
    /// 1–127, or 0xFF for an unconfigured node that waits for LSS (CiA 305).
    pub node_id: u8,
    /// 0x1000 device type.
    pub device_type: u32,
    /// 0x1008, when the device lacks one.
    pub device_name: String,
    /// 0x1018.
    pub identity: Identity,
    /// RPDOs and TPDOs the node adds (0x1400…/0x1600…, 0x1800…/0x1A00…).
    pub rpdos: u16,
    pub tpdos: u16,
    /// Mapping entries per PDO (sub-indices 1..=n of 0x1600…, 0x1A00…).
    pub mapping_entries: u8,
    /// Entries of 0x1016.
    pub heartbeat_consumers: u8,
    /// Entries of 0x1003.
    pub error_history: u8,
    /// 0x1017 default, ms.
    pub heartbeat_ms: u16,
    /// 0x1029:01 default.
    pub error_behaviour: ErrorBehaviour,
    /// An SDO transfer with no frame from the client for this long is aborted (0x05040000).
    pub sdo_timeout: Duration,
    /// Block size the server offers in block download (1–127).
    pub sdo_block_size: u8,
    /// Largest value an SDO download may carry (0x05040005 beyond).
    pub sdo_max_len: usize,
    /// Whether PDO parameters (0x1400–0x1BFF) may be written in Operational. CiA 301 allows it;
    /// some devices refuse with 0x08000022.
    pub pdo_config_in_operational: bool,
    /// LSS bit timing table index (CiA 305 Table 1; 0 = 1 Mbit/s).
    pub bit_timing: u8,
    /// EMCY frames held while the inhibit time runs; older ones are dropped beyond this.
    pub emcy_queue: usize,
}

impl Default for NodeConfig {
    fn default() -> Self {
        NodeConfig {
            node_id: 1,
            device_type: 0,
            device_name: "mcemu CANopen node".to_string(),
            identity: Identity::default(),
            rpdos: 4,
            tpdos: 4,
            mapping_entries: 8,
            heartbeat_consumers: 4,
            error_history: 8,
            heartbeat_ms: 0,
            error_behaviour: ErrorBehaviour::PreOperational,
            sdo_timeout: Duration::from_secs(1),
            sdo_block_size: 127,
            sdo_max_len: MAX_VARIABLE_LEN,
            pdo_config_in_operational: true,
            bit_timing: 0,
            emcy_queue: 16,
        }
    }
}

/// Whether `id` is a node id a configured node may have.
pub const fn valid_node_id(id: u8) -> bool {
    matches!(id, 1..=127)
}

/// Node id of an unconfigured LSS slave.
pub const UNCONFIGURED: u8 = 0xFF;

/// The communication objects of `config`, with node-id-dependent COB-IDs for `node_id`
/// (pre-defined connection set, CiA 301 §7.3.5).
pub fn communication_objects(config: &NodeConfig, node_id: u8) -> Vec<EntryDef> {
    use idx::*;
    use Access::{Const, Ro, Rw};
    use Value::{String as S, U16, U32, U8};
    let id = u32::from(node_id & 0x7F);
    let e = EntryDef::new;
    let mut t = vec![
        e(
            DEVICE_TYPE,
            0,
            "Device type",
            Const,
            U32(config.device_type),
        ),
        e(ERROR_REGISTER, 0, "Error register", Ro, U8(0)).pdo(),
        e(ERROR_HISTORY, 0, "Number of errors", Rw, U8(0)),
    ];
    for n in 1..=config.error_history {
        t.push(e(ERROR_HISTORY, n, "Standard error field", Ro, U32(0)));
    }
    t.extend([
        e(COB_ID_SYNC, 0, "COB-ID SYNC", Rw, U32(0x80)),
        e(SYNC_PERIOD, 0, "Communication cycle period", Rw, U32(0)),
        e(
            DEVICE_NAME,
            0,
            "Manufacturer device name",
            Const,
            S(config.device_name.clone()),
        ),
        e(GUARD_TIME, 0, "Guard time", Rw, U16(0)),
        e(LIFE_TIME_FACTOR, 0, "Life time factor", Rw, U8(0)),
        e(STORE, 0, "Highest sub-index supported", Const, U8(3)),
        e(STORE, 1, "Save all parameters", Rw, U32(1)),
        e(STORE, 2, "Save communication parameters", Rw, U32(1)),
        e(STORE, 3, "Save application parameters", Rw, U32(1)),
        e(RESTORE, 0, "Highest sub-index supported", Const, U8(3)),
        e(RESTORE, 1, "Restore all default parameters", Rw, U32(1)),
        e(
            RESTORE,
            2,
            "Restore communication default parameters",
            Rw,
            U32(1),
        ),
        e(
            RESTORE,
            3,
            "Restore application default parameters",
            Rw,
            U32(1),
        ),
        e(COB_ID_EMCY, 0, "COB-ID EMCY", Rw, U32(0x80 + id)),
        e(EMCY_INHIBIT, 0, "Inhibit time EMCY", Rw, U16(0)),
        e(
            CONSUMER_HEARTBEAT,
            0,
            "Highest sub-index supported",
            Const,
            U8(config.heartbeat_consumers),
        ),
    ]);
    for n in 1..=config.heartbeat_consumers {
        t.push(e(
            CONSUMER_HEARTBEAT,
            n,
            "Consumer heartbeat time",
            Rw,
            U32(0),
        ));
    }
    let ident = config.identity;
    t.extend([
        e(
            PRODUCER_HEARTBEAT,
            0,
            "Producer heartbeat time",
            Rw,
            U16(config.heartbeat_ms),
        ),
        e(IDENTITY, 0, "Highest sub-index supported", Const, U8(4)),
        e(IDENTITY, 1, "Vendor-ID", Ro, U32(ident.vendor_id)),
        e(IDENTITY, 2, "Product code", Ro, U32(ident.product_code)),
        e(IDENTITY, 3, "Revision number", Ro, U32(ident.revision)),
        e(IDENTITY, 4, "Serial number", Ro, U32(ident.serial)),
        e(
            SYNC_OVERFLOW,
            0,
            "Synchronous counter overflow value",
            Rw,
            U8(0),
        ),
        e(
            ERROR_BEHAVIOUR,
            0,
            "Highest sub-index supported",
            Const,
            U8(1),
        ),
        e(
            ERROR_BEHAVIOUR,
            1,
            "Communication error",
            Rw,
            U8(config.error_behaviour.code()),
        ),
        e(SDO_SERVER, 0, "Highest sub-index supported", Const, U8(2)),
        e(
            SDO_SERVER,
            1,
            "COB-ID client to server",
            Ro,
            U32(0x600 + id),
        ),
        e(
            SDO_SERVER,
            2,
            "COB-ID server to client",
            Ro,
            U32(0x580 + id),
        ),
    ]);
    for n in 0..config.rpdos.min(idx::PDO_RANGE) {
        let cob = predefined_pdo_cob(0x200, n, id);
        t.extend([
            e(
                RPDO_COMM + n,
                0,
                "Highest sub-index supported",
                Const,
                U8(5),
            ),
            e(RPDO_COMM + n, 1, "COB-ID used by RPDO", Rw, U32(cob)),
            e(RPDO_COMM + n, 2, "Transmission type", Rw, U8(254)),
            e(RPDO_COMM + n, 5, "Event-timer", Rw, U16(0)),
            e(RPDO_MAP + n, 0, "Number of mapped objects", Rw, U8(0)),
        ]);
        for s in 1..=config.mapping_entries {
            t.push(e(RPDO_MAP + n, s, "Mapped object", Rw, U32(0)));
        }
    }
    for n in 0..config.tpdos.min(idx::PDO_RANGE) {
        let cob = predefined_pdo_cob(0x180, n, id);
        t.extend([
            e(
                TPDO_COMM + n,
                0,
                "Highest sub-index supported",
                Const,
                U8(6),
            ),
            e(TPDO_COMM + n, 1, "COB-ID used by TPDO", Rw, U32(cob)),
            e(TPDO_COMM + n, 2, "Transmission type", Rw, U8(254)),
            e(TPDO_COMM + n, 3, "Inhibit time", Rw, U16(0)),
            e(TPDO_COMM + n, 5, "Event timer", Rw, U16(0)),
            e(TPDO_COMM + n, 6, "SYNC start value", Rw, U8(0)),
            e(TPDO_MAP + n, 0, "Number of mapped objects", Rw, U8(0)),
        ]);
        for s in 1..=config.mapping_entries {
            t.push(e(TPDO_MAP + n, s, "Mapped object", Rw, U32(0)));
        }
    }
    t
}

/// COB-ID of PDO `n` (0-based): the pre-defined connection set for the first four, valid;
/// an invalid (bit 31) placeholder beyond.
fn predefined_pdo_cob(base: u32, n: u16, id: u32) -> u32 {
    if n < 4 {
        base + 0x100 * u32::from(n) + id
    } else {
        0x8000_0000 | (base + 0x100 * 3 + id)
    }
}

/// Add every object of `defs` whose index the dictionary lacks entirely. An object the device
/// defines (even with fewer sub-indices) is kept as the device defines it.
pub(crate) fn add_missing(od: &mut ObjectDictionary, defs: Vec<EntryDef>) {
    let present: std::collections::BTreeSet<u16> = defs
        .iter()
        .map(|d| d.index)
        .filter(|&i| od.contains_object(i))
        .collect();
    for def in defs {
        if !present.contains(&def.index) {
            let _ = od.insert(def);
        }
    }
}

/// Pre-defined connection set bases of the node-id-dependent COB-IDs: (index, sub-index,
/// function code base). COB-IDs in base..=base+0x7F follow the node id at reset communication.
pub(crate) const NODE_ID_COBS: [(u16, u8, u32); 11] = [
    (idx::COB_ID_EMCY, 0, 0x80),
    (idx::SDO_SERVER, 1, 0x600),
    (idx::SDO_SERVER, 2, 0x580),
    (idx::RPDO_COMM, 1, 0x200),
    (idx::RPDO_COMM + 1, 1, 0x300),
    (idx::RPDO_COMM + 2, 1, 0x400),
    (idx::RPDO_COMM + 3, 1, 0x500),
    (idx::TPDO_COMM, 1, 0x180),
    (idx::TPDO_COMM + 1, 1, 0x280),
    (idx::TPDO_COMM + 2, 1, 0x380),
    (idx::TPDO_COMM + 3, 1, 0x480),
];

/// CAN identifiers CiA 301 §7.3.5 (Table 39 "restricted CAN-IDs") forbids for PDO, SYNC and
/// EMCY COB-IDs.
pub const fn restricted_can_id(id: u16) -> bool {
    matches!(
        id,
        0x000..=0x07F | 0x101..=0x180 | 0x581..=0x5FF | 0x601..=0x67F | 0x6E0..=0x6FF | 0x701..=0x7FF
    )
}
