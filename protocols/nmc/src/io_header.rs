//! The C declarations of the I/O-by-type, extension-module and controller-service families
//! (0x12xx, digest 001 §3.10, §3.12, §3.18, §3.19): constants and structs `mtn_lib20.h` needs
//! for their prototypes. Values the manual leaves undefined (§8 item 3) are mcemu's, recorded
//! in docs/decisions.md ("NMC I/O, encoders, modules and controller services").

/// Appended to `mtn_lib20.h`'s preamble by [`crate::header`].
pub const IO_PREAMBLE: &str = r#"/* DO and DI types (digest 001 §2.8, §3.10), extension modules. */
#define DO_TYPE_MOTOR_ENABLE 1
#define DO_TYPE_MOTOR_CLEAR  2
#define DO_TYPE_MOTOR_CLEA   DO_TYPE_MOTOR_CLEAR
#define DO_TYPE_GPDO         3
#define DO_TYPE_HSIO         4
#define DI_TYPE_GPI     0
#define DI_TYPE_LMTN    1
#define DI_TYPE_LMTP    2
#define DI_TYPE_HOME    3
#define DI_TYPE_Z       4
#define IOMODULE_TYPE_IO64    1
#define IOMODULE_TYPE_IO32_DA 2

/* NMC_DoBitPulseEnable channels (digest 001 §2.7; the count is mcemu's, §8 item 3). */
#define MAX_NUM_DOBIT_PULSE 8
/* NMC_SetDioMapping: at most 8 mappings (digest 001 §3.12). */
typedef struct { unsigned char enable; unsigned char pinGrp; unsigned char pinIndex;
                 unsigned char outEnable; unsigned char newGrp; unsigned char newIndex; } TDioMappingCfg;
#define MAX_DIO_MAPPING 8

/* NMC_GetBackedVarGroup2 (digest 001 §3.18). */
typedef struct { long crdSegNo[2]; long crdPrfPos[2][3]; long axPrfPos[12]; long axisPos[12]; long encPos[12]; } TBackGroup2;
/* NMC_DevGetPara / NMC_DevSetPara ids (undefined by the manual, §8 item 3; mcemu's). */
#define PARA_IP_ADDRESS 1
#define PARA_WRITE_EN   0xFFFF

/* NMC_GetMtLibVersion: not defined by the manual (digest 001 §8 item 3); mcemu's. */
typedef struct { char strVer[16]; short major; short minor; short patch; short reserved; } TmLibVersion;

"#;
