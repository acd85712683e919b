/* The user parameter areas are non-volatile (digest 001 §2.20): `user_para_restart save` writes
 * both areas; `user_para_restart check`, against a restarted mcemu on the same state
 * directory, reads them back. */
#include <string.h>
#include "check.h"

int main(int argc, char **argv) {
    HAND dev = 0;
    unsigned char buf[1000], back[1000];
    int i;
    int save = argc > 1 && strcmp(argv[1], "save") == 0;

    for (i = 0; i < 1000; i++) buf[i] = (unsigned char)(i * 13 + 5);
    OK(NMC_DevOpen(0, &dev));
    if (save) {
        OK(NMC_UserParaWr(dev, 1792, 256, buf));
        OK(NMC_UserParaWrEx(dev, 31768, 1000, buf));
        OK(NMC_DevReset(dev));
    }
    OK(NMC_UserParaRd(dev, 1792, 256, back));
    for (i = 0; i < 256; i++) CHECK(back[i] == buf[i], "byte %d: %u", i, back[i]);
    OK(NMC_UserParaRdEx(dev, 31768, 1000, back));
    for (i = 0; i < 1000; i++) CHECK(back[i] == buf[i], "ex byte %d: %u", i, back[i]);
    OK(NMC_UserParaRd(dev, 0, 4, back));
    CHECK(back[0] == 0 && back[3] == 0, "unwritten bytes read 0");
    printf("ok\n");
    return 0;
}
