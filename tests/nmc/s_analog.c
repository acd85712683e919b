/* S-IO's analog part (digest 001 §5, C2§8.3) with TV41, the analog voltages, and the summary
 * table's NMC_SetDOGGroup/NMC_GetDOGGroup spellings (Appendix A) with TV38. */
#include "check.h"

int main(void) {
    HAND devHandle = 0;
    short d = 0, m = 0, r = -1, f = -1, hi = 0, lo = 0, b = -1, c = -1;
    double volts[2] = {0, 0};
    double set[2] = {2.5, -1.25};
    long v = 0;

    OK(NMC_DevOpen(0, &devHandle));

    /* S-IO / TV41 */
    OK(NMC_SetDacMode(devHandle, 0, 4));
    OK(NMC_SetDac(devHandle, 0, 32767));
    OK(NMC_GetDac(devHandle, 0, &d));
    OK(NMC_GetDacMode(devHandle, 0, &m));
    CHECK(d == 32767 && m == 4, "TV41: %d %d", d, m);
    OK(NMC_GetDacVoltageMulti(devHandle, 0, 1, volts));
    CHECK(volts[0] == 10.0, "32767 at ±10 V is %f V", volts[0]);
    OK(NMC_SetAdcMode(devHandle, 0, 4, 0));
    OK(NMC_GetAdcMode(devHandle, 0, &r, &f));
    CHECK(r == 4 && f == 0, "adc mode %d %d", r, f);
    OK(NMC_GetAdc(devHandle, 0, &d));
    CHECK(d == 0, "open analog input reads %d", d);
    OK(NMC_GetAdcVoltageMulti(devHandle, 0, 2, volts));

    /* Range 1 (0-10 V): half scale is 5 V; bias and limits apply to the output. */
    OK(NMC_SetDacMode(devHandle, 1, 1));
    OK(NMC_SetDac(devHandle, 1, 16384));
    OK(NMC_GetDacVoltageMulti(devHandle, 1, 1, volts));
    CHECK(volts[0] > 4.99 && volts[0] < 5.01, "half scale of 0-10 V: %f", volts[0]);
    OK(NMC_SetDacLmt(devHandle, 1, 8000, -8000));
    OK(NMC_GetDacLmt(devHandle, 1, &hi, &lo));
    CHECK(hi == 8000 && lo == -8000, "limits %d %d", hi, lo);
    OK(NMC_GetDacVoltageMulti(devHandle, 1, 1, volts));
    CHECK(volts[0] < 2.45, "limited output %f", volts[0]);
    OK(NMC_SetDacBias(devHandle, 1, 10));
    OK(NMC_GetDacBias(devHandle, 1, &d));
    CHECK(d == 10, "bias %d", d);

    /* Voltages of two channels at once. */
    OK(NMC_SetDacVoltageMulti(devHandle, 2, 2, set));
    OK(NMC_GetDacVoltageMulti(devHandle, 2, 2, volts));
    CHECK(volts[0] == 2.5 && volts[1] == -1.25, "volts %f %f", volts[0], volts[1]);
    OK(NMC_GetDac(devHandle, 2, &d));
    CHECK(d == 8192, "2.5 V at ±10 V is raw %d", d);

    /* Bad input. */
    CHECK(NMC_SetDacMode(devHandle, 0, 6) == RTN_ARG_RANGE, "mode 6");
    CHECK(NMC_SetDac(devHandle, 99, 0) == RTN_ARG_RANGE, "channel 99");
    CHECK(NMC_GetAdcVoltageMulti(devHandle, 0, 9, volts) == RTN_ARG_RANGE, "count 9");
    CHECK(NMC_GetDac(devHandle, 0, NULL) == RTN_NULL_POINTER, "NULL");
    CHECK(NMC_SetAdcMode(devHandle, 0, 4, 65) == RTN_ARG_RANGE, "filter 65");

    /* Appendix A + TV38 */
    OK(NMC_SetDOGGroup(devHandle, 0xFFFD, 0));
    OK(NMC_GetDOGGroup(devHandle, &v, 0));
    OK(NMC_GetDOBit(devHandle, 1, &b));
    OK(NMC_GetDOBit(devHandle, 0, &c));
    CHECK(v == 0xFFFD && b == 0 && c == 1, "TV38 via DOG: %#lx %d %d", v, b, c);
    printf("ok\n");
    return 0;
}
