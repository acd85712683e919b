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

#ifdef __cplusplus
}
#endif

#endif /* MTN_LIB20_H */
