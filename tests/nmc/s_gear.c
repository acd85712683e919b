/* S-GEAR (digest 001 §5, C3§6.3) with TV58: slave axis 0 follows axis 1's planned position at
 * 4:5 after a 2000-pulse clutch; the settings read back; bad arguments refused. */
#include "check.h"

int main(void) {
    HAND devHandle = 0, axisHandle[2] = {0, 0};
    short dir = 9, no = 9, type = 9, mode = 0, sts = 0;
    long me = 0, se = 0, slope = 0, slave = 0, master = 0;

    OK(NMC_DevOpen(0, &devHandle));
    OK(NMC_MtOpen(devHandle, 0, &axisHandle[0]));
    OK(NMC_MtOpen(devHandle, 1, &axisHandle[1]));
    OK(NMC_MtSetSvOn(axisHandle[0]));
    OK(NMC_MtSetSvOn(axisHandle[1]));

    OK(NMC_MtSetPrfMode(axisHandle[0], MT_GEAR_PRF_MODE));
    OK(NMC_MtGearSetDir(axisHandle[0], 0));
    OK(NMC_MtGearSetMaster(axisHandle[0], 1, 1));
    OK(NMC_MtGearSetRatio(axisHandle[0], 5, 4, 2000));
    OK(NMC_MtGearGetDir(axisHandle[0], &dir));
    OK(NMC_MtGearGetMaster(axisHandle[0], &no, &type));
    OK(NMC_MtGearGetRatio(axisHandle[0], &me, &se, &slope));
    CHECK(dir == 0 && no == 1 && type == 1, "dir %d master %d type %d", dir, no, type);
    CHECK(me == 5 && se == 4 && slope == 2000, "ratio %ld:%ld slope %ld", me, se, slope);

    /* The manual's ranges: masterSlope ≠ 1, type 1-3, a master that exists, NULL outs. */
    CHECK(NMC_MtGearSetRatio(axisHandle[0], 5, 4, 1) != 0, "masterSlope 1 accepted");
    CHECK(NMC_MtGearSetRatio(axisHandle[0], 0, 4, 0) != 0, "masterEven 0 accepted");
    CHECK(NMC_MtGearSetMaster(axisHandle[0], 1, 4) != 0, "masterType 4 accepted");
    CHECK(NMC_MtGearSetMaster(axisHandle[0], 99, 1) != 0, "master 99 accepted");
    CHECK(NMC_MtGearGetMaster(axisHandle[0], NULL, &type) == RTN_NULL_POINTER, "NULL out");
    CHECK(NMC_MtGearStartMtn(axisHandle[0], 1, NULL) == RTN_NULL_POINTER, "NULL array");

    OK(NMC_MtGearStartMtn(axisHandle[0], 0, NULL));
    OK(NMC_MtGetPrfMode(axisHandle[0], &mode));
    CHECK(mode == MT_GEAR_PRF_MODE, "slave mode %d", mode);

    /* TV58: the master moves +10000; the slave ends at 4/5 of it less the clutch's 800. */
    OK(NMC_MtMovePtpAbs(axisHandle[1], 0.5, 0.5, 0, 0, 20, 0, 10000));
    wait_still(axisHandle[1]);
    OK(NMC_MtGetPrfPos(axisHandle[1], &master));
    OK(NMC_MtGetPrfPos(axisHandle[0], &slave));
    CHECK(master == 10000, "master at %ld", master);
    CHECK(slave >= 7190 && slave <= 7210, "slave at %ld, expected 7200 (8000 - 800)", slave);

    /* A running gear takes a new ratio through its clutch (the engine's: the 2000 pulses of
     * the start), 4:5 ramping to 1:1, 1800 of slave travel for 2000 of master. */
    OK(NMC_MtGearSetRatio(axisHandle[0], 1, 1, 0));
    OK(NMC_MtMovePtpAbs(axisHandle[1], 0.5, 0.5, 0, 0, 20, 0, 12000));
    wait_still(axisHandle[1]);
    OK(NMC_MtGetPrfPos(axisHandle[0], &slave));
    CHECK(slave >= 8990 && slave <= 9010, "slave at %ld after 1:1, expected 9000", slave);
    OK(NMC_MtGetSts(axisHandle[0], &sts));
    CHECK(!(sts & BIT_AXIS_MVERR), "slave sts %#x", sts);
    printf("ok\n");
    return 0;
}
