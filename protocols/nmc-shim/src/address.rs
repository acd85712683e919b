//! Which mcemu a device opens: the `MCEMU_NMC` environment variable (digest 001 §7: the manual
//! has no transport of its own to emulate).
//!
//! - unset: `127.0.0.1:7700`, for every device;
//! - `host:port` or `unix:/path`: that address for every device;
//! - otherwise the path of a small TOML file mapping device index, ID and IP each to an
//!   address, with an optional `default` for what is not listed:
//!
//! ```toml
//! default = "127.0.0.1:7700"
//! [index]
//! 0 = "unix:/run/mcemu/nmc.sock"
//! [id]
//! CARD1 = "127.0.0.1:7700"
//! [ip]
//! "192.168.1.110" = "127.0.0.1:7700"
//! ```

use std::net::{SocketAddr, ToSocketAddrs};
use std::path::PathBuf;

/// The variable.
pub const VARIABLE: &str = "MCEMU_NMC";
/// Its default.
pub const DEFAULT: &str = "127.0.0.1:7700";

/// One address.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Address {
    Tcp(String),
    Unix(PathBuf),
}

impl std::fmt::Display for Address {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Address::Tcp(a) => write!(f, "{a}"),
            Address::Unix(p) => write!(f, "unix:{}", p.display()),
        }
    }
}

impl Address {
    pub fn parse(s: &str) -> Address {
        match s.strip_prefix("unix:") {
            Some(path) => Address::Unix(PathBuf::from(path)),
            None => Address::Tcp(s.to_string()),
        }
    }

    /// The socket addresses of a TCP address (empty if it does not resolve).
    pub fn resolve(&self) -> Vec<SocketAddr> {
        match self {
            Address::Tcp(a) => a.to_socket_addrs().map(|i| i.collect()).unwrap_or_default(),
            Address::Unix(_) => Vec::new(),
        }
    }
}

/// How a program names a device.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum DeviceKey {
    Index(i16),
    Id(String),
    Ip([u8; 4]),
}

/// The resolution `MCEMU_NMC` describes.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Resolver {
    default: Option<String>,
    index: Vec<(String, String)>,
    id: Vec<(String, String)>,
    ip: Vec<(String, String)>,
}

impl Resolver {
    /// From the environment. A file that cannot be read resolves nothing (every open fails
    /// with `RTN_NO_DEVICE`).
    pub fn from_env() -> Resolver {
        let value = std::env::var(VARIABLE).unwrap_or_else(|_| DEFAULT.to_string());
        Resolver::from_value(&value)
    }

    pub fn from_value(value: &str) -> Resolver {
        let is_address = value.starts_with("unix:")
            || (value.contains(':') && !std::path::Path::new(value).is_file());
        if is_address {
            return Resolver {
                default: Some(value.to_string()),
                ..Resolver::default()
            };
        }
        std::fs::read_to_string(value)
            .map(|text| Resolver::from_toml(&text))
            .unwrap_or_default()
    }

    /// The TOML subset of the mapping file: `key = "value"` lines, `[index]`, `[id]`, `[ip]`
    /// sections, `#` comments, keys bare or quoted.
    pub fn from_toml(text: &str) -> Resolver {
        let mut r = Resolver::default();
        let mut section = String::new();
        for line in text.lines() {
            let line = line.split(" #").next().unwrap_or("").trim();
            if line.is_empty() || line.starts_with('#') {
                continue;
            }
            if let Some(name) = line.strip_prefix('[').and_then(|l| l.strip_suffix(']')) {
                section = name.trim().to_string();
                continue;
            }
            let Some((key, value)) = line.split_once('=') else {
                continue;
            };
            let unquote = |s: &str| s.trim().trim_matches('"').to_string();
            let (key, value) = (unquote(key), unquote(value));
            match section.as_str() {
                "" if key == "default" => r.default = Some(value),
                "index" => r.index.push((key, value)),
                "id" => r.id.push((key, value)),
                "ip" => r.ip.push((key, value)),
                _ => {}
            }
        }
        r
    }

    /// The address of device `key`.
    pub fn resolve(&self, key: &DeviceKey) -> Option<Address> {
        let (list, k) = match key {
            DeviceKey::Index(n) => (&self.index, n.to_string()),
            DeviceKey::Id(s) => (&self.id, s.clone()),
            DeviceKey::Ip([a, b, c, d]) => (&self.ip, format!("{a}.{b}.{c}.{d}")),
        };
        list.iter()
            .find(|(name, _)| *name == k)
            .map(|(_, a)| a.as_str())
            .or(self.default.as_deref())
            .map(Address::parse)
    }

    /// Every address a search should ask, each once, by device index first.
    pub fn all(&self) -> Vec<Address> {
        let mut out: Vec<Address> = Vec::new();
        let listed = self.index.iter().chain(&self.id).chain(&self.ip);
        for a in listed.map(|(_, a)| a).chain(&self.default) {
            let a = Address::parse(a);
            if !out.contains(&a) {
                out.push(a);
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_address_serves_every_key() {
        let r = Resolver::from_value("127.0.0.1:7711");
        let tcp = Some(Address::Tcp("127.0.0.1:7711".into()));
        assert_eq!(r.resolve(&DeviceKey::Index(3)), tcp);
        assert_eq!(r.resolve(&DeviceKey::Id("CARD1".into())), tcp);
        let r = Resolver::from_value("unix:/tmp/nmc.sock");
        assert_eq!(
            r.resolve(&DeviceKey::Ip([192, 168, 1, 110])),
            Some(Address::Unix("/tmp/nmc.sock".into()))
        );
    }

    #[test]
    fn a_mapping_file_maps_index_id_and_ip() {
        let r = Resolver::from_toml(
            "# two cards\n[index]\n0 = \"unix:/a\"\n1 = \"127.0.0.1:1\"\n\
             [id]\nCARD2 = \"127.0.0.1:2\" # the second\n[ip]\n\"192.168.1.111\" = \"127.0.0.1:3\"\n",
        );
        assert_eq!(
            r.resolve(&DeviceKey::Index(0)),
            Some(Address::Unix("/a".into()))
        );
        assert_eq!(
            r.resolve(&DeviceKey::Id("CARD2".into())),
            Some(Address::Tcp("127.0.0.1:2".into()))
        );
        assert_eq!(
            r.resolve(&DeviceKey::Ip([192, 168, 1, 111])),
            Some(Address::Tcp("127.0.0.1:3".into()))
        );
        assert_eq!(r.resolve(&DeviceKey::Index(5)), None);
        assert_eq!(r.all().len(), 4);
    }
}
