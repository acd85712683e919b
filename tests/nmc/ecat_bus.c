/* TV34-TV36 (digest 001 §2.1, §3.13, §3.14, C5§4) on fixtures/gaochuan-gcn-ecat.toml: two
 * EtherCAT drives (axes 16, 17; SDO devId 0, 1) and one I/O slave (devId 2) after the card's
 * two local pulse axes. The bus axes power up through their drives' state machines, move,
 * report a drive fault as the alarm bit, clear it by a fault reset, home in the drive (CiA 402
 * method 21, a home sensor active from -3000 down), answer SDOs with their abort codes, and
 * are named by axis-number arguments (masks, a gear master, the advanced E-stop's diIndex,
 * typed-DO bitIndex, DI filters, encId, the collection index, MtPrfConfig's default map) as
 * 16 and 17; a short mask and the reverse counters reach the local axes only. */
#include <string.h>
#include "check.h"

#define OPERATION_ENABLED 0x0027 /* CiA 402 statusword, mask 0x006F */
#define SWITCH_ON_DISABLED 0x0040 /* mask 0x004F */

static unsigned short statusword(HAND dev, short devId) {
    unsigned char v[2] = {0, 0};
    unsigned int abort_code = 0xFFFFFFFFu;
    OK(NMC_EcatSdoRead(dev, devId, 0x6041, 0, 2, v, &abort_code));
    CHECK(abort_code == 0, "abort %#x", abort_code);
    return (unsigned short)(v[0] | v[1] << 8);
}

static long sdo_i32(HAND dev, short devId, unsigned short idx) {
    unsigned char v[4] = {0, 0, 0, 0};
    unsigned int abort_code = 1;
    OK(NMC_EcatSdoRead(dev, devId, idx, 0, 4, v, &abort_code));
    return (long)(int)((unsigned)v[0] | (unsigned)v[1] << 8 | (unsigned)v[2] << 16 | (unsigned)v[3] << 24);
}

static unsigned char home_sts(HAND ax) {
    unsigned char s = 0xFF;
    OK(NMC_EcatGetHomeSts(ax, &s));
    return s;
}

/* TV35's poll: "in progress" (000, or 010 found and stopping) until it ends; the end. */
static unsigned char home_end(HAND ax) {
    unsigned char s = home_sts(ax);
    long polls = 0;
    CHECK(s == 0, "in progress right after the start: %u", s);
    while (s == 0 || s == 2) {
        s = home_sts(ax);
        CHECK(++polls < 10000000L, "homing never ended");
    }
    return s;
}

static void servo_on(HAND ax) {
    short sts = 0;
    OK(NMC_MtSetSvOn(ax));
    EVENTUALLY(NMC_MtGetSts(ax, &sts), sts & BIT_AXIS_SVON);
}

int main(void) {
    HAND dev = 0, ax1 = 0, ax16 = 0, ax17 = 0, bad = 0;
    short slaves = -1, drives = -1, io = -1, sts = 0;
    unsigned short err = 0, home = 0, w = 0;
    unsigned char v[4] = {0}, st = 0;
    unsigned int abort_code = 0;
    char gml[] = "test.gml";
    long pos = 0, pos2 = 0, di = 0;
    short master = -1, kind = -1;
    THomeSetting hs;
    TPtpPara ptp;
    TEstopExParam ex;
    short revs = -1, filt = -1, map = -1, port = -1, len = 0;
    unsigned long counts[2] = {0}, addr = 0;

    OK(NMC_DevOpen(0, &dev));
    /* Nothing is online before the master runs (S-ECAT-START, TV33). */
    OK(NMC_EcatGetResource(dev, &slaves, &drives, &io));
    CHECK(slaves == 0 && drives == 0 && io == 0, "before start: %d %d %d", slaves, drives, io);
    CHECK(NMC_EcatSdoRead(dev, 0, 0x6041, 0, 2, v, &abort_code) == RTN_INVALID_STATE, "SDO before start");
    OK(NMC_EcatLoadConfigFromFile(dev, gml, 0));
    OK(NMC_EcatStart(dev));

    /* TV34: 2 drives + 1 I/O slave; axis 16 is the first drive, 17 the second. */
    OK(NMC_EcatGetResource(dev, &slaves, &drives, &io));
    CHECK(slaves == 3 && drives == 2 && io == 1, "TV34: %d %d %d", slaves, drives, io);
    OK(NMC_MtOpen(dev, 1, &ax1));
    OK(NMC_MtOpen(dev, 16, &ax16));
    OK(NMC_MtOpen(dev, 17, &ax17));
    CHECK(NMC_MtOpen(dev, 18, &bad) == RTN_ARG_RANGE, "bus axis 18 beyond the 2 drives");
    CHECK(NMC_MtOpen(dev, 2, &bad) == RTN_ARG_RANGE, "local axis 2: the card has 0 and 1");
    CHECK((statusword(dev, 0) & 0x4F) == SWITCH_ON_DISABLED, "drive 0 starts disabled");
    OK(NMC_MtGetSts(ax16, &sts));
    CHECK(!(sts & BIT_AXIS_SVON), "SVON before servo on %#x", sts);
    servo_on(ax16);
    EVENTUALLY((w = statusword(dev, 0), 0), (w & 0x6F) == OPERATION_ENABLED); /* TV34 */
    CHECK((statusword(dev, 1) & 0x4F) == SWITCH_ON_DISABLED, "TV34: drive 1 untouched");

    /* Motion on a bus axis: the card's profile, the drive's actual position (0x6064). */
    OK(NMC_MtMovePtpAbs(ax16, 1, 1, 0, 0, 50, 0, 5000));
    wait_still(ax16);
    OK(NMC_MtGetPrfPos(ax16, &pos));
    CHECK(pos == 5000, "prfPos %ld", pos);
    EVENTUALLY((pos = sdo_i32(dev, 0, 0x6064), 0), pos == 5000);

    /* SDO download and upload, and the aborts (CiA 301 codes in abort_code). */
    v[0] = 0xD2; v[1] = 0x04; v[2] = 0; v[3] = 0; /* 1234 */
    OK(NMC_EcatSdoWrite(dev, 1, 0x6065, 0, 4, v, &abort_code));
    CHECK(abort_code == 0, "abort %#x", abort_code);
    CHECK(sdo_i32(dev, 1, 0x6065) == 1234, "0x6065 read back");
    CHECK(NMC_EcatSdoWrite(dev, 1, 0x6065, 0, 2, v, &abort_code) == RTN_OBJECT, "short write");
    CHECK(abort_code == 0x06070013u, "length too low: %#x", abort_code);
    CHECK(NMC_EcatSdoWrite(dev, 0, 0x6041, 0, 2, v, &abort_code) == RTN_OBJECT, "read-only");
    CHECK(abort_code == 0x06010002u, "read-only: %#x", abort_code);
    CHECK(NMC_EcatSdoRead(dev, 0, 0x2000, 0, 4, v, &abort_code) == RTN_OBJECT, "no object");
    CHECK(abort_code == 0x06020000u, "no object: %#x", abort_code);
    abort_code = 0;
    CHECK(NMC_EcatSdoRead(dev, 2, 0x6041, 0, 2, v, &abort_code) == RTN_OBJECT, "I/O slave");
    CHECK(abort_code == 0x06020000u, "I/O slave has no dictionary: %#x", abort_code);
    CHECK(NMC_EcatSdoRead(dev, 3, 0x6041, 0, 2, v, &abort_code) == RTN_INVALID_SLAVE, "devId 3");
    CHECK(NMC_EcatSdoRead(dev, -1, 0x6041, 0, 2, v, &abort_code) == RTN_INVALID_SLAVE, "devId -1");

    /* Drive functions on a bus axis; refused on a local pulse axis. */
    OK(NMC_EcatAxisGetErrorCode(ax16, &err));
    CHECK(err == 0, "error code %#x", err);
    OK(NMC_EcatAxisGetDi(ax16, &di));
    CHECK(di == 0, "0x60FD at 5000, off the home sensor: %#lx", di);
    CHECK(NMC_EcatStartHome(ax1, 21, 20, 2, 1, 0) == RTN_NOT_ON_THIS_CARD, "pulse axis");
    CHECK(NMC_EcatGetHomeSts(ax1, &st) == RTN_NOT_ON_THIS_CARD, "pulse axis");
    CHECK(NMC_EcatStartHome(ax16, 36, 20, 2, 1, 0) == RTN_ARG_RANGE, "method 36");
    CHECK(NMC_EcatStartHome(ax16, 21, 0, 2, 1, 0) == RTN_ARG_RANGE, "velSwitch 0");
    CHECK(NMC_EcatStartHome(ax17, 21, 20, 2, 1, 0) == RTN_AXIS_DISABLED, "servo off");
    CHECK(home_sts(ax17) == 1, "not started: 001");

    /* TV35: drive homing, method 21: 000 (in progress) ... 011 (OK); the home point reads 0. */
    OK(NMC_EcatStartHome(ax16, 21, 20, 2, 1, 0));
    st = home_end(ax16);
    CHECK(st == 3, "TV35: ended with %u", st);
    EVENTUALLY(NMC_MtGetHomeSts(ax16, &home), home == 0x2);
    wait_still(ax16);
    OK(NMC_MtGetPrfPos(ax16, &pos));
    CHECK(pos > -50 && pos < 50, "home point reads 0, the axis rests just past it: %ld", pos);
    OK(NMC_EcatAxisGetDi(ax16, &di));
    CHECK(!(di & 0x4), "off the home sensor after homing: %#lx", di);
    OK(NMC_MtMovePtpAbs(ax16, 1, 1, 0, 0, 50, 0, -4000));
    wait_still(ax16);
    EVENTUALLY(NMC_EcatAxisGetDi(ax16, &di), di & 0x4);
    /* The encoder of a bus axis is the drive's 0x6064, which the homing redefined (0x607C at
     * the home point): every reading of it says -4000, not the power-on count -7000. */
    EVENTUALLY((pos = sdo_i32(dev, 0, 0x6064), 0), pos == -4000);
    OK(NMC_MtGetEncPos(ax16, &pos));
    CHECK(pos == -4000, "MtGetEncPos after the drive's homing: %ld", pos);
    OK(NMC_GetEncPos(dev, 16, &pos));
    CHECK(pos == -4000, "GetEncPos after the drive's homing: %ld", pos);

    /* TV35: NMC_EcatStopHome mid-way: not 011. */
    servo_on(ax17);
    OK(NMC_EcatStartHome(ax17, 21, 5, 1, 1, 0));
    CHECK(home_sts(ax17) == 0, "in progress");
    EVENTUALLY(NMC_MtGetPrfPos(ax17, &pos), pos < -100);
    OK(NMC_EcatStopHome(ax17));
    wait_still(ax17);
    st = home_sts(ax17);
    CHECK(st == 1, "TV35: a stopped homing reads 001 (interrupted), not 011: %u", st);

    /* TV36: THomeSetting.mode = 1021 + NMC_MtHome = NMC_EcatStartHome method 21. */
    OK(NMC_MtGetHomePara(ax17, &hs));
    hs.mode = 1021;
    hs.scan1stVel = 20;
    hs.scan2ndVel = 2;
    hs.acc = 1;
    hs.offset = 0;
    OK(NMC_MtSetHomePara(ax17, &hs));
    OK(NMC_MtHome(ax17));
    OK(NMC_MtGetHomeSts(ax17, &home));
    CHECK(home & 0x1, "TV36: homing at once %#x", home);
    st = home_end(ax17);
    CHECK(st == 3, "TV36: ended with %u", st);
    EVENTUALLY(NMC_MtGetHomeSts(ax17, &home), home == 0x2);
    hs.mode = 1036;
    OK(NMC_MtSetHomePara(ax17, &hs));
    CHECK(NMC_MtHome(ax17) == RTN_ARG_RANGE, "mode 1036: method 36");

    /* A drive fault is the alarm bit; NMC_MtClrError resets the drive (E-stop → Fault). */
    OK(NMC_MtEstp(ax16));
    EVENTUALLY(NMC_MtGetSts(ax16, &sts), (sts & BIT_AXIS_ALM) && !(sts & BIT_AXIS_SVON));
    EVENTUALLY((w = statusword(dev, 0), 0), (w & 0x4F) == 0x0008); /* Fault */
    OK(NMC_EcatAxisGetErrorCode(ax16, &err));
    CHECK(err != 0, "0x603F names the fault");
    OK(NMC_MtClrError(ax16));
    EVENTUALLY(NMC_MtGetSts(ax16, &sts), !(sts & (BIT_AXIS_ALM | BIT_AXIS_ESTP)));
    EVENTUALLY((w = statusword(dev, 0), 0), (w & 0x4F) == SWITCH_ON_DISABLED); /* reset */
    servo_on(ax16);
    OK(NMC_MtSetSvOff(ax16));
    EVENTUALLY(NMC_MtGetSts(ax16, &sts), !(sts & BIT_AXIS_SVON));
    EVENTUALLY((w = statusword(dev, 0), 0), (w & 0x4F) == SWITCH_ON_DISABLED);

    /* Axis numbers passed as arguments name the bus drives from 16, as NMC_MtOpen does: mask
     * bit 17 of NMC_MtUpdateMulti starts axis 17's PTP move; bit 2 names no axis of this card
     * (its local axes are 0 and 1) and is refused, as is a gear master 2; master 16 is kept. */
    memset(&ptp, 0, sizeof ptp);
    ptp.acc = 1;
    ptp.dec = 1;
    wait_still(ax17);
    OK(NMC_MtGetPrfPos(ax17, &pos));
    OK(NMC_MtSetPrfMode(ax17, MT_PTP_PRF_MODE));
    OK(NMC_MtSetPtpPara(ax17, &ptp));
    OK(NMC_MtSetVel(ax17, 50));
    OK(NMC_MtSetPtpTgtPos(ax17, pos + 3000));
    CHECK(NMC_MtUpdateMulti(ax1, 1L << 2) == RTN_ARG_RANGE, "mask bit 2: no axis 2 on this card");
    OK(NMC_MtUpdateMulti(ax1, 1L << 17));
    wait_still(ax17);
    OK(NMC_MtGetPrfPos(ax17, &pos2));
    CHECK(pos2 == pos + 3000, "UpdateMulti bit 17: from %ld to %ld", pos, pos2);
    CHECK(NMC_MtGearSetMaster(ax1, 2, 1) == RTN_ARG_RANGE, "gear master 2");
    OK(NMC_MtGearSetMaster(ax1, 16, 1));
    OK(NMC_MtGearGetMaster(ax1, &master, &kind));
    CHECK(master == 16 && kind == 1, "gear master read back: %d %d", master, kind);

    /* Argument numbers that name bus axes (decisions.md "NMC EtherCAT bus axes"). ax16 rests
     * at -4000 on its home sensor, so an advanced E-stop group on "home input of axis 16"
     * stops local axis 1 (axMask bit 1) at once; axMask bit 2 (no local axis 2) and diIndex 2
     * are refused. */
    memset(&ex, 0, sizeof ex);
    ex.axMask = 1 << 2;
    ex.diType = 3;
    ex.diIndex = 16;
    ex.diSense = 1;
    CHECK(NMC_SetEstopDIEx(dev, &ex, 0) == RTN_ARG_RANGE, "axMask bit 2: no local axis 2");
    ex.axMask = 1 << 1;
    ex.diIndex = 2;
    CHECK(NMC_SetEstopDIEx(dev, &ex, 0) == RTN_ARG_RANGE, "diIndex 2: no axis 2");
    ex.diIndex = 16;
    OK(NMC_SetEstopDIEx(dev, &ex, 0));
    EVENTUALLY(NMC_MtGetSts(ax1, &sts), sts & BIT_AXIS_ESTP);
    OK(NMC_ClrEstopDIEx(dev, 0));
    OK(NMC_MtClrError(ax1));
    EVENTUALLY(NMC_MtGetSts(ax1, &sts), !(sts & BIT_AXIS_ESTP));
    /* Typed DO: servo-enable/alarm-clear bit k = axis k. */
    OK(NMC_SetDOBitRevsEx(dev, 2, 0, 17, 1));
    OK(NMC_GetDOBitRevsEx(dev, 2, 0, 17, &revs));
    CHECK(revs == 1, "alarm clear of axis 17 inverted: %d", revs);
    OK(NMC_GetDOBitRevsEx(dev, 2, 0, 16, &revs));
    CHECK(revs == 0, "axis 16 untouched: %d", revs);
    CHECK(NMC_SetDOBitRevsEx(dev, 2, 0, 2, 1) == RTN_ARG_RANGE, "bitIndex 2: no axis 2");
    /* A dedicated input's filter by axis number. */
    OK(NMC_SetDIFilter(dev, 3, 0, 16, 7));
    OK(NMC_GetDIFilter(dev, 3, 0, 16, &filt));
    CHECK(filt == 7, "home filter of axis 16: %d", filt);
    CHECK(NMC_SetDIFilter(dev, 3, 0, 2, 7) == RTN_ARG_RANGE, "diIndex 2: no axis 2");
    /* Reverse counters: "others 0~7", the local axes. */
    CHECK(NMC_GetDiReverseCount(dev, 3, 16, counts, 1) == RTN_ARG_RANGE, "counter of axis 16");
    CHECK(NMC_GetDiReverseCount(dev, 3, 1, counts, 2) == RTN_ARG_RANGE, "axes 1, 2");
    OK(NMC_GetDiReverseCount(dev, 3, 0, counts, 2));
    /* encId: an axis's encoder by its NMC number (its actual position, at rest its prfPos). */
    OK(NMC_MtGetPrfPos(ax16, &pos));
    OK(NMC_GetEncPos(dev, 16, &pos2));
    CHECK(pos2 == pos && pos == -4000, "encoder 16 %ld, axis 16 %ld", pos2, pos);
    CHECK(NMC_GetEncPos(dev, 2, &pos2) == RTN_ARG_RANGE, "encId 2: no axis 2");
    /* The collection index. */
    OK(NMC_GetCollectDataAddr(dev, 17, COLLECT_ADDRESS_PRF_POS, &addr, &len));
    CHECK((addr & 0xFFFF) == 17, "address of axis 17's prfPos %#lx", addr);
    CHECK(NMC_GetCollectDataAddr(dev, 2, COLLECT_ADDRESS_PRF_POS, &addr, &len) == RTN_ARG_RANGE,
          "collection index 2: no axis 2");
    /* MtPrfConfig's mapAxisNo defaults to the axis itself. */
    OK(NMC_MtGetPrfConfig(ax17, &map, &port, &pos));
    CHECK(map == 17 && port == 0 && pos == 0, "axis 17 maps to %d %d %ld", map, port, pos);
    printf("ok\n");
    return 0;
}
