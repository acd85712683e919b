/* E-stop inputs (digest 001 §2.3): NMC_MtSetEstopDI on DI1 (active low) and NMC_SetEstopDIEx
 * group 0 on DI2 (active high, axes 1 and 2), which the harness (tests/tests/nmc_examples.rs)
 * drives through the control API: DI1 starts high and DI2 low. The program prints a line and
 * waits for one after each step: "jogging" (the harness pulls DI1 low), "release" (DI1 back
 * high), "jogging2" (DI2 high). DI1's rising edge at "release" also starts axis 3's PT
 * stream, armed by NMC_MtPtStartMtnEx (digest 001 §2.8); its falling edge before did not. */
#include <string.h>
#include "check.h"

static void step(const char *what) {
    char line[64];
    printf("%s\n", what);
    fflush(stdout);
    if (!fgets(line, sizeof line, stdin)) exit(2);
}

/* Poll until the axis has stopped with BIT_AXIS_ESTP latched. */
static short wait_estop(HAND ax) {
    short sts = 0;
    long polls = 0;
    do {
        OK(NMC_MtGetSts(ax, &sts));
        CHECK(++polls < 10000000L, "axis never E-stopped, sts %#x", sts);
    } while ((sts & BIT_AXIS_BUSY) || !(sts & BIT_AXIS_ESTP));
    return sts;
}

int main(void) {
    HAND dev = 0, ax1 = 0, ax2 = 0, ax3 = 0;
    double ptPos[2] = {1000, 1000};
    long ptTime[2] = {100, 200}, pos = 0, polls = 0;
    short ptType[2] = {MT_PT_NORMAL, MT_PT_STOP}, mode = 0;
    short gpi = 0, sense = 0, sts = 0;
    TEstopExParam ex, back;

    OK(NMC_DevOpen(0, &dev));
    OK(NMC_MtOpen(dev, 1, &ax1));
    OK(NMC_MtOpen(dev, 2, &ax2));
    OK(NMC_MtSetSvOn(ax1));
    OK(NMC_MtSetSvOn(ax2));
    OK(NMC_MtOpen(dev, 3, &ax3));
    OK(NMC_MtSetSvOn(ax3));
    OK(NMC_MtPtBufClr(ax3));
    OK(NMC_MtPtPush(ax3, 2, ptPos, ptTime, ptType));
    OK(NMC_MtPtStartMtnEx(ax3, 1, 1));
    OK(NMC_MtGetPrfMode(ax3, &mode));
    CHECK(mode == MT_PT_PRF_MODE, "PT mode after PtStartMtnEx: %d", mode);

    OK(NMC_MtGetEstopDI(ax1, &gpi, &sense));
    CHECK(gpi == -1, "E-stop input before any set %d", gpi);
    CHECK(NMC_MtSetEstopDI(ax1, 64, 0) == RTN_ARG_RANGE, "DI64 accepted");
    CHECK(NMC_MtSetEstopDI(ax1, 1, 2) == RTN_ARG_RANGE, "sense 2 accepted");
    OK(NMC_MtSetEstopDI(ax1, 1, 0));
    OK(NMC_MtGetEstopDI(ax1, &gpi, &sense));
    CHECK(gpi == 1 && sense == 0, "read back %d %d", gpi, sense);

    OK(NMC_MtMoveJog(ax1, 1, 1, 5, 0, 1));
    step("jogging");
    wait_estop(ax1); /* DI1 low */
    /* Held low: a new move is stopped again. */
    OK(NMC_MtClrError(ax1));
    OK(NMC_MtMoveJog(ax1, 1, 1, 5, 0, 1));
    wait_estop(ax1); /* a move while DI1 is held low is stopped too */
    OK(NMC_MtGetSts(ax3, &sts));
    CHECK(!(sts & BIT_AXIS_BUSY), "DI1's falling edge started the PT of axis 3: %#x", sts);
    step("release");
    for (polls = 0; pos < 1000; polls++) {
        CHECK(polls < 10000000L, "DI1's rising edge did not start the PT: at %ld", pos);
        OK(NMC_MtGetPrfPos(ax3, &pos)); /* DI1's rising edge starts it */
    }
    wait_still(ax3);
    OK(NMC_MtSetEstopDI(ax1, -1, 0));
    OK(NMC_MtGetEstopDI(ax1, &gpi, &sense));
    CHECK(gpi == -1, "E-stop input after cancel %d", gpi);
    OK(NMC_MtClrError(ax1));

    memset(&ex, 0, sizeof ex);
    ex.axMask = 0x6;
    ex.diType = 0;
    ex.diIndex = 2;
    ex.filter = 5;
    ex.diSense = 1;
    CHECK(NMC_SetEstopDIEx(dev, &ex, ESTOP_DI_EX_CH_NUM) == RTN_ARG_RANGE, "group 4 accepted");
    ex.diType = 5;
    CHECK(NMC_SetEstopDIEx(dev, &ex, 0) == RTN_ARG_RANGE, "diType 5 accepted");
    ex.diType = 0;
    ex.axMask = 0x10;
    CHECK(NMC_SetEstopDIEx(dev, &ex, 0) == RTN_ARG_RANGE, "axis 4 accepted");
    ex.axMask = 0x6;
    ex.filter = 256;
    CHECK(NMC_SetEstopDIEx(dev, &ex, 0) == RTN_ARG_RANGE, "filter 256 accepted");
    ex.filter = 5;
    CHECK(NMC_SetEstopDIEx(dev, NULL, 0) == RTN_NULL_POINTER, "NULL accepted");
    CHECK(NMC_SetEstopDIEx(ax1, &ex, 0) == RTN_WRONG_HANDLE_KIND, "axis handle accepted");
    OK(NMC_SetEstopDIEx(dev, &ex, 0));
    OK(NMC_GetEstopDIEx(dev, &back, 0));
    CHECK(back.axMask == 0x6 && back.diIndex == 2 && back.filter == 5 && back.diSense == 1,
          "read back %#x %d %d %ld", back.axMask, back.diIndex, back.filter, back.diSense);

    OK(NMC_MtMoveJog(ax1, 1, 1, 5, 0, 1));
    OK(NMC_MtMoveJog(ax2, 1, 1, -5, 0, 1));
    step("jogging2");
    wait_estop(ax1); /* DI2 high stops both axes of the mask */
    wait_estop(ax2);
    OK(NMC_ClrEstopDIEx(dev, 0));
    OK(NMC_GetEstopDIEx(dev, &back, 0));
    CHECK(back.axMask == 0, "group 0 after clear %#x", back.axMask);
    CHECK(NMC_ClrEstopDIEx(dev, -1) == RTN_ARG_RANGE, "group -1 accepted");
    /* Cleared: DI2 still high, the axes move again. */
    OK(NMC_MtClrError(ax1));
    OK(NMC_MtMoveJog(ax1, 1, 1, 5, 0, 0));
    OK(NMC_MtGetSts(ax1, &sts));
    CHECK(sts & BIT_AXIS_BUSY, "axis 1 does not move after the clear: %#x", sts);
    OK(NMC_MtStop(ax1));
    wait_still(ax1);
    printf("ok\n");
    return 0;
}
