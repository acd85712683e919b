/* TV71 (digest 001 §6, C3§10.3(29)): NMC_SetWatchDog(dev, 500, 1, 0, 0); a jog keeps running
 * while the host calls every 50 ms; once the host stops calling, the watchdog stops the axis
 * at once (no E-stop flag) and writes 0 to DO group 0. mcemu judges the 500 ms on its virtual
 * clock; this program only waits twice as long before it looks. */
#include <time.h>
#include "check.h"

static void sleep_ms(long ms) {
    struct timespec t = {ms / 1000, (ms % 1000) * 1000000L};
    nanosleep(&t, NULL);
}

int main(void) {
    HAND dev = 0, ax = 0;
    long dos = 0;
    double v = 0;
    short sts = 0;
    int i;

    OK(NMC_DevOpen(0, &dev));
    OK(NMC_MtOpen(dev, 1, &ax));
    OK(NMC_MtSetSvOn(ax));
    OK(NMC_SetDOGroup(dev, 0xFF, 0));
    OK(NMC_GetDOGroup(dev, &dos, 0));
    CHECK(dos == 0xFF, "DO group 0 %#lx", dos);

    CHECK(NMC_SetWatchDog(dev, 500, 2, 0, 0) == RTN_ARG_RANGE, "stopMode 2 accepted");
    CHECK(NMC_SetWatchDog(dev, 500, 1, 99, 0) == RTN_ARG_RANGE, "group 99 accepted");
    CHECK(NMC_SetWatchDog(ax, 500, 1, 0, 0) == RTN_WRONG_HANDLE_KIND, "axis handle accepted");
    OK(NMC_SetWatchDog(dev, 500, 1, 0, 0));
    OK(NMC_MtMoveJog(ax, 1, 1, 5, 0, 1));
    /* 1.5 s of calls 50 ms apart: the watchdog stays quiet. */
    for (i = 0; i < 30; i++) {
        sleep_ms(50);
        OK(NMC_MtGetPrfVel(ax, &v));
    }
    CHECK(v > 4.9, "the jog stopped while the host was calling: v %f", v);
    OK(NMC_GetDOGroup(dev, &dos, 0));
    CHECK(dos == 0xFF, "DO group 0 written while the host was calling: %#lx", dos);

    /* Silence. */
    sleep_ms(1000);
    OK(NMC_MtGetSts(ax, &sts));
    OK(NMC_MtGetPrfVel(ax, &v));
    CHECK(!(sts & BIT_AXIS_BUSY) && v == 0.0, "still jogging after the timeout: sts %#x v %f",
          sts, v);
    CHECK(!(sts & BIT_AXIS_ESTP), "the watchdog latched ESTP %#x", sts);
    OK(NMC_GetDOGroup(dev, &dos, 0));
    CHECK(dos == 0, "DO group 0 after the timeout %#lx", dos);

    /* Off: a new jog keeps running through the same silence. */
    OK(NMC_SetWatchDog(dev, 0, 1, 0, 0));
    OK(NMC_MtMoveJog(ax, 1, 1, 5, 0, 1));
    sleep_ms(1000);
    OK(NMC_MtGetPrfVel(ax, &v));
    CHECK(v > 4.9, "stopped with the watchdog off: v %f", v);
    OK(NMC_MtStop(ax));
    wait_still(ax);
    printf("ok\n");
    return 0;
}
