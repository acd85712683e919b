/* S-LEADSCREW, S-BACKLASH, S-2DCOMP (digest 001 §5, C3§9) with TV72: the corrections show as
 * cmdPos (pulses sent) − prfPos (planned). */
#include "check.h"

static long correction(HAND ax) {
    long prf = 0, cmd = 0;
    OK(NMC_MtGetPrfPos(ax, &prf));
    OK(NMC_MtGetCmdPos(ax, &cmd));
    return cmd - prf;
}

int main(void) {
    HAND devHandle = 0, ax2 = 0, ax3 = 0;
    short compPos[3] = {10, 20, -10}, compNeg[3] = {5, -5, 5};
    long value = 0, dir = 0, i;
    double delta = 0;
    T2DCompensationTable table = {{3, 4}, {0, 0}, {0, 0}, {3000, 4000}, 0};
    T2DCompensationTable back;
    TCompData data[12], dataBack[12];
    T2DCompensation comp, compBack;

    OK(NMC_DevOpen(0, &devHandle));
    OK(NMC_MtOpen(devHandle, 2, &ax2));
    OK(NMC_MtOpen(devHandle, 3, &ax3));
    OK(NMC_MtSetSvOn(ax2));
    OK(NMC_MtSetSvOn(ax3));

    /* S-LEADSCREW on axis 2: 3 points over [10000, 30000]; +20 at 20000 moving positive. */
    CHECK(NMC_MtSetLeadScrewCompPara(ax2, 1, 10000, 20000, compPos, compNeg) != 0, "num 1");
    CHECK(NMC_MtSetLeadScrewCompPara(ax2, 3, 10000, 20000, NULL, compNeg) == RTN_NULL_POINTER,
          "NULL table");
    OK(NMC_MtSetLeadScrewCompPara(ax2, 3, 10000, 20000, compPos, compNeg));
    OK(NMC_MtEnableLeadScrew(ax2, 1));
    OK(NMC_MtMovePtpAbs(ax2, 1, 1, 0, 0, 20, 0, 20000));
    wait_still(ax2);
    CHECK(correction(ax2) == 20, "lead screw at 20000: %ld", correction(ax2));
    OK(NMC_MtEnableLeadScrew(ax2, 0));
    OK(NMC_MtMovePtpAbs(ax2, 1, 1, 0, 0, 20, 0, 0));
    wait_still(ax2);
    CHECK(correction(ax2) == 0, "lead screw off: %ld", correction(ax2));

    /* S-BACKLASH / TV72 on axis 3: 1000 pulses while moving negative, 200 per period. */
    OK(NMC_MtSetBacklash(ax3, 1000, 200, 1));
    OK(NMC_MtGetBacklash(ax3, &value, &delta, &dir));
    CHECK(value == 1000 && delta == 200 && dir == 1, "TV72: %ld %f %ld", value, delta, dir);
    CHECK(NMC_MtSetBacklash(ax3, 1000, 0, 1) != 0, "compDelta 0 accepted");
    CHECK(NMC_MtSetBacklash(ax3, 1000, 200, 2) != 0, "compDir 2 accepted");
    OK(NMC_MtMovePtpAbs(ax3, 1, 1, 0, 0, 20, 0, -5000));
    wait_still(ax3);
    CHECK(labs(correction(ax3)) == 1000, "backlash moving negative: %ld", correction(ax3));
    OK(NMC_MtMovePtpAbs(ax3, 1, 1, 0, 0, 20, 0, 0));
    wait_still(ax3);
    CHECK(correction(ax3) == 0, "backlash moving positive: %ld", correction(ax3));

    /* S-2DCOMP: a 3 x 4 table from (0,0), steps (3000, 4000); z corrections on axis 3 from the
     * X = axis 2, Y = axis 3 encoder positions. */
    for (i = 0; i < 12; i++) {
        data[i].xDirComp = i % 3;
        data[i].yDirComp = i / 4;
        data[i].zDirComp = 10 * i;
    }
    table.angle = 400;
    CHECK(NMC_Set2DCompensationTable(devHandle, 0, &table, data) != 0, "angle 400 accepted");
    /* A turned table (its axes turned about the first point, docs/decisions.md) is kept. */
    table.angle = 30;
    OK(NMC_Set2DCompensationTable(devHandle, 0, &table, data));
    OK(NMC_Get2DCompensationTable(devHandle, 0, &back, dataBack));
    CHECK(back.angle == 30, "angle read back: %f", back.angle);
    table.angle = 0;
    table.count[0] = 1;
    CHECK(NMC_Set2DCompensationTable(devHandle, 0, &table, data) != 0, "count 1 accepted");
    table.count[0] = 3;
    CHECK(NMC_Set2DCompensationTable(devHandle, 1, &table, data) != 0, "table 1 accepted");
    OK(NMC_Set2DCompensationTable(devHandle, 0, &table, data));
    OK(NMC_Get2DCompensationTable(devHandle, 0, &back, dataBack));
    CHECK(back.count[0] == 3 && back.count[1] == 4 && back.step[1] == 4000, "table read back");
    CHECK(dataBack[11].zDirComp == 110 && dataBack[5].xDirComp == 2, "data read back");
    comp.tableIndex = 0;
    comp.axisType[0] = 1;
    comp.axisType[1] = 1;
    comp.axisIndex[0] = 2;
    comp.axisIndex[1] = 3;
    comp.axisIndex[2] = -1;
    comp.enable = 1;
    OK(NMC_Set2DCompensation(devHandle, &comp));
    OK(NMC_Get2DCompensation(devHandle, &compBack));
    CHECK(compBack.enable == 1 && compBack.axisIndex[1] == 3 && compBack.axisIndex[2] == -1,
          "comp read back");
    /* At (0, 0) the X correction of axis 2 is data[0].x = 0; at X = 6000 it is data[2].x = 2. */
    OK(NMC_MtMovePtpAbs(ax2, 1, 1, 0, 0, 20, 0, 6000));
    wait_still(ax2);
    CHECK(correction(ax2) == 2, "2-D X correction at (6000, 0): %ld", correction(ax2));
    comp.enable = 0;
    OK(NMC_Set2DCompensation(devHandle, &comp));
    OK(NMC_MtMovePtpAbs(ax2, 1, 1, 0, 0, 20, 0, 0));
    wait_still(ax2);
    CHECK(correction(ax2) == 0, "2-D off: %ld", correction(ax2));
    printf("ok\n");
    return 0;
}
