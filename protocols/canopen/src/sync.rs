//! SYNC consumer (CiA 301 §7.2.5): COB-ID 0x1005, counter overflow 0x1019.

use axes::od::ObjectDictionary;

use crate::device::{get_u32, get_u8};
use crate::objects::idx;

#[derive(Debug, Default)]
pub(crate) struct SyncConsumer {
    pub(crate) can_id: Option<u16>,
    /// 0x1019: 0 = SYNC without counter; 2–240 = SYNC carries a counter 1..=overflow.
    pub(crate) overflow: u8,
}

/// A SYNC whose length disagrees with 0x1019 (EMCY 0x8240).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct SyncLengthError;

impl SyncConsumer {
    pub(crate) fn load(&mut self, od: &ObjectDictionary) {
        // Bit 31 is "don't care" for a consumer; bit 29 (extended frame) is refused on write.
        self.can_id = get_u32(od, idx::COB_ID_SYNC, 0).map(|c| (c & 0x7FF) as u16);
        self.overflow = get_u8(od, idx::SYNC_OVERFLOW, 0).unwrap_or(0);
    }

    /// A SYNC frame: its counter (if 0x1019 asks for one), or a length error.
    pub(crate) fn on_frame(&self, data: &[u8]) -> Result<Option<u8>, SyncLengthError> {
        match (self.overflow, data) {
            (0, []) => Ok(None),
            (1.., [counter]) => Ok(Some(*counter)),
            _ => Err(SyncLengthError),
        }
    }
}
