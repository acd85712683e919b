/* S-IO (digest 001 §5, C2§8.3) with TV38–TV39: DI groups and bits, DO group and bits. */
#include "check.h"

int main(void) {
    HAND devHandle = 0;
    long value = -1;
    short bit = -1, c = -1;

    OK(NMC_DevOpen(0, &devHandle));
    OK(NMC_GetDIGroup(devHandle, &value, 0));
    OK(NMC_GetDIBit(devHandle, 0, &bit));
    CHECK((value & 1) == bit, "DI group bit 0 %ld vs bit %d", value & 1, bit);
    CHECK(NMC_GetDIGroup(devHandle, &value, 2) == RTN_ARG_RANGE, "group 2 without modules");
    /* TV38 */
    OK(NMC_SetDOGroup(devHandle, 0xFFFD, 0));
    OK(NMC_GetDOBit(devHandle, 1, &bit));
    OK(NMC_GetDOBit(devHandle, 0, &c));
    CHECK(bit == 0 && c == 1, "TV38: b %d c %d", bit, c);
    OK(NMC_GetDOGroup(devHandle, &value, 0));
    CHECK(value == 0xFFFD, "DO group %#lx", value);
    OK(NMC_SetDOBit(devHandle, 33, 1));
    OK(NMC_GetDOGroup(devHandle, &value, 1));
    CHECK(value == 2, "DO group 1 %#lx", value);
    CHECK(NMC_SetDOBit(devHandle, 64, 1) == RTN_ARG_RANGE, "bit 64");
    printf("ok\n");
    return 0;
}
