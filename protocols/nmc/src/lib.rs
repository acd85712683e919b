//! The NMC wire protocol between the `nmc_lib20` shim (a drop-in replacement of Gaochuan's
//! `NMC_*` C library, digest 001) and mcemu's NMC front-end, sans-IO: bytes in, frames out.
//! The manual defines no wire format (digest 001 §7): this one is mcemu's.
//!
//! - [`frame`]: the fixed 16-byte little-endian header (magic, version, kind, sequence,
//!   function id, status, payload length), the frame size limit, and [`frame::FrameDecoder`]
//!   (push bytes, pop frames);
//! - [`payload`]: the encoding of the C argument kinds (`short`, `long` as i64, `double`,
//!   strings, arrays, structs) in a request or reply payload;
//! - [`table`]: THE function table — id, name, arguments with their C types and directions —
//!   from which the shim's calls, the server's dispatch and the C header are all made; adding a
//!   function is one row here plus its handler in the server and its export in the shim;
//! - [`structs`]: the manual's structs (`TPtpPara` …) as the wire carries them;
//! - [`sync_structs`], [`sync_header`]: the structs and header text of the gear, PT/PVT,
//!   capture, compare, gantry, handwheel and compensation families;
//! - [`laser`]: the laser and SHIO structs (`TTimeArrayPara`, `TLaserPower`, `TSHIOPara`) and
//!   their header text;
//! - [`io_structs`], [`io_header`]: the structs and header text of the I/O-by-type,
//!   extension-module and controller-service families (0x12xx);
//! - [`axis_config`]: `TSafePara` as the wire carries it;
//! - [`ax_structs`], [`ax_header`]: the packed status and PTP structs and the advanced E-stop
//!   input of the axis-level additions (family 0x13xx);
//! - [`buf_pack`]: `TAdvBufIoParam` and the `NMC_CrdBufDataPack` stream (family 0x16xx);
//! - [`crd`]: the coordinate-system structs (`TCrdConfig` …) and their C declarations;
//! - [`sdo`]: the CiA 301 abort code in an SDO refusal's text (`NMC_EcatSdoRead`/`Write`);
//! - [`sys`]: the data-collection structs and header text of the system family (0x18xx);
//! - [`crd_frames`]: the structs of the transforms, arc sections and move protection (0x17xx);
//! - [`errors`]: the return codes of `mtn_lib20_err.h` (not in the manual: mcemu's, stable);
//! - [`header`]: the C headers generated from the table (checked against the committed ones);
//! - [`handle`]: what a `HAND` encodes (kind, library slot, axis number);
//! - [`session`]: the server side of one connection (version negotiation, then requests).

pub mod ax_header;
pub mod ax_structs;
pub mod axis_config;
pub mod buf_pack;
pub mod crd;
pub mod crd_frames;
pub mod crd_lookahead;
pub mod errors;
pub mod frame;
pub mod handle;
pub mod header;
pub mod io_header;
pub mod io_structs;
pub mod laser;
pub mod payload;
pub mod sdo;
pub mod session;
pub mod structs;
pub mod sync_header;
pub mod sync_structs;
pub mod sys;
pub mod table;
