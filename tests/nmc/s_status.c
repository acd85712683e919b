/* S-STATUS (digest 001 §5, C2§4.3): the status word's bits, positions, velocity, the clock. */
#include "check.h"

int main(void) {
    HAND devHandle = 0, axisHandle = 0;
    short sts = 0;
    long prfPos = -1, encPos = -1, axisPos = -1, cmdPos = -1;
    double prfVel = -1;
    unsigned long clock1 = 0, loop1 = 0, clock2 = 0, loop2 = 0;

    OK(NMC_DevOpen(0, &devHandle));
    OK(NMC_MtOpen(devHandle, 2, &axisHandle));
    OK(NMC_MtSetSvOn(axisHandle));
    OK(NMC_MtGetSts(axisHandle, &sts));
    CHECK(!(sts & BIT_AXIS_BUSY), "busy at rest: %#x", sts);
    CHECK(!(sts & (BIT_AXIS_MVERR | BIT_AXIS_LMTP | BIT_AXIS_LMTN | BIT_AXIS_SOFTPOSLMT |
                   BIT_AXIS_SOFTNEGLMT | BIT_AXIS_ALM | BIT_AXIS_POSERR)), "errors: %#x", sts);
    OK(NMC_MtClrError(axisHandle));
    OK(NMC_MtGetPrfPos(axisHandle, &prfPos));
    OK(NMC_MtGetEncPos(axisHandle, &encPos));
    OK(NMC_MtGetAxisPos(axisHandle, &axisPos));
    OK(NMC_MtGetCmdPos(axisHandle, &cmdPos));
    OK(NMC_MtGetPrfVel(axisHandle, &prfVel));
    CHECK(prfPos == 0 && encPos == 0 && axisPos == 0 && cmdPos == 0, "positions %ld %ld %ld %ld", prfPos, encPos, axisPos, cmdPos);
    CHECK(prfVel == 0.0, "velocity %f", prfVel);
    /* 125 µs ticks: 8 per 1 ms servo cycle (digest 001 §1.4). */
    OK(NMC_GetClock(devHandle, &clock1, &loop1));
    wait_still(axisHandle);
    OK(NMC_MtMovePtpRel(axisHandle, 0.2, 0.2, 0, 0, 2, 0, 100));
    wait_still(axisHandle);
    OK(NMC_GetClock(devHandle, &clock2, &loop2));
    CHECK(loop2 > loop1, "loops %lu → %lu", loop1, loop2);
    CHECK(clock2 - clock1 == 8 * (loop2 - loop1), "clock %lu→%lu loop %lu→%lu", clock1, clock2, loop1, loop2);
    printf("ok\n");
    return 0;
}
