//! SDO server (CiA 301 §7.2.4): expedited, segmented and block transfers both ways.
//!
//! The server is a state machine over one client's requests; what it reads and writes goes
//! through [`ObjectAccess`], which the node implements with its own rules for communication
//! objects in front of the device's dictionary.

mod abort;
mod block;
pub mod crc;
mod server;

pub use abort::SdoAbort;
pub use server::SdoCounters;
pub(crate) use server::SdoServer;

/// A failed step of a transfer: the multiplexer to report and the code.
pub(crate) type Failure = (u16, u8, SdoAbort);

/// How a download ended on the device side.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Completion {
    /// Stored; the server confirms now.
    Done,
    /// The application must act first (store/restore parameters); the node confirms through
    /// [`SdoServer::finish_deferred`].
    Deferred,
}

/// Object access as the SDO server needs it.
pub(crate) trait ObjectAccess {
    /// The value's bytes for an upload, or why not.
    fn upload(&mut self, index: u16, subindex: u8) -> Result<Vec<u8>, SdoAbort>;
    /// Whether a download of `size` bytes (if indicated) to the entry may start.
    fn check_download(
        &mut self,
        index: u16,
        subindex: u8,
        size: Option<usize>,
    ) -> Result<(), SdoAbort>;
    /// The encoded size of the entry's type, if fixed.
    fn fixed_size(&self, index: u16, subindex: u8) -> Option<usize>;
    /// The most bytes a download to the entry may bring (its size if fixed), if it exists.
    fn max_len(&self, index: u16, subindex: u8) -> Option<usize>;
    /// Store a downloaded value.
    fn download(&mut self, index: u16, subindex: u8, data: &[u8]) -> Result<Completion, SdoAbort>;
}

/// How many bytes a download may bring, and the abort once it brings more: the object's own
/// maximum (0x06070012, "length of service parameter too high") or the server's buffer
/// (`sdo_max_len`, 0x05040005 "out of memory"), whichever is smaller.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Limit {
    pub len: usize,
    pub abort: SdoAbort,
}

impl Limit {
    pub(crate) fn new(object: Option<usize>, server: usize) -> Limit {
        match object {
            Some(len) if len <= server => Limit {
                len,
                abort: SdoAbort::LENGTH_HIGH,
            },
            _ => Limit {
                len: server,
                abort: SdoAbort::OUT_OF_MEMORY,
            },
        }
    }
}

/// Multiplexer (index, sub-index) of an SDO frame.
pub(crate) fn mux(d: &[u8; 8]) -> (u16, u8) {
    (u16::from_le_bytes([d[1], d[2]]), d[3])
}

/// A frame's bytes 4..8 as u32.
pub(crate) fn word(d: &[u8; 8]) -> u32 {
    u32::from_le_bytes([d[4], d[5], d[6], d[7]])
}

/// An SDO frame with command byte and multiplexer.
pub(crate) fn with_mux(cmd: u8, index: u16, subindex: u8, tail: [u8; 4]) -> [u8; 8] {
    let i = index.to_le_bytes();
    [
        cmd, i[0], i[1], subindex, tail[0], tail[1], tail[2], tail[3],
    ]
}
