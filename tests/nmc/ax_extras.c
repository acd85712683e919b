/* PTP compare (digest 001 §2.5: a velocity change when the axis passes a position), PT
 * parameters read back, the 2-D compare status under its comment name (Appendix A), the
 * damping compensation's ranges and PtStartMtnEx's. The PT start on a DI edge itself is in
 * estop_di.c, whose harness drives the inputs. */
#include "check.h"

int main(void) {
    HAND dev = 0, ax = 0, ax3 = 0;
    short active = 9, out = 9, mode = 0;
    long pos = 0;
    double v = 0;
    TPtPara para = {0}, back = {0};
    TComp2DimensSts a, b;

    OK(NMC_DevOpen(0, &dev));
    OK(NMC_MtOpen(dev, 0, &ax));
    OK(NMC_MtOpen(dev, 3, &ax3));
    OK(NMC_MtSetSvOn(ax));

    /* PTP compare: from 10 to 2 pulse/ms once past 5000. */
    OK(NMC_MtGetPtpCompareSts(ax, &active, &out));
    CHECK(active == 0 && out == 0, "before any compare %d %d", active, out);
    CHECK(NMC_MtSetPtpComparePara(ax, 2, 5000, 2) == RTN_ARG_RANGE, "dir 2 accepted");
    CHECK(NMC_MtSetPtpComparePara(ax, 1, 5000, 0) == RTN_ARG_RANGE, "velocity 0 accepted");
    OK(NMC_MtSetPtpComparePara(ax, 1, 5000, 2));
    OK(NMC_MtGetPtpCompareSts(ax, &active, &out));
    CHECK(active == 1 && out == 0, "armed %d %d", active, out);
    OK(NMC_MtMovePtpAbs(ax, 1, 1, 0, 0, 10, 0, 20000));
    do {
        OK(NMC_MtGetPrfPos(ax, &pos));
        OK(NMC_MtGetPrfVel(ax, &v));
        if (pos < 4500) CHECK(v <= 10.0 + 1e-9, "over 10 before the compare: %f", v);
    } while (pos < 8000);
    CHECK(v > 2.0 - 1e-6 && v < 2.0 + 1e-6, "velocity %f past the compare at %ld", v, pos);
    OK(NMC_MtGetPtpCompareSts(ax, &active, &out));
    CHECK(active == 0 && out == 1, "after the compare %d %d", active, out);
    wait_still(ax);
    OK(NMC_MtGetPrfPos(ax, &pos));
    CHECK(pos == 20000, "the move ended at %ld", pos);

    /* PT parameters read back. */
    para.smoothDec = 0.5;
    OK(NMC_MtPtSetPara(ax3, &para));
    OK(NMC_MtPtGetPara(ax3, &back));
    CHECK(back.smoothDec == 0.5, "smoothDec %f", back.smoothDec);
    CHECK(NMC_MtPtGetPara(ax3, NULL) == RTN_NULL_POINTER, "NULL accepted");

    /* PtStartMtnEx's ranges (diIndex [0, 32], diSns 0/1). */
    CHECK(NMC_MtPtStartMtnEx(ax3, 33, 1) == RTN_ARG_RANGE, "DI 33 accepted");
    CHECK(NMC_MtPtStartMtnEx(ax3, 0, 2) == RTN_ARG_RANGE, "diSns 2 accepted");
    CHECK(NMC_MtPtStartMtnEx(dev, 0, 1) == RTN_WRONG_HANDLE_KIND, "device handle accepted");
    OK(NMC_MtGetPrfMode(ax3, &mode));
    CHECK(mode != MT_PT_PRF_MODE, "a refused start set PT mode");

    /* The alias reads what the Ex call reads. */
    OK(NMC_Comp2DimensStatusEx(dev, 0, &a, 0));
    OK(NMC_Comp2DimensStatus(dev, 0, &b, 0));
    CHECK(a.sts == b.sts && a.freeSpace == b.freeSpace && a.usedSpace == b.usedSpace,
          "Ex %d %ld %ld vs %d %ld %ld", a.sts, a.freeSpace, a.usedSpace, b.sts, b.freeSpace,
          b.usedSpace);
    CHECK(NMC_Comp2DimensStatus(dev, 0, NULL, 0) == RTN_NULL_POINTER, "NULL accepted");

    /* Damping compensation: kept only; its ranges. */
    OK(NMC_MtSetAxisDampCompParam(ax, 1, 100, 1000));
    CHECK(NMC_MtSetAxisDampCompParam(ax, 1, 5, 1000) == RTN_ARG_RANGE, "param1 5 accepted");
    CHECK(NMC_MtSetAxisDampCompParam(ax, 1, 501, 1000) == RTN_ARG_RANGE, "param1 501 accepted");
    CHECK(NMC_MtSetAxisDampCompParam(ax, 2, 100, 1000) == RTN_ARG_RANGE, "enable 2 accepted");
    CHECK(NMC_MtSetAxisDampCompParam(ax, 1, 100, 0) == RTN_ARG_RANGE, "param2 0 accepted");
    printf("ok\n");
    return 0;
}
