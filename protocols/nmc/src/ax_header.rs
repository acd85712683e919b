//! The part of `mtn_lib20.h` before the prototypes that the axis-level additions (id family
//! 0x13xx) add: the packed status and packed PTP structs and the advanced E-stop input
//! and the Follow master types (digest 001 §3.4, §3.6, §3.17, verbatim names; `long` the
//! platform's).

/// Appended to `crate::header`'s preamble.
pub const AX_PREAMBLE: &str = r#"/* Packed PTP moves, NMC_MtMovePtpAbsPack8 / NMC_MtMovePtpRelPack8 (digest 001 §3.6). */
typedef struct {
    short axisMask;
    short clrStsFlag;
    short reserved[2];
    double acc[8];
    double dec[8];
    double startVel[8];
    double endVel[8];
    double maxVel[8];
    short smoothCoef[8];
    long tgtPos[8];
} TMovePtpPack8;

/* Packed status of 12 axes, NMC_MtGetStsPack12Ex (digest 001 §3.4). */
typedef struct {
    short mtSts[12];
    short mtMio[12];
    short mtMioLog[12];
    long mtPrfPos[12];
    long mtEncPos[12];
    float mtPrfVel[12];
    short crdSts[2];
    float crdPrfVel[2];
    long crdUserSeg[2];
    long crdFreeSpace[2];
    long crdUsedSpace[2];
    long gpi;
    long gpo;
    long crdLeftLen[2];
    long crdAllCmdCnt[2];
    long extDi[6];
    long extDo[6];
    short adc[4];
    short adcAux[2];
    short dac[4];
    short dacAux[2];
    long reserved[10];
} TAxisStsPack12Ex;

/* Advanced E-stop inputs, NMC_SetEstopDIEx (digest 001 §3.6); the group count is mcemu's. */
#define ESTOP_DI_EX_CH_NUM 4
typedef struct {
    short axMask;
    short diType;
    short diIndex;
    short filter;
    long diSense;
    long reserved[3];
} TEstopExParam;

/* Follow masters, NMC_MtFollowSetMaster (digest 001 §3.17). */
#define PROFILE_FOLLOW_MASTER_NONE     (0)
#define PROFILE_FOLLOW_MASTER_AXIS_PRF (1)
#define PROFILE_FOLLOW_MASTER_AXIS_ENC (2)
#define PROFILE_FOLLOW_MASTER_ENC      (3)

/* Closed loop, NMC_MtSetCloseLoopDac / NMC_MtSetPIDPara (digest 001 §3.17). */
typedef struct { short inverse; short bias; short dacLmt; } TDacMotor;
typedef struct { float kp; float ki; float kd; float kvff; long integralLimit; long derivativeLimit; short outLimit; } TPidPara;

"#;
