/* NMC_CrdStartExeTimeCalc / _NMC_CrdGetExeTime (digest 001 §2.7 (11)-(12), App. A): the time a
 * buffered program takes, computed from what is pushed (not run), in ms; the pushed commands
 * never reach the coordinate system. */
#include "check.h"

static HAND devHandle, crdHandle;

static void line(long seg, long x, double vel, double acc) {
    long tgt[3];
    tgt[0] = x;
    tgt[1] = 0;
    tgt[2] = 0;
    /* endVel 0 and lookaheadDis 1: an exact stop at the end (no blending). */
    OK(NMC_CrdLineXYZEx(crdHandle, seg, 0x7, tgt, 0, vel, acc, 1));
}

static double fabs_(double v) { return v < 0 ? -v : v; }

int main(void) {
    TCrdConfig crdConfig = {0};
    TCrdPara crdPara = {0};
    HAND ax;
    double t = -1;
    long used = -1;
    short i;

    /* No device open: nothing to calculate on. */
    CHECK(NMC_CrdStartExeTimeCalc() == RTN_INVALID_HANDLE, "no device");
    OK(NMC_DevOpen(0, &devHandle));
    CHECK(_NMC_CrdGetExeTime(&t) == RTN_INVALID_STATE, "read before start");
    CHECK(NMC_CrdGetExeTime(NULL) == RTN_NULL_POINTER, "NULL pTime");
    for (i = 0; i < 3; i++) {
        OK(NMC_MtOpen(devHandle, i, &ax));
        OK(NMC_MtClrError(ax));
        OK(NMC_MtSetSvOn(ax));
    }
    OK(NMC_CrdOpen(devHandle, &crdHandle));
    crdConfig.axCnts = 3;
    crdConfig.pAxArray[0] = 0;
    crdConfig.pAxArray[1] = 1;
    crdConfig.pAxArray[2] = 2;
    crdConfig.pAxArray[3] = -1;
    OK(NMC_CrdConfig(crdHandle, &crdConfig));
    crdPara.orgFlag = 1;
    crdPara.synAccMax = 50;
    crdPara.synVelMax = 800;
    OK(NMC_CrdSetPara(crdHandle, &crdPara));
    OK(NMC_CrdClrError(crdHandle));
    OK(NMC_CrdBufClr(crdHandle));

    /* 10000 pulses at 10 pulse/ms, 1 pulse/ms²: 10 + 990 + 10 ms; then a 100 ms delay. */
    OK(NMC_CrdStartExeTimeCalc());
    line(1, 10000, 10, 1);
    OK(NMC_CrdBufDelay(crdHandle, 2, CRD_BUFF_DELAY_SCALE_MS, 100));
    OK(_NMC_CrdGetExeTime(&t));
    CHECK(fabs_(t - 1110) < 1e-6, "line + delay: %.6f ms", t);
    /* Nothing was kept: the buffer is empty, and the calculation has stopped. */
    OK(NMC_CrdBufGetUsed(crdHandle, &used));
    CHECK(used == 0, "buffer holds %ld", used);
    CHECK(NMC_CrdGetExeTime(&t) == RTN_INVALID_STATE, "second read");

    /* There and back, the way back at 5 pulse/ms, 0.5 pulse/ms²: 1010 + (10 + 2000) ms. */
    OK(NMC_CrdStartExeTimeCalc());
    line(3, 10000, 10, 1);
    line(4, 0, 5, 0.5);
    OK(NMC_CrdGetExeTime(&t));
    CHECK(fabs_(t - 3020) < 1e-6, "there and back: %.6f ms", t);

    printf("ok\n");
    return 0;
}
