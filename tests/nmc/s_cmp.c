/* S-CMP-2D (digest 001 §5, C3§1.3) with TV63: 100 points on the XY diagonal, GATE channel,
 * encoder positions, errZone 10; X and Y driven together to (10000, 10000). Then a 1-D
 * compare on axis 2 in level mode. */
#include "check.h"

int main(void) {
    HAND devHandle = 0, ax0 = 0, ax1 = 0, ax2 = 0;
    TComp2DimensParamEx param;
    TComp2DimensSts status;
    TPtpPara ptp = {0.5, 0.5, 0, 0, 0, {0, 0, 0}};
    long pos[200], line[5] = {1000, 2000, 3000, 4000, 5000};
    long i, doValue = 0;

    OK(NMC_DevOpen(0, &devHandle));
    OK(NMC_MtOpen(devHandle, 0, &ax0));
    OK(NMC_MtOpen(devHandle, 1, &ax1));
    OK(NMC_MtOpen(devHandle, 2, &ax2));
    OK(NMC_MtSetSvOn(ax0));
    OK(NMC_MtSetSvOn(ax1));
    OK(NMC_MtSetSvOn(ax2));

    OK(NMC_Comp2DimensGetParamEx(devHandle, 0, &param, 0));
    param.dir1No = 0;
    param.dir2No = 1;
    param.chnType = 1;
    param.outputType = 0;
    param.outputChn = 0;
    param.errZone = 10;
    param.gateTime = 10;
    param.posSrc = 1;
    param.stLevel = 0;
    OK(NMC_Comp2DimensSetParamEx(devHandle, 0, &param, 0));
    for (i = 0; i < 100; i++) {
        pos[2 * i] = 100 * i + 100;
        pos[2 * i + 1] = 100 * i + 100;
    }
    OK(NMC_Comp2DimensSetData(devHandle, 0, pos, 0, 0));
    OK(NMC_Comp2DimensSetData(devHandle, 0, pos, 100, 0));
    OK(NMC_Comp2DimensStatusEx(devHandle, 0, &status, 0));
    CHECK(status.sts == 0 && status.usedSpace == 100, "before: sts %d used %ld",
          status.sts, status.usedSpace);
    CHECK(NMC_Comp2DimensSetData(devHandle, 2, pos, 1, 0) != 0, "group 2 accepted");
    CHECK(NMC_Comp2DimensSetData(devHandle, 0, pos, 1, 1) != 0, "chn 1 accepted");
    CHECK(NMC_Comp2DimensStatusEx(devHandle, 0, NULL, 0) == RTN_NULL_POINTER, "NULL");
    OK(NMC_Comp2DimensOnoff(devHandle, 0, 1, 0));
    OK(NMC_Comp2DimensStatusEx(devHandle, 0, &status, 0));
    CHECK(status.sts == 1, "running: sts %d", status.sts);

    /* The diagonal: both axes, same parameters, started in one tick. */
    OK(NMC_MtSetPrfMode(ax0, MT_PTP_PRF_MODE));
    OK(NMC_MtSetPrfMode(ax1, MT_PTP_PRF_MODE));
    OK(NMC_MtSetPtpPara(ax0, &ptp));
    OK(NMC_MtSetPtpPara(ax1, &ptp));
    OK(NMC_MtSetVel(ax0, 10));
    OK(NMC_MtSetVel(ax1, 10));
    OK(NMC_MtSetPtpTgtPos(ax0, 10500));
    OK(NMC_MtSetPtpTgtPos(ax1, 10500));
    OK(NMC_MtUpdateMulti(ax0, 0x3));
    wait_still(ax0);
    wait_still(ax1);
    OK(NMC_Comp2DimensStatusEx(devHandle, 0, &status, 0));
    CHECK(status.outCount == 100 && status.usedSpace == 0 && status.sts == 0,
          "TV63: outCount %ld used %ld sts %d", status.outCount, status.usedSpace, status.sts);
    OK(NMC_Comp2DimensOnoff(devHandle, 0, 0, 0));

    /* 1-D, level mode on GPO 5: five points toggle it five times (from stLevel 0 to 1). */
    param.dir1No = 2;
    param.dir2No = -1;
    param.chnType = 0;
    param.outputChn = 5;
    param.outputType = 1;
    param.posSrc = 0;
    OK(NMC_Comp2DimensSetParamEx(devHandle, 1, &param, 0));
    OK(NMC_Comp2DimensSetData(devHandle, 1, line, 5, 0));
    OK(NMC_Comp2DimensOnoff(devHandle, 1, 1, 0));
    OK(NMC_MtMovePtpAbs(ax2, 0.5, 0.5, 0, 0, 10, 0, 6000));
    wait_still(ax2);
    OK(NMC_Comp2DimensStatusEx(devHandle, 1, &status, 0));
    CHECK(status.outCount == 5 && status.usedSpace == 0, "1-D: outCount %ld used %ld",
          status.outCount, status.usedSpace);
    OK(NMC_GetDOGroup(devHandle, &doValue, 0));
    CHECK((doValue & 0x20) != 0, "GPO 5 after an odd number of toggles: %#lx", doValue);
    CHECK(NMC_Comp2DimensOnoff(devHandle, 1, 3, 0) != 0, "onOff 3 accepted");
    printf("ok\n");
    return 0;
}
