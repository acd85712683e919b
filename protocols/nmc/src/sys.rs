//! The system family (0x18xx, helper nmcsys): data collection (digest 001 §2.20 "Data
//! collection", §3.19, S-COLLECT), users, the configuration file, the execution-time
//! calculation. Its C declarations and its structs as the wire carries them (fields in
//! declaration order, `unsigned long` as u64). Values the manual leaves undefined (§8 item 3:
//! `COLLECT_LIST_MAX`, the trigger modes, the status bits) are mcemu's, recorded in
//! docs/decisions.md ("NMC system functions (nmcsys)").

use crate::payload::{PayloadError, Reader, Writer};

/// Variables one collection records (`COLLECT_LIST_MAX`; the engine's sampler holds 8).
pub const COLLECT_LIST_MAX: usize = 8;
/// Bytes one `NMC_GetCollectData` returns at most (digest 001 §2.20).
pub const COLLECT_DATA_MAX: usize = 1440;
/// Bytes of a configuration text the wire carries (one frame's payload, less its header).
pub const CONFIG_TEXT_MAX: usize = 16 * 1024 - 64;

/// Appended to `mtn_lib20.h`'s preamble by [`crate::header`].
pub const SYS_PREAMBLE: &str = r#"/* Data collection (digest 001 §3.19). COLLECT_LIST_MAX, the trigger modes and the status
 * bits are not in the manual (§8 item 3): mcemu's. Every value is 8 bytes, a little-endian
 * double (pulses, pulse/ms, 0/1), as the manual's example reads them into a double array. */
#define COLLECT_ADDRESS_PRF_POS (0)
#define COLLECT_ADDRESS_AXIS_POS (1)
#define COLLECT_ADDRESS_ENC_POS (2)
#define COLLECT_ADDRESS_CMD_POS (3)
#define COLLECT_ADDRESS_AXIS_VEL (4)
#define COLLECT_ADDRESS_CRD_POS (5)
#define COLLECT_ADDRESS_CRD_VEL (6)
#define COLLECT_ADDRESS_CRD_POS0 (5)
#define COLLECT_ADDRESS_CRD_VELO (6)
#define COLLECT_ADDRESS_CRD_VEL0 (6)
#define COLLECT_ADDRESS_ENC_VEL (7)
#define COLLECT_ADDRESS_CMD_VEL (8)
#define COLLECT_ADDRESS_CRD_POS1 (9)
#define COLLECT_ADDRESS_CRD_VEL1 (10)
#define COLLECT_ADDRESS_LASER_OUTPUT (11)
#define COLLECT_ADDRESS_LASER_GATE (12)
#define COLLECT_ADDRESS_LASER_POWER (13)
#define COLLECT_ADDRESS_DI (14)
#define COLLECT_ADDRESS_DO (15)
#define COLLECT_LIST_MAX 8
#define COLLECT_DATA_MAX 1440
/* TCollectTrig.mode: NONE records at once; RISE / FALL when channel source1 of the list
 * crosses value upwards / downwards. */
#define COLLECT_MODE_NONE 0
#define COLLECT_MODE_RISE 1
#define COLLECT_MODE_FALL 2
/* NMC_GetCollectSts bits. */
#define COLLECT_STS_ON        0x1
#define COLLECT_STS_TRIGGERED 0x2
#define COLLECT_STS_FULL      0x4
/* NMC_DevGetConfigText (mtn_lib20_ext.h, mcemu's) writes at most this many bytes. */
#define NMC_CONFIG_TEXT_MAX 16320
typedef struct { short count; short interval; unsigned long address[COLLECT_LIST_MAX];
                 short length[COLLECT_LIST_MAX]; } TCollectCfg;
typedef struct { short mode; short source1; short source2; short startDelay; double value; } TCollectTrig;

"#;

/// `TCollectCfg`: `count` variables, each an address of `NMC_GetCollectDataAddr` and its byte
/// length; `interval` ms between samples, 0 every planning period.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CollectCfg {
    pub count: i16,
    pub interval: i16,
    pub address: [u64; COLLECT_LIST_MAX],
    pub length: [i16; COLLECT_LIST_MAX],
}

impl CollectCfg {
    pub fn write(&self, w: &mut Writer) {
        w.i16(self.count).i16(self.interval);
        for a in self.address {
            w.u64(a);
        }
        for l in self.length {
            w.i16(l);
        }
    }
    pub fn read(r: &mut Reader<'_>) -> Result<CollectCfg, PayloadError> {
        let mut c = CollectCfg {
            count: r.i16()?,
            interval: r.i16()?,
            ..CollectCfg::default()
        };
        for a in &mut c.address {
            *a = r.u64()?;
        }
        for l in &mut c.length {
            *l = r.i16()?;
        }
        Ok(c)
    }
}

/// `TCollectTrig`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CollectTrig {
    pub mode: i16,
    pub source1: i16,
    pub source2: i16,
    pub start_delay: i16,
    pub value: f64,
}

impl CollectTrig {
    pub fn write(&self, w: &mut Writer) {
        w.i16(self.mode)
            .i16(self.source1)
            .i16(self.source2)
            .i16(self.start_delay)
            .f64(self.value);
    }
    pub fn read(r: &mut Reader<'_>) -> Result<CollectTrig, PayloadError> {
        Ok(CollectTrig {
            mode: r.i16()?,
            source1: r.i16()?,
            source2: r.i16()?,
            start_delay: r.i16()?,
            value: r.f64()?,
        })
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn structs_round_trip() {
        let c = CollectCfg {
            count: 2,
            interval: 1,
            address: [7, 9, 0, 0, 0, 0, 0, u64::MAX],
            length: [8, 8, 0, 0, 0, 0, 0, -1],
        };
        let t = CollectTrig {
            mode: 1,
            source1: 0,
            source2: 0,
            start_delay: 0,
            value: 2.5,
        };
        let mut w = Writer::new();
        c.write(&mut w);
        t.write(&mut w);
        let mut r = Reader::new(&w.bytes);
        assert_eq!(CollectCfg::read(&mut r).unwrap(), c);
        assert_eq!(CollectTrig::read(&mut r).unwrap(), t);
        r.finish().unwrap();
    }
}
