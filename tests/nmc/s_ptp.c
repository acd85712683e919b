/* S-PTP-STEPWISE, S-PTP-ABS, S-PTP-REL (digest 001 §5, C2§5.3.1–5.3.3) with TV11–TV15, TV69. */
#include "check.h"

int main(void) {
    HAND devHandle = 0, axisHandle = 0;
    TPtpPara ptpPara = {0};
    TPtpPara back;
    long pos = 0, tgt = 0;
    short mode = -1, sts;
    double vel = 0, peak = 0, v;
    int raised = 0;

    OK(NMC_DevOpen(0, &devHandle));
    OK(NMC_MtOpen(devHandle, 0, &axisHandle));
    OK(NMC_MtSetSvOn(axisHandle));

    /* TV11 */
    OK(NMC_MtSetPrfMode(axisHandle, MT_JOG_PRF_MODE));
    OK(NMC_MtGetPrfMode(axisHandle, &mode));
    CHECK(mode == 1, "mode %d", mode);

    /* S-PTP-STEPWISE / TV14: vel 1 → 5 after 2000 pulses, target 10000. */
    OK(NMC_MtSetPrfMode(axisHandle, MT_PTP_PRF_MODE));
    ptpPara.acc = 0.5;
    ptpPara.dec = 0.5;
    ptpPara.endVel = 0;
    ptpPara.startVel = 0;
    ptpPara.smoothCoef = 0;
    OK(NMC_MtSetPtpPara(axisHandle, &ptpPara));
    OK(NMC_MtGetPtpPara(axisHandle, &back));
    CHECK(back.acc == 0.5 && back.dec == 0.5 && back.smoothCoef == 0, "ptp para read back");
    OK(NMC_MtSetVel(axisHandle, 1));
    CHECK(NMC_MtSetVel(axisHandle, -5) != 0, "TV15: negative PTP velocity accepted");
    OK(NMC_MtSetPtpTgtPos(axisHandle, 10000));
    OK(NMC_MtUpdate(axisHandle));
    do {
        OK(NMC_MtGetSts(axisHandle, &sts));
        OK(NMC_MtGetAxisPos(axisHandle, &pos));
        OK(NMC_MtGetPrfVel(axisHandle, &v));
        if (!raised) CHECK(v <= 1.0 + 1e-9, "faster than 1 pulse/ms before the change: %f", v);
        if (!raised && pos > 2000) {
            OK(NMC_MtSetVel(axisHandle, 5));
            OK(NMC_MtUpdate(axisHandle));
            raised = 1;
        }
        if (v > peak) peak = v;
    } while (sts & BIT_AXIS_BUSY);
    OK(NMC_MtGetPrfPos(axisHandle, &pos));
    OK(NMC_MtGetPtpTgtPos(axisHandle, &tgt));
    OK(NMC_MtGetVel(axisHandle, &vel));
    CHECK(raised && pos == 10000 && tgt == 10000, "stepwise: raised %d pos %ld tgt %ld", raised, pos, tgt);
    CHECK(peak > 1.0 + 1e-9 && peak <= 5.0 + 1e-9 && vel == 5.0, "stepwise peak %f vel %f", peak, vel);

    /* S-PTP-ABS / TV12: back to 0 first, then to 10000 at 10 pulse/ms. */
    OK(NMC_MtMovePtpAbs(axisHandle, 0.5, 0.5, 0, 0, 10, 0, 0));
    wait_still(axisHandle);
    OK(NMC_MtMovePtpAbs(axisHandle, 0.5, 0.5, 0, 0, 10, 0, 10000));
    peak = 0;
    do {
        OK(NMC_MtGetSts(axisHandle, &sts));
        OK(NMC_MtGetPrfVel(axisHandle, &v));
        if (v > peak) peak = v;
    } while (sts & BIT_AXIS_BUSY);
    OK(NMC_MtGetPrfPos(axisHandle, &pos));
    CHECK(pos == 10000, "abs: %ld", pos);
    CHECK(peak > 9.0 && peak <= 10.0 + 1e-9, "abs peak %f", peak);

    /* S-PTP-REL / TV13 */
    OK(NMC_MtMovePtpRel(axisHandle, 0.5, 0.5, 0, 0, 10, 0, 10010));
    wait_still(axisHandle);
    OK(NMC_MtGetPrfPos(axisHandle, &pos));
    OK(NMC_MtGetPtpTgtPos(axisHandle, &tgt));
    CHECK(pos == 20010 && tgt == 20010, "rel: %ld %ld", pos, tgt);

    /* TV69: smoothCoef 200 is outside [0,199]. */
    CHECK(NMC_MtMovePtpAbs(axisHandle, 0.5, 0.5, 0, 0, 10, 200, 0) == RTN_ARG_RANGE, "TV69");
    printf("ok\n");
    return 0;
}
