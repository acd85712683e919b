/* NMC_SaveMotionConfig (digest 001 §1.5, §2.2): `motion_config save` writes a configuration
 * on axis 1 and the encoder 1 mode, saves it, changes one value and checks NMC_DevReset brings
 * the saved one back; `motion_config check`, against a restarted mcemu on the same state
 * directory, reads the saved values back. */
#include <string.h>
#include "check.h"

int main(int argc, char **argv) {
    HAND dev = 0, ax = 0;
    short inv = 0, mode = 0, en = 0;
    unsigned short encMode = 0;
    long pos = 0, neg = 0, err = 0;
    int save = argc > 1 && strcmp(argv[1], "save") == 0;

    OK(NMC_DevOpen(0, &dev));
    OK(NMC_MtOpen(dev, 1, &ax));
    if (save) {
        OK(NMC_MtSwLmtValue(ax, 100000, -100000));
        OK(NMC_MtSwLmtOnOff(ax, 1));
        OK(NMC_MtSetStepMode(ax, 1, 1));
        OK(NMC_SetEncMode(dev, 1, 0x0000));
        OK(NMC_MtSetPosErrLmt(ax, 1234));
        CHECK(NMC_SaveMotionConfig(dev, 2) == RTN_ARG_RANGE, "enable 2 accepted");
        CHECK(NMC_SaveMotionConfig(ax, 1) == RTN_WRONG_HANDLE_KIND, "axis handle accepted");
        OK(NMC_SaveMotionConfig(dev, 1));
        OK(NMC_MtSetPosErrLmt(ax, 99));
        OK(NMC_DevReset(dev));
    }
    OK(NMC_MtGetSwLmtValue(ax, &pos, &neg));
    CHECK(pos == 100000 && neg == -100000, "soft limits %ld %ld", pos, neg);
    OK(NMC_MtGetSwLmtOnOff(ax, &en));
    CHECK(en == 1, "soft limits on %d", en);
    OK(NMC_MtGetStepMode(ax, &inv, &mode));
    CHECK(inv == 1 && mode == 1, "step mode %d %d", inv, mode);
    OK(NMC_GetEncMode(dev, 1, &encMode));
    CHECK(encMode == 0x0000, "encoder mode %#x", encMode);
    OK(NMC_MtGetPosErrLmt(ax, &err));
    CHECK(err == 1234, "following-error limit %ld", err);
    printf("ok\n");
    return 0;
}
