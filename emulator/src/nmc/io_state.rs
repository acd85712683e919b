//! The NMC device's I/O settings the engine has no model of (digest 001 §2.8, §2.20, §4.8):
//! which extension modules are enabled and as what, the alarm-clear and high-speed outputs, the
//! ID string written for the next power-up, the inverted bits. Shared by the device's
//! connections.

use std::collections::{BTreeMap, BTreeSet};

use mcemu_nmc::buf_pack::{AdvBufIoParam, MAX_ADV_BUFIO_GROUP};
use mcemu_nmc::io_structs::DioMapping;

/// Extension modules take ids 2 … 9 (digest 001 §2.8, §4.8).
pub const MODULE_FIRST: u8 = 2;
pub const MODULE_LAST: u8 = 9;
/// `IOMODULE_TYPE_IO64`: 32 DI and 32 DO (digest 001 §3.10).
pub const IOMODULE_TYPE_IO64: i16 = 1;
/// `IOMODULE_TYPE_IO32_DA`: 4 AD and 4 DA.
pub const IOMODULE_TYPE_IO32_DA: i16 = 2;
/// Local general I/O bits (groups 0 and 1); extension module `k` holds bits
/// 64 + 32·(k − 2) … + 31 (digest 001 §4.8).
pub const LOCAL_BITS: usize = 64;

#[derive(Clone, Debug)]
pub struct IoState {
    /// `NMC_IOModuleSetEn` type by module id − 2 (0 = not enabled).
    pub modules: [i16; (MODULE_LAST - MODULE_FIRST + 1) as usize],
    /// The alarm-clear outputs (DO_TYPE_MOTOR_CLEAR), bit = axis; 1 = inactive (high), the
    /// default (NMC_MtSetSvClr: 0 active).
    pub alarm_clear: u32,
    /// The high-speed outputs (DO_TYPE_HSIO): the machine has none; stored and read back.
    pub hsio: u32,
    /// `NMC_DevWriteID`: what `NMC_DevReadID` reads; `NMC_DevOpenByID` takes it after a restart
    /// (the manual: "effective after power cycle").
    pub written_id: Option<String>,
    /// General DI bits inverted by `NMC_SetDIBitRevs` (what `NMC_GetDIEx` / `GetDIGroup` read).
    pub di_revs: BTreeSet<usize>,
    /// General DO bits inverted by `NMC_SetDOBitRevs`: the terminal drives the opposite level.
    pub do_revs: BTreeSet<usize>,
    /// `NMC_SetDOBitRevsEx` of the servo-enable (1) and alarm-clear (2) outputs, by (type,
    /// axis): stored and read back (the machine models no terminal for them).
    pub do_revs_ex: BTreeSet<(i16, usize)>,
    /// `NMC_SetDIFilter` by (type, group, index), ms; unset = 3 (digest 001 §2.8).
    pub di_filters: BTreeMap<(i16, i16, i16), i16>,
    /// `NMC_SetDiReverseCount`: the engine's edge count of a general DI at which the counter
    /// read 0 (wrapping), by bit.
    pub edge_base: BTreeMap<usize, u32>,
    /// `NMC_DoBitPulseEnable` channel → the DO bit its train drives.
    pub pulse_channels: [Option<usize>; MAX_NUM_DOBIT_PULSE],
    /// `NMC_SetDioMapping`, at most [`MAX_DIO_MAPPING`], in the order added.
    pub dio_mappings: Vec<DioMapping>,
    /// The system password (`NMC_SetTime`, `NMC_ChangePassword`).
    pub password: String,
    /// `NMC_DevSetPara` values by id, and whether `PARA_WRITE_EN` persisted them.
    pub para: BTreeMap<u64, i64>,
    pub para_written: bool,
    /// `NMC_SetTime`: the RTC minus the host's clock, seconds.
    pub rtc_offset: i64,
    /// `NMC_SetBackedVarOnOff` (default off).
    pub backed: bool,
    /// `NMC_AdvBufIoSetParam` by channel (`MAX_ADV_BUFIO_GROUP`), none until set.
    pub adv_buf_io: [Option<AdvBufIoChannel>; MAX_ADV_BUFIO_GROUP],
}

/// One advanced buffered I/O channel: its parameters, the digital output they name, and the
/// engine's pulse count of that output when they were set (`NMC_AdvBufIoGetPulseCnt` counts
/// from there).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AdvBufIoChannel {
    pub param: AdvBufIoParam,
    pub output: u16,
    pub pulse_base: u32,
}

/// The system password of a fresh device (the manual gives none; mcemu's).
pub const DEFAULT_PASSWORD: &str = "123456";

/// `MAX_NUM_DOBIT_PULSE` (mtn_lib20.h).
pub const MAX_NUM_DOBIT_PULSE: usize = 8;
/// Mappings `NMC_SetDioMapping` keeps (digest 001 §3.12: ≤ 8).
pub const MAX_DIO_MAPPING: usize = 8;
/// The DI filter of an input never set, ms (digest 001 §2.8).
pub const DEFAULT_DI_FILTER: i16 = 3;

impl Default for IoState {
    fn default() -> IoState {
        IoState {
            modules: [0; (MODULE_LAST - MODULE_FIRST + 1) as usize],
            alarm_clear: u32::MAX,
            hsio: 0,
            written_id: None,
            di_revs: BTreeSet::new(),
            do_revs: BTreeSet::new(),
            do_revs_ex: BTreeSet::new(),
            di_filters: BTreeMap::new(),
            edge_base: BTreeMap::new(),
            pulse_channels: [None; MAX_NUM_DOBIT_PULSE],
            adv_buf_io: [None; MAX_ADV_BUFIO_GROUP],
            dio_mappings: Vec::new(),
            password: DEFAULT_PASSWORD.to_string(),
            para: BTreeMap::new(),
            para_written: false,
            rtc_offset: 0,
            backed: false,
        }
    }
}

impl IoState {
    /// The inverted DI bits of the 32 from `start`, as a mask.
    pub fn di_revs_word(&self, start: usize) -> u32 {
        self.di_revs
            .range(start..start + 32)
            .fold(0, |v, b| v | 1 << (b - start))
    }

    /// The inverted DO bits of the 32 from `start`, as a mask.
    pub fn do_revs_word(&self, start: usize) -> u32 {
        self.do_revs
            .range(start..start + 32)
            .fold(0, |v, b| v | 1 << (b - start))
    }

    /// Whether DO bit `bit` is inverted.
    pub fn do_rev(&self, bit: usize) -> bool {
        self.do_revs.contains(&bit)
    }

    /// The enabled type of module `id` (0 = not enabled or no such id).
    pub fn module_type(&self, id: u8) -> i16 {
        id.checked_sub(MODULE_FIRST)
            .and_then(|k| self.modules.get(usize::from(k)))
            .copied()
            .unwrap_or(0)
    }
}
