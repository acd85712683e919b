/* mtn_lib20.h: mcemu's nmc_lib20, a drop-in replacement of the Gaochuan NMC_* library.
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

/* PT segment types, NMC_MtPtPush (digest 001 §3.17). */
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

/* Laser and SHIO (digest 001 §2.12, §3.20). */
#define LASER_DISABLE_MODE     (0)
#define BASIC_OUTPUT_MODE      (1)
#define TIME_ARRAY_OUTPUT_MODE (2)
#define SHIO_OUTPUT_MODE       (3)
#define LASER_NONE        (0)
#define LASER_DA          (1)
#define LASER_PWM_DUTY    (2)
#define LASER_PWM_FRQ     (3)
#define LASER_PWM_FRQ_EXT (4)
#define LASER_GROUP (12)
#define LASET_POINT (40)

typedef struct {
    short pwmEnable;
    short outputType;
    short outputCh;
    short stLevelRevs;
    long pwmPeriod;
    long pwmWidth;
    long gateDistance;
    long minFrqFrq;
    short posSrc;
    short axisMask;
    short minFrqEn;
    short reserved2;
} TTimeArrayPara;
typedef struct { unsigned short time[LASET_POINT]; short power[LASET_POINT]; short count; } TLaserPower;
typedef struct {
    short isArray;
    short outMode;
    short posSrc;
    short axisMask;
    double delay;
    double gateTime;
    long gateDistance;
    long k;
    long startDot;
    long lowFrqRange;
    long reserved4;
    long reserved5;
} TSHIOPara;

/* Packed PTP moves, NMC_MtMovePtpAbsPack8 / NMC_MtMovePtpRelPack8 (digest 001 §3.6). */
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

/* DO and DI types (digest 001 §2.8, §3.10), extension modules. */
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

/* Coordinate system (digest 001 §3.7, §3.8, §3.10). */
#define BIT_CORD_BUSY           0x00000001
#define BIT_CORD_MVERR          0x00000002
#define BIT_CORD_EMPTY          0x00000004
#define BIT_CORD_FULL           0x00000008
#define BIT_CORD_NODATASTOP     0x00000010
#define BIT_CORD_SDRAM_HWERR    0x00000020
#define BIT_CORD_POSREC         0x00000040
#define BIT_CORD_AUXAXIS_BUSY   0x00000080
#define BIT_CORD_AUXAXIS_ERR    0x00000100
#define BIT_CORD_AXIS_ERR       0x00000200
#define BIT_CORD_SDRAM_CALC_ERR 0x00000400
#define BIT_CORD_SCARA_CALC_ERR 0x00000800
#define CRD_BUFF_DO_MOTOR_ENABLE 1
#define CRD_BUFF_DO_MOTOR_CLEAR  2
#define CRD_BUFF_DO_GPDO1        3
#define CRD_BUFF_DO_GPDO2        4
#define CRD_BUFF_DO_EXTDO1       5
#define CRD_BUFF_DO_EXTDO2       6
#define CRD_BUFF_DO_EXTDO3       7
#define CRD_BUFF_DO_EXTDO4       8
#define CRD_BUFF_DO_EXTDO5       9
#define CRD_BUFF_DO_EXTDO6       10
#define CRD_BUFF_DELAY_SCALE_MS  0
#define CRD_BUFF_DELAY_SCALE_S   1

typedef struct { short axCnts; short reserved[3]; short pAxArray[4]; short port[4]; } TCrdConfig;
typedef struct {
    short orgFlag;
    short reserved[3];
    long offset[4];
    double synAccMax;
    double synVelMax;
} TCrdPara;
typedef struct {
    double startVel;
    double T;
    double smoothDec;
    double abruptDec;
    short lookAheadSwitch;
    short eventTime;
    short reserved[2];
} TExtCrdPara;
typedef struct { double estpDec; double maxAcc; double maxVel; } TCrdSafePara;
typedef struct {
    long segNo;
    short crdAxMask;
    short extAxMask;
    long tgPos[8];
    float vel;
    float endVel;
    float acc;
    short lookaheadDis;
    short reserved;
} TCrdLineXYZD8Unit;

/* Coordinate system: look-ahead and packed status (digest 001 §3.4, §3.9). */
#define CRD_MAX_DIMENSION 4
#define CRD_WAIT_POS_LE 0
#define CRD_WAIT_POS_GE 1
typedef struct {
    short lookAheadSwitch;
    short centAccEn;
    short crossEn;
    short eventTime;
    double accMax;
    double T;
    double slowAng;
    double stopAng;
    double crossProp;
    double centAcc;
    double dvMax[CRD_MAX_DIMENSION];
    double daMax[CRD_MAX_DIMENSION];
    double radiusCoef;
    double radiusErr;
    double radiusAng;
    double radiusAngMax;
    double radiusAngMin;
    short axPropTimeUnitProp;
    short preHandleEn;
    short reserved;
    float preHandleDisAngMin;
    float preHandleDisAngMax;
    float preHandleTol;
    float minCornerVel;
    float axProp[CRD_MAX_DIMENSION];
} TLookaheadPara;
typedef struct {
    short crdSts;
    short axSts[4];
    long prfPos[4];
    long axisPos[4];
    long encPos[4];
    long userSeg;
    double prfVel;
    long gpDi;
    long gpDo;
    short motDi[4];
    short reserved;
    long crdFreeSpace;
    long crdUsedSpace;
} TPackedCrdSts4;

/* Advanced buffered I/O, NMC_AdvBufIoSetParam (digest 001 §3.12). */
#define MAX_ADV_BUFIO_GROUP 2
#define BUF_OUT_GROUP_DA  0
#define BUF_OUT_GROUP_PWM 1
typedef struct {
    short outType;
    short outGroup;
    short outIndex;
    short outSns;
    short pulseMode;
    short reserved1;
    long pulseOnTime;
    long pulseOffTime;
    unsigned char reserved[32];
} TAdvBufIoParam;

/* NMC_CrdBufDataPack (digest 001 §3.11): [short cmdType][struct] repeated, at most 1000
 * bytes. The structs are mcemu's (the manual defines none): each holds the arguments of
 * the function its type stands for, after the handle, in order. */
#define BUF_LINE 0
#define BUF_DO 1
#define BUF_OUT 2
#define BUF_DELAY 3
#define BUF_AXMOVE 4
#define BUF_DOEX 5
#define BUF_ARC_R 6
#define BUF_ARC_C 7
#define BUF_LASER_SETPOWER 8
#define BUF_LASER_ONOFF 9
#define BUF_LASER_SETFOLLOW 10
#define BUF_LASER_SETPARAM 11
#define BUF_LINEXYZA 12
#define BUF_SHIO_GATEPULSE 13
#define BUF_DOBITPULSE 14
#define BUF_XYZD8 15
#define BUF_SHIOMINFRQ 16
#define BUF_SHIOSETPARAM 17
#define BUF_SHIOGATEONOFF 18
#define BUF_WAITENCINPOS 19
#define BUF_WAITDI 20
typedef struct { long segNo; short mask; long tgPos[3]; double endVel; double vel; double synAcc; short lookaheadDis; } TCrdBufLine;
typedef struct { long segNo; short doType; long ch; long value; } TCrdBufDo;
typedef struct { long segNo; short group; short ch; long value; } TCrdBufOut;
typedef struct { long segNo; short scale; long count; } TCrdBufDelay;
typedef struct { long segNo; short axisMask; long tgPos[8]; double vel; double acc; short blockEn; short synEn; } TCrdBufAxMove;
typedef struct { long segNo; short group; long doMask; long doValue; } TCrdBufDoEx;
typedef struct { long segNo; long tgPos[2]; double radius; short circleDir; double endVel; double vel; double synAcc; short lookaheadDis; } TCrdBufArcR;
typedef struct { long segNo; long tgPos[2]; long centerPos[2]; short circleDir; double endVel; double vel; double synAcc; short lookaheadDis; } TCrdBufArcC;
typedef struct { long segNo; long power; short ch; } TCrdBufLaserPower;
typedef struct { long segNo; short onOff; short ch; } TCrdBufLaserOnOff;
typedef struct { long segNo; double overRide; short followType; short ch; } TCrdBufLaserFollow;
typedef struct { long segNo; long onDelay; long offDelay; long minValue; long maxValue; long standbyPower; short ch; } TCrdBufLaserParam;
typedef struct { long segNo; short mask; long tgPos[4]; double endVel; double vel; double synAcc; short lookaheadDis; } TCrdBufLineXYZA;
typedef struct { long segNo; double gateTime; double gateFrq; long outCount; short ch; } TCrdBufShioGatePulse;
typedef struct { long segNo; short doType; short doIndex; long highLevelTime; long lowLevelTime; long outCount; short initialLevel; short ch; } TCrdBufDoBitPulse;
typedef struct { long segNo; long minFrq; short ch; } TCrdBufShioMinFrq;
typedef struct { long segNo; double delay; double gateTime; double gateDistance; short ch; } TCrdBufShioParam;
typedef struct { long segNo; short onOff; short ch; } TCrdBufShioGateOnOff;
typedef struct { long segNo; long axisMask; long overTime; } TCrdBufWaitEncInPos;
typedef struct { long segNo; short index; short diValue; long waitLastTime; } TCrdBufWaitDI;

/* Coordinate transforms, arc sections, move protection (digest 001 §2.7, §3.7). */
#define MAX_ERR_TABLE_SECTION 2
typedef struct {
    double minSectionLen;
    double maxArcDiff;
    double r[MAX_ERR_TABLE_SECTION];
    double err[MAX_ERR_TABLE_SECTION + 1];
} TArcSecSetting;
typedef struct {
    short crdNo[2];
    short crdAxNo[2];
    short moveDir[2];
    long orgDis;
    long mvProtectDis;
    long safeWaitPos;
    double mvToSafeAcc;
    double mvToSafeVel;
    short stopCrdNo;
    short reserved[3];
} TmvProtectPara;
typedef TmvProtectPara TMvProtectPara;

/* Data collection (digest 001 §3.19). COLLECT_LIST_MAX, the trigger modes and the status
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

short NMC_GetDllVersion(char *pVersion);
short NMC_SetCommPara(HAND devHandle, unsigned long waitTimeInUs, unsigned long retryTimes);
short NMC_GetLastErr(void);
short NMC_GetErrDesc(short errCode, char *errDesc);
short NMC_SetErrCodeMode(short mode);
short NMC_DevSearch(TSearchMode mode, unsigned short *pDevNo, TDevInfo *pInfoList);
short NMC_DevOpen(short devNo, PHAND pDevHandle);
short NMC_DevOpenByID(char *idStr, PHAND pDevHandle);
short NMC_DevOpenByIP(unsigned char *pIPv4Array, PHAND pDevHandle);
short NMC_DevReset(HAND devHandle);
short NMC_GetCardInfo(HAND devHandle, TCardInfo *pInfo);
short NMC_GetClock(HAND devHandle, unsigned long *pClock, unsigned long *pLoop);
short NMC_MtOpen(HAND devHandle, short itemNo, PHAND pAxisHandle);
short NMC_MtGetSts(HAND axisHandle, short *pStsWord);
short NMC_MtGetStsEx(HAND axisHandle, short *pStsWord);
short NMC_MtClrError(HAND axisHandle);
short NMC_MtClrStsByBits(HAND axisHandle, short stsMask);
short NMC_MtGetPrfPos(HAND axisHandle, long *pos);
short NMC_MtGetPrfVel(HAND axisHandle, double *pVel);
short NMC_MtGetAxisPos(HAND axisHandle, long *pos);
short NMC_MtGetCmdPos(HAND axisHandle, long *pos);
short NMC_MtGetEncPos(HAND axisHandle, long *pPos);
short NMC_MtSetSvOn(HAND axisHandle);
short NMC_MtSetSvOff(HAND axisHandle);
short NMC_MtGetMotionIO(HAND axisHandle, long *inValue);
short NMC_MtSetPrfMode(HAND axisHandle, short mode);
short NMC_MtGetPrfMode(HAND axisHandle, short *mode);
short NMC_MtSetPtpPara(HAND axisHandle, TPtpPara *pAxPara);
short NMC_MtGetPtpPara(HAND axisHandle, TPtpPara *pAxPara);
short NMC_MtSetPtpTgtPos(HAND axisHandle, long pos);
short NMC_MtGetPtpTgtPos(HAND axisHandle, long *pos);
short NMC_MtSetVel(HAND axisHandle, double vel);
short NMC_MtGetVel(HAND axisHandle, double *vel);
short NMC_MtSetJogPara(HAND axisHandle, TJogPara *pAxPara);
short NMC_MtGetJogPara(HAND axisHandle, TJogPara *pAxPara);
short NMC_MtUpdate(HAND axisHandle);
short NMC_MtUpdateMulti(HAND axisHandle, long mask);
short NMC_MtStop(HAND axisHandle);
short NMC_MtAbruptStop(HAND axisHandle);
short NMC_MtStopMulti(HAND axisHandle, long mask);
short NMC_MtEstp(HAND axisHandle);
short NMC_MtMovePtpAbs(HAND axisHandle, double acc, double dec, double startVel, double endVel, double maxVel, short smoothCoef, long tgtPos);
short NMC_MtMovePtpRel(HAND axisHandle, double acc, double dec, double startVel, double endVel, double maxVel, short smoothCoef, long relPos);
short NMC_MtMoveJog(HAND axisHandle, double acc, double dec, double maxVel, short smoothCoef, short clrStsFlag);
short NMC_MtSetHomePara(HAND axisHandle, THomeSetting *pHomePara);
short NMC_MtGetHomePara(HAND axisHandle, THomeSetting *pHomePara);
short NMC_MtHome(HAND axisHandle);
short NMC_MtTryHome(HAND axisHandle);
short NMC_MtHomeStop(HAND axisHandle);
short NMC_MtGetHomeSts(HAND axisHandle, unsigned short *pStsWord);
short NMC_MtGetHomeError(HAND axisHandle, long *cmdPos);
short NMC_SetDOGroup(HAND devHandle, long value, short groupID);
short NMC_GetDOGroup(HAND devHandle, long *pDoValue, short groupID);
short NMC_SetDOBit(HAND devHandle, short bitIndex, short value);
short NMC_GetDOBit(HAND devHandle, short bitIndex, short *bitValue);
short NMC_GetDIGroup(HAND devHandle, long *pInValue, short groupID);
short NMC_GetDIBit(HAND devHandle, short bitIndex, short *bitValue);
short NMC_CrdOpen(HAND devHandle, PHAND pCrdHandle);
short NMC_CrdOpenEx(HAND devHandle, short itemNo, PHAND pCrdHandle);
short NMC_CrdClose(PHAND pCrdHandle);
short NMC_CrdConfig(HAND crdHandle, TCrdConfig *pConfig);
short NMC_CrdGetConfig(HAND crdHandle, TCrdConfig *pConfig);
short NMC_CrdDelete(HAND crdHandle);
short NMC_CrdSetPara(HAND crdHandle, TCrdPara *pCrdPara);
short NMC_CrdGetPara(HAND crdHandle, TCrdPara *pCrdPara);
short NMC_CrdSetExtPara(HAND crdHandle, TExtCrdPara *extCrdPara);
short NMC_CrdGetExtPara(HAND crdHandle, TExtCrdPara *extCrdPara);
short NMC_CrdSetSafePara(HAND crdHandle, TCrdSafePara *pSafePara);
short NMC_CrdSetLookAheadCentriAcc(HAND crdHandle, short isUsingSetAcc, double centriAcc);
short NMC_CrdLineXYZEx(HAND crdHandle, long segNo, short crdAxMask, long *pTgPosArray, double endVel, double vel, double synAcc, short lookaheadDis);
short NMC_CrdLineXYZA(HAND crdHandle, long segNo, short crdAxMask, long *pTgPosArray, double endVel, double vel, double synAcc, short lookaheadDis);
short NMC_CrdLineXYZ(HAND crdHandle, long segNo, short crdAxMask, long *pTgPosArray, double endVel, double vel, double synAcc);
short NMC_CrdLineXYZD8(HAND crdHandle, long segNo, long crdAxmask, long extAxMask, long *pTgPosArray, double endVel, double vel, double synAcc, short lookaheadDis);
short NMC_CrdLineXYZD8Pack(HAND crdHandle, short count, TCrdLineXYZD8Unit *pCmdArray);
short NMC_CrdArcCenterEx(HAND crdHandle, long segNo, long *pTgPosArray, long *pCenterPosArray, short circleDir, double endVel, double vel, double synAcc, short lookaheadDis);
short NMC_CrdArcCenterYZEx(HAND crdHandle, long segNo, long *pTgPos, long *pCenterPos, short circleDir, double velEnd, double vel, double synAcc, short lookaheadDis);
short NMC_CrdArcCenterZXEx(HAND crdHandle, long segNo, long *pTgPos, long *pCenterPos, short circleDir, double velEnd, double vel, double synAcc, short lookaheadDis);
short NMC_CrdArcCenter(HAND crdHandle, long segNo, long *pTgPosArray, long *pCenterPosArray, short circleDir, double endVel, double vel, double synAcc);
short NMC_CrdArcRadiusEx(HAND crdHandle, long segNo, long *pTgPosArray, double radius, short circleDir, double endVel, double vel, double synAcc, short lookaheadDis);
short NMC_CrdArcRadiusYZEx(HAND crdHandle, long segNo, long *pTgPos, double radius, short circleDir, double velEnd, double vel, double synAcc, short lookaheadDis);
short NMC_CrdArcRadiusZXEx(HAND crdHandle, long segNo, long *pTgPos, double radius, short circleDir, double velEnd, double vel, double synAcc, short lookaheadDis);
short NMC_CrdArcPPPEx(HAND crdHandle, long segNo, long *pMidPosArray, long *pTgPosArray, double endVel, double vel, double synAcc, short lookaheadDis);
short NMC_CrdHelixCenterEx(HAND crdHandle, long segNo, long *pTgPosArray, long *pCenterPosArray, short circleDir, double rounds, double endVel, double vel, double synAcc, short lookaheadDis);
short NMC_CrdArc3DEx(HAND crdHandle, long segNo, long *pMidPos, long *pTgPos, double velEnd, double vel, double synAcc, short lookaheadDis);
short NMC_CrdArc3D(HAND crdHandle, long segNo, long *pMidPos, long *pTgPos, double velEnd, double vel, double synAcc);
short NMC_CrdEllipse(HAND crdHandle, long segNo, double abRatio, long *pCenterPos, short ellipseDir, double vel, double synAcc);
short NMC_CrdBufDo(HAND crdHandle, long segNo, short doType, long ch, long value);
short NMC_CrdBufDoEx(HAND crdHandle, long segNo, short group, long doMask, long doValue);
short NMC_CrdBufDelay(HAND crdHandle, long segNo, short scale, long count);
short NMC_CrdBufWaitDI(HAND crdHandle, long segNo, short index, short diValue, long waitLastTime);
short NMC_CrdBufAxMoveEx(HAND crdHandle, long segNo, short axisMask, long *pTgPos, double vel, double acc, short blockEn, short synEn);
short NMC_CrdBufWaitEncInPosition(HAND crdHandle, long segNo, long axisMask, long overTime);
short NMC_CrdBufSetPtpMovePara(HAND crdHandle, long segNo, short axisNo, double vel, double acc, short soomthCoef);
short NMC_CrdBufAxMoveRel(HAND crdHandle, long segNo, short axisMask, long *pRelPos, short blockEn, short synEn);
short NMC_CrdStartMtn(HAND crdHandle);
short NMC_CrdEndMtn(HAND crdHandle);
short NMC_CrdStopMtn(HAND crdHandle);
short NMC_CrdEstopMtn(HAND crdHandle);
short NMC_CrdClrError(HAND crdHandle);
short NMC_CrdBufClr(HAND crdHandle);
short NMC_CrdSetOverride(HAND crdHandle, double override);
short NMC_CrdGetOverride(HAND crdHandle, double *pOverride);
short NMC_CrdSetOverRide(HAND crdHandle, double override);
short NMC_CrdGetOverRide(HAND crdHandle, double *pOverride);
short NMC_CrdGetSts(HAND crdHandle, short *pStsWord);
short NMC_CrdGetStsEx(HAND crdHandle, short *pSts, long *pUserSeg);
short NMC_CrdGetInnerSts(HAND crdHandle, long *pStsWord);
short NMC_CrdGetPrfPos(HAND crdHandle, short cnts, long *pPosArray);
short NMC_CrdGePrftPos(HAND crdHandle, short cnts, long *pPosArray);
short NMC_CrdGetAxisPos(HAND crdHandle, short cnts, long *pPosArray);
short NMC_CrdGetEncPos(HAND crdHandle, short cnts, long *pPosArray);
short NMC_CrdGetVel(HAND crdHandle, double *pVel);
short NMC_CrdBufGetFree(HAND crdHandle, long *pRes);
short NMC_CrdBufGetUsed(HAND crdHandle, long *pLen);
short NMC_CrdGetUserSegNo(HAND crdHandle, long *pSegNo);
short NMC_CrdGetBufAllCmdCnt(HAND crdHandle, long *pCnt);
short NMC_CrdGetBufLeftLength(HAND crdHandle, double *pLen);
short NMC_MtSetAlarmCfg(HAND axisHandle, short alarmEnable, short alarmSns);
short NMC_MtGetAlarmOnOff(HAND axisHandle, short *enable);
short NMC_MtGetAlarmSns(HAND axisHandle, short *swt);
short NMC_MtSetLmtCfg(HAND axisHandle, short posLmtEnable, short negLmtEnable, short posLmtSns, short negLmtSns);
short NMC_MtGetLmtOnOff(HAND axisHandle, short *posEn, short *negEn);
short NMC_MtGetLmtSns(HAND axisHandle, short *posSwt, short *negSwt);
short NMC_MtSwLmtOnOff(HAND axisHandle, short enable);
short NMC_MtGetSwLmtOnOff(HAND axisHandle, short *enable);
short NMC_MtSwLmtValue(HAND axisHandle, long posLmt, long negLmt);
short NMC_MtGetSwLmtValue(HAND axisHandle, long *posLmt, long *negLmt);
short NMC_MtSetStepMode(HAND axisHandle, short inv, short mode);
short NMC_MtGetStepMode(HAND axisHandle, short *pInv, short *pMode);
short NMC_SetEncMode(HAND devHandle, unsigned char encId, unsigned short encMode);
short NMC_GetEncMode(HAND devHandle, unsigned char encId, unsigned short *encMode);
short NMC_MtSetSafePara(HAND axisHandle, TSafePara *pPara);
short NMC_MtGetSafePara(HAND axisHandle, TSafePara *pPara);
short NMC_MtSetPosErrLmt(HAND axisHandle, long posErr);
short NMC_MtGetPosErrLmt(HAND axisHandle, long *posErr);
short NMC_MtSetAxisVelFilter(HAND axisHandle, short filterCoef);
short NMC_MtGetAxisVelFilter(HAND axisHandle, short *filterCoef);
short NMC_MtSetStepFilter(HAND axisHandle, unsigned short coe);
short NMC_MtGetStepFilter(HAND axisHandle, unsigned short *pCoe);
short NMC_MtSetPosErrAction(HAND axisHandle, short actionsBits);
short NMC_MtGetPosErrAction(HAND axisHandle, short *pActionsBits);
short NMC_MtSetAxisArrivalPara(HAND axisHandle, long arrivalBand, long stableTime);
short NMC_MtGetAxisArrivalPara(HAND axisHandle, long *pArrivalBand, long *pStableTime);
short NMC_SetDOGGroup(HAND devHandle, long value, short groupID);
short NMC_GetDOGGroup(HAND devHandle, long *pDoValue, short groupID);
short NMC_SetDacMode(HAND devHandle, short ch, short mode);
short NMC_GetDacMode(HAND devHandle, short ch, short *pMode);
short NMC_SetAdcMode(HAND devHandle, short ch, short range, short filterCoe);
short NMC_GetAdcMode(HAND devHandle, short ch, short *pRange, short *pFilterCoe);
short NMC_SetDac(HAND devHandle, short ch, short dacValue);
short NMC_GetDac(HAND devHandle, short ch, short *pDacValue);
short NMC_GetAdc(HAND devHandle, short ch, short *pAdcValue);
short NMC_SetDacBias(HAND devHandle, short ch, short bias);
short NMC_GetDacBias(HAND devHandle, short ch, short *pBias);
short NMC_SetDacLmt(HAND devHandle, short ch, short maxVal, short minVal);
short NMC_GetDacLmt(HAND devHandle, short ch, short *pMaxVal, short *pMinVal);
short NMC_GetAdcVoltageMulti(HAND devHandle, short ch, short count, double *pAdcVolArray);
short NMC_SetDacVoltageMulti(HAND devHandle, short ch, short count, double *pDacVolArray);
short NMC_GetDacVoltageMulti(HAND devHandle, short ch, short count, double *pDacVolArray);
short NMC_EcatLoadConfigFromFile(HAND devHandle, char *gmlFileName, short masterIdx);
short NMC_EcatStart(HAND devHandle);
short NMC_EcatStop(HAND devHandle);
short NMC_EcatGetSts(HAND devHandle, unsigned short *pSts);
short NMC_EcatGetResource(HAND devHandle, short *pSlaveCnt, short *pDriverCnt, short *pIoCnt);
short NMC_EcatStartHome(HAND axisHandle, int method, int velSwitch, int velZero, int acc, int prmEx);
short NMC_EcatGetHomeSts(HAND axisHandle, unsigned char *pStatus);
short NMC_EcatStopHome(HAND axisHandle);
short NMC_EcatSdoRead(HAND devHandle, short devId, unsigned short idx, unsigned char sub_idx, unsigned int len, unsigned char *val, unsigned int *abort_code);
short NMC_EcatSdoWrite(HAND devHandle, short devId, unsigned short idx, unsigned char sub_idx, unsigned int len, unsigned char *val, unsigned int *abort_code);
short NMC_EcatAxisGetErrorCode(HAND axisHandle, unsigned short *pError);
short NMC_EcatAxisGetDi(HAND axisHandle, long *pDiVal);
short NMC_UserParaWr(HAND devHandle, unsigned long add, unsigned long len, unsigned char *pWrData);
short NMC_UserParaRd(HAND devHandle, unsigned long add, unsigned long len, unsigned char *pRdData);
short NMC_UserParaWrEx(HAND devHandle, unsigned long add, unsigned long len, unsigned char *pWrData);
short NMC_UserParaRdEx(HAND devHandle, unsigned long add, unsigned long len, unsigned char *pRdData);
short NMC_MtGearSetDir(HAND axisHandle, short dir);
short NMC_MtGearGetDir(HAND axisHandle, short *pdir);
short NMC_MtGearSetMaster(HAND axisHandle, short masterNo, short masterType);
short NMC_MtGearGetMaster(HAND axisHandle, short *pmasterNo, short *pmasterType);
short NMC_MtGearSetRatio(HAND axisHandle, long masterEven, long slaveEven, long masterSlope);
short NMC_MtGearGetRatio(HAND axisHandle, long *pMasterEven, long *pSlaveEven, long *pMasterSlope);
short NMC_MtGearStartMtn(HAND axisHandle, short syncAxCnts, short *pSyncAxArray);
short NMC_MtPtSetStatic(HAND axisHandle, short onOff, long loopCount);
short NMC_MtPtGetStatic(HAND axisHandle, short *pOnOff, long *pLoopCount);
short NMC_MtPtGetSpace(HAND axisHandle, short *pSpace, short *pUsed);
short NMC_MtPtPush(HAND axisHandle, short count, double *pPosArray, long *pTimeArray, short *pTypeArray);
short NMC_MtPtBufClr(HAND axisHandle);
short NMC_MtPtStartMtn(HAND axisHandle, short otherSynAxCnts, short *pOtherSynAxArray);
short NMC_MtPtSetPara(HAND axisHandle, TPtPara *pPara);
short NMC_MtPvtSetPara(HAND axisHandle, TPvtPara *pPara);
short NMC_MtPvtGetPara(HAND axisHandle, TPvtPara *pPara);
short NMC_MtPvtData(HAND axisHandle, short count, double *pPosArray, double *pTimeArray, double *pVelArray);
short NMC_MtPvtBufGetSpace(HAND axisHandle, short *pFreeSpace, short *pUsedSpace);
short NMC_MtPvtBufClr(HAND axisHandle);
short NMC_MtPvtStartMtn(HAND axisHandle, short otherSynAxCnts, short *pOtherSynAxArray);
short NMC_MtSetCaptSns(HAND axisHandle, short mode, short ioSrc, short level);
short NMC_MtGetCaptSns(HAND axisHandle, short *pMode, short *pIoSrc, short *pLevel);
short NMC_MtSetCapt(HAND axisHandle);
short NMC_MtGetCaptPos(HAND axisHandle, long *pPos);
short NMC_MtClrCaptSts(HAND axisHandle);
short NMC_MtSetAdvCaptParam(HAND devHandle, TAdvCaptureParam *pParam, short ch);
short NMC_MtClrAdvCaptSts(HAND devHandle, short ch);
short NMC_MtGetAdvCaptPos(HAND devHandle, short *captSts, long *pPosArray, short ch);
short NMC_MtSetCaptRepeat(HAND axisHandle, short count);
short NMC_MtGetCaptRepeatStatus(HAND axisHandle, short *pCount);
short NMC_MtGetCaptRepeatPosMulti(HAND axisHandle, long *pPosArray, short startNum, short count);
short NMC_Comp2DimensSetParamEx(HAND devHandle, short group, TComp2DimensParamEx *param, short chn);
short NMC_Comp2DimensGetParamEx(HAND devHandle, short group, TComp2DimensParamEx *param, short chn);
short NMC_Comp2DimensSetData(HAND devHandle, short group, long *pArrayPos, short count, short chn);
short NMC_Comp2DimensOnoff(HAND devHandle, short group, short onOff, short chn);
short NMC_Comp2DimensStatusEx(HAND devHandle, short group, TComp2DimensSts *pStatus, short chn);
short NMC_SetGantryMaster(HAND axisHandle, short group);
short NMC_SetGantrySlave(HAND axisHandle, short group, long gantryErrLmt);
short NMC_DelGantryGroup(HAND axisHandle, short group);
short NMC_SetHandWheel(HAND devHandle, short axis, double ratio, double acc, double vel);
short NMC_SetHandWheelInput(HAND devHandle, short index);
short NMC_SetHandWheelRatio(HAND devHandle, double ratio);
short NMC_ClrHandWheel(HAND devHandle);
short NMC_MtSetLeadScrewCompPara(HAND axisHandle, short num, long startPos, long cmpLen, short *pCompPos, short *pCompNeg);
short NMC_MtEnableLeadScrew(HAND axisHandle, short enable);
short NMC_MtSetBacklash(HAND axisHandle, long compValue, double compDelta, long compDir);
short NMC_MtGetBacklash(HAND axisHandle, long *pCompValue, double *pCompDelta, long *pCompDir);
short NMC_Set2DCompensationTable(HAND devHandle, short tableIndex, T2DCompensationTable *pTable, TCompData *pData);
short NMC_Get2DCompensationTable(HAND devHandle, short tableIndex, T2DCompensationTable *pTable, TCompData *pData);
short NMC_Set2DCompensation(HAND devHandle, T2DCompensation *pComp);
short NMC_Get2DCompensation(HAND devHandle, T2DCompensation *pComp);
short NMC_GetDIEx(HAND devHandle, short diType, short groupID, long *pDiValue);
short NMC_GetDIRaw(HAND devHandle, short diType, short groupID, long *pDiValue);
short NMC_GetDOEx(HAND devHandle, short doType, short groupID, long *pOutValue);
short NMC_SetDOMask(HAND devHandle, long outMask, long outValue, short doType, short groupID);
short NMC_GetEncPos(HAND devHandle, short encId, long *pPos);
short NMC_GetEncVel(HAND devHandle, unsigned char encId, double *vel);
short NMC_SetEncPos(HAND devHandle, short encId, long encPos);
short NMC_IOModuleSetEn(HAND devHandle, unsigned char chDevId, short chDevType);
short NMC_IOModuleGetType(HAND devHandle, unsigned char chDevId, short *pChDevType);
short NMC_IOModuleRd16Bit(HAND devHandle, unsigned char chDevId, unsigned char offset, unsigned short *pData);
short NMC_IOModuleRd32Bit(HAND devHandle, unsigned char chDevId, unsigned char offset, unsigned long *pData);
short NMC_IOModuleRdOut16Bit(HAND devHandle, unsigned char chDevId, unsigned char offset, unsigned short *pData);
short NMC_IOModuleRdOut32Bit(HAND devHandle, unsigned char chDevId, unsigned char offset, unsigned long *pData);
short NMC_IOModuleWr16Bit(HAND devHandle, unsigned char chDevId, unsigned char offset, unsigned short data);
short NMC_IOModuleWr32Bit(HAND devHandle, unsigned char chDevId, unsigned char offset, unsigned long data);
short NMC_GetIOModuleSts(HAND devHandle, unsigned long *sts);
short NMC_DevReadID(HAND devHandle, char *pIdStr);
short NMC_GetUID(HAND devHandle, unsigned long *pUID);
short NMC_GetMtLibVersion(HAND devHandle, TmLibVersion *pVersion);
short NMC_GetDI(HAND devHandle, long *pInValue, short groupID);
short NMC_GetDO(HAND devHandle, long *pDoValue, short groupID);
short NMC_SetDO(HAND devHandle, long value, short groupID);
short NMC_SetDIBitRevs(HAND devHandle, short bitIndex, short revs);
short NMC_GetDIBitRevs(HAND devHandle, short bitIndex, short *pRevs);
short NMC_SetDOBitRevs(HAND devHandle, short bitIndex, short revs);
short NMC_GetDOBitRevs(HAND devHandle, short bitIndex, short *pRevs);
short NMC_SetDOBitRevsEx(HAND devHandle, short doType, short group, short bitIndex, short revs);
short NMC_GetDOBitRevsEx(HAND devHandle, short doType, short group, short bitIndex, short *pRevs);
short NMC_SetDOBitAutoReverse(HAND devHandle, short bitIndex, short value, short reverseTime);
short NMC_DoBitPulseEnable(HAND devHandle, short doType, short doIndex, long highLevelTime, long lowLevelTime, long outCount, short initialLevel, short ch);
short NMC_DoBitPulseDisable(HAND devHandle, short ch);
short NMC_SetDIFilter(HAND devHandle, short diType, short diGroup, short diIndex, short filtTime);
short NMC_GetDIFilter(HAND devHandle, short diType, short diGroup, short diIndex, short *pFiltTime);
short NMC_SetDiReverseCount(HAND devHandle, short diType, short diIndex, unsigned long *pReverseCountArray, short count);
short NMC_GetDiReverseCount(HAND devHandle, short diType, short diIndex, unsigned long *pReverseCountArray, short count);
short NMC_SetDioMapping(HAND devHandle, TDioMappingCfg *pDioCfg);
short NMC_GetAllDioMapping(HAND devHandle, TDioMappingCfg *pDioCfg);
short NMC_ClrAllDioMapping(HAND devHandle);
short NMC_DevWriteID(HAND devHandle, char *pIdStr);
short NMC_DevGetPara(HAND devHandle, unsigned long paraID, long *pValue);
short NMC_DevSetPara(HAND devHandle, unsigned long paraID, long value);
short NMC_GetTime(HAND devHandle, TNMCTime *pTime);
short NMC_SetTime(HAND devHandle, TNMCTime *pTime, char *pPassword);
short NMC_VerifyPassword(HAND devHandle, char *pPassword);
short NMC_ChangePassword(HAND devHandle, char *pPasswordOld, char *pPasswordNew);
short NMC_SetBackedVarOnOff(HAND devHandle, short en);
short NMC_GetBackedVarOnOff(HAND devHandle, short *pEn);
short NMC_GetBackedVarGroup2(HAND devHandle, TBackGroup2 *pBackVar);
short NMC_MtGetStsMulti(HAND firstAxisHandle, short *pStsArray, short count, unsigned long *pClock);
short NMC_MtGetStsPack12Ex(HAND axisFirstHandle, TAxisStsPack12Ex *pPackSts);
short NMC_MtMovePtpAbsPack8(HAND axisFirstHandle, TMovePtpPack8 *pPackData);
short NMC_MtMovePtpRelPack8(HAND axisFirstHandle, TMovePtpPack8 *pPackData);
short NMC_MtSetAxisPos(HAND axisHandle, long axisPos);
short NMC_MtSetEncPos(HAND axisHandle, long encPos);
short NMC_MtZeroPos(HAND axisHandle);
short NMC_MtSetSvClr(HAND axisHandle, short swt);
short NMC_MtHomeSns(HAND axisHandle, short sns);
short NMC_MtSetEstopDI(HAND axisHandle, short gpiIndex, short sense);
short NMC_MtGetEstopDI(HAND axisHandle, short *gpiIndex, short *sense);
short NMC_MtGetMotionIOLogical(HAND axisHandle, long *pIoValue);
short NMC_SetProfilePeriod(HAND devHandle, short period);
short NMC_GetProfilePeriod(HAND devHandle, short *pPeriod);
short NMC_SetWatchDog(HAND devHandle, long timeout, short stopMode, short groupID, long doValue);
short NMC_SetEstopDIEx(HAND devHandle, TEstopExParam *pParam, short group);
short NMC_GetEstopDIEx(HAND devHandle, TEstopExParam *pParam, short group);
short NMC_ClrEstopDIEx(HAND devHandle, short group);
short NMC_MtFollowSetMaster(HAND axisHandle, short masterNo, short masterType);
short NMC_MtFollowGetMaster(HAND axisHandle, short *pMasterNo, short *pMasterType);
short NMC_MtFollowSetEvent(HAND axisHandle, short eventType, short masterDir, long pos);
short NMC_MtFollowGetEvent(HAND axisHandle, short *pEventType, short *pMasterDir, long *pPos);
short NMC_MtFollowSetDir(HAND axisHandle, short dir);
short NMC_MtFollowGetDir(HAND axisHandle, short *pDir);
short NMC_MtFollowSetLoopCount(HAND axisHandle, long loopCnt);
short NMC_MtFollowGetLoopCount(HAND axisHandle, long *pLoopCnt);
short NMC_MtFollowPushData(HAND axisHandle, long masterPos, double slavePos, short segType, short fifoNo);
short NMC_MtFollowGetSpace(HAND axisHandle, short *pSpace, short fifoNo);
short NMC_MtFollowClear(HAND axisHandle, short fifoNo);
short NMC_MtFollowStart(HAND axisHandle, short syncAxCnts, short *pSyncAxArray);
short NMC_MtFollowSwitch(HAND axisHandle, short syncAxCnts, short *pSyncAxArray);
short NMC_MtPtStartMtnEx(HAND axisHandle, short diIndex, short diSns);
short NMC_MtPtGetPara(HAND axisHandle, TPtPara *pPara);
short NMC_MtSetPtpComparePara(HAND axisHandle, short dir, long comparaPos, double upDateVel);
short NMC_MtGetPtpCompareSts(HAND axisHandle, short *pIsCompareActive, short *pIsCompareOut);
short NMC_Comp2DimensStatus(HAND devHandle, short group, TComp2DimensSts *pStatus, short chn);
short NMC_MtSetAxisDampCompParam(HAND axisHandle, short enable, short param1, short param2);
short NMC_MtSetCtrlMode(HAND axisHandle, short mode);
short NMC_MtGetCtrlMode(HAND axisHandle, short *pMode);
short NMC_MtSetPIDPara(HAND axisHandle, short index, TPidPara *pidPara);
short NMC_MtGetPIDPara(HAND axisHandle, short index, TPidPara *pPidPara);
short NMC_MtSetPIDIndex(HAND axisHandle, short index);
short NMC_MtGetPIDIndex(HAND axisHandle, short *pIndex);
short NMC_MtSetCloseLoopDac(HAND axisHandle, TDacMotor *pDacPara);
short NMC_MtGetCloseLoopDac(HAND axisHandle, TDacMotor *pDacPara);
short NMC_SetCloseLoopDac(HAND axisHandle, TDacMotor *pDacPara);
short NMC_MtPrfConfig(HAND axisHandle, short mapAxisNo, short port, long startPos);
short NMC_MtGetPrfConfig(HAND axisHandle, short *mapAxisNo, short *port, long *startPos);
short NMC_MtSetPrfCoe(HAND axisHandle, double inCoe);
short NMC_MtGetPrfCoe(HAND axisHandle, double *inCoe);
short NMC_MtSetEncCoe(HAND axisHandle, double encCoe);
short NMC_MtGetEncCoe(HAND axisHandle, double *pEncCoe);
short NMC_SaveMotionConfig(HAND devHandle, short enable);
short NMC_CrdSetLookaheadPara(HAND crdHandle, TLookaheadPara *lkhPara);
short NMC_CrdGetLookaheadPara(HAND crdHandle, TLookaheadPara *lkhPara, short defaultFlag);
short NMC_CrdGetStsPack4(HAND crdHandle, TPackedCrdSts4 *pPackSts);
short NMC_CrdBufWaitPos(HAND crdHandle, long segNo, short axisNo, short condition, long pos, short posSrc, long overTime);
short NMC_CrdCircle3DEx(HAND crdHandle, long segNo, long *pMidPos, long *pTgPos, double velEnd, double vel, double synAcc, short lookaheadDis);
short NMC_CrdCirclePPP(HAND crdHandle, long segNo, short planeIdx, long *pStPos, long *pMidPosArray, long *pTgPosArray, double endVel, double vel, double synAcc, short lookaheadDis);
short NMC_CrdSetBufLengthFlag(HAND crdHandle, short flag);
short NMC_CrdGetBufLength(HAND crdHandle, double *pLen);
short NMC_LaserSetMode(HAND devHandle, short mode, short ch);
short NMC_LaserSetModes(HAND devHandle, short mode, short ch);
short NMC_LaserSetOutputTypeEx(HAND devHandle, short outputType, short index, double optionVal, short ch);
short NMC_LaserSetOutputType(HAND devHandle, short outputType, short index, long optionVal, short ch);
short NMC_LaserSetParam(HAND devHandle, long onDelay, long offDelay, long minValue, long maxValue, long standbyPower, short ch);
short NMC_LaserGetParam(HAND devHandle, long *pOnDelay, long *pOffDelay, long *pMinValue, long *pMaxValue, long *pStandbyPower, short ch);
short NMC_LaserSetPowerEx(HAND devHandle, double outVal, short ch);
short NMC_LaserOnOff(HAND devHandle, short onOff, short ch);
short NMC_LaserGetPower(HAND devHandle, double *pVal, short ch);
short NMC_LaserGetOnOff(HAND devHandle, short *pOnOffState, short ch);
short NMC_LaserSetFollowParam(HAND devHandle, short powerFilter, short followAdvMode, short ch);
short NMC_SetLaserPowerCmpTable(HAND devHandle, short tableNo, long *pXCmpPos, long *pYCmpPos, short xCount, short yCount, unsigned long powerMin, unsigned long powerMax, unsigned long *pLaserCmpPower, short ch);
short NMC_StartLaserPowerComp(HAND devHandle, short *pAxisNo, short ch);
short NMC_StopLaserPowerComp(HAND devHandle, short ch);
short NMC_LaserSetTimeArrayPara(HAND devHandle, TTimeArrayPara *pPara, short ch);
short NMC_LaserSetTimeArrayPower(HAND devHandle, short group, TLaserPower *pLaserPower);
short NMC_LaserTimeArrayExe(HAND devHandle, short group, short ch);
short NMC_SHIOConfigPara(HAND devHandle, TSHIOPara *pSHIOPara, short ch);
short NMC_SHIOEnableMinFrq(HAND devHandle, long minFrq, short ch);
short NMC_SHIODisableMinFrq(HAND devHandle, short ch);
short NMC_SHIOEnableMinFrg(HAND devHandle, long minFrq, short ch);
short NMC_SHIODisableMinFrg(HAND devHandle, short ch);
short NMC_SHIOChangeAxisMask(HAND devHandle, short axisMask, short ch);
short NMC_SHIOGateOn(HAND devHandle, short ch);
short NMC_SHIOGateOff(HAND devHandle, short ch);
short NMC_SHIOTriggerOn(HAND devHandle, double freq, double width, short ch);
short NMC_SHIOTriggerOff(HAND devHandle, short ch);
short NMC_SHIOGatePulse(HAND devHandle, double gateTime, double gateFrq, long outCount, short ch);
short NMC_SetPwmToGate(HAND devHandle, short pwmCh, short gateCh, short onOff);
short NMC_PwmPulseOut(HAND devHandle, double onTime, double pwmFrq, long outCount, short ch);
short NMC_SetPWMPort(HAND devHandle, short portType, short portIdx, short ch);
short NMC_GetPWMPort(HAND devHandle, short *pPortType, short *pGpoIdx, short ch);
short NMC_CrdBufLaserOnOff(HAND crdHandle, long segNo, short onOff, short ch);
short NMC_CrdBufLaserPower(HAND crdHandle, long segNo, long power, short ch);
short NMC_CrdBufLaserSetFollow(HAND crdHandle, long segNo, double overRide, short followType, short ch);
short NMC_CrdBufLaserSetParam(HAND crdHandle, long segment, long onDelay, long offDelay, long minValue, long maxValue, long standbyPower, short ch);
short NMC_CrdBufLaserTimeArrayExe(HAND crdHandle, long segNo, short group, short ch);
short NMC_CrdBufSHIOGatePulse(HAND crdHandle, long segNo, double gateTime, double gateFrq, long outCount, short ch);
short NMC_CrdBufSHIOSetParam(HAND crdHandle, long segment, double delay, double gateTime, double gateDistance, short ch);
short NMC_CrdBufSHIOChangeAxisMask(HAND crdHandle, long segment, short axisMask, short ch);
short NMC_CrdBufSHIOSetMinFrq(HAND crdHandle, long segment, long minFrq, short ch);
short NMC_CrdBufSHIOClrMinFrq(HAND crdHandle, long segment, short ch);
short NMC_CrdBufSHIOSetMinFrg(HAND crdHandle, long segment, long minFrq, short ch);
short NMC_CrdBufSHIOClrMinFrg(HAND crdHandle, long segment, short ch);
short NMC_BufSHIOGateOn(HAND crdHandle, long segNo, short ch);
short NMC_BufSHIOGateOff(HAND crdHandle, long segNo, short ch);
short NMC_CrdBufOut(HAND crdHandle, long segNo, short group, short ch, long value);
short NMC_CrdBufStopMtn(HAND crdHandle, long segNo, short crdIdx);
short NMC_CrdBufSetEstopDI(HAND crdHandle, long segNo, short axis, short gpiIndex, short sense);
short NMC_CrdBufEstopDIExOnOff(HAND crdHandle, long segNo, short onOff, short group);
short NMC_CrdBufDoBitPulseEnable(HAND crdHandle, long segNo, short doType, short doIndex, long highLevelTime, long lowLevelTime, long outCount, short initialLevel, short ch);
short NMC_CrdBufDoBitPulseDisable(HAND crdHandle, long segNo, short ch);
short NMC_CrdBufBeforeAxSyncMove(HAND crdHandle, long segNo, short axis, long relDistance, double vel);
short NMC_CrdBufDataPack(HAND crdHandle, unsigned char *pBufData, short dataLen);
short NMC_AdvBufIoSetParam(HAND devHandle, TAdvBufIoParam *pPrm, short ch);
short NMC_AdvBufIoGetParam(HAND devHandle, TAdvBufIoParam *pPrm, short ch);
short NMC_AdvBufIoOut(HAND devHandle, long value, short ch);
short NMC_AdvBufIoGetPulseCnt(HAND devHandle, long *pOutCout, short ch);
short NMC_CrdAdvBufIoOnAfterLen(HAND crdHandle, long segNo, long outLength, long value, short ch);
short NMC_CrdAdvBufIoOffBeforeLen(HAND crdHandle, long segNo, long outLength, short ch);
short NMC_CrdSetTransRotate(HAND crdHandle, short rotAxisNo, double angleRadEqual, long firstAxisInitPos, long secAxisInitPos);
short NMC_CrdDelTransRotate(HAND crdHandle);
short NMC_CrdSetTransPolar(HAND crdHandle, short rotAxNo, short transAxNo, double rotEquiv);
short NMC_CrdRunToPolarPos(HAND crdHandle, double xPos, double yPos, double rotVel, double transVel);
short NMC_CrdRunToPolarTheta(HAND crdHandle, double theta, double vel, short clrRoundFlag);
short NMC_CrdDelTransPolar(HAND crdHandle);
short NMC_CrdSetTransXYZA(HAND crdHandle, short *pAxisMapArray);
short NMC_CrdDelTransXYZA(HAND crdHandle);
short NMC_CrdSetXYZAToolCalc(HAND crdHandle, double deltaTheta, long deltaX, long deltaY, long *pToolX, long *pToolY);
short NMC_CrdSetXYZAPara(HAND crdHandle, double pulse2Rad, long toolX, long toolY);
short NMC_CrdGetXYZAPara(HAND crdHandle, double *pPulse2Rad, long *ToolX, long *pToolY);
short NMC_CrdSetOffset(HAND crdHandle, short count, long *pOffsetArray);
short NMC_CrdSetArcSecPara(HAND crdHandle, TArcSecSetting *pSetting);
short NMC_CrdGetArcSecPara(HAND crdHandle, TArcSecSetting *pSetting);
short NMC_CrdSetFourthAxisToTurnVel(HAND crdHandle, double tolVel);
short NMC_CrdGotoBreak(HAND crdHandle, double acc, double vel);
short NMC_SetMvProtect(HAND devHandle, short groupNo, short mode);
short NMC_DelMvProtect(HAND devHandle, short groupNo);
short NMC_SetMvProtectMode01Para(HAND devHandle, short groupNo, TMvProtectPara *pMvProtectPara);
short NMC_GetMvProtectMode01Para(HAND devHandle, short groupNo, TmvProtectPara *pMvProtectPara);
short NMC_GetMvProtectSts(HAND devHandle, short groupNo, short *pSts);
short NMC_GetCollectDataAddr(HAND devHandle, short index, short dataType, unsigned long *pAddr, short *pDataLen);
short NMC_ConfigCollect(HAND devHandle, TCollectCfg *pCollect, TCollectTrig *pTrig);
short NMC_CollectOnOff(HAND devHandle, short en);
short NMC_GetCollectSts(HAND devHandle, short *pSts, long *pDataLen);
short NMC_GetCollectData(HAND devHandle, short len, unsigned char *pData);
short NMC_ClearCollectSts(HAND devHandle);
short NMC_UserSetPassword(HAND devHandle, char *pUserName, char *pPasswordOld, char *pPasswordNew);
short NMC_UserLogin(HAND devHandle, char *pUserName, char *pPassword);
short NMC_UserLogout(HAND devHandle, char *pUserName);
short NMC_SetCmdDebug(short enable, char *debugOutputFile);
short NMC_UserPrint(char *msg);
short NMC_SaveConfigToFile(HAND devHandle, char *pFilePath);
short NMC_LoadConfigFromFile(HAND devHandle, char *pFilePath);
short NMC_CrdStartExeTimeCalc(void);
short NMC_CrdGetExeTime(double *pTime);
short _NMC_CrdGetExeTime(double *pTime);

#ifdef __cplusplus
}
#endif

#endif /* MTN_LIB20_H */
