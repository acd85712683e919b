/* The 0x14xx coordinate-system functions (digest 001 §2.7, §3.4, §3.9) on the GCN400 fixture:
 * NMC_CrdSetLookaheadPara / GetLookaheadPara (stated defaults, shared settings, lookAheadSwitch 0
 * stops between segments), NMC_CrdGetStsPack4 against the single calls, NMC_CrdBufWaitPos
 * (the path stands until another axis passes a position; a timeout is MVERR). Run on a scaled
 * clock. */
#include "crd_open.h"

static HAND devHandle, crdHandle, ax[4];

static long iabs(long v) { return v < 0 ? -v : v; }

static void line(long seg, long x, long y, double vel, double acc) {
    long tgt[3];
    tgt[0] = x;
    tgt[1] = y;
    tgt[2] = 0;
    OK(NMC_CrdLineXYZEx(crdHandle, seg, 0x7, tgt, 0, vel, acc, 0));
}

static void wait_crd(void) {
    short sts = 0;
    long polls = 0;
    do {
        OK(NMC_CrdGetSts(crdHandle, &sts));
        CHECK(!(sts & BIT_CORD_MVERR), "MVERR, sts %#x", sts);
        CHECK(++polls < 100000000L, "never finished, sts %#x", sts);
    } while (sts & BIT_CORD_BUSY);
}

/* Two collinear lines 0 → 10000 → 20000 on X: the lowest path velocity seen around the joint
 * (1 if no poll fell in the window). */
static double joint_velocity(void) {
    long pos[3];
    short sts = 0;
    double v = 0, low = 1e9;
    int seen = 0;
    OK(NMC_CrdBufClr(crdHandle));
    line(1, 10000, 0, 10, 0.01);
    line(2, 20000, 0, 10, 0.01);
    OK(NMC_CrdEndMtn(crdHandle));
    OK(NMC_CrdStartMtn(crdHandle));
    do {
        OK(NMC_CrdGetSts(crdHandle, &sts));
        OK(NMC_CrdGetPrfPos(crdHandle, 3, pos));
        OK(NMC_CrdGetVel(crdHandle, &v));
        /* At 0.01 pulse/ms² a stop at 10000 slows the path from 5000 on: anywhere in the window
         * it is below 9; a path that keeps its speed is at 10 there. */
        if (pos[0] > 6000 && pos[0] < 14000) {
            seen = 1;
            if (v < low) low = v;
        }
    } while (sts & BIT_CORD_BUSY);
    CHECK(seen, "no poll around the joint");
    line(3, 0, 0, 50, 1);
    OK(NMC_CrdStartMtn(crdHandle));
    wait_crd();
    return low;
}

int main(void) {
    TExtCrdPara ext;
    TLookaheadPara def, lkh, back;
    TPackedCrdSts4 pack;
    long pos[4], enc[4], used = -1, free_ = -1, seg = -1;
    short sts = 0, axSts = 0, i;
    double low;

    OK(NMC_DevOpen(0, &devHandle));
    servo_on_axes(devHandle, 4, ax);
    crdHandle = open_crd(devHandle, 3, 1);

    /* §3.9: the stated defaults. */
    OK(NMC_CrdGetLookaheadPara(crdHandle, &def, 1));
    CHECK(def.lookAheadSwitch == 1 && def.centAccEn == 0 && def.eventTime == 10 && def.accMax == 1000 &&
              def.T == 1 && def.radiusCoef == 1 && def.radiusErr == 200 && def.radiusAng == 7 &&
              def.radiusAngMax == 7 && def.radiusAngMin == 0.5 && iabs((long)(def.preHandleDisAngMin * 10 + 0.5)) == 1 &&
              def.preHandleDisAngMax == 10,
          "defaults: switch %d eventTime %d accMax %f T %f radiusErr %f", def.lookAheadSwitch, def.eventTime,
          def.accMax, def.T, def.radiusErr);
    CHECK(NMC_CrdGetLookaheadPara(crdHandle, &def, 2) == RTN_ARG_RANGE, "defaultFlag 2");
    CHECK(NMC_CrdGetLookaheadPara(crdHandle, NULL, 1) == RTN_NULL_POINTER, "NULL lkhPara");
    CHECK(NMC_CrdSetLookaheadPara(crdHandle, NULL) == RTN_NULL_POINTER, "NULL set");
    CHECK(NMC_CrdGetLookaheadPara(ax[0], &def, 1) == RTN_WRONG_HANDLE_KIND, "axis handle");

    /* Bad values are refused, nothing changes. */
    lkh = def;
    lkh.slowAng = 100;
    lkh.stopAng = 50;
    CHECK(NMC_CrdSetLookaheadPara(crdHandle, &lkh) == RTN_ARG_RANGE, "slowAng > stopAng");
    lkh = def;
    lkh.stopAng = 190;
    CHECK(NMC_CrdSetLookaheadPara(crdHandle, &lkh) == RTN_ARG_RANGE, "stopAng > 180");
    lkh = def;
    lkh.accMax = -1;
    CHECK(NMC_CrdSetLookaheadPara(crdHandle, &lkh) == RTN_ARG_RANGE, "accMax < 0");
    lkh = def;
    lkh.lookAheadSwitch = -1;
    CHECK(NMC_CrdSetLookaheadPara(crdHandle, &lkh) == RTN_ARG_RANGE, "lookAheadSwitch < 0");
    lkh = def;
    lkh.axPropTimeUnitProp = 3;
    CHECK(NMC_CrdSetLookaheadPara(crdHandle, &lkh) == RTN_ARG_RANGE, "axPropTimeUnitProp 3");

    /* Look-ahead on: the path keeps its speed through the joint of two collinear lines. */
    low = joint_velocity();
    CHECK(low > 9.5, "look-ahead on: joint velocity %f", low);

    /* Set and read back; lookAheadSwitch, T and eventTime are TExtCrdPara's too. */
    lkh = def;
    lkh.lookAheadSwitch = 0;
    lkh.T = 2;
    lkh.eventTime = 20;
    lkh.slowAng = 10;
    lkh.stopAng = 170;
    lkh.accMax = 500;
    lkh.centAccEn = 1;
    lkh.centAcc = 0.5;
    lkh.daMax[2] = 3;
    lkh.axProp[1] = 2.5f;
    lkh.minCornerVel = 0.25f;
    OK(NMC_CrdSetLookaheadPara(crdHandle, &lkh));
    OK(NMC_CrdGetLookaheadPara(crdHandle, &back, 0));
    CHECK(back.lookAheadSwitch == 0 && back.T == 2 && back.eventTime == 20 && back.slowAng == 10 &&
              back.stopAng == 170 && back.accMax == 500 && back.centAccEn == 1 && back.centAcc == 0.5 &&
              back.daMax[2] == 3 && back.axProp[1] == 2.5f && back.minCornerVel == 0.25f,
          "read back: switch %d T %f eventTime %d slow %f stop %f", back.lookAheadSwitch, back.T, back.eventTime,
          back.slowAng, back.stopAng);
    OK(NMC_CrdGetExtPara(crdHandle, &ext));
    CHECK(ext.lookAheadSwitch == 0 && ext.T == 2 && ext.eventTime == 20, "ext para: switch %d T %f eventTime %d",
          ext.lookAheadSwitch, ext.T, ext.eventTime);
    OK(NMC_CrdSetLookAheadCentriAcc(crdHandle, 0, 0));
    OK(NMC_CrdGetLookaheadPara(crdHandle, &back, 0));
    CHECK(back.centAccEn == 0 && back.centAcc == 0, "centripetal off: %d %f", back.centAccEn, back.centAcc);
    OK(NMC_CrdGetLookaheadPara(crdHandle, &back, 1));
    CHECK(back.lookAheadSwitch == 1 && back.accMax == 1000, "defaults unchanged");

    /* Look-ahead off: the path stops at the joint. */
    low = joint_velocity();
    CHECK(low < 9.5, "look-ahead off: joint velocity %f", low);
    lkh.lookAheadSwitch = 1;
    lkh.slowAng = 0;
    lkh.stopAng = 0;
    OK(NMC_CrdSetLookaheadPara(crdHandle, &lkh));
    low = joint_velocity();
    CHECK(low > 9.5, "look-ahead back on: joint velocity %f", low);

    /* §3.4 NMC_CrdGetStsPack4 agrees with the single calls. */
    OK(NMC_SetDOBit(devHandle, 2, 0));
    OK(NMC_CrdBufClr(crdHandle));
    line(7, 3000, -2000, 10, 1);
    OK(NMC_CrdStartMtn(crdHandle));
    wait_crd();
    for (i = 0; i < 3; i++) wait_still(ax[i]);
    /* The encoder follows the command with a lag: fence on it reaching the target (a bounded
     * poll; on a loaded host the calls are milliseconds apart) before comparing the reads. */
    {
        long polls = 0;
        do {
            OK(NMC_CrdGetEncPos(crdHandle, 3, enc));
            CHECK(++polls < 1000000L, "encoder never reached (3000,-2000): (%ld,%ld)", enc[0], enc[1]);
        } while (iabs(enc[0] - 3000) > 1 || iabs(enc[1] + 2000) > 1);
    }
    OK(NMC_CrdGetStsPack4(crdHandle, &pack));
    OK(NMC_CrdGetSts(crdHandle, &sts));
    OK(NMC_CrdGetPrfPos(crdHandle, 3, pos));
    OK(NMC_CrdGetEncPos(crdHandle, 3, enc));
    OK(NMC_CrdBufGetUsed(crdHandle, &used));
    OK(NMC_CrdBufGetFree(crdHandle, &free_));
    OK(NMC_CrdGetUserSegNo(crdHandle, &seg));
    OK(NMC_MtGetSts(ax[1], &axSts));
    CHECK(pack.crdSts == sts && (pack.crdSts & BIT_CORD_EMPTY), "crdSts %#x vs %#x", pack.crdSts, sts);
    CHECK(pack.prfPos[0] == 3000 && pack.prfPos[1] == -2000 && pack.prfPos[2] == 0 && pack.prfPos[3] == 0,
          "prfPos %ld %ld %ld", pack.prfPos[0], pack.prfPos[1], pack.prfPos[2]);
    CHECK(pack.axisPos[0] == 3000 && pack.axisPos[1] == -2000, "axisPos %ld %ld", pack.axisPos[0], pack.axisPos[1]);
    /* Settled above: the pack and the single call read the same encoder within a count. */
    CHECK(iabs(pack.encPos[0] - enc[0]) <= 1 && iabs(pack.encPos[1] - enc[1]) <= 1 && iabs(enc[0] - 3000) <= 1 &&
              iabs(pack.encPos[0] - 3000) <= 1,
          "encPos %ld/%ld", pack.encPos[0], enc[0]);
    CHECK(pack.userSeg == seg && seg == 7, "userSeg %ld %ld", pack.userSeg, seg);
    CHECK(pack.crdUsedSpace == used && pack.crdFreeSpace == free_ && free_ > 0, "used %ld/%ld free %ld/%ld",
          pack.crdUsedSpace, used, pack.crdFreeSpace, free_);
    CHECK(pack.axSts[1] == axSts, "axSts %#x vs %#x", pack.axSts[1], axSts);
    CHECK(pack.prfVel == 0 && (pack.gpDo & 0x4) == 0, "prfVel %f gpDo %#lx", pack.prfVel, pack.gpDo);
    OK(NMC_SetDOBit(devHandle, 2, 1));
    OK(NMC_CrdGetStsPack4(crdHandle, &pack));
    CHECK(pack.gpDo & 0x4, "gpDo %#lx after DO2 on", pack.gpDo);
    CHECK(NMC_CrdGetStsPack4(crdHandle, NULL) == RTN_NULL_POINTER, "NULL pack");

    /* NMC_CrdBufWaitPos: the path stands at (3000,-2000) until axis 3's planned position is ≥ 2000. */
    CHECK(NMC_CrdBufWaitPos(crdHandle, 8, 3, 2, 2000, 1, 0) == RTN_ARG_RANGE, "condition 2");
    CHECK(NMC_CrdBufWaitPos(crdHandle, 8, 3, 1, 2000, 2, 0) == RTN_ARG_RANGE, "posSrc 2");
    CHECK(NMC_CrdBufWaitPos(crdHandle, 8, 99, 1, 2000, 1, 0) == RTN_ARG_RANGE, "axisNo 99");
    CHECK(NMC_CrdBufWaitPos(crdHandle, 8, 3, 1, 2000, 1, -1) == RTN_ARG_RANGE, "overTime -1");
    OK(NMC_MtSetPrfMode(ax[3], MT_PTP_PRF_MODE));
    OK(NMC_MtMovePtpAbs(ax[3], 1, 1, 0, 0, 20, 0, 0));
    wait_still(ax[3]);
    OK(NMC_CrdBufClr(crdHandle));
    OK(NMC_CrdBufWaitPos(crdHandle, 8, 3, 1, 2000, 1, 0));
    line(9, 0, 0, 10, 1);
    OK(NMC_CrdStartMtn(crdHandle));
    {
        long i3 = 0, k;
        for (k = 0; k < 2000; k++) {
            OK(NMC_CrdGetPrfPos(crdHandle, 3, pos));
            CHECK(pos[0] == 3000 && pos[1] == -2000, "left before axis 3 passed 2000: (%ld,%ld)", pos[0], pos[1]);
            OK(NMC_CrdGetSts(crdHandle, &sts));
            CHECK(sts & BIT_CORD_BUSY, "not busy while waiting: %#x", sts);
        }
        OK(NMC_MtMovePtpAbs(ax[3], 0.1, 0.1, 0, 0, 5, 0, 4000));
        do {
            OK(NMC_CrdGetPrfPos(crdHandle, 3, pos));
            OK(NMC_MtGetPrfPos(ax[3], &i3));
        } while (pos[0] == 3000);
        CHECK(i3 >= 2000, "the path left with axis 3 at %ld", i3);
    }
    wait_crd();
    OK(NMC_CrdGetPrfPos(crdHandle, 3, pos));
    CHECK(pos[0] == 0 && pos[1] == 0, "after the wait at (%ld,%ld)", pos[0], pos[1]);
    wait_still(ax[3]);

    /* ≤ on the encoder position, already met: no stop at all; then one never met times out. */
    OK(NMC_CrdBufClr(crdHandle));
    OK(NMC_CrdBufWaitPos(crdHandle, 10, 3, 0, 5000, 0, 0));
    line(11, 1000, 0, 10, 1);
    OK(NMC_CrdBufWaitPos(crdHandle, 12, 3, 0, -5000, 0, 200));
    line(13, 0, 0, 10, 1);
    OK(NMC_CrdStartMtn(crdHandle));
    do {
        OK(NMC_CrdGetSts(crdHandle, &sts));
    } while ((sts & BIT_CORD_BUSY) && !(sts & BIT_CORD_MVERR));
    OK(NMC_CrdGetPrfPos(crdHandle, 3, pos));
    CHECK((sts & BIT_CORD_MVERR) && pos[0] == 1000, "timeout: sts %#x at %ld", sts, pos[0]);
    OK(NMC_CrdClrError(crdHandle));

    OK(NMC_CrdClose(&crdHandle));
    printf("ok\n");
    return 0;
}
