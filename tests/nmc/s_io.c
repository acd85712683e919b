/* S-IO (digest 001 §5, C2§8.3) with TV37–TV39: DI groups and bits, DO group and bits. TV37's
 * I/O slave is here the fixture's extension module 2, which holds group 2 (bits 64–95). */
#include "check.h"

int main(void) {
    HAND devHandle = 0;
    long value = -1;
    short bit = -1, c = -1;

    OK(NMC_DevOpen(0, &devHandle));
    OK(NMC_GetDIGroup(devHandle, &value, 0));
    OK(NMC_GetDIBit(devHandle, 0, &bit));
    CHECK((value & 1) == bit, "DI group bit 0 %ld vs bit %d", value & 1, bit);
    CHECK(NMC_GetDIGroup(devHandle, &value, 2) == RTN_ARG_RANGE, "group 2 before IOModuleSetEn");
    CHECK(NMC_SetDOBit(devHandle, 64, 1) == RTN_ARG_RANGE, "bit 64 before IOModuleSetEn");
    OK(NMC_IOModuleSetEn(devHandle, 2, 1)); /* the example's optional step */
    OK(NMC_GetDIGroup(devHandle, &value, 2));
    OK(NMC_GetDIBit(devHandle, 64, &bit));
    CHECK((value & 1) == bit, "DI group 2 bit 0 %ld vs bit 64 %d", value & 1, bit);
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
    /* TV37 */
    OK(NMC_SetDOBit(devHandle, 64, 1));
    OK(NMC_GetDOGroup(devHandle, &value, 2));
    CHECK(value == 1, "DO group 2 %#lx", value);
    CHECK(NMC_SetDOBit(devHandle, 96, 1) == RTN_ARG_RANGE, "bit 96");
    CHECK(NMC_GetDOGroup(devHandle, &value, 3) == RTN_ARG_RANGE, "group 3: no module 3");
    printf("ok\n");
    return 0;
}
