//! The user parameter areas kept in the state directory (digest 001 §2.20: a non-volatile area
//! the controller keeps across power cycles): `nmc/<section>.user_para.bin` (2048 bytes) and
//! `nmc/<section>.user_para_ex.bin` (32768 bytes), each written whole after every
//! `NMC_UserParaWr`/`…Ex` (replaced atomically, as `saved_config.rs` replaces its file) and read
//! back when the section starts. Without a state directory the areas live while mcemu runs.

use super::service::NmcService;

/// Which area: the file's suffix.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AreaFile {
    Basic,
    Extended,
}

impl AreaFile {
    /// The area's size in bytes (digest 001 §2.20).
    pub const fn size(self) -> usize {
        match self {
            AreaFile::Basic => 2048,
            AreaFile::Extended => 32768,
        }
    }

    fn name(self, service: &NmcService) -> String {
        let suffix = match self {
            AreaFile::Basic => "user_para",
            AreaFile::Extended => "user_para_ex",
        };
        format!("nmc/{}.{suffix}.bin", service.section())
    }
}

/// Write `bytes`, the whole area, to its file. No state directory: nothing to do.
pub fn save(service: &NmcService, area: AreaFile, bytes: &[u8]) -> Result<(), String> {
    let Some(dir) = service.state_dir() else {
        return Ok(());
    };
    let name = area.name(service);
    dir.write(&name, bytes)
        .map_err(|e| format!("cannot write {}: {e}", dir.display(&name)))
}

/// Both areas as saved, into the service's stored state (at section start).
pub fn restore_at_start(service: &NmcService) {
    let basic = load(service, AreaFile::Basic);
    let extended = load(service, AreaFile::Extended);
    let mut stored = service.stored();
    if let Some(bytes) = basic {
        stored.user_para = bytes;
    }
    if let Some(bytes) = extended {
        stored.user_para_ex = bytes;
    }
}

/// The saved area, zero-padded or cut to the area's size, or `None` when nothing was saved. A
/// file that cannot be read is reported and ignored: the area starts zeroed.
fn load(service: &NmcService, area: AreaFile) -> Option<Vec<u8>> {
    let dir = service.state_dir()?;
    let name = area.name(service);
    match dir.read(&name) {
        Ok(Some(mut bytes)) => {
            bytes.resize(area.size(), 0);
            Some(bytes)
        }
        Ok(None) => None,
        Err(e) => {
            tracing::warn!(file = %dir.display(&name), "NMC user parameter area not read: {e}");
            None
        }
    }
}
