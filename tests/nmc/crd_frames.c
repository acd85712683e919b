/* Coordinate transforms, the buffer offset, arc sections, the A axis's corner velocity and the
 * break point (family 0x17xx; digest 001 §2.7, §2.20 C3§10.5, §3.7; S-TRANS-ROTATE,
 * S-TRANS-XYZA) on the GCN400 fixture on a scaled clock: what each call does to the positions,
 * what it reads back, and the documented code for bad arguments. */
#include <math.h>
#include <string.h>
#include "crd_open.h"

#define PI_ 3.14159265358979

static HAND devHandle, crdHandle, ax[4];

static void configure(short n) {
    TCrdConfig cfg;
    short i;
    memset(&cfg, 0, sizeof cfg);
    cfg.axCnts = n;
    for (i = 0; i < 4; i++) cfg.pAxArray[i] = i < n ? i : -1;
    OK(NMC_CrdConfig(crdHandle, &cfg));
    OK(NMC_CrdClrError(crdHandle));
    OK(NMC_CrdBufClr(crdHandle));
}

/* Start what was pushed and wait until the coordinate system is still. */
static void run(void) {
    OK(NMC_CrdEndMtn(crdHandle));
    OK(NMC_CrdStartMtn(crdHandle));
    crd_still(crdHandle);
}

static long prf(short k) {
    long p = 0;
    OK(NMC_MtGetPrfPos(ax[k], &p));
    return p;
}

/* Axis k's planned position within `tol` pulses of `want`. */
static void near(short k, long want, long tol, const char *what) {
    long p = prf(k);
    CHECK(labs(p - want) <= tol, "%s: axis %d at %ld, expected %ld", what, k, p, want);
}

static void desc_names(short rc, const char *word) {
    char d[512];
    NMC_GetErrDesc(rc, d);
    CHECK(strstr(d, word) != NULL, "description \"%s\" does not name %s", d, word);
}

static void ptp(short k, long target) {
    OK(NMC_MtMovePtpAbs(ax[k], 0.1, 0.1, 0, 0, 20, 0, target));
    wait_still(ax[k]);
}

/* S-TRANS-ROTATE (C3§10.5.3a) in short: the table (axis 3, 10000 pulses a turn) turns about
 * (0, 15000) between segments; a program point is fixed to the table. */
static void rotate(void) {
    long p[4] = {10000, 15000, 0, 0}, rot = -2500, user[2];
    short rc;

    rc = NMC_CrdSetTransRotate(crdHandle, 0, 2 * PI_ / 10000, 0, 15000);
    CHECK(rc == RTN_ARG_RANGE, "a member as the table: %d", rc);
    desc_names(rc, "rotAxisNo");
    CHECK(NMC_CrdSetTransRotate(crdHandle, 9, 2 * PI_ / 10000, 0, 15000) == RTN_ARG_RANGE, "axis 9");
    CHECK(NMC_CrdSetTransRotate(crdHandle, 3, 0, 0, 15000) == RTN_ARG_RANGE, "angleRadEqual 0");
    CHECK(NMC_CrdSetTransRotate(crdHandle, 3, NAN, 0, 15000) == RTN_ARG_RANGE, "angleRadEqual NaN");
    OK(NMC_CrdSetTransRotate(crdHandle, 3, 2 * PI_ / 10000, 0, 15000));

    OK(NMC_CrdBufClr(crdHandle));
    OK(NMC_CrdBufSetPtpMovePara(crdHandle, 0, 3, 3, 0.1, 0));
    /* Table at 0: the program point is the machine point. */
    OK(NMC_CrdLineXYZEx(crdHandle, 1, 0x3, p, 0, 50, 1, 0));
    /* −90°, and the path waits for it (blockEn). */
    OK(NMC_CrdBufAxMoveRel(crdHandle, 2, 0x8, &rot, 1, 0));
    /* (20000, 15000) on the table turned by −90° about (0, 15000): (0, −5000). */
    p[0] = 20000;
    OK(NMC_CrdLineXYZEx(crdHandle, 3, 0x3, p, 0, 50, 1, 0));
    run();
    wait_still(ax[3]);
    near(3, -2500, 0, "table");
    near(0, 0, 2, "rotated X");
    near(1, -5000, 2, "rotated Y");
    /* NMC_CrdGetPrfPos reads the coordinate system's own (program) coordinates, seen on the
     * turned table; NMC_CrdGetAxisPos the machine's. */
    OK(NMC_CrdGetPrfPos(crdHandle, 2, user));
    CHECK(labs(user[0] - 20000) <= 2 && labs(user[1] - 15000) <= 2, "program point (%ld, %ld)", user[0], user[1]);
    OK(NMC_CrdGetAxisPos(crdHandle, 2, user));
    CHECK(labs(user[0]) <= 2 && labs(user[1] + 5000) <= 2, "machine point (%ld, %ld)", user[0], user[1]);

    /* Deleted: machine coordinates again. */
    OK(NMC_CrdDelTransRotate(crdHandle));
    OK(NMC_CrdDelTransRotate(crdHandle)); /* nothing left to delete: still 0 */
    OK(NMC_CrdBufClr(crdHandle));
    p[0] = 1000;
    p[1] = 1000;
    OK(NMC_CrdLineXYZEx(crdHandle, 4, 0x3, p, 0, 50, 1, 0));
    run();
    near(0, 1000, 0, "X after DelTransRotate");
    near(1, 1000, 0, "Y after DelTransRotate");
    ptp(3, 0);
}

/* The polar machine: axis 3 turns (10000 pulses a turn), axis 2 moves along the radius. */
static void polar(void) {
    short rc;
    CHECK(NMC_CrdSetTransPolar(crdHandle, 3, 3, 2 * PI_ / 10000) == RTN_ARG_RANGE, "the same axis twice");
    CHECK(NMC_CrdSetTransPolar(crdHandle, 3, 2, 0) == RTN_ARG_RANGE, "rotEquiv 0");
    rc = NMC_CrdRunToPolarTheta(crdHandle, 1, 10, 0);
    CHECK(rc == RTN_INVALID_STATE, "RunToPolarTheta without the transform: %d", rc);
    OK(NMC_CrdSetTransPolar(crdHandle, 3, 2, 2 * PI_ / 10000));

    /* Two and a half turns, then (5000, 5000): the turns are cleared (25000 → 5000) and the
     * table goes to 45° = 1250 pulses, the radius to √2·5000 = 7071. */
    ptp(3, 25000);
    OK(NMC_CrdRunToPolarPos(crdHandle, 5000, 5000, 10, 10));
    wait_still(ax[3]);
    wait_still(ax[2]);
    near(3, 1250, 0, "polar angle 45°");
    near(2, 7071, 0, "polar radius");

    /* θ = π without clearing: 5000; then from 3 turns + 5000 with clearing, −π/2: −2500. */
    OK(NMC_CrdRunToPolarTheta(crdHandle, PI_, 10, 0));
    wait_still(ax[3]);
    near(3, 5000, 0, "theta π");
    ptp(3, 35000);
    OK(NMC_CrdRunToPolarTheta(crdHandle, -PI_ / 2, 10, 1));
    wait_still(ax[3]);
    near(3, -2500, 0, "theta −π/2 after clearing 3 turns");

    CHECK(NMC_CrdRunToPolarPos(crdHandle, 1, 1, 0, 10) == RTN_ARG_RANGE, "rotVel 0");
    CHECK(NMC_CrdRunToPolarPos(crdHandle, NAN, 1, 10, 10) == RTN_ARG_RANGE, "xPos NaN");
    CHECK(NMC_CrdRunToPolarTheta(crdHandle, 1, 10, 2) == RTN_ARG_RANGE, "clrRoundFlag 2");
    OK(NMC_CrdDelTransPolar(crdHandle));
    CHECK(NMC_CrdRunToPolarTheta(crdHandle, 1, 10, 0) == RTN_INVALID_STATE, "after DelTransPolar");
    ptp(3, 0);
    ptp(2, 0);
}

/* The buffered motion's offset: the user origin at (1000, 2000). */
static void offset(void) {
    long off[2] = {1000, 2000}, zero[2] = {0, 0}, p[2] = {500, 500}, user[2];
    TCrdPara para;
    short rc;

    rc = NMC_CrdSetOffset(crdHandle, 3, off);
    CHECK(rc == RTN_ARG_RANGE, "count 3 on 2 axes: %d", rc);
    desc_names(rc, "count");
    CHECK(NMC_CrdSetOffset(crdHandle, 0, off) == RTN_ARG_RANGE, "count 0");
    CHECK(NMC_CrdSetOffset(crdHandle, 2, NULL) == RTN_NULL_POINTER, "NULL array");
    OK(NMC_CrdSetOffset(crdHandle, 2, off));
    OK(NMC_CrdGetPara(crdHandle, &para));
    CHECK(para.orgFlag == 1 && para.offset[0] == 1000 && para.offset[1] == 2000, "offset read back");
    OK(NMC_CrdBufClr(crdHandle));
    OK(NMC_CrdLineXYZEx(crdHandle, 1, 0x3, p, 0, 50, 1, 0));
    run();
    near(0, 1500, 0, "X with the offset");
    near(1, 2500, 0, "Y with the offset");
    OK(NMC_CrdGetPrfPos(crdHandle, 2, user));
    CHECK(user[0] == 500 && user[1] == 500, "user position (%ld, %ld)", user[0], user[1]);
    OK(NMC_CrdSetOffset(crdHandle, 2, zero));
}

static void arc_sections(void) {
    TArcSecSetting s, back;
    short rc;
    memset(&s, 0, sizeof s);
    s.minSectionLen = 2;
    s.maxArcDiff = 3;
    s.r[0] = 100;
    s.r[1] = 1000;
    s.err[0] = 0.5;
    s.err[1] = 1;
    s.err[2] = 2;
    OK(NMC_CrdSetArcSecPara(crdHandle, &s));
    OK(NMC_CrdGetArcSecPara(crdHandle, &back));
    CHECK(memcmp(&s, &back, sizeof s) == 0, "TArcSecSetting read back");
    back.minSectionLen = 0.5;
    rc = NMC_CrdSetArcSecPara(crdHandle, &back);
    CHECK(rc == RTN_ARG_RANGE, "minSectionLen 0.5: %d", rc);
    desc_names(rc, "minSectionLen");
    back.minSectionLen = 2;
    back.r[0] = 1000;
    back.r[1] = 100;
    CHECK(NMC_CrdSetArcSecPara(crdHandle, &back) == RTN_ARG_RANGE, "descending radii");
    back.r[0] = 100;
    back.r[1] = 1000;
    back.err[1] = -1;
    CHECK(NMC_CrdSetArcSecPara(crdHandle, &back) == RTN_ARG_RANGE, "negative error");
    CHECK(NMC_CrdSetArcSecPara(crdHandle, NULL) == RTN_NULL_POINTER, "NULL");
    OK(NMC_CrdGetArcSecPara(crdHandle, &back));
    CHECK(memcmp(&s, &back, sizeof s) == 0, "a refused setting changes nothing");
    /* Off again (all radii 0). */
    memset(&s, 0, sizeof s);
    s.minSectionLen = 1;
    OK(NMC_CrdSetArcSecPara(crdHandle, &s));

    OK(NMC_CrdSetFourthAxisToTurnVel(crdHandle, 5));
    CHECK(NMC_CrdSetFourthAxisToTurnVel(crdHandle, -1) == RTN_ARG_RANGE, "tolVel −1");
    CHECK(NMC_CrdSetFourthAxisToTurnVel(crdHandle, NAN) == RTN_ARG_RANGE, "tolVel NaN");
    OK(NMC_CrdSetFourthAxisToTurnVel(crdHandle, 0)); /* off again */
}

/* The break point: an E-stop with a slow estpDec carries the axes past where the path was
 * stopped, and keeps the buffer ("急停(并不清空指令缓冲区)"); NMC_CrdGotoBreak brings them
 * back to it and NMC_CrdStartMtn finishes the path: the rest of segment 1, then segment 2. */
static void goto_break(void) {
    long x_back;
    TSafePara slow = {0.05, 32767, 32767}, fast = {32767, 32767, 32767};
    long p[2] = {300000, 2500}, p2[2] = {300000, 12500}, at[2], seg = 0, x_before, x_stopped;
    short rc, k, sts = 0, saw_rest_of_1 = 0, saw_2 = 0;

    for (k = 0; k < 2; k++) OK(NMC_MtSetSafePara(ax[k], &slow));
    rc = NMC_CrdGotoBreak(crdHandle, 1, 10);
    CHECK(rc == RTN_GROUP_STATE, "no break point yet: %d", rc);
    CHECK(NMC_CrdGotoBreak(crdHandle, 0, 10) == RTN_ARG_RANGE, "acc 0");
    CHECK(NMC_CrdGotoBreak(crdHandle, 1, -1) == RTN_ARG_RANGE, "vel −1");

    OK(NMC_CrdBufClr(crdHandle));
    OK(NMC_CrdLineXYZEx(crdHandle, 1, 0x3, p, 0, 20, 1, 0));
    OK(NMC_CrdLineXYZEx(crdHandle, 2, 0x3, p2, 0, 20, 1, 0));
    OK(NMC_CrdStartMtn(crdHandle));
    do {
        OK(NMC_CrdGetPrfPos(crdHandle, 2, at));
    } while (at[0] < 30000);
    x_before = at[0];
    OK(NMC_CrdEstopMtn(crdHandle));
    wait_still(ax[0]);
    x_stopped = prf(0);
    CHECK(x_stopped > x_before + 2000, "the E-stop ramp: from %ld to %ld", x_before, x_stopped);
    rc = NMC_CrdGotoBreak(crdHandle, 1, 10);
    CHECK(rc == RTN_GROUP_STATE, "before NMC_CrdClrError: %d", rc);
    OK(NMC_CrdClrError(crdHandle));
    OK(NMC_CrdGotoBreak(crdHandle, 1, 10));
    OK(NMC_CrdStartMtn(crdHandle));
    do {
        OK(NMC_CrdGetStsEx(crdHandle, &sts, &seg));
        CHECK(!(sts & BIT_CORD_MVERR), "MVERR, sts %#x", sts);
        OK(NMC_CrdGetPrfPos(crdHandle, 2, at));
        if (seg == 1 && at[0] > x_stopped && at[0] < p[0]) {
            /* The rest of segment 1, on its line (not a line from where the ramp ended); the
             * position is read after the segment number, so only before its end. */
            saw_rest_of_1 = 1;
            CHECK(labs(at[1] - 2500) <= 1, "segment 1 off its line at (%ld, %ld)", at[0], at[1]);
        }
        if (seg == 2) saw_2 = 1;
    } while (sts & BIT_CORD_BUSY);
    CHECK(saw_rest_of_1 && saw_2, "segments run after the return: 1 %d, 2 %d", saw_rest_of_1, saw_2);
    near(0, p2[0], 0, "X at the programmed end");
    near(1, p2[1], 0, "Y at the programmed end");
    OK(NMC_CrdGetUserSegNo(crdHandle, &seg));
    CHECK(seg == 2, "last user segment %ld", seg);
    CHECK(NMC_CrdGotoBreak(crdHandle, 1, 10) == RTN_GROUP_STATE, "the break point is used up");
    for (k = 0; k < 2; k++) OK(NMC_MtSetSafePara(ax[k], &fast));

    /* After NMC_CrdStopMtn the axes stand on the path where it halted: nothing to move, and
     * NMC_CrdStartMtn goes on to the end. */
    OK(NMC_CrdBufClr(crdHandle));
    x_back = prf(0);
    p[0] = x_back + 40000;
    p[1] = prf(1);
    OK(NMC_CrdLineXYZEx(crdHandle, 2, 0x3, p, 0, 20, 1, 0));
    OK(NMC_CrdStartMtn(crdHandle));
    do {
        OK(NMC_CrdGetPrfPos(crdHandle, 2, at));
    } while (at[0] < x_back + 10000);
    OK(NMC_CrdStopMtn(crdHandle));
    crd_still(crdHandle);
    x_stopped = prf(0);
    OK(NMC_CrdGotoBreak(crdHandle, 1, 10));
    near(0, x_stopped, 0, "GotoBreak after StopMtn does not move");
    run();
    near(0, p[0], 0, "resumed to the end");
}

/* S-TRANS-XYZA (C3§10.5.3c): A turns 288000 pulses a turn; the tool offset from the
 * manual's measurement (π/3 turned, X −3687 and Y −9494 to come back to the same point). */
static void xyza(void) {
    long tx = 0, ty = 0, tool_x, tool_y, p[4] = {10000, 20000, 0, 48000};
    double rad = 0;
    short map[4] = {0, 1, 2, 3}, bad[4] = {0, 1, 3, 2}, rc;

    configure(4);
    OK(NMC_CrdSetXYZAToolCalc(crdHandle, PI_ / 3, -3687, -9494, &tx, &ty));
    CHECK(labs(tx - 6379) <= 1 && labs(ty + 7940) <= 1, "tool (%ld, %ld)", tx, ty);
    CHECK(NMC_CrdSetXYZAToolCalc(crdHandle, 0, -3687, -9494, &tx, &ty) == RTN_ARG_RANGE, "no turn");
    CHECK(NMC_CrdSetXYZAToolCalc(crdHandle, 1, 1, 1, NULL, &ty) == RTN_NULL_POINTER, "NULL pToolX");
    OK(NMC_CrdSetXYZAPara(crdHandle, 2 * PI_ / 288000, tx, ty));
    OK(NMC_CrdGetXYZAPara(crdHandle, &rad, &tool_x, &tool_y));
    CHECK(rad == 2 * PI_ / 288000 && tool_x == tx && tool_y == ty, "XYZA parameters read back");
    rc = NMC_CrdSetTransXYZA(crdHandle, bad);
    CHECK(rc == RTN_ARG_RANGE, "a map that is not the coordinate system's: %d", rc);
    desc_names(rc, "pAxisMapArray");
    CHECK(NMC_CrdSetTransXYZA(crdHandle, NULL) == RTN_NULL_POINTER, "NULL map");
    OK(NMC_CrdSetTransXYZA(crdHandle, map));

    /* A to 60° with the tip on (10000, 20000, 0): X and Y move as the measurement did. */
    OK(NMC_CrdBufClr(crdHandle));
    OK(NMC_CrdLineXYZA(crdHandle, 1, 0xF, p, 0, 20, 0.2, 0));
    run();
    near(3, 48000, 0, "A");
    near(0, 10000 - 3687, 2, "X with the tool offset");
    near(1, 20000 - 9494, 2, "Y with the tool offset");
    near(2, 0, 0, "Z");
    {
        long prog[4];
        OK(NMC_CrdGetPrfPos(crdHandle, 4, prog));
        CHECK(labs(prog[0] - 10000) <= 2 && labs(prog[1] - 20000) <= 2 && prog[2] == 0 && prog[3] == 48000,
              "the tip in program coordinates (%ld, %ld, %ld, %ld)", prog[0], prog[1], prog[2], prog[3]);
    }

    /* Deleted: the machine point again. */
    OK(NMC_CrdDelTransXYZA(crdHandle));
    OK(NMC_CrdBufClr(crdHandle));
    p[3] = 0;
    OK(NMC_CrdLineXYZA(crdHandle, 2, 0xF, p, 0, 20, 0.2, 0));
    run();
    near(0, 10000, 0, "X after DelTransXYZA");
    near(1, 20000, 0, "Y after DelTransXYZA");
}

int main(void) {
    OK(NMC_DevOpen(0, &devHandle));
    servo_on_axes(devHandle, 4, ax);
    OK(NMC_CrdOpen(devHandle, &crdHandle));
    configure(2);
    rotate();
    polar();
    offset();
    arc_sections();
    goto_break();
    xyza();
    OK(NMC_CrdClose(&crdHandle));
    printf("ok\n");
    return 0;
}
