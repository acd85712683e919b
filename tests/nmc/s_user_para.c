/* The user parameter areas (digest 001 §2.20) with TV66. */
#include "check.h"

int main(void) {
    HAND devHandle = 0;
    unsigned char buf[1000], back[1000];
    int i;

    OK(NMC_DevOpen(0, &devHandle));
    for (i = 0; i < 1000; i++) buf[i] = (unsigned char)(i * 7);

    /* TV66 */
    CHECK(NMC_UserParaWr(devHandle, 0, 257, buf) == RTN_ARG_RANGE, "TV66: 257 bytes");
    CHECK(NMC_UserParaWr(devHandle, 2000, 100, buf) == RTN_ARG_RANGE, "TV66: past 2048");
    OK(NMC_UserParaWr(devHandle, 1792, 256, buf));
    OK(NMC_UserParaRd(devHandle, 1792, 256, back));
    for (i = 0; i < 256; i++) CHECK(back[i] == buf[i], "byte %d", i);
    OK(NMC_UserParaRd(devHandle, 0, 4, back));
    CHECK(back[0] == 0 && back[3] == 0, "unwritten bytes read 0");

    CHECK(NMC_UserParaWrEx(devHandle, 0, 1001, buf) == RTN_ARG_RANGE, "1001 bytes");
    OK(NMC_UserParaWrEx(devHandle, 31768, 1000, buf));
    OK(NMC_UserParaRdEx(devHandle, 31768, 1000, back));
    for (i = 0; i < 1000; i++) CHECK(back[i] == buf[i], "ex byte %d", i);
    CHECK(NMC_UserParaRd(devHandle, 0, 4, NULL) == RTN_NULL_POINTER, "NULL");
    printf("ok\n");
    return 0;
}
