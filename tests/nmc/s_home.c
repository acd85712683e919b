/* S-HOME-1 (digest 001 §5, C2§6.3) with TV29–TV30: HM_MODE1 in the negative direction onto the
 * home cam of axis x (gaochuan fixture: [0, 5000] pulses). The manual passes a `short *` for
 * the `unsigned short *` status; fixed here (-Werror rejects the sign mismatch). */
#include <string.h>
#include "check.h"

int main(void) {
    HAND devHandle = 0, axisHandle = 0;
    THomeSetting homePara;
    unsigned short homeSts = 0;
    long pos = 0, enc = 0;
    short sts;

    OK(NMC_DevOpen(0, &devHandle));
    OK(NMC_MtOpen(devHandle, 0, &axisHandle));
    OK(NMC_MtSetSvOn(axisHandle));
    /* Start above the cam so the negative search crosses its upper edge. */
    OK(NMC_MtMovePtpAbs(axisHandle, 1, 1, 0, 0, 20, 0, 12000));
    wait_still(axisHandle);

    memset(&homePara, 0, sizeof homePara);
    homePara.mode = HM_MODE1;
    homePara.dir = 0;
    homePara.offset = 0;
    homePara.scan1stVel = 5;
    homePara.scan2ndVel = 0;
    homePara.acc = 0.5;
    OK(NMC_MtSetHomePara(axisHandle, &homePara));
    /* One encoder, two readers: NMC_MtSetEncPos shows in NMC_GetEncPos, NMC_SetEncPos in
     * NMC_MtGetEncPos; the homing then clears it with the position (digest 001 §2.6). */
    OK(NMC_MtSetEncPos(axisHandle, 50000));
    OK(NMC_GetEncPos(devHandle, 0, &enc));
    CHECK(enc == 50000, "GetEncPos after MtSetEncPos %ld", enc);
    OK(NMC_SetEncPos(devHandle, 0, 40000));
    OK(NMC_MtGetEncPos(axisHandle, &enc));
    CHECK(enc == 40000, "MtGetEncPos after SetEncPos %ld", enc);
    OK(NMC_MtHome(axisHandle));
    do {
        OK(NMC_MtGetHomeSts(axisHandle, &homeSts));
        CHECK(!(homeSts & (BIT_AXHOME_FAIL | BIT_AXHOME_ERR_MV | BIT_AXHOME_ERR_SWT)), "home failed %#x", homeSts);
    } while (!(homeSts & BIT_AXHOME_OK));
    sts = wait_still(axisHandle);
    OK(NMC_MtGetPrfPos(axisHandle, &pos));
    CHECK(!(sts & BIT_AXIS_MVERR), "sts %#x", sts);
    printf("home at %ld\n", pos);
    CHECK(pos > -1000 && pos < 1000, "home position %ld", pos);
    EVENTUALLY(NMC_MtGetEncPos(axisHandle, &enc), enc == pos);
    OK(NMC_GetEncPos(devHandle, 0, &enc));
    CHECK(enc == pos, "GetEncPos after homing %ld, prfPos %ld", enc, pos);

    /* TV30: scan1stVel 0 starts nothing and shows bit 3. */
    homePara.scan1stVel = 0;
    OK(NMC_MtSetHomePara(axisHandle, &homePara));
    CHECK(NMC_MtHome(axisHandle) != 0, "homing with scan1stVel 0");
    OK(NMC_MtGetHomeSts(axisHandle, &homeSts));
    CHECK(homeSts & BIT_AXHOME_ERR_MV, "home sts %#x", homeSts);
    OK(NMC_MtGetSts(axisHandle, &sts));
    CHECK(!(sts & BIT_AXIS_BUSY), "moved: %#x", sts);
    printf("ok\n");
    return 0;
}
