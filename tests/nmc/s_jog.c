/* S-JOG-1, S-JOG-2 (digest 001 §5, C2§5.3.4–5.3.5) with TV16–TV20. */
#include "check.h"

int main(void) {
    HAND devHandle = 0, axisHandle = 0;
    TJogPara jogPara;
    long pos = 0;
    short sts;
    double v = 0, peak = 0;
    int slowed = 0;

    OK(NMC_DevOpen(0, &devHandle));
    OK(NMC_MtOpen(devHandle, 1, &axisHandle));
    OK(NMC_MtSetSvOn(axisHandle));

    /* S-JOG-1: 5 pulse/ms, 1 after 10000, stop after 20000. */
    OK(NMC_MtSetPrfMode(axisHandle, MT_JOG_PRF_MODE));
    jogPara.acc = 0.5;
    jogPara.dec = 0.5;
    jogPara.smoothCoef = 0;
    OK(NMC_MtSetJogPara(axisHandle, &jogPara));
    OK(NMC_MtSetVel(axisHandle, 5));
    OK(NMC_MtUpdate(axisHandle));
    for (;;) {
        OK(NMC_MtGetAxisPos(axisHandle, &pos));
        OK(NMC_MtGetPrfVel(axisHandle, &v));
        if (v > peak) peak = v;
        if (pos > 10000 && !slowed) {
            OK(NMC_MtSetVel(axisHandle, 1));
            OK(NMC_MtUpdate(axisHandle));
            slowed = 1;
        }
        if (pos > 20000) {
            OK(NMC_MtStop(axisHandle));                  /* TV18 */
            break;
        }
    }
    sts = wait_still(axisHandle);
    OK(NMC_MtGetPrfPos(axisHandle, &pos));
    CHECK(peak > 4.9 && peak <= 5.0 + 1e-9, "jog peak %f", peak);
    CHECK(pos > 20000 && pos < 20100, "stopped at %ld", pos);
    CHECK(!(sts & (BIT_AXIS_MVERR | BIT_AXIS_ESTP)), "errors after stop %#x", sts);

    /* S-JOG-2 / TV17 negative, then TV20 abrupt stop: no ESTP, next move allowed. */
    OK(NMC_MtMoveJog(axisHandle, 0.5, 0.5, -5, 0, 0));
    do { OK(NMC_MtGetPrfVel(axisHandle, &v)); } while (v > -5.0 + 1e-9);
    OK(NMC_MtAbruptStop(axisHandle));
    sts = wait_still(axisHandle);
    CHECK(!(sts & BIT_AXIS_ESTP), "abrupt stop set ESTP %#x", sts);

    /* TV16 then TV19: E-stop latches ESTP; clrStsFlag 0 cannot move; ClrError clears it. */
    OK(NMC_MtMoveJog(axisHandle, 0.5, 0.5, 5, 0, 0));
    do { OK(NMC_MtGetPrfVel(axisHandle, &v)); } while (v < 5.0 - 1e-9);
    OK(NMC_MtGetSts(axisHandle, &sts));
    CHECK(sts & BIT_AXIS_BUSY, "jogging sts %#x", sts);
    OK(NMC_MtEstp(axisHandle));
    sts = wait_still(axisHandle);
    CHECK(sts & BIT_AXIS_ESTP, "E-stop sts %#x", sts);
    CHECK(NMC_MtMoveJog(axisHandle, 0.5, 0.5, 5, 0, 0) != 0, "moved with ESTP latched");
    OK(NMC_MtClrError(axisHandle));
    OK(NMC_MtGetSts(axisHandle, &sts));
    CHECK(!(sts & BIT_AXIS_ESTP), "ESTP after ClrError %#x", sts);
    OK(NMC_MtMoveJog(axisHandle, 0.5, 0.5, 5, 0, 1));
    OK(NMC_MtStop(axisHandle));
    wait_still(axisHandle);
    printf("ok\n");
    return 0;
}
