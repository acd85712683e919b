/* The watchdog (TV71) and the E-stop inputs on the virtual clock: the engine judges them on
 * the tick, so time advanced in one long step by the harness (tests/tests/nmc_examples.rs)
 * stops the axes where real time would. The program prints a line and waits for one after
 * each step; meanwhile the harness advances time and drives DI1 (high at the start) and DI2
 * (low). Jogs at 5 pulse/ms, 1 pulse/ms²: 12.5 pulses of ramp, then 5 per ms. */
#include <string.h>
#include "check.h"

static void step(const char *what) {
    char line[64];
    printf("%s\n", what);
    fflush(stdout);
    if (!fgets(line, sizeof line, stdin)) exit(2);
}

static long position(HAND ax) {
    long pos = 0;
    OK(NMC_MtGetPrfPos(ax, &pos));
    return pos;
}

int main(void) {
    HAND dev = 0, ax1 = 0, ax2 = 0;
    long dos = 0, start = 0, pos = 0;
    short sts = 0;
    TEstopExParam ex;

    OK(NMC_DevOpen(0, &dev));
    OK(NMC_MtOpen(dev, 1, &ax1));
    OK(NMC_MtOpen(dev, 2, &ax2));
    OK(NMC_MtSetSvOn(ax1));
    OK(NMC_MtSetSvOn(ax2));
    OK(NMC_SetDOGroup(dev, 0xFF, 0));

    /* The watchdog: 500 ms after the last request (the jog's), during one advance of 10 s. */
    OK(NMC_SetWatchDog(dev, 500, 1, 0, 0));
    start = position(ax1);
    OK(NMC_MtMoveJog(ax1, 1, 1, 5, 0, 1));
    step("watchdog"); /* the harness advances 10 s */
    pos = position(ax1) - start;
    OK(NMC_MtGetSts(ax1, &sts));
    CHECK(!(sts & BIT_AXIS_BUSY), "still jogging after 10 s of silence: %#x", sts);
    /* Stopped at 500 ms: 12.5 + 495 × 5 pulses, and what the abrupt stop takes. */
    CHECK(pos >= 2480 && pos < 2600, "the watchdog stopped the jog after %ld pulses", pos);
    OK(NMC_GetDOGroup(dev, &dos, 0));
    CHECK(dos == 0, "DO group 0 after the timeout %#lx", dos);
    OK(NMC_SetWatchDog(dev, 0, 1, 0, 0));

    /* DI1 low E-stops axis 2: the harness advances 200 ms, pulls DI1 low, advances 5 s. */
    OK(NMC_MtSetEstopDI(ax2, 1, 0));
    start = position(ax2);
    OK(NMC_MtMoveJog(ax2, 1, 1, 5, 0, 1));
    step("estop");
    pos = position(ax2) - start;
    OK(NMC_MtGetSts(ax2, &sts));
    CHECK(!(sts & BIT_AXIS_BUSY) && (sts & BIT_AXIS_ESTP), "axis 2 not E-stopped: %#x", sts);
    CHECK(pos >= 962 && pos < 1100, "DI1 stopped the jog after %ld pulses", pos);
    OK(NMC_MtSetEstopDI(ax2, -1, 0));
    OK(NMC_MtClrError(ax2));

    /* Advanced group 0 on DI2 (high), filter 50 ms, axis 1: the harness advances 100 ms,
     * sets DI2, advances 5 s: the stop comes 50 ms after the input. */
    memset(&ex, 0, sizeof ex);
    ex.axMask = 1 << 1;
    ex.diType = 0;
    ex.diIndex = 2;
    ex.filter = 50;
    ex.diSense = 1;
    OK(NMC_SetEstopDIEx(dev, &ex, 0));
    OK(NMC_MtClrError(ax1));
    start = position(ax1);
    OK(NMC_MtMoveJog(ax1, 1, 1, 5, 0, 1));
    step("estop2");
    pos = position(ax1) - start;
    OK(NMC_MtGetSts(ax1, &sts));
    CHECK(!(sts & BIT_AXIS_BUSY) && (sts & BIT_AXIS_ESTP), "axis 1 not E-stopped: %#x", sts);
    CHECK(pos >= 712 && pos < 850, "DI2 stopped the jog after %ld pulses", pos);
    OK(NMC_ClrEstopDIEx(dev, 0));
    printf("ok\n");
    return 0;
}
