/* The axis-level additions (digest 001 §2.3-§2.8, §2.20, §3.4, §3.6): several axes' status at
 * once, the 12-axis packed status, packed PTP moves, redefining positions, the home level seen
 * in the electrical motion-I/O levels, the alarm-clear output, the planning period (TV64); each
 * with a bad argument and its code. */
#include <string.h>
#include "check.h"

#define AXES 4

int main(void) {
    HAND dev = 0, ax[AXES];
    short sts[AXES], one = 0, period = 0;
    unsigned long clock1 = 0, clock2 = 0;
    long pos = 0, enc = 0, io = 0, logical = 0;
    TMovePtpPack8 pack;
    TAxisStsPack12Ex packed;
    int i;

    OK(NMC_DevOpen(0, &dev));
    for (i = 0; i < AXES; i++) OK(NMC_MtOpen(dev, (short)i, &ax[i]));

    /* TV64: the planning period. */
    OK(NMC_GetProfilePeriod(dev, &period));
    CHECK(period == 1000, "default period %d", period);
    OK(NMC_SetProfilePeriod(dev, 500));
    OK(NMC_GetProfilePeriod(dev, &period));
    CHECK(period == 500, "period %d", period);
    CHECK(NMC_SetProfilePeriod(dev, 300) == RTN_ARG_RANGE, "period 300 accepted");
    CHECK(NMC_SetProfilePeriod(ax[0], 250) == RTN_WRONG_HANDLE_KIND, "axis handle accepted");
    OK(NMC_GetProfilePeriod(dev, &period));
    CHECK(period == 500, "period after refusal %d", period);

    /* Packed PTP: axes 0 and 1 in one call, absolute then relative. */
    for (i = 0; i < 2; i++) OK(NMC_MtSetSvOn(ax[i]));
    memset(&pack, 0, sizeof pack);
    pack.axisMask = 0x3;
    pack.clrStsFlag = 1;
    for (i = 0; i < 8; i++) {
        pack.acc[i] = 1;
        pack.dec[i] = 1;
        pack.maxVel[i] = 20;
    }
    pack.tgtPos[0] = 3000;
    pack.tgtPos[1] = -2000;
    OK(NMC_MtMovePtpAbsPack8(ax[0], &pack));
    OK(NMC_MtGetSts(ax[0], &one));
    CHECK(one & BIT_AXIS_BUSY, "axis 0 not moving after Pack8: %#x", one);
    wait_still(ax[0]);
    wait_still(ax[1]);
    OK(NMC_MtGetPrfPos(ax[0], &pos));
    CHECK(pos == 3000, "axis 0 at %ld", pos);
    OK(NMC_MtGetPrfPos(ax[1], &pos));
    CHECK(pos == -2000, "axis 1 at %ld", pos);
    pack.tgtPos[0] = 1000;
    pack.tgtPos[1] = 1000;
    OK(NMC_MtMovePtpRelPack8(ax[0], &pack));
    wait_still(ax[0]);
    wait_still(ax[1]);
    OK(NMC_MtGetPrfPos(ax[0], &pos));
    CHECK(pos == 4000, "axis 0 at %ld after rel", pos);
    OK(NMC_MtGetPrfPos(ax[1], &pos));
    CHECK(pos == -1000, "axis 1 at %ld after rel", pos);
    pack.smoothCoef[1] = 200; /* TV69's range, per axis */
    CHECK(NMC_MtMovePtpAbsPack8(ax[0], &pack) == RTN_ARG_RANGE, "smoothCoef 200 accepted");
    OK(NMC_MtGetPrfPos(ax[0], &pos));
    CHECK(pos == 4000, "a refused pack moved axis 0 to %ld", pos);
    pack.smoothCoef[1] = 0;
    pack.axisMask = 0;
    CHECK(NMC_MtMovePtpAbsPack8(ax[0], &pack) == RTN_ARG_RANGE, "empty mask accepted");
    pack.axisMask = 0x4; /* axis 2 + 2 = 4: past the GCN400's last */
    CHECK(NMC_MtMovePtpAbsPack8(ax[2], &pack) == RTN_ARG_RANGE, "axis 4 accepted");
    CHECK(NMC_MtMovePtpAbsPack8(ax[0], NULL) == RTN_NULL_POINTER, "NULL pack accepted");

    /* Several status words and the clock. */
    OK(NMC_MtGetStsMulti(ax[0], sts, AXES, &clock1));
    for (i = 0; i < AXES; i++) {
        OK(NMC_MtGetSts(ax[i], &one));
        CHECK(sts[i] == one, "axis %d: multi %#x single %#x", i, sts[i], one);
    }
    CHECK(sts[0] & BIT_AXIS_SVON, "axis 0 not SVON in multi: %#x", sts[0]);
    CHECK(!(sts[3] & BIT_AXIS_SVON), "axis 3 SVON in multi: %#x", sts[3]);
    OK(NMC_MtGetStsMulti(ax[1], sts, 3, &clock2));
    CHECK(clock2 >= clock1 && clock1 > 0, "clock %lu then %lu", clock1, clock2);
    CHECK(NMC_MtGetStsMulti(ax[1], sts, 4, &clock2) == RTN_ARG_RANGE, "4 axes from axis 1");
    CHECK(NMC_MtGetStsMulti(ax[0], sts, 0, &clock2) == RTN_ARG_RANGE, "count 0");
    CHECK(NMC_MtGetStsMulti(ax[0], NULL, 1, &clock2) == RTN_NULL_POINTER, "NULL array");

    /* The packed status of 12 axes from axis 0. */
    /* Axis 0 is a servo: its encoder settles after the plan ends; compare once it has. */
    for (i = 0;; i++) {
        OK(NMC_MtGetStsPack12Ex(ax[0], &packed));
        OK(NMC_MtGetEncPos(ax[0], &enc));
        if (packed.mtEncPos[0] == enc) break;
        CHECK(i < 1000000, "packed encoder %ld, single %ld", packed.mtEncPos[0], enc);
    }
    CHECK(packed.mtPrfPos[0] == 4000 && packed.mtPrfPos[1] == -1000, "packed positions %ld %ld",
          packed.mtPrfPos[0], packed.mtPrfPos[1]);
    for (i = 0; i < AXES; i++) {
        OK(NMC_MtGetSts(ax[i], &one));
        CHECK(packed.mtSts[i] == one, "packed sts %d: %#x vs %#x", i, packed.mtSts[i], one);
        OK(NMC_MtGetMotionIO(ax[i], &io));
        CHECK(packed.mtMio[i] == io, "packed mio %d: %#x vs %#lx", i, packed.mtMio[i], io);
    }
    CHECK(packed.mtSts[4] == 0 && packed.mtPrfPos[11] == 0, "axes past the last not zero");
    CHECK(packed.mtPrfVel[0] == 0.0f, "still axis has velocity %f", packed.mtPrfVel[0]);
    CHECK(NMC_MtGetStsPack12Ex(dev, &packed) == RTN_WRONG_HANDLE_KIND, "device handle");

    /* Redefining positions on axis 2, a stepper whose encoder counts its own pulses: the
     * plan, the encoder, both to zero. */
    OK(NMC_MtSetSvOn(ax[2]));
    OK(NMC_MtSetAxisPos(ax[2], 5000));
    OK(NMC_MtGetPrfPos(ax[2], &pos));
    CHECK(pos == 5000, "prfPos after SetAxisPos %ld", pos);
    OK(NMC_MtGetAxisPos(ax[2], &pos));
    CHECK(pos == 5000, "axisPos after SetAxisPos %ld", pos);
    OK(NMC_MtSetEncPos(ax[2], 777));
    OK(NMC_MtGetEncPos(ax[2], &enc));
    CHECK(enc == 777, "encPos after SetEncPos %ld", enc);
    OK(NMC_MtGetPrfPos(ax[2], &pos));
    CHECK(pos == 5000, "SetEncPos moved the plan to %ld", pos);
    OK(NMC_MtZeroPos(ax[2]));
    OK(NMC_MtGetPrfPos(ax[2], &pos));
    OK(NMC_MtGetEncPos(ax[2], &enc));
    CHECK(pos == 0 && enc == 0, "after ZeroPos prf %ld enc %ld", pos, enc);
    /* Static only: refused while moving. */
    OK(NMC_MtMoveJog(ax[2], 1, 1, 5, 0, 0));
    CHECK(NMC_MtSetAxisPos(ax[2], 1) == RTN_INVALID_STATE, "SetAxisPos accepted while moving");
    CHECK(NMC_MtSetEncPos(ax[2], 1) == RTN_INVALID_STATE, "SetEncPos accepted while moving");
    CHECK(NMC_MtZeroPos(ax[2]) == RTN_INVALID_STATE, "ZeroPos accepted while moving");
    OK(NMC_MtStop(ax[2]));
    wait_still(ax[2]);

    /* The home level: the electrical level of the home input flips with its sense. */
    OK(NMC_MtHomeSns(ax[2], 1));
    OK(NMC_MtGetMotionIO(ax[2], &io));
    OK(NMC_MtGetMotionIOLogical(ax[2], &logical));
    CHECK(((logical >> 2) & 1) == ((io >> 2) & 1), "high-active home: io %#lx logical %#lx",
          io, logical);
    OK(NMC_MtHomeSns(ax[2], 0));
    OK(NMC_MtGetMotionIO(ax[2], &io));
    OK(NMC_MtGetMotionIOLogical(ax[2], &logical));
    CHECK(((logical >> 2) & 1) != ((io >> 2) & 1), "low-active home: io %#lx logical %#lx",
          io, logical);
    CHECK(NMC_MtHomeSns(ax[2], 2) == RTN_ARG_RANGE, "home sense 2 accepted");
    CHECK(NMC_MtGetMotionIOLogical(ax[2], NULL) == RTN_NULL_POINTER, "NULL io");

    /* The alarm-clear output: active clears a latched E-stop once its cause is gone. */
    OK(NMC_MtEstp(ax[1]));
    wait_still(ax[1]);
    OK(NMC_MtGetSts(ax[1], &one));
    CHECK(one & BIT_AXIS_ESTP, "no ESTP after MtEstp %#x", one);
    OK(NMC_MtSetSvClr(ax[1], 0));
    OK(NMC_MtGetSts(ax[1], &one));
    CHECK(!(one & BIT_AXIS_ESTP), "ESTP after SvClr %#x", one);
    OK(NMC_MtSetSvClr(ax[1], 1));
    CHECK(NMC_MtSetSvClr(ax[1], 2) == RTN_ARG_RANGE, "swt 2 accepted");
    printf("ok\n");
    return 0;
}
