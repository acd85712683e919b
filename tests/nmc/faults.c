/* Server-side faults and a mcemu killed during a call. For each line on stdin ("go") it makes
 * one call and prints its code as "faulted RC", then a second call as "after RC"; the harness
 * installs one fault (count 1) before each line, or kills and restarts mcemu. The timeout is
 * 400 ms. A line "during" prints "calling" first and then "lost RC". */
#include <string.h>
#include "check.h"

int main(void) {
    HAND devHandle = 0, axisHandle = 0;
    short sts = 0, rc;
    char line[64];
    OK(NMC_DevOpen(0, &devHandle));
    OK(NMC_SetCommPara(devHandle, 400000, 0));
    OK(NMC_MtOpen(devHandle, 0, &axisHandle));
    OK(NMC_MtGetSts(axisHandle, &sts));
    printf("ready\n");
    fflush(stdout);
    while (fgets(line, sizeof line, stdin)) {
        if (strncmp(line, "during", 6) == 0) {
            printf("calling\n");
            fflush(stdout);
            rc = NMC_MtGetSts(axisHandle, &sts);
            printf("lost %d\n", rc);
        } else if (strncmp(line, "after", 5) == 0) {
            rc = NMC_MtGetSts(axisHandle, &sts);
            printf("after %d\n", rc);
        } else {
            rc = NMC_MtGetSts(axisHandle, &sts);
            printf("faulted %d\n", rc);
            rc = NMC_MtGetSts(axisHandle, &sts);
            printf("after %d\n", rc);
        }
        fflush(stdout);
    }
    return 0;
}
