/* S-CAPT, S-ADVCAPT (digest 001 §5, C3§8.3) with TV60 and TV62, on axis 0: its home cam
 * covers [0, 5000] pulses and its encoder has an index every 10000 counts. */
#include "check.h"

static void move_to(HAND ax, long pos) {
    OK(NMC_MtMovePtpAbs(ax, 1, 1, 0, 0, 20, 0, pos));
    wait_still(ax);
}

int main(void) {
    HAND devHandle = 0, axisHandle = 0;
    short sts = 0, mode = 9, src = 9, level = 9, count = 0;
    long pos = -1, repeat[32];
    long adv[2] = {-1, -1};
    TAdvCaptureParam para;
    int polls = 0;

    OK(NMC_DevOpen(0, &devHandle));
    OK(NMC_MtOpen(devHandle, 0, &axisHandle));
    OK(NMC_MtSetSvOn(axisHandle));
    move_to(axisHandle, -2000);

    /* S-CAPT with the home input, rising edge (level bit 1): entering the cam at 0 (TV60). */
    OK(NMC_MtSetCaptSns(axisHandle, CAPT_MODE_IO, CAPT_IO_SRC_HOME, 2));
    OK(NMC_MtGetCaptSns(axisHandle, &mode, &src, &level));
    CHECK(mode == CAPT_MODE_IO && src == CAPT_IO_SRC_HOME && level == 2, "sns read back");
    OK(NMC_MtSetCapt(axisHandle));
    OK(NMC_MtGetSts(axisHandle, &sts));
    CHECK(!(sts & BIT_AXIS_CAPTSET), "CAPTSET before the edge %#x", sts);
    move_to(axisHandle, 2000);
    OK(NMC_MtGetSts(axisHandle, &sts));
    CHECK(sts & BIT_AXIS_CAPTSET, "CAPTSET after the edge %#x", sts);
    OK(NMC_MtGetCaptPos(axisHandle, &pos));
    CHECK(pos >= -5 && pos <= 5, "captured at %ld, the cam's edge is 0", pos);
    OK(NMC_MtClrCaptSts(axisHandle));
    OK(NMC_MtGetSts(axisHandle, &sts));
    CHECK(!(sts & BIT_AXIS_CAPTSET), "CAPTSET after MtClrCaptSts %#x", sts);

    /* Repeat capture on the index (TV62: at most 64). */
    CHECK(NMC_MtSetCaptRepeat(axisHandle, 65) != 0, "65 repeats accepted");
    CHECK(NMC_MtSetCaptSns(axisHandle, 4, 0, 0) != 0, "mode 4 accepted");
    OK(NMC_MtSetCaptSns(axisHandle, CAPT_MODE_Z, 0, 1));
    OK(NMC_MtSetCaptRepeat(axisHandle, 3));
    move_to(axisHandle, 35000);
    OK(NMC_MtGetCaptRepeatStatus(axisHandle, &count));
    CHECK(count == 3, "%d index pulses captured", count);
    OK(NMC_MtGetCaptRepeatPosMulti(axisHandle, repeat, 0, 3));
    CHECK(labs(repeat[0] - 10000) <= 2 && labs(repeat[1] - 20000) <= 2 && labs(repeat[2] - 30000) <= 2,
          "index at %ld %ld %ld", repeat[0], repeat[1], repeat[2]);
    CHECK(NMC_MtGetCaptRepeatPosMulti(axisHandle, repeat, 0, 33) != 0, "count 33 accepted");
    CHECK(NMC_MtGetCaptRepeatPosMulti(axisHandle, NULL, 0, 3) == RTN_NULL_POINTER, "NULL");
    OK(NMC_MtSetCaptRepeat(axisHandle, 0));

    /* S-ADVCAPT on the home input of axis 0: the leading edge entering the cam, the trailing
     * edge leaving it at 5000 (sts 0x3). */
    move_to(axisHandle, -2000);
    para.capPosIndex = 0;
    para.filter = 100;
    para.trigIndex = 0;
    para.trigSrc = CAPT_EX_SRC_HOME;
    para.trigValue = 0;
    OK(NMC_MtSetAdvCaptParam(devHandle, &para, 0));
    move_to(axisHandle, 7000);
    do {
        OK(NMC_MtGetAdvCaptPos(devHandle, &sts, adv, 0));
        CHECK(++polls < 1000000, "advanced capture sts %#x", sts);
    } while (sts != 0x3);
    CHECK(adv[0] >= -5 && adv[0] <= 5 && adv[1] >= 4995 && adv[1] <= 5005,
          "edges at %ld and %ld", adv[0], adv[1]);
    OK(NMC_MtClrAdvCaptSts(devHandle, 0));
    OK(NMC_MtGetAdvCaptPos(devHandle, &sts, adv, 0));
    CHECK(sts == 0, "after MtClrAdvCaptSts %#x", sts);
    para.trigSrc = CAPT_EX_SRC_PRFPOS;
    CHECK(NMC_MtSetAdvCaptParam(devHandle, &para, 0) != 0, "threshold source accepted");
    CHECK(NMC_MtSetAdvCaptParam(devHandle, &para, 4) != 0, "channel 4 accepted");
    CHECK(NMC_MtSetAdvCaptParam(axisHandle, &para, 0) == RTN_WRONG_HANDLE_KIND, "axis handle");
    printf("ok\n");
    return 0;
}
