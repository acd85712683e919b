/* NMC_CrdStartExeTimeCalc / _NMC_CrdGetExeTime (digest 001 §2.7 (11)-(12), App. A): the time a
 * buffered program takes, from a dry run of the engine (not run), in ms; the pushed commands
 * never reach the coordinate system. The time is the ticks until the coordinate system is at
 * rest, the last (settling) tick included. A program with blends and arcs is then run, and the
 * ticks it takes, counted by a data collection of the coordinate system, are the estimate. */
#include "collect.h"

static HAND devHandle, crdHandle;

static void line(long seg, long x, double vel, double acc) {
    long tgt[3];
    tgt[0] = x;
    tgt[1] = 0;
    tgt[2] = 0;
    /* endVel 0 and lookaheadDis 1: an exact stop at the end (no blending). */
    OK(NMC_CrdLineXYZEx(crdHandle, seg, 0x7, tgt, 0, vel, acc, 1));
}

/* Lines blended into arcs and each other (look-ahead on, lookaheadDis 0), the last one ending
 * at rest at (0, 0). */
static void blended_program(void) {
    long tgt[3] = {0, 0, 0}, center[3] = {0, 0, 0};
    tgt[0] = 8000;
    OK(NMC_CrdLineXYZEx(crdHandle, 10, 0x3, tgt, 0, 20, 2, 0));
    tgt[0] = 12000;
    tgt[1] = 4000;
    center[0] = 0; /* relative to the arc's start */
    center[1] = 4000;
    OK(NMC_CrdArcCenterEx(crdHandle, 11, tgt, center, 1, 0, 20, 2, 0));
    tgt[0] = 12000;
    tgt[1] = 9000;
    OK(NMC_CrdLineXYZEx(crdHandle, 12, 0x3, tgt, 0, 15, 2, 0));
    tgt[0] = 4000;
    tgt[1] = 9000;
    OK(NMC_CrdArcRadiusEx(crdHandle, 13, tgt, 4000, 1, 0, 20, 2, 0));
    tgt[0] = 0;
    tgt[1] = 0;
    OK(NMC_CrdLineXYZEx(crdHandle, 14, 0x3, tgt, 0, 20, 2, 1));
}

/* Estimate the blended program, then run it with X, Y and the path velocity collected every
 * tick from the first moving one: the samples up to the first at rest at (0, 0), plus the
 * settling tick, are the ticks it took. */
static void estimate_equals_run(HAND dev) {
    TExtCrdPara ext;
    short sts = 0;
    unsigned long clock0 = 0, clock = 0, loop = 0;
    long dataLen = 0, n;
    double t = -1, *data;

    OK(NMC_CrdGetExtPara(crdHandle, &ext));
    ext.lookAheadSwitch = 1;
    OK(NMC_CrdSetExtPara(crdHandle, &ext));
    OK(NMC_CrdStartExeTimeCalc());
    blended_program();
    OK(NMC_CrdGetExeTime(&t));
    CHECK(t > 2000 && t < 5000, "blended program: %.3f ms", t);

    collect_crd(dev, COLLECT_ADDRESS_CRD_VEL0, 1e-9, 0);
    /* Armed for a tick at least, so that the first moving tick is a rising edge. */
    OK(NMC_GetClock(dev, &clock0, &loop));
    do OK(NMC_GetClock(dev, &clock, &loop)); while (clock == clock0);
    blended_program();
    OK(NMC_CrdStartMtn(crdHandle));
    do {
        OK(NMC_CrdGetSts(crdHandle, &sts));
        CHECK(!(sts & BIT_CORD_MVERR), "MVERR %#x", sts);
    } while (sts & BIT_CORD_BUSY);
    OK(NMC_CollectOnOff(dev, 0));
    OK(NMC_GetCollectSts(dev, &sts, &dataLen));
    CHECK(sts & COLLECT_STS_TRIGGERED, "never moved %#x", sts);
    data = read_all(dev, dataLen);
    for (n = 0; n < dataLen / 24; n++) {
        if (fabs_(data[3 * n]) < 1e-6 && fabs_(data[3 * n + 1]) < 1e-6 && data[3 * n + 2] == 0) break;
    }
    CHECK(n < dataLen / 24, "never at rest at (0, 0) in %ld samples", dataLen / 24);
    CHECK(t == (double)(n + 2), "estimate %.3f ms, ran %ld ticks", t, n + 2);
    free(data);
}

int main(void) {
    double t = -1;
    long used = -1;

    /* No device open: nothing to calculate on. */
    CHECK(NMC_CrdStartExeTimeCalc() == RTN_INVALID_HANDLE, "no device");
    OK(NMC_DevOpen(0, &devHandle));
    CHECK(_NMC_CrdGetExeTime(&t) == RTN_INVALID_STATE, "read before start");
    CHECK(NMC_CrdGetExeTime(NULL) == RTN_NULL_POINTER, "NULL pTime");
    servo_on_axes(devHandle, 3, NULL);
    crdHandle = open_crd(devHandle, 3, 1);

    /* 10000 pulses at 10 pulse/ms, 1 pulse/ms²: 10 + 990 + 10 ms; then a 100 ms delay. */
    OK(NMC_CrdStartExeTimeCalc());
    line(1, 10000, 10, 1);
    OK(NMC_CrdBufDelay(crdHandle, 2, CRD_BUFF_DELAY_SCALE_MS, 100));
    OK(_NMC_CrdGetExeTime(&t));
    /* 1110 ms and the settling tick. */
    CHECK(fabs_(t - 1111) < 1e-6, "line + delay: %.6f ms", t);
    /* Nothing was kept: the buffer is empty, and the calculation has stopped. */
    OK(NMC_CrdBufGetUsed(crdHandle, &used));
    CHECK(used == 0, "buffer holds %ld", used);
    CHECK(NMC_CrdGetExeTime(&t) == RTN_INVALID_STATE, "second read");

    /* There and back, the way back at 5 pulse/ms, 0.5 pulse/ms²: 1010 + (10 + 2000) ms. */
    OK(NMC_CrdStartExeTimeCalc());
    line(3, 10000, 10, 1);
    line(4, 0, 5, 0.5);
    OK(NMC_CrdGetExeTime(&t));
    CHECK(fabs_(t - 3021) < 1e-6, "there and back: %.6f ms", t);

    estimate_equals_run(devHandle);

    printf("ok\n");
    return 0;
}
