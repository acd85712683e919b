//! The coordinate-system buffered I/O additions (id family 0x16xx): `TAdvBufIoParam` as the
//! wire carries it, and `NMC_CrdBufDataPack`'s stream (digest 001 §2.7, §3.11, §3.12).
//!
//! A pack is `[short cmdType][struct]` repeated, copied back to back with `memcpy` (no padding
//! between entries), at most 1000 bytes. The manual names the command types but defines none
//! of the structs except `TCrdLineXYZD8Unit`: mcemu's (in [`KINDS`], emitted into the header
//! from the same table) are the arguments of the function each type stands for, after the
//! handle, in order, with the field names of the manual's example (`TCrdBufLine`: `segNo`,
//! `mask`, `tgPos`, `endVel`, `vel`, `synAcc`, `lookaheadDis`). A struct is read with the C
//! layout of the platform the library is built for (LP64: `long` 8 bytes; natural alignment,
//! the size rounded up to the largest member's) and becomes the wire payload of its function,
//! without the handle ([`decode`]). Input: the bytes; output: the entries in order, or what
//! is wrong with the first bad one.

use crate::payload::{PayloadError, Reader, Writer};
use crate::table::{self, Function};

/// `MAX_ADV_BUFIO_GROUP` (digest 001 §3.10).
pub const MAX_ADV_BUFIO_GROUP: usize = 2;
/// The most bytes one `NMC_CrdBufDataPack` takes (§3.11).
pub const PACK_MAX_BYTES: usize = 1000;

/// `TAdvBufIoParam` (§3.12): output type (0 general, 1 gate), group, index, active level (0 low,
/// 1 high), mode (0 level, 1 pulses), on and off times (µs, pulse mode).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct AdvBufIoParam {
    pub out_type: i16,
    pub out_group: i16,
    pub out_index: i16,
    pub out_sns: i16,
    pub pulse_mode: i16,
    pub pulse_on_time: i64,
    pub pulse_off_time: i64,
}

impl AdvBufIoParam {
    pub fn write(&self, w: &mut Writer) {
        w.i16(self.out_type)
            .i16(self.out_group)
            .i16(self.out_index)
            .i16(self.out_sns)
            .i16(self.pulse_mode)
            .i64(self.pulse_on_time)
            .i64(self.pulse_off_time);
    }
    pub fn read(r: &mut Reader<'_>) -> Result<AdvBufIoParam, PayloadError> {
        Ok(AdvBufIoParam {
            out_type: r.i16()?,
            out_group: r.i16()?,
            out_index: r.i16()?,
            out_sns: r.i16()?,
            pulse_mode: r.i16()?,
            pulse_on_time: r.i64()?,
            pulse_off_time: r.i64()?,
        })
    }
}

/// One C member of a packed struct.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Field {
    Short,
    Long,
    Float,
    Double,
    /// `long x[N]`, an array argument: on the wire u16 N, then the values.
    Longs(usize),
    /// `long x[N]` inside a struct the wire carries whole: the values only.
    LongsInline(usize),
    /// `short reserved`: read past, not sent.
    Reserved,
}

impl Field {
    fn size(self) -> usize {
        match self {
            Field::Short | Field::Reserved => 2,
            Field::Float => 4,
            Field::Long | Field::Double => 8,
            Field::Longs(n) | Field::LongsInline(n) => 8 * n,
        }
    }
    fn align(self) -> usize {
        match self {
            Field::Short | Field::Reserved => 2,
            Field::Float => 4,
            _ => 8,
        }
    }
    fn c_decl(self, name: &str) -> String {
        match self {
            Field::Short | Field::Reserved => format!("short {name};"),
            Field::Long => format!("long {name};"),
            Field::Float => format!("float {name};"),
            Field::Double => format!("double {name};"),
            Field::Longs(n) | Field::LongsInline(n) => format!("long {name}[{n}];"),
        }
    }
}

/// One command type of the pack.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Kind {
    pub cmd_type: i16,
    /// `BUF_LINE` …
    pub macro_name: &'static str,
    /// `TCrdBufLine` …
    pub struct_name: &'static str,
    /// The function the entry is a call of; for `BUF_XYZD8` `NMC_CrdLineXYZD8Pack` with one
    /// unit, for `BUF_SHIOMINFRQ` and `BUF_SHIOGATEONOFF` the set / on one (the server picks
    /// the clear / off one by the value).
    pub function: Function,
    pub fields: &'static [(&'static str, Field)],
}

use Field::*;

macro_rules! kind {
    ($t:literal, $m:literal, $s:literal, $f:expr, [$($n:literal: $k:expr),* $(,)?]) => {
        Kind { cmd_type: $t, macro_name: $m, struct_name: $s, function: $f, fields: &[$(($n, $k)),*] }
    };
}

/// Every command type of §3.11, in type order.
pub const KINDS: &[Kind] = &[
    kind!(0, "BUF_LINE", "TCrdBufLine", table::CRD_LINE_XYZ_EX,
        ["segNo": Long, "mask": Short, "tgPos": Longs(3), "endVel": Double, "vel": Double, "synAcc": Double, "lookaheadDis": Short]),
    kind!(1, "BUF_DO", "TCrdBufDo", table::CRD_BUF_DO,
        ["segNo": Long, "doType": Short, "ch": Long, "value": Long]),
    kind!(2, "BUF_OUT", "TCrdBufOut", table::CRD_BUF_OUT,
        ["segNo": Long, "group": Short, "ch": Short, "value": Long]),
    kind!(3, "BUF_DELAY", "TCrdBufDelay", table::CRD_BUF_DELAY,
        ["segNo": Long, "scale": Short, "count": Long]),
    kind!(4, "BUF_AXMOVE", "TCrdBufAxMove", table::CRD_BUF_AX_MOVE_EX,
        ["segNo": Long, "axisMask": Short, "tgPos": Longs(8), "vel": Double, "acc": Double, "blockEn": Short, "synEn": Short]),
    kind!(5, "BUF_DOEX", "TCrdBufDoEx", table::CRD_BUF_DO_EX,
        ["segNo": Long, "group": Short, "doMask": Long, "doValue": Long]),
    kind!(6, "BUF_ARC_R", "TCrdBufArcR", table::CRD_ARC_RADIUS_EX,
        ["segNo": Long, "tgPos": Longs(2), "radius": Double, "circleDir": Short, "endVel": Double, "vel": Double, "synAcc": Double, "lookaheadDis": Short]),
    kind!(7, "BUF_ARC_C", "TCrdBufArcC", table::CRD_ARC_CENTER_EX,
        ["segNo": Long, "tgPos": Longs(2), "centerPos": Longs(2), "circleDir": Short, "endVel": Double, "vel": Double, "synAcc": Double, "lookaheadDis": Short]),
    kind!(8, "BUF_LASER_SETPOWER", "TCrdBufLaserPower", table::CRD_BUF_LASER_POWER,
        ["segNo": Long, "power": Long, "ch": Short]),
    kind!(9, "BUF_LASER_ONOFF", "TCrdBufLaserOnOff", table::CRD_BUF_LASER_ON_OFF,
        ["segNo": Long, "onOff": Short, "ch": Short]),
    kind!(10, "BUF_LASER_SETFOLLOW", "TCrdBufLaserFollow", table::CRD_BUF_LASER_SET_FOLLOW,
        ["segNo": Long, "overRide": Double, "followType": Short, "ch": Short]),
    kind!(11, "BUF_LASER_SETPARAM", "TCrdBufLaserParam", table::CRD_BUF_LASER_SET_PARAM,
        ["segNo": Long, "onDelay": Long, "offDelay": Long, "minValue": Long, "maxValue": Long, "standbyPower": Long, "ch": Short]),
    kind!(12, "BUF_LINEXYZA", "TCrdBufLineXYZA", table::CRD_LINE_XYZA,
        ["segNo": Long, "mask": Short, "tgPos": Longs(4), "endVel": Double, "vel": Double, "synAcc": Double, "lookaheadDis": Short]),
    kind!(13, "BUF_SHIO_GATEPULSE", "TCrdBufShioGatePulse", table::CRD_BUF_SHIO_GATE_PULSE,
        ["segNo": Long, "gateTime": Double, "gateFrq": Double, "outCount": Long, "ch": Short]),
    kind!(14, "BUF_DOBITPULSE", "TCrdBufDoBitPulse", table::CRD_BUF_DO_BIT_PULSE_ENABLE,
        ["segNo": Long, "doType": Short, "doIndex": Short, "highLevelTime": Long, "lowLevelTime": Long, "outCount": Long, "initialLevel": Short, "ch": Short]),
    kind!(15, "BUF_XYZD8", "TCrdLineXYZD8Unit", table::CRD_LINE_XYZ_D8_PACK,
        ["segNo": Long, "crdAxMask": Short, "extAxMask": Short, "tgPos": LongsInline(8), "vel": Float, "endVel": Float, "acc": Float, "lookaheadDis": Short, "reserved": Reserved]),
    kind!(16, "BUF_SHIOMINFRQ", "TCrdBufShioMinFrq", table::CRD_BUF_SHIO_SET_MIN_FRQ,
        ["segNo": Long, "minFrq": Long, "ch": Short]),
    kind!(17, "BUF_SHIOSETPARAM", "TCrdBufShioParam", table::CRD_BUF_SHIO_SET_PARAM,
        ["segNo": Long, "delay": Double, "gateTime": Double, "gateDistance": Double, "ch": Short]),
    kind!(18, "BUF_SHIOGATEONOFF", "TCrdBufShioGateOnOff", table::BUF_SHIO_GATE_ON,
        ["segNo": Long, "onOff": Short, "ch": Short]),
    kind!(19, "BUF_WAITENCINPOS", "TCrdBufWaitEncInPos", table::CRD_BUF_WAIT_ENC_IN_POSITION,
        ["segNo": Long, "axisMask": Long, "overTime": Long]),
    kind!(20, "BUF_WAITDI", "TCrdBufWaitDI", table::CRD_BUF_WAIT_DI,
        ["segNo": Long, "index": Short, "diValue": Short, "waitLastTime": Long]),
];

/// The C size of `fields` (natural alignment, rounded up to the largest member's).
pub fn c_size(fields: &[(&str, Field)]) -> usize {
    let mut at = 0usize;
    let mut max_align = 1usize;
    for (_, f) in fields {
        at = at.next_multiple_of(f.align());
        at += f.size();
        max_align = max_align.max(f.align());
    }
    at.next_multiple_of(max_align)
}

/// One entry of a pack: its kind and its function's wire payload after the handle.
#[derive(Clone, Debug, PartialEq)]
pub struct Entry {
    pub kind: &'static Kind,
    pub wire: Vec<u8>,
}

/// What is wrong with a pack.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum PackError {
    TooLong(usize),
    UnknownType {
        entry: usize,
        at: usize,
        cmd_type: i16,
    },
    Truncated {
        entry: usize,
        at: usize,
        name: &'static str,
        need: usize,
        left: usize,
    },
}

impl std::fmt::Display for PackError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            PackError::TooLong(n) => write!(f, "the pack holds {n} bytes; at most {PACK_MAX_BYTES}"),
            PackError::UnknownType { entry, at, cmd_type } => write!(
                f,
                "entry {entry} at byte {at}: cmdType {cmd_type} is none of BUF_LINE (0) … BUF_WAITDI (20)"
            ),
            PackError::Truncated { entry, at, name, need, left } => write!(
                f,
                "entry {entry} at byte {at}: {name} needs {need} bytes; {left} are left"
            ),
        }
    }
}

fn le<const N: usize>(b: &[u8], at: usize) -> [u8; N] {
    let mut out = [0u8; N];
    if let Some(s) = b.get(at..at + N) {
        out.copy_from_slice(s);
    }
    out
}

/// The entries of pack `bytes`, in order.
pub fn decode(bytes: &[u8]) -> Result<Vec<Entry>, PackError> {
    if bytes.len() > PACK_MAX_BYTES {
        return Err(PackError::TooLong(bytes.len()));
    }
    let mut out = Vec::new();
    let mut at = 0;
    while at < bytes.len() {
        let entry = out.len();
        let left = bytes.len() - at;
        if left < 2 {
            return Err(PackError::Truncated {
                entry,
                at,
                name: "cmdType",
                need: 2,
                left,
            });
        }
        let cmd_type = i16::from_le_bytes(le(bytes, at));
        let kind = KINDS
            .iter()
            .find(|k| k.cmd_type == cmd_type)
            .ok_or(PackError::UnknownType {
                entry,
                at,
                cmd_type,
            })?;
        at += 2;
        let size = c_size(kind.fields);
        let left = bytes.len() - at;
        let body = bytes.get(at..at + size).ok_or(PackError::Truncated {
            entry,
            at,
            name: kind.struct_name,
            need: size,
            left,
        })?;
        out.push(Entry {
            kind,
            wire: transcode(kind.fields, body),
        });
        at += size;
    }
    Ok(out)
}

/// The wire form of one C struct (`body` is exactly its size).
fn transcode(fields: &[(&str, Field)], body: &[u8]) -> Vec<u8> {
    let mut w = Writer::new();
    let mut at = 0usize;
    for (_, f) in fields {
        at = at.next_multiple_of(f.align());
        match *f {
            Short => {
                w.i16(i16::from_le_bytes(le(body, at)));
            }
            Reserved => {}
            Long => {
                w.i64(i64::from_le_bytes(le(body, at)));
            }
            Float => {
                w.f64(f64::from(f32::from_le_bytes(le(body, at))));
            }
            Double => {
                w.f64(f64::from_le_bytes(le(body, at)));
            }
            Longs(n) | LongsInline(n) => {
                if matches!(f, Longs(_)) {
                    w.u16(n as u16);
                }
                for k in 0..n {
                    w.i64(i64::from_le_bytes(le(body, at + 8 * k)));
                }
            }
        }
        at += f.size();
    }
    w.bytes
}

/// The header text: the command types and mcemu's structs (`TCrdLineXYZD8Unit` is declared
/// with the coordinate-system structs).
pub fn c_declarations() -> String {
    let mut s = String::from(
        "/* Advanced buffered I/O, NMC_AdvBufIoSetParam (digest 001 §3.12). */\n\
         #define MAX_ADV_BUFIO_GROUP 2\n\
         #define BUF_OUT_GROUP_DA  0\n\
         #define BUF_OUT_GROUP_PWM 1\n\
         typedef struct {\n    short outType;\n    short outGroup;\n    short outIndex;\n    \
         short outSns;\n    short pulseMode;\n    short reserved1;\n    long pulseOnTime;\n    \
         long pulseOffTime;\n    unsigned char reserved[32];\n} TAdvBufIoParam;\n\n\
         /* NMC_CrdBufDataPack (digest 001 §3.11): [short cmdType][struct] repeated, at most 1000\n \
         * bytes. The structs are mcemu's (the manual defines none): each holds the arguments of\n \
         * the function its type stands for, after the handle, in order. */\n",
    );
    for k in KINDS {
        s.push_str(&format!("#define {} {}\n", k.macro_name, k.cmd_type));
    }
    for k in KINDS
        .iter()
        .filter(|k| k.struct_name != "TCrdLineXYZD8Unit")
    {
        s.push_str("typedef struct {");
        for (name, f) in k.fields {
            s.push(' ');
            s.push_str(&f.c_decl(name));
        }
        s.push_str(&format!(" }} {};\n", k.struct_name));
    }
    s.push('\n');
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_line_struct_has_the_c_layout_and_reads_back_as_its_call() {
        let line = KINDS.first().unwrap();
        // long, short(+6), long[3], 3 double, short(+6).
        assert_eq!(c_size(line.fields), 8 + 8 + 24 + 24 + 8);
        let mut pack = Vec::new();
        pack.extend_from_slice(&0i16.to_le_bytes());
        let mut body = vec![0u8; 72];
        body[0..8].copy_from_slice(&7i64.to_le_bytes());
        body[8..10].copy_from_slice(&3i16.to_le_bytes());
        body[16..24].copy_from_slice(&2000i64.to_le_bytes());
        body[24..32].copy_from_slice(&1000i64.to_le_bytes());
        body[48..56].copy_from_slice(&10f64.to_le_bytes());
        pack.extend_from_slice(&body);
        let e = decode(&pack).unwrap();
        assert_eq!(e.len(), 1);
        let mut r = Reader::new(&e[0].wire);
        assert_eq!(r.i64().unwrap(), 7);
        assert_eq!(r.i16().unwrap(), 3);
        assert_eq!(r.u16().unwrap(), 3);
        assert_eq!(
            [r.i64().unwrap(), r.i64().unwrap(), r.i64().unwrap()],
            [2000, 1000, 0]
        );
        assert_eq!(r.f64().unwrap(), 0.0);
        assert_eq!(r.f64().unwrap(), 10.0);
    }

    #[test]
    fn bad_packs_name_the_entry() {
        assert!(matches!(
            decode(&[21, 0]),
            Err(PackError::UnknownType { cmd_type: 21, .. })
        ));
        assert!(matches!(
            decode(&[3, 0, 1, 2]),
            Err(PackError::Truncated { entry: 0, .. })
        ));
        assert_eq!(decode(&[0; 1001]), Err(PackError::TooLong(1001)));
        assert_eq!(decode(&[]), Ok(Vec::new()));
    }

    #[test]
    fn every_type_of_the_manual_is_there_once() {
        let types: Vec<i16> = KINDS.iter().map(|k| k.cmd_type).collect();
        assert_eq!(types, (0..=20).collect::<Vec<i16>>());
    }
}
