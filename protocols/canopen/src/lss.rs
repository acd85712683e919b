//! LSS slave (CiA 305): switch state global/selective, configure node id and bit timing,
//! activate bit timing, store configuration, inquire identity and node id, identify remote and
//! non-configured slaves, fastscan. Requests on 0x7E5, responses on 0x7E4.

use crate::objects::{valid_node_id, UNCONFIGURED};

pub const LSS_RX_ID: u16 = 0x7E5;
pub const LSS_TX_ID: u16 = 0x7E4;

/// Command specifiers (CiA 305 §6).
mod cs {
    pub const SWITCH_GLOBAL: u8 = 0x04;
    pub const CONFIGURE_NODE_ID: u8 = 0x11;
    pub const CONFIGURE_BIT_TIMING: u8 = 0x13;
    pub const ACTIVATE_BIT_TIMING: u8 = 0x15;
    pub const STORE: u8 = 0x17;
    pub const SELECT_VENDOR: u8 = 0x40;
    pub const SELECT_SERIAL: u8 = 0x43;
    pub const SELECTED: u8 = 0x44;
    pub const IDENTIFY_VENDOR: u8 = 0x46;
    pub const IDENTIFY_SERIAL_HIGH: u8 = 0x4B;
    pub const IDENTIFY_NON_CONFIGURED: u8 = 0x4C;
    pub const IDENTIFIED: u8 = 0x4F;
    pub const NON_CONFIGURED: u8 = 0x50;
    pub const FASTSCAN: u8 = 0x51;
    pub const INQUIRE_VENDOR: u8 = 0x5A;
    pub const INQUIRE_SERIAL: u8 = 0x5D;
    pub const INQUIRE_NODE_ID: u8 = 0x5E;
}

/// LSS state of the slave.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum LssMode {
    #[default]
    Waiting,
    Configuration,
}

/// What the node must do after an LSS request.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum LssEffect {
    /// Configuration → waiting: an unconfigured node takes its new node id now.
    BackToWaiting,
    ActivateBitTiming {
        table_index: u8,
        delay_ms: u16,
    },
    Store {
        node_id: u8,
        bit_timing: u8,
    },
}

#[derive(Debug, Default)]
pub(crate) struct LssSlave {
    pub(crate) mode: LssMode,
    /// Node id configured by LSS, taken at the next reset communication.
    pub(crate) pending_id: u8,
    pub(crate) bit_timing: u8,
    /// Progress of switch state selective (matched fields).
    selected: u8,
    /// Progress of identify remote slave; bit per matched field.
    identify: u8,
    /// Fastscan: the identity field being scanned, once a scan started.
    fastscan: Option<u8>,
}

impl LssSlave {
    pub(crate) fn new(node_id: u8, bit_timing: u8) -> LssSlave {
        LssSlave {
            pending_id: node_id,
            bit_timing,
            ..LssSlave::default()
        }
    }

    /// One request; the reply (if any) and an effect for the node.
    pub(crate) fn on_request(
        &mut self,
        data: &[u8],
        identity: [u32; 4],
        active_id: u8,
    ) -> (Option<[u8; 8]>, Option<LssEffect>) {
        let mut d = [0u8; 8];
        for (slot, b) in d.iter_mut().zip(data) {
            *slot = *b;
        }
        if data.len() != 8 {
            return (None, None);
        }
        let value = u32::from_le_bytes([d[1], d[2], d[3], d[4]]);
        let reply = |cs: u8, a: u8, b: u8| Some([cs, a, b, 0, 0, 0, 0, 0]);
        let config = self.mode == LssMode::Configuration;
        match d[0] {
            cs::SWITCH_GLOBAL => match d[1] {
                0 => {
                    let was = std::mem::take(&mut self.mode);
                    let effect =
                        (was == LssMode::Configuration).then_some(LssEffect::BackToWaiting);
                    (None, effect)
                }
                1 => {
                    self.mode = LssMode::Configuration;
                    (None, None)
                }
                _ => (None, None),
            },
            c @ cs::SELECT_VENDOR..=cs::SELECT_SERIAL => {
                let field = c - cs::SELECT_VENDOR;
                let ok = self.selected == field && identity.get(usize::from(field)) == Some(&value);
                self.selected = if ok { field + 1 } else { 0 };
                if ok && c == cs::SELECT_SERIAL {
                    self.selected = 0;
                    self.mode = LssMode::Configuration;
                    return (reply(cs::SELECTED, 0, 0), None);
                }
                (None, None)
            }
            cs::CONFIGURE_NODE_ID if config => {
                let id = d[1];
                if valid_node_id(id) || id == UNCONFIGURED {
                    self.pending_id = id;
                    (reply(cs::CONFIGURE_NODE_ID, 0, 0), None)
                } else {
                    (reply(cs::CONFIGURE_NODE_ID, 1, 0), None)
                }
            }
            cs::CONFIGURE_BIT_TIMING if config => {
                // Table 0 (CiA 305 Table 1): indices 0–8, 5 reserved.
                if d[1] == 0 && d[2] <= 8 && d[2] != 5 {
                    self.bit_timing = d[2];
                    (reply(cs::CONFIGURE_BIT_TIMING, 0, 0), None)
                } else {
                    (reply(cs::CONFIGURE_BIT_TIMING, 1, 0), None)
                }
            }
            cs::ACTIVATE_BIT_TIMING if config => (
                None,
                Some(LssEffect::ActivateBitTiming {
                    table_index: self.bit_timing,
                    delay_ms: u16::from_le_bytes([d[1], d[2]]),
                }),
            ),
            cs::STORE if config => (
                reply(cs::STORE, 0, 0),
                Some(LssEffect::Store {
                    node_id: self.pending_id,
                    bit_timing: self.bit_timing,
                }),
            ),
            c @ cs::INQUIRE_VENDOR..=cs::INQUIRE_SERIAL if config => {
                let v = identity
                    .get(usize::from(c - cs::INQUIRE_VENDOR))
                    .copied()
                    .unwrap_or(0)
                    .to_le_bytes();
                (Some([c, v[0], v[1], v[2], v[3], 0, 0, 0]), None)
            }
            cs::INQUIRE_NODE_ID if config => (reply(cs::INQUIRE_NODE_ID, active_id, 0), None),
            c @ cs::IDENTIFY_VENDOR..=cs::IDENTIFY_SERIAL_HIGH => (
                self.identify_step(c - cs::IDENTIFY_VENDOR, value, identity),
                None,
            ),
            cs::IDENTIFY_NON_CONFIGURED if active_id == UNCONFIGURED => {
                (reply(cs::NON_CONFIGURED, 0, 0), None)
            }
            cs::FASTSCAN => (self.fastscan_step(&d, value, identity, active_id), None),
            _ => (None, None),
        }
    }

    /// Identify remote slave (CiA 305 §6.5.2): vendor, product, revision low/high, serial
    /// low/high; the slave answers when its identity is inside all the ranges.
    fn identify_step(&mut self, step: u8, value: u32, id: [u32; 4]) -> Option<[u8; 8]> {
        let ok = match step {
            0 => id[0] == value,
            1 => id[1] == value,
            2 => id[2] >= value,
            3 => id[2] <= value,
            4 => id[3] >= value,
            _ => id[3] <= value,
        };
        if step == 0 {
            self.identify = 0;
        }
        if ok && self.identify == step {
            self.identify = step + 1;
        } else {
            self.identify = 0xFF;
        }
        (step == 5 && self.identify == 6).then_some([cs::IDENTIFIED, 0, 0, 0, 0, 0, 0, 0])
    }

    /// LSS fastscan (CiA 305 §6.7): only an unconfigured slave in waiting state takes part.
    fn fastscan_step(
        &mut self,
        d: &[u8; 8],
        value: u32,
        id: [u32; 4],
        active_id: u8,
    ) -> Option<[u8; 8]> {
        let (bitcheck, sub, next) = (d[5], d[6], d[7]);
        let answer = Some([cs::IDENTIFIED, 0, 0, 0, 0, 0, 0, 0]);
        if self.mode != LssMode::Waiting || active_id != UNCONFIGURED {
            return None;
        }
        if bitcheck == 0x80 {
            self.fastscan = Some(0);
            return answer;
        }
        if bitcheck > 31 || sub > 3 || next > 3 || self.fastscan != Some(sub) {
            return None;
        }
        let mask = u32::MAX << bitcheck;
        if (id.get(usize::from(sub)).copied().unwrap_or(0) ^ value) & mask != 0 {
            return None;
        }
        if bitcheck == 0 {
            self.fastscan = Some(next);
            if next < sub {
                self.fastscan = None;
                self.mode = LssMode::Configuration;
            }
        }
        answer
    }
}
