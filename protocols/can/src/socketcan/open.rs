//! Opening a SocketCAN interface, with errors that say what to fix.

use std::io;
use std::path::Path;

use socketcan::SocketOptions;

/// Why an interface could not be opened or stopped working. Every message names it.
#[derive(Debug, thiserror::Error)]
pub enum SocketCanError {
    #[error("`{0}` is not an interface name (1 to 15 characters, no '/' or whitespace)")]
    BadName(String),
    #[error(
        "{interface}: this kernel has no CAN support ({detail}); run SocketCAN tests through \
         tests/vcan/run, or serve the bus over socketcand"
    )]
    NoKernelSupport {
        interface: String,
        detail: &'static str,
    },
    #[error(
        "{interface}: no such interface (a virtual one: `ip link add dev {interface} type vcan \
         && ip link set up {interface}`)"
    )]
    NoSuchInterface { interface: String },
    #[error("{interface}: not a CAN interface (link type {link_type}, CAN is 280)")]
    NotCan {
        interface: String,
        link_type: String,
    },
    #[error("{interface}: the interface is down (`ip link set up {interface}`)")]
    InterfaceDown { interface: String },
    #[error("{interface}: {what}: {source}")]
    Io {
        interface: String,
        what: &'static str,
        source: io::Error,
    },
}

impl SocketCanError {
    /// An I/O error of `what` on `interface`, with the errnos that have a clearer meaning.
    pub fn from_io(interface: &str, what: &'static str, source: io::Error) -> Self {
        let interface = interface.to_string();
        match source.raw_os_error() {
            Some(libc::EAFNOSUPPORT) => Self::NoKernelSupport {
                interface,
                detail: "address family not supported",
            },
            Some(libc::EPROTONOSUPPORT) => Self::NoKernelSupport {
                interface,
                detail: "raw CAN protocol not supported: is the can-raw module loaded?",
            },
            Some(libc::ENODEV | libc::ENXIO) => Self::NoSuchInterface { interface },
            Some(libc::ENETDOWN) => Self::InterfaceDown { interface },
            _ => Self::Io {
                interface,
                what,
                source,
            },
        }
    }
}

/// Open `interface` for classic CAN frames, receiving error frames of every class.
///
/// Checks in the order that gives the most useful answer: the name, whether this kernel has
/// CAN at all (an `AF_CAN` socket), whether the interface exists, is CAN and is up (sysfs,
/// when mounted), then the socket itself. Must be called within a tokio runtime.
pub fn open(interface: &str) -> Result<socketcan::tokio::CanSocket, SocketCanError> {
    if interface.is_empty()
        || interface.len() > 15
        || interface.contains('/')
        || interface.chars().any(char::is_whitespace)
    {
        return Err(SocketCanError::BadName(interface.to_string()));
    }
    probe_kernel().map_err(|e| SocketCanError::from_io(interface, "CAN socket", e))?;
    check_sysfs(interface)?;
    let socket = socketcan::tokio::CanSocket::open(interface)
        .map_err(|e| SocketCanError::from_io(interface, "open", e))?;
    socket
        .set_error_filter_accept_all()
        .map_err(|e| SocketCanError::from_io(interface, "enable error frames", e))?;
    Ok(socket)
}

/// A raw CAN socket that is opened and closed: fails with `EAFNOSUPPORT` on a kernel without
/// CAN.
fn probe_kernel() -> io::Result<()> {
    let domain = socket2::Domain::from(libc::AF_CAN);
    let protocol = socket2::Protocol::from(libc::CAN_RAW);
    socket2::Socket::new(domain, socket2::Type::RAW, Some(protocol)).map(drop)
}

/// What sysfs says of the interface; nothing when sysfs is not mounted.
pub(crate) fn check_sysfs(interface: &str) -> Result<(), SocketCanError> {
    let net = Path::new("/sys/class/net");
    if !net.is_dir() {
        return Ok(());
    }
    let dir = net.join(interface);
    if !dir.exists() {
        return Err(SocketCanError::NoSuchInterface {
            interface: interface.to_string(),
        });
    }
    let read = |file: &str| std::fs::read_to_string(dir.join(file)).map(|s| s.trim().to_string());
    if let Ok(link_type) = read("type") {
        if link_type != "280" {
            return Err(SocketCanError::NotCan {
                interface: interface.to_string(),
                link_type,
            });
        }
    }
    if let Ok(flags) = read("flags") {
        let up = u32::from_str_radix(flags.trim_start_matches("0x"), 16).map(|f| f & 1 != 0);
        if up == Ok(false) {
            return Err(SocketCanError::InterfaceDown {
                interface: interface.to_string(),
            });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[tokio::test]
    async fn failures_name_the_interface_and_the_reason() {
        for bad in ["", "a/b", "sixteen-chars-xx", "a b"] {
            assert!(
                matches!(open(bad), Err(SocketCanError::BadName(_))),
                "{bad:?}"
            );
        }
        // Without CAN in the kernel (this machine) the probe says so; with it, the interface
        // is missing. Either way the message names it.
        let err = open("mcemunone0")
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert!(err.starts_with("mcemunone0: "), "{err}");
        assert!(
            err.contains("this kernel has no CAN support (address family not supported)")
                || err.contains("no such interface"),
            "{err}"
        );
        // `lo` exists everywhere but is not CAN (on a kernel without CAN, the probe answers).
        let err = open("lo").err().map(|e| e.to_string()).unwrap_or_default();
        assert!(
            err.contains("not a CAN interface") || err.contains("no CAN support"),
            "{err}"
        );
    }
}
