//! The part of `mtn_lib20.h` before the prototypes that the synchronised-motion families add:
//! their constants and structs (digest 001 §3.15–§3.17, verbatim names; `long` the platform's).

/// Appended to `crate::header`'s preamble.
pub const SYNC_PREAMBLE: &str = r#"/* PT segment types, NMC_MtPtPush (digest 001 §3.17). */
#define MT_PT_NORMAL (0)
#define MT_PT_STOP   (1)
#define MT_PT_EVEN   (2)

typedef struct { double smoothDec; double abruptDec; double reserved1[2]; long reserved2[4]; } TPtPara;
typedef struct { double smoothDec; double abruptDec; double reserved1[2]; long dataMode; long loopCount; long reserved2[4]; } TPvtPara;

/* Capture (digest 001 §3.15). */
#define CAPT_MODE_Z        0
#define CAPT_MODE_IO       1
#define CAPT_MODE_Z_AND_IO 2
#define CAPT_MODE_Z_AFT_IO 3
#define CAPT_IO_SRC_HOME 0
#define CAPT_IO_SRC_LMTN 1
#define CAPT_IO_SRC_LMTP 2
#define CAPT_IO_SRC_DI0  3
#define CAPT_IO_SRC_DI1  4
#define CAPT_IO_SRC_DI2  5
#define CAPT_IO_SRC_DI3  6
#define CAPT_IO_SRC_DI4  7
#define CAPT_IO_SRC_DI5  8
#define CAPT_IO_SRC_DI6  9
#define CAPT_IO_SRC_DI7  10
#define CAPT_IO_SRC_DI8  11
#define CAPT_IO_SRC_DI9  12
#define CAPT_IO_SRC_DI10 13
#define CAPT_IO_SRC_DI11 14
#define CAPT_IO_SRC_DI12 15
#define CAPT_EX_SRC_GPI    0
#define CAPT_EX_SRC_NEGLMT 1
#define CAPT_EX_SRC_POSLMT 2
#define CAPT_EX_SRC_HOME   3
#define CAPT_EX_SRC_Z      4
#define CAPT_EX_SRC_PRFPOS 5
#define CAPT_EX_SRC_ENCPOS 6
#define REPEAT_CAPT_MAX_NUM 64

typedef struct {
    short capPosIndex;
    short trigSrc;
    short trigIndex;
    short filter;
    long trigValue;
} TAdvCaptureParam;

/* Position compare (digest 001 §3.16). */
typedef struct {
    short outputChn;
    short outputType;
    short chnType;
    short dir1No;
    short dir2No;
    short posSrc;
    short stLevel;
    short errZone;
    short directOutZone;
    short vibrateRange;
    long gateTime;
    long minIntervalTime;
    long reserved[8];
} TComp2DimensParamEx;
typedef struct { short sts; short reserved1; long freeSpace; long usedSpace; long outCount; long reserved2[4]; } TComp2DimensSts;

/* Compensation (digest 001 §3.17). */
typedef struct { short count[2]; short reserved[2]; long posBegin[2]; long step[2]; double angle; } T2DCompensationTable;
typedef struct { long xDirComp; long yDirComp; long zDirComp; } TCompData;
typedef struct { short enable; short tableIndex; short axisType[2]; short axisIndex[3]; } T2DCompensation;

"#;
