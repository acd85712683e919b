/* S-CRD-INIT, -LINE, -ARC, -HELIX, -3DARC, -D8, -BUFIO, -FULL, -RUN (digest 001 §5, C2§7) with
 * TV04, TV42-TV54 on the GCN400 fixture (4 axes: the D8 example's extra axes 3-5 become axis 3,
 * TV47's six targets four). Run on a scaled clock; times are read from NMC_GetClock (125 µs). */
#include "check.h"

static HAND devHandle, crdHandle, ax[4];

static long iabs(long v) { return v < 0 ? -v : v; }

/* Extremes of X and Y seen while the coordinate system runs, and the longest XY chord between
 * two polls, squared: on a loaded host the polls can be far apart. */
typedef struct {
    long minX, maxX, minY, maxY;
    double max_step2;
} Box;

/* 30 pulses, plus what polls a chord c apart can miss of an arc of radius r at its extreme:
 * r(1 − cos(c/2r)) ≤ c²/8r (as in s_crd_circle.c). */
static long slack(const Box *b, double r) { return 30 + (long)(b->max_step2 / (8 * r)); }

static void run(Box *box) {
    short sts = 0;
    long pos[3], last[2] = {0, 0}, polls = 0;
    if (box) {
        box->minX = box->minY = 2147483647L;
        box->maxX = box->maxY = -2147483647L;
        box->max_step2 = 0;
    }
    OK(NMC_CrdEndMtn(crdHandle));
    OK(NMC_CrdStartMtn(crdHandle));
    do {
        OK(NMC_CrdGetSts(crdHandle, &sts));
        OK(NMC_CrdGetPrfPos(crdHandle, 3, pos));
        if (box) {
            double dx = (double)(pos[0] - last[0]), dy = (double)(pos[1] - last[1]);
            if (polls > 0 && dx * dx + dy * dy > box->max_step2) box->max_step2 = dx * dx + dy * dy;
            last[0] = pos[0];
            last[1] = pos[1];
            if (pos[0] < box->minX) box->minX = pos[0];
            if (pos[0] > box->maxX) box->maxX = pos[0];
            if (pos[1] < box->minY) box->minY = pos[1];
            if (pos[1] > box->maxY) box->maxY = pos[1];
        }
        if (sts & BIT_CORD_MVERR) {
            long segNo = -1;
            OK(NMC_CrdGetUserSegNo(crdHandle, &segNo));
            CHECK(0, "MVERR while running segment %ld at (%ld,%ld,%ld), sts %#x", segNo, pos[0], pos[1], pos[2], sts);
        }
        CHECK(++polls < 100000000L, "never finished, sts %#x", sts);
    } while (sts & BIT_CORD_BUSY);
}

static void at(long x, long y, long z) {
    long pos[3];
    OK(NMC_CrdGetPrfPos(crdHandle, 3, pos));
    CHECK(pos[0] == x && pos[1] == y && pos[2] == z, "at (%ld,%ld,%ld), expected (%ld,%ld,%ld)",
          pos[0], pos[1], pos[2], x, y, z);
}

static void line(long seg, long x, long y, long z, double vel, double acc) {
    long tgt[3];
    tgt[0] = x;
    tgt[1] = y;
    tgt[2] = z;
    OK(NMC_CrdLineXYZEx(crdHandle, seg, 0x7, tgt, 0, vel, acc, 0));
}

static unsigned long clock_ms(void) {
    unsigned long clk = 0, loop = 0;
    OK(NMC_GetClock(devHandle, &clk, &loop));
    return clk / 8; /* 125 µs ticks */
}

int main(void) {
    TCrdConfig crdConfig = {0}, back = {0};
    TCrdPara crdPara = {0};
    TCrdSafePara crdSafePara;
    TCrdLineXYZD8Unit pack[19];
    HAND other = 0;
    long used = -1, cnt = -1, seg = -1, pos[4], d8[8], one[1], tgt[3], center[3];
    short sts = 0, i;
    double ovr = 0, v = 0, peak = 0;
    Box box;

    OK(NMC_DevOpen(0, &devHandle));
    for (i = 0; i < 4; i++) {
        OK(NMC_MtOpen(devHandle, i, &ax[i]));
        OK(NMC_MtClrError(ax[i]));
        OK(NMC_MtSetSvOn(ax[i]));
    }

    /* TV04: itemNo ∈ [0,1]. */
    CHECK(NMC_CrdOpenEx(devHandle, 2, &other) == RTN_ARG_RANGE, "TV04");
    OK(NMC_CrdOpen(devHandle, &crdHandle));

    /* TV52: at most 4 axes. */
    crdConfig.axCnts = 5;
    CHECK(NMC_CrdConfig(crdHandle, &crdConfig) == RTN_ARG_RANGE, "TV52");

    /* S-CRD-INIT */
    crdConfig.axCnts = 3;
    crdConfig.pAxArray[0] = 0;
    crdConfig.pAxArray[1] = 1;
    crdConfig.pAxArray[2] = 2;
    crdConfig.pAxArray[3] = -1;
    OK(NMC_CrdConfig(crdHandle, &crdConfig));
    OK(NMC_CrdGetConfig(crdHandle, &back));
    CHECK(back.axCnts == 3 && back.pAxArray[2] == 2 && back.pAxArray[3] == -1, "config read back");
    crdPara.orgFlag = 1;
    crdPara.synAccMax = 50;
    crdPara.synVelMax = 800;
    OK(NMC_CrdSetPara(crdHandle, &crdPara));
    crdSafePara.estpDec = 1000;
    crdSafePara.maxAcc = 50;
    crdSafePara.maxVel = 800;
    OK(NMC_CrdSetSafePara(crdHandle, &crdSafePara));
    OK(NMC_CrdClrError(crdHandle));
    OK(NMC_CrdBufClr(crdHandle));

    /* TV50 */
    OK(NMC_CrdBufGetUsed(crdHandle, &used));
    OK(NMC_CrdGetSts(crdHandle, &sts));
    CHECK(used == 0 && (sts & BIT_CORD_EMPTY) && !(sts & BIT_CORD_BUSY), "TV50: used %ld sts %#x", used, sts);

    /* TV51 */
    CHECK(NMC_CrdSetOverride(crdHandle, 10) == RTN_ARG_RANGE, "TV51: 10");
    CHECK(NMC_CrdSetOverride(crdHandle, 0) == RTN_ARG_RANGE, "TV51: 0");
    OK(NMC_CrdSetOverRide(crdHandle, 1));
    OK(NMC_CrdGetOverride(crdHandle, &ovr));
    CHECK(ovr == 1, "override %f", ovr);

    /* Bad handles and pointers. */
    CHECK(NMC_CrdGetSts(crdHandle, NULL) == RTN_NULL_POINTER, "NULL status");
    CHECK(NMC_CrdLineXYZEx(crdHandle, 0, 7, NULL, 0, 10, 1, 0) == RTN_NULL_POINTER, "NULL target");
    CHECK(NMC_CrdGetSts(ax[0], &sts) == RTN_WRONG_HANDLE_KIND, "axis handle as crd handle");
    CHECK(NMC_CrdGetSts(0, &sts) == RTN_INVALID_HANDLE, "handle 0");

    /* S-CRD-LINE: pushed first, nothing moves before the start. */
    line(0, 10000, 10000, 0, 10, 0.5);
    line(1, 0, 0, 0, 10, 0.5);
    OK(NMC_CrdBufGetUsed(crdHandle, &used));
    OK(NMC_CrdGetBufAllCmdCnt(crdHandle, &cnt));
    CHECK(used == 2 && cnt == 2, "pushed: used %ld count %ld", used, cnt);
    at(0, 0, 0);
    run(&box);
    at(0, 0, 0);
    /* Polled: the corner itself may fall between two polls on a loaded machine. */
    CHECK(box.maxX >= 9000 && box.maxY >= 9000, "S-CRD-LINE reached (%ld,%ld)", box.maxX, box.maxY);
    OK(NMC_CrdGetUserSegNo(crdHandle, &seg));
    CHECK(seg == 1, "last segment %ld", seg);

    /* TV49: stop mid-segment keeps the buffer; start resumes. */
    OK(NMC_CrdBufClr(crdHandle));
    line(0, 10000, 10000, 0, 10, 0.5);
    line(1, 0, 0, 0, 10, 0.5);
    OK(NMC_CrdStartMtn(crdHandle));
    do {
        OK(NMC_CrdGetPrfPos(crdHandle, 3, pos));
    } while (pos[0] < 3000);
    OK(NMC_CrdStopMtn(crdHandle));
    do {
        OK(NMC_CrdGetSts(crdHandle, &sts));
    } while (sts & BIT_CORD_BUSY);
    OK(NMC_CrdBufGetUsed(crdHandle, &used));
    OK(NMC_CrdGetPrfPos(crdHandle, 3, pos));
    CHECK(used > 0 && pos[0] < 10000, "TV49: used %ld x %ld", used, pos[0]);
    run(NULL);
    at(0, 0, 0);

    /* TV51: override 0.5 halves the path speed. */
    OK(NMC_CrdBufClr(crdHandle));
    OK(NMC_CrdSetOverride(crdHandle, 0.5));
    line(0, 10000, 0, 0, 10, 0.5);
    OK(NMC_CrdStartMtn(crdHandle));
    do {
        OK(NMC_CrdGetSts(crdHandle, &sts));
        OK(NMC_CrdGetVel(crdHandle, &v));
        if (v > peak) peak = v;
    } while (sts & BIT_CORD_BUSY);
    CHECK(peak > 4.5 && peak <= 5.0 + 1e-6, "TV51: peak %f at override 0.5", peak);
    OK(NMC_CrdSetOverride(crdHandle, 1));

    /* S-CRD-ARC / TV43: a full CW circle from (0,0) about (5000,5000). */
    OK(NMC_CrdBufClr(crdHandle));
    line(0, 0, 0, 0, 10, 1);
    tgt[0] = 0;
    tgt[1] = 0;
    center[0] = 5000;
    center[1] = 5000;
    OK(NMC_CrdArcCenterEx(crdHandle, 1, tgt, center, 0, 0, 10, 1, 0));
    run(&box);
    at(0, 0, 0);
    CHECK(iabs(box.maxX - 12071) <= slack(&box, 7071) && iabs(box.minX + 2071) <= slack(&box, 7071), "TV43: x in [%ld, %ld]", box.minX, box.maxX);

    /* TV44: semicircle by radius 2500 to (3000,4000), CCW: through (4000,2000) and (1500,-500). */
    OK(NMC_CrdBufClr(crdHandle));
    tgt[0] = 3000;
    tgt[1] = 4000;
    OK(NMC_CrdArcRadiusEx(crdHandle, 2, tgt, 2500, 1, 0, 10, 1, 0));
    /* S-CRD-ARC's three-point arc back to (0,0) through (5000,-5000). */
    tgt[0] = 0;
    tgt[1] = 0;
    center[0] = 5000;
    center[1] = -5000;
    OK(NMC_CrdArcPPPEx(crdHandle, 3, center, tgt, 0, 10, 1, 0));
    run(&box);
    at(0, 0, 0);
    CHECK(box.maxX >= 9000 && box.minY <= -4990, "ArcPPP passes (5000,-5000): x max %ld y min %ld", box.maxX, box.minY);

    OK(NMC_CrdBufClr(crdHandle));
    tgt[0] = 3000;
    tgt[1] = 4000;
    OK(NMC_CrdArcRadiusEx(crdHandle, 2, tgt, 2500, 1, 0, 10, 1, 0));
    run(&box);
    at(3000, 4000, 0);
    CHECK(iabs(box.maxX - 4000) <= slack(&box, 2500) && iabs(box.minY + 500) <= slack(&box, 2500) && box.minX >= -2, "TV44: x [%ld,%ld] y min %ld",
          box.minX, box.maxX, box.minY);

    /* TV45: +r the minor arc, -r the major one. */
    OK(NMC_CrdBufClr(crdHandle));
    line(0, 0, 0, 0, 10, 1);
    run(NULL);
    OK(NMC_CrdBufClr(crdHandle));
    tgt[0] = 10000;
    tgt[1] = 0;
    /* CCW (dir 1), so that Y stays above the fixture's -10000 limit. */
    OK(NMC_CrdArcRadiusEx(crdHandle, 1, tgt, 10000, 1, 0, 20, 1, 0));
    run(&box);
    at(10000, 0, 0);
    CHECK(iabs(box.minY + 1340) <= slack(&box, 10000) && box.maxY <= 1, "TV45 minor: y [%ld,%ld]", box.minY, box.maxY);
    OK(NMC_CrdBufClr(crdHandle));
    tgt[0] = 0;
    OK(NMC_CrdArcRadiusEx(crdHandle, 1, tgt, -10000, 1, 0, 20, 1, 0));
    run(&box);
    at(0, 0, 0);
    CHECK(iabs(box.maxY - 18660) <= slack(&box, 10000), "TV45 major: y [%ld,%ld]", box.minY, box.maxY);

    /* S-CRD-HELIX / TV46: 5 CW turns about (5000,0), Z 0 → 20000. */
    OK(NMC_CrdBufClr(crdHandle));
    line(15, 0, 0, 0, 10, 1);
    run(NULL);
    OK(NMC_CrdBufClr(crdHandle));
    tgt[0] = 0;
    tgt[1] = 0;
    tgt[2] = 20000;
    center[0] = 5000;
    center[1] = 0;
    OK(NMC_CrdHelixCenterEx(crdHandle, 16, tgt, center, 0, 5, 0, 50, 1, 0));
    run(&box);
    at(0, 0, 20000);
    CHECK(iabs(box.maxX - 10000) <= slack(&box, 5000) && iabs(box.maxY - 5000) <= slack(&box, 5000), "TV46: x max %ld y max %ld", box.maxX, box.maxY);

    /* S-CRD-3DARC: the legacy 7-argument NMC_CrdArc3D. */
    OK(NMC_CrdBufClr(crdHandle));
    line(17, 0, 0, 0, 50, 1);
    run(NULL);
    OK(NMC_CrdBufClr(crdHandle));
    center[0] = 5000;
    center[1] = 5000;
    center[2] = 5000;
    tgt[0] = 0;
    tgt[1] = 0;
    tgt[2] = 10000;
    OK(NMC_CrdArc3D(crdHandle, 18, center, tgt, 0, 10, 1));
    run(&box);
    at(0, 0, 10000);
    CHECK(box.maxX >= 4900 && box.maxY >= 4900, "3-D arc through (5000,5000,5000): %ld %ld", box.maxX, box.maxY);

    /* S-CRD-D8 / TV47 with axis 3 as the extra axis; TV53. */
    OK(NMC_CrdBufClr(crdHandle));
    for (i = 0; i < 8; i++) d8[i] = 10000;
    OK(NMC_CrdLineXYZD8(crdHandle, 4, 0x7, 0x8, d8, 0, 10, 1, 0));
    d8[0] = 0;
    d8[1] = 10000;
    d8[2] = 0;
    d8[3] = 0;
    OK(NMC_CrdLineXYZD8(crdHandle, 5, 0x7, 0x8, d8, 0, 10, 1, 0));
    for (i = 0; i < 19; i++) {
        long k;
        pack[i].segNo = 6 + i;
        pack[i].crdAxMask = 0x7;
        pack[i].extAxMask = 0x8;
        for (k = 0; k < 8; k++) pack[i].tgPos[k] = 0;
        pack[i].tgPos[0] = 1000 * i;
        pack[i].tgPos[1] = -1000 * i;
        pack[i].tgPos[2] = 1000 * i;
        pack[i].tgPos[3] = -1000 * i;
        pack[i].acc = 1;
        pack[i].endVel = 0;
        pack[i].vel = 10; /* the manual's example leaves it uninitialised [sic] */
        pack[i].lookaheadDis = 0;
    }
    CHECK(NMC_CrdLineXYZD8Pack(crdHandle, 19, pack) == RTN_ARG_RANGE, "TV53");
    OK(NMC_CrdLineXYZD8Pack(crdHandle, 10, pack));
    run(NULL);
    wait_still(ax[3]);
    at(9000, -9000, 9000);
    OK(NMC_MtGetPrfPos(ax[3], &pos[3]));
    CHECK(pos[3] == -9000, "TV47: axis 3 at %ld", pos[3]);

    /* S-CRD-BUFIO / TV48 */
    {
        short bit = -1;
        int low_seen = 0, high_seen = 0;
        unsigned long arrived = 0, high_at = 0;
        OK(NMC_SetDOBit(devHandle, 0, 1));
        OK(NMC_CrdBufClr(crdHandle));
        line(19, 0, 0, 0, 10, 1);
        line(20, 10000, 10000, 0, 10, 1);
        OK(NMC_CrdBufDo(crdHandle, 21, 3, 0, 0));
        line(21, 0, 0, 0, 10, 1);
        OK(NMC_CrdBufDelay(crdHandle, 22, 0, 1000));
        OK(NMC_CrdBufDo(crdHandle, 23, 3, 0, 1));
        line(24, 10000, 10000, 0, 10, 1);
        one[0] = 10000;
        OK(NMC_CrdBufAxMoveEx(crdHandle, 25, 0x8, one, 10, 1, 0, 1));
        line(26, 0, 0, 0, 10, 1);
        OK(NMC_CrdEndMtn(crdHandle));
        OK(NMC_CrdStartMtn(crdHandle));
        do {
            OK(NMC_CrdGetSts(crdHandle, &sts));
            OK(NMC_CrdGetPrfPos(crdHandle, 3, pos));
            OK(NMC_GetDOBit(devHandle, 0, &bit));
            if (!low_seen && bit == 0) {
                low_seen = 1;
                CHECK(pos[0] >= 8000 && pos[1] >= 8000, "TV48: DO0 low at (%ld,%ld)", pos[0], pos[1]);
            }
            if (low_seen && !arrived && pos[0] == 0 && pos[1] == 0) {
                arrived = clock_ms();
                CHECK(bit == 0, "TV48: DO0 already high on arriving at the origin");
            }
            if (low_seen && !high_seen && bit == 1) {
                high_seen = 1;
                high_at = clock_ms();
                CHECK(iabs(pos[0]) < 3000 && iabs(pos[1]) < 3000, "TV48: DO0 high at (%ld,%ld)", pos[0], pos[1]);
            }
        } while (sts & BIT_CORD_BUSY);
        CHECK(low_seen && high_seen && arrived, "TV48: low %d high %d arrived %lu", low_seen, high_seen, arrived);
        /* 1000 ms of dwell; the arrival is seen at the first poll after it (a loaded machine
         * polls late), so only half is asserted. */
        CHECK(high_at >= arrived + 500, "TV48: DO0 high %lu ms after arriving", high_at - arrived);
        wait_still(ax[3]);
        OK(NMC_MtGetPrfPos(ax[3], &pos[3]));
        CHECK(pos[3] == 10000, "TV48: axis 3 at %ld", pos[3]);
        at(0, 0, 0);
    }

    /* Relative buffered axis moves with their own parameters; the path waits for them. */
    OK(NMC_CrdBufClr(crdHandle));
    one[0] = -5000;
    CHECK(NMC_CrdBufAxMoveRel(crdHandle, 30, 0x8, one, 1, 0) != 0, "relative move before its parameters");
    OK(NMC_CrdBufSetPtpMovePara(crdHandle, 30, 3, 20, 1, 0));
    OK(NMC_CrdBufAxMoveRel(crdHandle, 31, 0x8, one, 1, 0));
    line(32, 1000, 0, 0, 10, 1);
    OK(NMC_CrdBufWaitEncInPosition(crdHandle, 33, 0x8, 0));
    line(34, 0, 0, 0, 10, 1);
    run(NULL);
    OK(NMC_MtGetPrfPos(ax[3], &pos[3]));
    CHECK(pos[3] == 5000, "relative axis move: axis 3 at %ld", pos[3]);
    at(0, 0, 0);
    OK(NMC_CrdSetLookAheadCentriAcc(crdHandle, 1, 0.5));
    CHECK(NMC_CrdSetLookAheadCentriAcc(crdHandle, 2, 0.5) == RTN_ARG_RANGE, "isUsingSetAcc 2");
    OK(NMC_CrdSetLookAheadCentriAcc(crdHandle, 0, 0));

    /* TV54: a 2 s dwell (scale 1) between two lines. */
    {
        unsigned long t0, t1;
        OK(NMC_CrdBufClr(crdHandle));
        line(1, 100, 0, 0, 10, 1);
        OK(NMC_CrdBufDelay(crdHandle, 2, 1, 2));
        line(3, 0, 0, 0, 10, 1);
        t0 = clock_ms();
        run(NULL);
        t1 = clock_ms();
        CHECK(t1 - t0 >= 2000, "TV54: %lu ms", t1 - t0);
    }

    /* S-CRD-FULL / TV42: XYZ, synAccMax 10, synVelMax 50, legacy line and arc, DO1 cleared
     * 100 ms after arriving. */
    {
        long origin[3] = {0, 0, 0};
        long end[2] = {10000, 0};
        long c3[3] = {5000, 0, 0};
        short bit = -1;
        crdPara.synAccMax = 10;
        crdPara.synVelMax = 50;
        OK(NMC_CrdSetPara(crdHandle, &crdPara));
        OK(NMC_SetDOBit(devHandle, 1, 1));
        OK(NMC_CrdBufClr(crdHandle));
        OK(NMC_CrdLineXYZ(crdHandle, 1, 0x7, origin, 0, 2, 0.5));
        OK(NMC_CrdArcCenter(crdHandle, 2, end, c3, 1, 0, 2, 0.5));
        OK(NMC_CrdBufDelay(crdHandle, 3, CRD_BUFF_DELAY_SCALE_MS, 100));
        OK(NMC_CrdBufDo(crdHandle, 4, CRD_BUFF_DO_GPDO1, 1, 0));
        run(&box);
        at(10000, 0, 0);
        CHECK(iabs(box.minY + 5000) <= slack(&box, 5000) && box.maxY <= 1, "TV42: CCW through (5000,-5000): y [%ld,%ld]", box.minY,
              box.maxY);
        OK(NMC_GetDOBit(devHandle, 1, &bit));
        CHECK(bit == 0, "TV42: DO1 %d", bit);
    }

    /* E-stop: MVERR and NODATASTOP until NMC_CrdClrError. */
    OK(NMC_CrdBufClr(crdHandle));
    line(1, 0, 0, 0, 10, 1);
    OK(NMC_CrdStartMtn(crdHandle));
    OK(NMC_CrdEstopMtn(crdHandle));
    OK(NMC_CrdGetSts(crdHandle, &sts));
    CHECK((sts & BIT_CORD_MVERR) && (sts & BIT_CORD_NODATASTOP), "e-stop sts %#x", sts);
    for (i = 0; i < 3; i++) wait_still(ax[i]);
    OK(NMC_CrdClrError(crdHandle));
    OK(NMC_CrdGetSts(crdHandle, &sts));
    CHECK(!(sts & BIT_CORD_MVERR), "after ClrError sts %#x", sts);

    OK(NMC_CrdClose(&crdHandle));
    CHECK(crdHandle == 0, "closed handle %#x", crdHandle);
    printf("ok\n");
    return 0;
}
