/* NMC_SetDiReverseCount / NMC_GetDiReverseCount on the dedicated inputs (digest 001 §2.8
 * (46)-(47): diType 1 negative limit, 2 positive limit, 3 home, 4 Z; diIndex = the axis, 0~7):
 * axis 0's home cam on [0, 5000] pulses (the fixture) changes once leaving it and once coming
 * back; the limits do not change. */
#include "check.h"

int main(void) {
    HAND dev = 0, ax = 0;
    unsigned long zero[2] = {0, 0}, c[2] = {9, 9}, hundred[1] = {100};

    OK(NMC_DevOpen(0, &dev));
    OK(NMC_MtOpen(dev, 0, &ax));
    OK(NMC_MtClrError(ax));
    OK(NMC_MtSetSvOn(ax));

    OK(NMC_SetDiReverseCount(dev, 3, 0, zero, 1));
    OK(NMC_SetDiReverseCount(dev, 1, 0, zero, 2));
    OK(NMC_GetDiReverseCount(dev, 3, 0, c, 1));
    CHECK(c[0] == 0, "home count after set %lu", c[0]);

    OK(NMC_MtMovePtpAbs(ax, 1, 1, 0, 0, 20, 0, 10000)); /* leaves the cam at 5000 */
    wait_still(ax);
    EVENTUALLY(NMC_GetDiReverseCount(dev, 3, 0, c, 1), c[0] == 1);
    OK(NMC_MtMovePtpAbs(ax, 1, 1, 0, 0, 20, 0, 2000)); /* back onto it */
    wait_still(ax);
    EVENTUALLY(NMC_GetDiReverseCount(dev, 3, 0, c, 1), c[0] == 2);
    OK(NMC_GetDiReverseCount(dev, 1, 0, c, 2));
    CHECK(c[0] == 0 && c[1] == 0, "negative limits of axes 0, 1 changed: %lu %lu", c[0], c[1]);

    /* Set moves the counter's zero. */
    OK(NMC_SetDiReverseCount(dev, 3, 0, hundred, 1));
    OK(NMC_GetDiReverseCount(dev, 3, 0, c, 1));
    CHECK(c[0] == 100, "home count set to 100: %lu", c[0]);

    /* Bad arguments: axes 0~7 and those the device has (4), diType 0~4, count [1, 16]. */
    CHECK(NMC_GetDiReverseCount(dev, 3, 3, c, 2) == RTN_ARG_RANGE, "axes 3, 4 of 4");
    CHECK(NMC_GetDiReverseCount(dev, 2, -1, c, 1) == RTN_ARG_RANGE, "index -1");
    CHECK(NMC_GetDiReverseCount(dev, 5, 0, c, 1) == RTN_ARG_RANGE, "diType 5");
    CHECK(NMC_GetDiReverseCount(dev, 4, 0, c, 0) == RTN_ARG_RANGE, "count 0");
    CHECK(NMC_GetDiReverseCount(dev, 4, 0, NULL, 1) == RTN_NULL_POINTER, "NULL");

    printf("ok\n");
    return 0;
}
