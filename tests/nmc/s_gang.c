/* S-GANTRY and S-HANDWHEEL (digest 001 §5, C2§9.3, C2§10.3) with TV73. */
#include "check.h"

int main(void) {
    HAND devHandle = 0, master = 0, slave = 0, ax2 = 0;
    long mpos = 0, spos = 0;
    short mode = 0;

    OK(NMC_DevOpen(0, &devHandle));
    OK(NMC_MtOpen(devHandle, 0, &master));
    OK(NMC_MtOpen(devHandle, 1, &slave));
    OK(NMC_MtOpen(devHandle, 2, &ax2));
    OK(NMC_MtSetSvOn(master));
    OK(NMC_MtSetSvOn(slave));
    OK(NMC_MtSetSvOn(ax2));

    /* S-GANTRY: the slave receives the master's pulses; error limit (0, 32767] (TV73). */
    OK(NMC_SetGantryMaster(master, 0));
    CHECK(NMC_SetGantrySlave(slave, 0, 0) != 0, "TV73: limit 0 accepted");
    CHECK(NMC_SetGantrySlave(slave, 0, 40000) != 0, "TV73: limit 40000 accepted");
    CHECK(NMC_SetGantrySlave(slave, 1, 2000) != 0, "a group without a master accepted");
    CHECK(NMC_SetGantrySlave(master, 0, 2000) != 0, "the master as its own slave");
    OK(NMC_SetGantrySlave(slave, 0, 2000));
    OK(NMC_MtGetPrfMode(slave, &mode));
    CHECK(mode == MT_GANTRY_MODE, "slave mode %d", mode);
    CHECK(NMC_MtMovePtpAbs(slave, 1, 1, 0, 0, 10, 0, 1000) != 0, "a ganged slave moved alone");
    OK(NMC_MtMovePtpAbs(master, 1, 1, 0, 0, 20, 0, 5000));
    wait_still(master);
    OK(NMC_MtGetPrfPos(master, &mpos));
    OK(NMC_MtGetPrfPos(slave, &spos));
    CHECK(mpos == 5000 && spos == 5000, "master %ld slave %ld", mpos, spos);
    CHECK(NMC_DelGantryGroup(slave, 0) != 0, "deleted through the slave");
    OK(NMC_DelGantryGroup(master, 0));
    OK(NMC_MtMovePtpAbs(slave, 1, 1, 0, 0, 20, 0, 0));
    wait_still(slave);
    OK(NMC_MtGetPrfPos(slave, &spos));
    CHECK(spos == 0, "released slave at %ld", spos);

    /* S-HANDWHEEL: clear (nothing on), input 256, axis 2 follows the wheel x5. */
    OK(NMC_ClrHandWheel(devHandle));
    CHECK(NMC_SetHandWheelRatio(devHandle, 2) != 0, "ratio without a handwheel");
    CHECK(NMC_SetHandWheelInput(devHandle, 300) != 0, "input 300 accepted");
    OK(NMC_SetHandWheelInput(devHandle, 256));
    CHECK(NMC_SetHandWheel(devHandle, 2, 0, 1, 10) != 0, "ratio 0 accepted");
    CHECK(NMC_SetHandWheel(devHandle, 9, 5, 1, 10) != 0, "axis 9 accepted");
    OK(NMC_SetHandWheel(devHandle, 2, 5, 1, 10));
    CHECK(NMC_MtMovePtpAbs(ax2, 1, 1, 0, 0, 10, 0, 1000) != 0, "moved alone on a handwheel");
    OK(NMC_SetHandWheelRatio(devHandle, 2));
    OK(NMC_ClrHandWheel(devHandle));
    OK(NMC_MtMovePtpAbs(ax2, 1, 1, 0, 0, 10, 0, 1000));
    wait_still(ax2);
    printf("ok\n");
    return 0;
}
