/* TV60 and TV61 (digest 001 §6, C3§8.3) on DI0, which the harness drives through the control
 * API: DI0 is high at the start; it falls with axis 2 (a stepper: its encoder counts its own
 * pulses) at 500 and rises again at 1500. The plain
 * capture (DI0, falling edge) latches 500 and sets BIT_AXIS_CAPTSET until cleared (TV60);
 * the advanced capture (CAPT_EX_SRC_GPI, DI0, active low) latches the leading edge at 500 and
 * the trailing edge at 1500, sts 0x3 (TV61). Prints "at 500" / "at 1500" and waits for a line
 * after each. */
#include "check.h"

int main(void) {
    HAND devHandle = 0, axisHandle = 0;
    short sts = 0;
    long pos = 0, adv[2] = {0, 0};
    char line[64];
    TAdvCaptureParam para = {2, CAPT_EX_SRC_GPI, 0, 100, 0};

    OK(NMC_DevOpen(0, &devHandle));
    OK(NMC_MtOpen(devHandle, 2, &axisHandle));
    OK(NMC_MtSetSvOn(axisHandle));
    OK(NMC_MtMovePtpAbs(axisHandle, 1, 1, 0, 0, 20, 0, 500));
    wait_still(axisHandle);
    OK(NMC_MtSetCaptSns(axisHandle, CAPT_MODE_IO, CAPT_IO_SRC_DI0, 0));
    OK(NMC_MtSetCapt(axisHandle));
    OK(NMC_MtSetAdvCaptParam(devHandle, &para, 1));
    printf("at 500\n");
    fflush(stdout);
    if (!fgets(line, sizeof line, stdin)) return 2;
    OK(NMC_MtGetSts(axisHandle, &sts));
    CHECK(sts & BIT_AXIS_CAPTSET, "TV60: CAPTSET %#x", sts);
    OK(NMC_MtGetCaptPos(axisHandle, &pos));
    CHECK(pos == 500, "TV60: captured %ld", pos);
    OK(NMC_MtGetAdvCaptPos(devHandle, &sts, adv, 1));
    CHECK(sts == 0x1 && adv[0] == 500, "TV61 leading: sts %#x pos %ld", sts, adv[0]);

    OK(NMC_MtMovePtpAbs(axisHandle, 1, 1, 0, 0, 20, 0, 1500));
    wait_still(axisHandle);
    printf("at 1500\n");
    fflush(stdout);
    if (!fgets(line, sizeof line, stdin)) return 2;
    OK(NMC_MtGetAdvCaptPos(devHandle, &sts, adv, 1));
    CHECK(sts == 0x3 && adv[0] == 500 && adv[1] == 1500, "TV61: sts %#x pos %ld, %ld", sts,
          adv[0], adv[1]);
    /* BIT_AXIS_CAPTSET stands for every capture channel of the axis, the advanced one that
     * latches its positions included (docs/decisions.md): both cleared, it clears. */
    OK(NMC_MtClrCaptSts(axisHandle));
    OK(NMC_MtClrAdvCaptSts(devHandle, 1));
    OK(NMC_MtGetSts(axisHandle, &sts));
    CHECK(!(sts & BIT_AXIS_CAPTSET), "TV60: CAPTSET after MtClrCaptSts %#x", sts);
    printf("ok\n");
    return 0;
}
