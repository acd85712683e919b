//! The C headers, generated from [`crate::table`] and [`crate::errors`]. The generated text is
//! committed under `protocols/nmc-shim/include/` (so `gcc -I protocols/nmc-shim/include` needs no
//! build step); a test fails when the committed files differ, and `NMC_BLESS=1 cargo test -p
//! mcemu-nmc header` rewrites them (docs/decisions.md, "NMC front-end (issue 13)").

use crate::errors::CODES;
use crate::table::{Arg, CType, Dir, HeaderFile, FUNCTIONS};

/// Types, structs and constants of `mtn_lib20.h` (digest 001 §3, verbatim names).
const MAIN_PREAMBLE: &str = r#"/* mtn_lib20.h: mcemu's nmc_lib20, a drop-in replacement of the Gaochuan NMC_* library.
 * Generated from protocols/nmc/src/table.rs by protocols/nmc/src/header.rs: do not edit.
 * Names, argument order and C types are the manual's (digest 001 §2-§3); `long` is the
 * platform's long. Every function returns 0 (RTN_CMD_SUCCESS) or an error code of
 * mtn_lib20_err.h. */
#ifndef MTN_LIB20_H
#define MTN_LIB20_H

#include "mtn_lib20_err.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef unsigned short HAND;
typedef HAND *PHAND;
typedef short Int16;

typedef enum { USB = 0, Ethernet = 1, RS485 = 2 } TSearchMode;

/* Axis status word, NMC_MtGetSts (digest 001 §3.1). */
#define BIT_AXIS_BUSY       0x00000001
#define BIT_AXIS_POSREC     0x00000002
#define BIT_AXIS_MVERR      0x00000004
#define BIT_AXIS_SVON       0x00000008
#define BIT_AXIS_CRD        0x00000010
#define BIT_AXIS_STEP       0x00000020
#define BIT_AXIS_LMTP       0x00000040
#define BIT_AXIS_LMTN       0x00000080
#define BIT_AXIS_SOFTPOSLMT 0x00000100
#define BIT_AXIS_SOFTNEGLMT 0x00000200
#define BIT_AXIS_ALM        0x00000400
#define BIT_AXIS_POSERR     0x00000800
#define BIT_AXIS_ESTP       0x00001000
#define BIT_AXIS_HWERR      0x00002000
#define BIT_AXIS_CAPTSET    0x00004000

/* Profile modes, NMC_MtSetPrfMode (digest 001 §3.2). */
#define MT_NONE_PRF_MODE   (-1)
#define MT_PTP_PRF_MODE    (0)
#define MT_JOG_PRF_MODE    (1)
#define MT_CRD_PRF_MODE    (3)
#define MT_GANTRY_MODE     (4)
#define MT_PT_PRF_MODE     (5)
#define MT_MULTI_LINE_MODE (6)
#define MT_GEAR_PRF_MODE   (7)
#define MT_FOLLOW_PRF_MODE (8)

/* Homing modes and NMC_MtGetHomeSts bits (digest 001 §3.13; values inferred, §8 item 3). */
#define HM_MODE1 (1)
#define HM_MODE2 (2)
#define HM_MODE3 (3)
#define HM_MODE4 (4)
#define HM_MODE5 (5)
#define HM_MODE6 (6)
#define BIT_AXHOME_BUSY    0x0001
#define BIT_AXHOME_OK      0x0002
#define BIT_AXHOME_FAIL    0x0004
#define BIT_AXHOME_ERR_MV  0x0008
#define BIT_AXHOME_ERR_SWT 0x0010

/* NMC_MtGetMotionIO bits (digest 001 §3.3; names inferred). */
#define BIT_AXMTIO_LMTN  0x0001
#define BIT_AXMTIO_LMTP  0x0002
#define BIT_AXMTIO_HOME  0x0004
#define BIT_AXMTIO_ALM   0x0008
#define BIT_AXMTIO_INP   0x0010
#define BIT_AXMTIO_CAPT  0x0020

typedef struct { double estpDec; double maxVel; double maxAcc; } TSafePara;
typedef struct { double acc; double dec; double startVel; double endVel; short smoothCoef; short reserved[3]; } TPtpPara;
typedef struct { double acc; double dec; double smoothCoef; } TJogPara;

typedef struct {
    short mode;
    short dir;
    long offset;
    double scan1stVel;
    double scan2ndVel;
    double acc;
    unsigned char reScanEn;
    unsigned char homeEdge;
    unsigned char lmtEdge;
    unsigned char zEdge;
    unsigned long iniRetPos;
    unsigned long retSwOffset;
    unsigned long safeLen;
    unsigned char usePreSetPtpPara;
    unsigned char reserved[3];
    long reserved2;
} THomeSetting;

typedef struct { short ear; short mon; short day; short hour; short min; short second; } TNMCTime;

typedef struct {
    char strVer[16];
    char strOemVer[16];
    short time[6];
    short axisNum; short encNum; short diNum; short doNum; short daNum; short adNum; short shioNum; short reserved;
    char ipv4[4];
    char idStr[16];
    unsigned long uid[4];
} TCardInfo;

typedef struct { unsigned short address; char idStr[16]; char description[64]; unsigned short ID; } TDevInfo;

"#;

const MAIN_END: &str = r#"
#ifdef __cplusplus
}
#endif

#endif /* MTN_LIB20_H */
"#;

const EXT_PREAMBLE: &str = r#"/* mtn_lib20_ext.h: mcemu's additions to the NMC_* API.
 * Generated from protocols/nmc/src/table.rs by protocols/nmc/src/header.rs: do not edit. */
#ifndef MTN_LIB20_EXT_H
#define MTN_LIB20_EXT_H

#include "mtn_lib20.h"

#ifdef __cplusplus
extern "C" {
#endif

"#;

const EXT_END: &str = r#"
#ifdef __cplusplus
}
#endif

#endif /* MTN_LIB20_EXT_H */
"#;

/// The C spelling of argument `a`: `short itemNo`, `PHAND pDevHandle`, `long *pos` …
fn c_arg(a: &Arg) -> String {
    let base = match a.ty {
        CType::Short => "short",
        CType::UShort => "unsigned short",
        CType::Int => "int",
        CType::UInt => "unsigned int",
        CType::Long => "long",
        CType::ULong => "unsigned long",
        CType::UChar => "unsigned char",
        CType::Double => "double",
        CType::Hand => "HAND",
        CType::SearchMode => "TSearchMode",
        CType::Str => return format!("char *{}", a.name),
        CType::Bytes => return format!("unsigned char *{}", a.name),
        CType::Ipv4 => return format!("unsigned char *{}", a.name),
        CType::Struct(s) | CType::StructArray(s) => return format!("{s} *{}", a.name),
        CType::ShortArray => return format!("short *{}", a.name),
        CType::LongArray => return format!("long *{}", a.name),
        CType::ULongArray => return format!("unsigned long *{}", a.name),
        CType::DoubleArray => return format!("double *{}", a.name),
    };
    match (a.ty, a.dir) {
        (CType::Hand, Dir::Out) => format!("PHAND {}", a.name),
        (_, Dir::Out) => format!("{base} *{}", a.name),
        (_, Dir::In) => format!("{base} {}", a.name),
    }
}

/// The prototypes of the rows declared in `file`.
fn prototypes(file: HeaderFile) -> String {
    let mut s = String::new();
    for f in FUNCTIONS.iter().filter(|f| f.header == file) {
        let args: Vec<String> = f.args.iter().map(c_arg).collect();
        let args = if args.is_empty() {
            "void".to_string()
        } else {
            args.join(", ")
        };
        s.push_str(&format!("short {}({args});\n", f.name));
    }
    s
}

/// `mtn_lib20.h`.
pub fn main_header() -> String {
    format!(
        "{MAIN_PREAMBLE}{}{}{}{}{}{}{}{}{}{}{MAIN_END}",
        crate::sync_header::SYNC_PREAMBLE,
        crate::laser::LASER_PREAMBLE,
        crate::ax_header::AX_PREAMBLE,
        crate::io_header::IO_PREAMBLE,
        crate::crd::C_DECLARATIONS,
        crate::crd_lookahead::C_DECLARATIONS,
        crate::buf_pack::c_declarations(),
        crate::crd_frames::C_DECLARATIONS,
        crate::sys::SYS_PREAMBLE,
        prototypes(HeaderFile::Main)
    )
}

/// `mtn_lib20_ext.h`.
pub fn ext_header() -> String {
    format!("{EXT_PREAMBLE}{}{EXT_END}", prototypes(HeaderFile::Ext))
}

/// `mtn_lib20_err.h`: the codes of [`crate::errors`].
pub fn err_header() -> String {
    let mut s = String::from(
        "/* mtn_lib20_err.h: the return codes of mcemu's nmc_lib20 (not in the manual: mcemu's,\n \
         * stable). Generated from protocols/nmc/src/errors.rs: do not edit. */\n\
         #ifndef MTN_LIB20_ERR_H\n#define MTN_LIB20_ERR_H\n\n\
         #define RTN_CMD_SUCCESS (0)\n",
    );
    for c in CODES {
        s.push_str(&format!(
            "#define {} ({}) /* {} */\n",
            c.name, c.code, c.description
        ));
    }
    s.push_str("\n#endif /* MTN_LIB20_ERR_H */\n");
    s
}

/// Every generated header: file name and text.
pub fn headers() -> [(&'static str, String); 3] {
    [
        ("mtn_lib20.h", main_header()),
        ("mtn_lib20_ext.h", ext_header()),
        ("mtn_lib20_err.h", err_header()),
    ]
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::table::{by_name, MT_MOVE_PTP_ABS};

    #[test]
    fn prototypes_read_as_the_manual_writes_them() {
        let h = main_header();
        assert!(h.contains("short NMC_MtGetSts(HAND axisHandle, short *pStsWord);\n"));
        assert!(h.contains("short NMC_DevOpen(short devNo, PHAND pDevHandle);\n"));
        assert!(h.contains("short NMC_GetLastErr(void);\n"));
        assert!(h.contains(
            "short NMC_MtMovePtpAbs(HAND axisHandle, double acc, double dec, double startVel, \
             double endVel, double maxVel, short smoothCoef, long tgtPos);\n"
        ));
        assert_eq!(MT_MOVE_PTP_ABS.args.len(), 8);
        assert!(ext_header().contains("short NMC_DevClose(PHAND pDevHandle);\n"));
        assert!(by_name("NMC_DevClose").is_some());
        assert!(err_header().contains("#define RTN_COMM_ERROR (-1)"));
    }

    /// The committed headers are the generated ones (`NMC_BLESS=1` rewrites them).
    #[test]
    fn committed_headers_are_up_to_date() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../nmc-shim/include");
        let bless = std::env::var_os("NMC_BLESS").is_some();
        for (name, text) in headers() {
            let path = dir.join(name);
            if bless {
                std::fs::create_dir_all(&dir).unwrap();
                std::fs::write(&path, &text).unwrap();
            }
            let committed = std::fs::read_to_string(&path).unwrap_or_default();
            assert!(
                committed == text,
                "{} differs from the table: run NMC_BLESS=1 cargo test -p mcemu-nmc header",
                path.display()
            );
        }
    }
}
