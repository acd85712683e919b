//! `[frontends.nmc]` (TCP, network controllers) and `[frontends.nmc_local]` (a Unix socket,
//! PCIe/GCE cards): where the NMC front-end listens, its bound, and the identity of the device
//! it presents (digest 001 §1.1–1.2).

use std::net::{Ipv4Addr, SocketAddr};
use std::path::PathBuf;

use serde::{Deserialize, Serialize};

/// What kind of card the device is: `NMC_DevOpenByIP` is refused on `pcie` and `ecat` cards
/// (digest 001 §2.2, TV03).
#[derive(
    Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema,
)]
#[serde(rename_all = "snake_case")]
pub enum DeviceKind {
    /// A GCN network controller, opened by index, ID or IP.
    #[default]
    Network,
    /// A GC/GCS PCIe card, opened by index or ID.
    Pcie,
    /// A GCE EtherCAT bus card, opened by index or ID.
    Ecat,
}

/// The device a program opens (`NMC_DevOpen`, `NMC_DevOpenByID`, `NMC_DevOpenByIP`,
/// `NMC_GetCardInfo`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct NmcDevice {
    pub kind: DeviceKind,
    /// `NMC_DevOpenByID`'s name, at most 15 bytes (the manual's default "CARD1").
    pub id: String,
    /// `NMC_DevOpenByIP`'s address (the manual's default 192.168.1.110).
    pub ip: Ipv4Addr,
    /// `NMC_DevOpen`'s index.
    pub index: i16,
    /// EtherCAT I/O slaves on an `ecat` card's bus after its drives (`NMC_EcatGetResource`'s
    /// IO count; each is a 32-bit DI/DO group from 2 up, digest 001 §2.1). The bus drives are
    /// the machine's `[[drives]]` with `master = "engine"`, in order: axes 16, 17, …
    pub io_slaves: u16,
}

impl Default for NmcDevice {
    fn default() -> Self {
        NmcDevice {
            kind: DeviceKind::Network,
            id: "CARD1".into(),
            ip: Ipv4Addr::new(192, 168, 1, 110),
            index: 0,
            io_slaves: 0,
        }
    }
}

/// The NMC protocol over TCP.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct NmcConfig {
    pub enabled: bool,
    /// Address to listen on.
    pub bind: SocketAddr,
    /// Open connections at most; at the bound the connection idle longest is closed.
    pub max_connections: usize,
    /// Seconds a connection may stay silent before it is closed; 0 = never.
    pub idle_timeout: f64,
    pub device: NmcDevice,
}

impl Default for NmcConfig {
    fn default() -> Self {
        NmcConfig {
            enabled: true,
            bind: SocketAddr::from(([127, 0, 0, 1], 7700)),
            max_connections: 16,
            idle_timeout: 0.0,
            device: NmcDevice::default(),
        }
    }
}

/// The NMC protocol on a Unix socket.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct NmcLocalConfig {
    pub enabled: bool,
    /// The socket's path (relative: from the working directory); a stale socket file there is
    /// replaced.
    pub path: PathBuf,
    pub max_connections: usize,
    /// Seconds a connection may stay silent before it is closed; 0 = never.
    pub idle_timeout: f64,
    pub device: NmcDevice,
}

impl Default for NmcLocalConfig {
    fn default() -> Self {
        NmcLocalConfig {
            enabled: true,
            path: PathBuf::from("mcemu-nmc.sock"),
            max_connections: 16,
            idle_timeout: 0.0,
            device: NmcDevice {
                kind: DeviceKind::Pcie,
                ..NmcDevice::default()
            },
        }
    }
}

/// The checks `Config::check` makes: `(key, reason)` of the first failure.
pub fn check(
    section: &str,
    max_connections: usize,
    idle_timeout: f64,
    device: &NmcDevice,
) -> Result<(), (String, String)> {
    if !(1..=4096).contains(&max_connections) {
        return Err((
            format!("frontends.{section}.max_connections"),
            format!("{max_connections} is outside 1 … 4096"),
        ));
    }
    if !(idle_timeout.is_finite() && idle_timeout >= 0.0) {
        return Err((
            format!("frontends.{section}.idle_timeout"),
            format!("{idle_timeout} is not a number of seconds ≥ 0"),
        ));
    }
    // Groups 2 … 9 (the extension modules' ids, digest 001 §2.8).
    if device.io_slaves > 8 {
        return Err((
            format!("frontends.{section}.device.io_slaves"),
            format!("{} is outside 0 … 8 (DI/DO groups 2 … 9)", device.io_slaves),
        ));
    }
    if device.id.is_empty() || device.id.len() > 15 {
        return Err((
            format!("frontends.{section}.device.id"),
            format!("{:?} must be 1 … 15 bytes (NMC_DevOpenByID)", device.id),
        ));
    }
    Ok(())
}
