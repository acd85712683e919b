/* S-PT-STATIC, S-PT-STREAM (digest 001 §5, C3§3.3) with TV55-TV57, and a PVT stream, on axis 3 (at 0 on a fresh
 * mcemu; PT positions are relative to where the stream starts). */
#include "check.h"

int main(void) {
    HAND devHandle = 0, axisHandle = 0;
    short space = 0, used = 0, onOff = 9, mode = 0, sts = 0;
    long loops = 0, pos = 0, i;
    double posArray[33];
    long timeArray[33];
    short typeArray[33];
    TPtPara ptPara = {0};
    TPvtPara pvtPara = {0};

    OK(NMC_DevOpen(0, &devHandle));
    OK(NMC_MtOpen(devHandle, 3, &axisHandle));
    OK(NMC_MtSetSvOn(axisHandle));

    /* S-PT-STATIC, loop count 1 (TV55). */
    OK(NMC_MtSetPrfMode(axisHandle, MT_PT_PRF_MODE));
    ptPara.smoothDec = 1;
    OK(NMC_MtPtSetPara(axisHandle, &ptPara));
    OK(NMC_MtPtSetStatic(axisHandle, 1, 1));
    OK(NMC_MtPtGetStatic(axisHandle, &onOff, &loops));
    CHECK(onOff == 1 && loops == 1, "static %d loops %ld", onOff, loops);
    OK(NMC_MtPtBufClr(axisHandle));
    OK(NMC_MtPtGetSpace(axisHandle, &space, &used));
    CHECK(space == 32 && used == 0, "TV57: space %d used %d", space, used);
    for (i = 0; i < 33; i++) {
        posArray[i] = 0;
        timeArray[i] = 10 * (i + 1);
        typeArray[i] = MT_PT_NORMAL;
    }
    CHECK(NMC_MtPtPush(axisHandle, 33, posArray, timeArray, typeArray) != 0, "TV56: 33 points");
    CHECK(NMC_MtPtPush(axisHandle, 0, posArray, timeArray, typeArray) != 0, "0 points");
    CHECK(NMC_MtPtPush(axisHandle, 1, NULL, timeArray, typeArray) == RTN_NULL_POINTER, "NULL");
    posArray[0] = 10000; posArray[1] = 30000; posArray[2] = 40000;
    timeArray[0] = 100; timeArray[1] = 200; timeArray[2] = 300;
    typeArray[3] = 7;
    CHECK(NMC_MtPtPush(axisHandle, 4, posArray, timeArray, typeArray) != 0, "type 7 accepted");
    OK(NMC_MtPtPush(axisHandle, 3, posArray, timeArray, typeArray));
    OK(NMC_MtPtGetSpace(axisHandle, &space, &used));
    CHECK(space == 29 && used == 3, "after push: space %d used %d", space, used);
    OK(NMC_MtPtStartMtn(axisHandle, 0, NULL));
    OK(NMC_MtGetPrfMode(axisHandle, &mode));
    CHECK(mode == MT_PT_PRF_MODE, "mode %d", mode);
    sts = wait_still(axisHandle);
    OK(NMC_MtGetPrfPos(axisHandle, &pos));
    CHECK(pos == 40000, "TV55: PT ended at %ld", pos);
    CHECK(!(sts & BIT_AXIS_MVERR), "sts %#x", sts);

    /* S-PT-STREAM: refresh mode, one period of a velocity wave (the manual's sine, A = 50
     * pulse/ms, T = 1 s, as a triangle so that no libm is needed) in 16 ms points, then a STOP
     * point at 0; pushed while there is space, started once full. */
    OK(NMC_MtPtSetStatic(axisHandle, 0, 0));
    OK(NMC_MtPtBufClr(axisHandle));
    {
        double p = 0, v = 0, vPrev = 0;
        long t = 0;
        int started = 0, done = 0;
        while (!done) {
            OK(NMC_MtPtGetSpace(axisHandle, &space, &used));
            if (space > 0) {
                short type = MT_PT_NORMAL;
                t += 16;
                if (t >= 1000) {
                    t = 1000;
                    p = 0;
                    type = MT_PT_STOP;
                    done = 1;
                } else {
                    v = t < 250 ? 0.2 * t : t < 750 ? 50 - 0.2 * (t - 250) : -50 + 0.2 * (t - 750);
                    p += (v + vPrev) * 16 / 2;
                    vPrev = v;
                }
                OK(NMC_MtPtPush(axisHandle, 1, &p, &t, &type));
            } else if (!started) {
                OK(NMC_MtPtStartMtn(axisHandle, 0, NULL));
                started = 1;
            }
        }
        if (!started) OK(NMC_MtPtStartMtn(axisHandle, 0, NULL));
    }
    sts = wait_still(axisHandle);
    OK(NMC_MtGetPrfPos(axisHandle, &pos));
    CHECK(pos == 40000, "stream ended at %ld, where it started", pos);
    CHECK(!(sts & BIT_AXIS_MVERR), "stream sts %#x", sts);

    /* PVT: refresh mode, two knots, rest to rest: 0 -> 5000 in 500 ms. */
    pvtPara.smoothDec = 1;
    pvtPara.dataMode = 0;
    OK(NMC_MtPvtSetPara(axisHandle, &pvtPara));
    pvtPara.dataMode = 9;
    OK(NMC_MtPvtGetPara(axisHandle, &pvtPara));
    CHECK(pvtPara.dataMode == 0 && pvtPara.smoothDec == 1, "PVT para read back");
    {
        double pp[2] = {2500, 5000}, tt[2] = {250, 500}, vv[2] = {15, 0};
        OK(NMC_MtPvtData(axisHandle, 2, pp, tt, vv));
    }
    OK(NMC_MtPvtBufGetSpace(axisHandle, &space, &used));
    CHECK(used == 2, "PVT used %d", used);
    OK(NMC_MtPvtStartMtn(axisHandle, 0, NULL));
    wait_still(axisHandle);
    OK(NMC_MtGetPrfPos(axisHandle, &pos));
    CHECK(pos == 45000, "PVT ended at %ld (5000 from its start)", pos);
    OK(NMC_MtPvtBufClr(axisHandle));
    printf("ok\n");
    return 0;
}
