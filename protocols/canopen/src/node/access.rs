//! What an SDO client may read and write: the device's dictionary behind the node's rules for
//! communication objects (CiA 301 §7.5.2).

use axes::od::{DataType, Value};

use super::Node;
use crate::device::{get_u32, Device};
use crate::emcy::clear_history;
use crate::events::NodeEvent;
use crate::nmt::NmtState;
use crate::objects::{idx, restricted_can_id};
use crate::pdo::config::{check_write, PdoObject};
use crate::sdo::{Completion, ObjectAccess, SdoAbort};
use crate::store::{self, ParameterGroup, LOAD_SIGNATURE, SAVE_SIGNATURE};

/// What a checked write does.
enum WriteEffect {
    /// Store in the dictionary.
    Write,
    /// 0x1003:00 = 0.
    ClearHistory,
    Store(ParameterGroup),
    Restore(ParameterGroup),
}

impl<D: Device> Node<D> {
    /// The node's rules for a write of `value` to a communication object.
    fn check_comm_write(
        &self,
        index: u16,
        subindex: u8,
        value: &Value,
    ) -> Result<WriteEffect, SdoAbort> {
        let od = self.device.od();
        // The node reads its communication objects as unsigned integers (CiA 301 §7.5.2 gives
        // each one's UNSIGNEDn type). A device table or user EDS/DCF may define one otherwise
        // (a VISIBLE_STRING 0x1017, an INTEGER32 COB-ID): the node then cannot act on the
        // value, which CiA 301 Table 22 calls a general internal incompatibility in the device.
        if interprets(index) {
            let data_type = od.entry(index, subindex).map(|e| e.def.data_type);
            if data_type.is_ok_and(|t| !is_unsigned(t)) {
                return Err(SdoAbort::INTERNAL_INCOMPATIBLE);
            }
        }
        let v = match value {
            Value::Bool(b) => u64::from(*b),
            other => other.as_u64().unwrap_or(u64::MAX),
        };
        match index {
            idx::ERROR_HISTORY if subindex == 0 => {
                if v == 0 {
                    Ok(WriteEffect::ClearHistory)
                } else {
                    Err(SdoAbort::INVALID_VALUE)
                }
            }
            idx::STORE | idx::RESTORE => {
                let group = ParameterGroup::from_subindex(subindex).ok_or(SdoAbort::NO_SUBINDEX)?;
                let (want, action) = if index == idx::STORE {
                    (SAVE_SIGNATURE, WriteEffect::Store(group))
                } else {
                    (LOAD_SIGNATURE, WriteEffect::Restore(group))
                };
                if v != u64::from(want) {
                    return Err(SdoAbort::CANNOT_STORE);
                }
                if self.persisting.is_some() {
                    return Err(SdoAbort::DEVICE_STATE);
                }
                Ok(action)
            }
            // The node consumes SYNC; it does not produce it (bit 30) nor use 29-bit ids.
            idx::COB_ID_SYNC => {
                if v & 0x6000_0000 != 0 || restricted_can_id((v & 0x7FF) as u16) {
                    Err(SdoAbort::INVALID_VALUE)
                } else {
                    Ok(WriteEffect::Write)
                }
            }
            // §7.5.2.17: the CAN-ID changes only while the EMCY is invalid (bit 31).
            idx::COB_ID_EMCY => {
                let old = get_u32(od, idx::COB_ID_EMCY, 0).unwrap_or(0x8000_0000);
                let both_valid = old & 0x8000_0000 == 0 && v & 0x8000_0000 == 0;
                if v & 0x2000_0000 != 0
                    || (both_valid && (old & 0x7FF) as u64 != v & 0x7FF)
                    || (v & 0x8000_0000 == 0 && restricted_can_id((v & 0x7FF) as u16))
                {
                    Err(SdoAbort::INVALID_VALUE)
                } else {
                    Ok(WriteEffect::Write)
                }
            }
            // §7.5.2.22: one entry per monitored node.
            idx::CONSUMER_HEARTBEAT if subindex > 0 => {
                let node = (v >> 16) & 0xFF;
                let time = v & 0xFFFF;
                if node != 0 && time != 0 {
                    let count = crate::device::get_u8(od, idx::CONSUMER_HEARTBEAT, 0).unwrap_or(0);
                    let clash = (1..=count).filter(|&s| s != subindex).any(|s| {
                        let other = u64::from(get_u32(od, idx::CONSUMER_HEARTBEAT, s).unwrap_or(0));
                        (other >> 16) & 0xFF == node && other & 0xFFFF != 0
                    });
                    if clash {
                        return Err(SdoAbort::PARAMETER_INCOMPATIBLE);
                    }
                }
                Ok(WriteEffect::Write)
            }
            // §7.5.2.23: 0x1019 changes only while 0x1006 is 0; values 0 or 2–240.
            idx::SYNC_OVERFLOW => {
                if get_u32(od, idx::SYNC_PERIOD, 0).unwrap_or(0) != 0 {
                    Err(SdoAbort::DEVICE_STATE)
                } else if v == 1 || v > 240 {
                    Err(SdoAbort::INVALID_VALUE)
                } else {
                    Ok(WriteEffect::Write)
                }
            }
            idx::ERROR_BEHAVIOUR if subindex == 1 && v > 2 => Err(SdoAbort::INVALID_VALUE),
            _ => match PdoObject::of(index) {
                Some(object) => {
                    if self.nmt == NmtState::Operational && !self.config.pdo_config_in_operational {
                        return Err(SdoAbort::DEVICE_STATE);
                    }
                    check_write(od, object, subindex, v).map(|()| WriteEffect::Write)
                }
                None => Ok(WriteEffect::Write),
            },
        }
    }

    fn persist(&mut self, store: bool, group: ParameterGroup) -> Completion {
        let previous = self.stored.as_deref();
        let image = if store {
            store::merge(previous, self.device.od(), group)
        } else {
            store::remove(previous, group)
        };
        self.persisting = Some(image.clone());
        self.event(if store {
            NodeEvent::StoreRequested { group, image }
        } else {
            NodeEvent::RestoreRequested { group, image }
        });
        Completion::Deferred
    }
}

/// Communication objects whose values the node acts on (and so reads as unsigned integers).
fn interprets(index: u16) -> bool {
    matches!(
        index,
        idx::ERROR_HISTORY
            | idx::COB_ID_SYNC
            | idx::SYNC_PERIOD
            | idx::GUARD_TIME
            | idx::LIFE_TIME_FACTOR
            | idx::STORE
            | idx::RESTORE
            | idx::COB_ID_EMCY
            | idx::EMCY_INHIBIT
            | idx::CONSUMER_HEARTBEAT
            | idx::PRODUCER_HEARTBEAT
            | idx::SYNC_OVERFLOW
            | idx::ERROR_BEHAVIOUR
            | idx::SDO_SERVER
    ) || PdoObject::of(index).is_some()
}

fn is_unsigned(data_type: DataType) -> bool {
    matches!(
        data_type,
        DataType::Unsigned8 | DataType::Unsigned16 | DataType::Unsigned32 | DataType::Unsigned64
    )
}

impl<D: Device> ObjectAccess for Node<D> {
    fn upload(&mut self, index: u16, subindex: u8) -> Result<Vec<u8>, SdoAbort> {
        self.device
            .od()
            .read_bytes(index, subindex)
            .map_err(SdoAbort::from)
    }

    fn check_download(
        &mut self,
        index: u16,
        subindex: u8,
        size: Option<usize>,
    ) -> Result<(), SdoAbort> {
        if self.local_control {
            return Err(SdoAbort::LOCAL_CONTROL);
        }
        let entry = self.device.od().entry(index, subindex)?;
        if !entry.def.access.writable() {
            return Err(SdoAbort::READ_ONLY);
        }
        // A size beyond the object's maximum (a DOMAIN's 1 MiB too) is refused before any data
        // comes (CiA 301 Table 22: 0x06070012).
        match (entry.def.data_type.size(), size) {
            (_, Some(s)) if s > entry.def.max_len() => Err(SdoAbort::LENGTH_HIGH),
            (Some(fixed), Some(s)) if s < fixed => Err(SdoAbort::LENGTH_LOW),
            _ => Ok(()),
        }
    }

    fn max_len(&self, index: u16, subindex: u8) -> Option<usize> {
        Some(self.device.od().entry(index, subindex).ok()?.def.max_len())
    }

    fn fixed_size(&self, index: u16, subindex: u8) -> Option<usize> {
        self.device
            .od()
            .entry(index, subindex)
            .ok()?
            .def
            .data_type
            .size()
    }

    fn download(&mut self, index: u16, subindex: u8, data: &[u8]) -> Result<Completion, SdoAbort> {
        if self.local_control {
            return Err(SdoAbort::LOCAL_CONTROL);
        }
        let value = self.device.od().decode(index, subindex, data)?;
        let completion = match self.check_comm_write(index, subindex, &value)? {
            WriteEffect::ClearHistory => {
                clear_history(self.device.od_mut());
                Completion::Done
            }
            WriteEffect::Store(group) => return Ok(self.persist(true, group)),
            WriteEffect::Restore(group) => return Ok(self.persist(false, group)),
            WriteEffect::Write => {
                self.device.write(index, subindex, value)?;
                Completion::Done
            }
        };
        self.reload_after_write(index, self.now);
        self.event(NodeEvent::ObjectWritten { index, subindex });
        Ok(completion)
    }
}
