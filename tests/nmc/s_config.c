/* S-CONFIG (digest 001 §5, C2§3.3) and TV05-TV10, TV22, TV68: the basic axis configuration. */
#include "check.h"

static int near(double a, double b) { return a - b < 1e-6 && b - a < 1e-6; }

int main(void) {
    HAND devHandle = 0, axisHandle = 0, ax0 = 0;
    short a = -1, b = -1, sts = 0;
    unsigned short m = 0, coe = 1;
    long pos = 0, neg = 0;
    TSafePara safe;

    OK(NMC_DevOpen(0, &devHandle));
    OK(NMC_MtOpen(devHandle, 1, &axisHandle));
    OK(NMC_MtOpen(devHandle, 0, &ax0));

    /* TV05 */
    OK(NMC_MtGetSwLmtOnOff(axisHandle, &a));
    OK(NMC_MtGetSwLmtValue(axisHandle, &pos, &neg));
    CHECK(a == 1 && pos == 2147483647L && neg == -2147483647L, "TV05: %d %ld %ld", a, pos, neg);
    /* TV06 */
    OK(NMC_MtGetAlarmOnOff(axisHandle, &a));
    CHECK(a == 0, "TV06: %d", a);
    /* TV07 */
    OK(NMC_MtGetSafePara(axisHandle, &safe));
    CHECK(near(safe.estpDec, 32767) && near(safe.maxVel, 32767) && near(safe.maxAcc, 32767), "TV07: %f %f %f",
          safe.estpDec, safe.maxVel, safe.maxAcc);
    /* TV08 */
    OK(NMC_MtGetStepMode(axisHandle, &a, &b));
    OK(NMC_MtGetStepFilter(axisHandle, &coe));
    CHECK(a == 0 && b == 0 && coe == 0, "TV08: %d %d %u", a, b, coe);

    /* S-CONFIG, with the manual's NMC_SetEncMode(axisHandle, …) [sic] refused for its handle. */
    OK(NMC_MtSetLmtCfg(axisHandle, 1, 1, 0, 0));
    OK(NMC_MtSetAlarmCfg(axisHandle, 1, 0));
    OK(NMC_MtSetStepMode(axisHandle, 0, 0));
    CHECK(NMC_SetEncMode(axisHandle, 0, 0x0000) == RTN_WRONG_HANDLE_KIND, "SetEncMode with an axis handle");
    OK(NMC_MtSetAxisVelFilter(axisHandle, 1));
    /* Low-active limits and alarm with every input low: all three are active, so the errors
     * cannot be cleared (the fixture's switches are open). */
    CHECK(NMC_MtClrError(axisHandle) == RTN_CAUSE_STILL_PRESENT, "S-CONFIG: limits and alarm active");
    /* TV09 */
    OK(NMC_MtGetLmtOnOff(axisHandle, &a, &b));
    CHECK(a == 1 && b == 1, "TV09 on/off: %d %d", a, b);
    OK(NMC_MtGetLmtSns(axisHandle, &a, &b));
    CHECK(a == 0 && b == 0, "TV09 sns: %d %d", a, b);
    OK(NMC_MtGetAlarmOnOff(axisHandle, &a));
    OK(NMC_MtGetAlarmSns(axisHandle, &b));
    CHECK(a == 1 && b == 0, "alarm cfg: %d %d", a, b);
    OK(NMC_MtGetAxisVelFilter(axisHandle, &a));
    CHECK(a == 1, "vel filter %d", a);
    /* TV68 */
    CHECK(NMC_MtSetAxisVelFilter(axisHandle, 6) == RTN_ARG_RANGE, "TV68");
    /* TV10 */
    OK(NMC_SetEncMode(devHandle, 0, 17664));
    OK(NMC_GetEncMode(devHandle, 0, &m));
    CHECK(m == 17664, "TV10: %u", m);
    OK(NMC_GetEncMode(devHandle, 2, &m));
    CHECK(m == 0x0100, "default encoder mode %#x", m);

    /* Read-backs of what the engine keeps. */
    safe.estpDec = 100;
    safe.maxVel = 50;
    safe.maxAcc = 2;
    OK(NMC_MtSetSafePara(axisHandle, &safe));
    safe.estpDec = safe.maxVel = safe.maxAcc = 0;
    OK(NMC_MtGetSafePara(axisHandle, &safe));
    CHECK(near(safe.estpDec, 100) && near(safe.maxVel, 50) && near(safe.maxAcc, 2), "safe para read back");
    CHECK(NMC_MtSetSafePara(axisHandle, NULL) == RTN_NULL_POINTER, "NULL safe para");
    OK(NMC_MtSetPosErrLmt(axisHandle, 100));
    OK(NMC_MtGetPosErrLmt(axisHandle, &pos));
    CHECK(pos == 100, "pos err limit %ld", pos);
    OK(NMC_MtSetPosErrAction(axisHandle, 2));
    OK(NMC_MtGetPosErrAction(axisHandle, &a));
    CHECK(a == 2, "pos err action %d", a);
    OK(NMC_MtSetAxisArrivalPara(axisHandle, 10, 5));
    OK(NMC_MtGetAxisArrivalPara(axisHandle, &pos, &neg));
    CHECK(pos == 10 && neg == 5, "arrival %ld %ld", pos, neg);
    OK(NMC_MtSetStepFilter(axisHandle, 7));
    OK(NMC_MtGetStepFilter(axisHandle, &coe));
    CHECK(coe == 7, "step filter %u", coe);
    CHECK(NMC_MtSwLmtValue(axisHandle, -5, 5) == RTN_ARG_RANGE, "posLmt below negLmt");

    /* TV22: soft limit at 5000 stops a move to 10000. */
    OK(NMC_MtSetSvOn(ax0));
    OK(NMC_MtSwLmtValue(ax0, 5000, -5000));
    OK(NMC_MtGetSwLmtValue(ax0, &pos, &neg));
    CHECK(pos == 5000 && neg == -5000, "soft limits %ld %ld", pos, neg);
    NMC_MtMovePtpAbs(ax0, 0.5, 0.5, 0, 0, 10, 0, 10000);
    sts = wait_still(ax0);
    OK(NMC_MtGetPrfPos(ax0, &pos));
    CHECK(pos <= 5000 && (sts & BIT_AXIS_SOFTPOSLMT), "TV22: at %ld, sts %#x", pos, sts);
    printf("ok\n");
    return 0;
}
