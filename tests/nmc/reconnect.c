/* Lost connection: prints "ready", waits for a line on stdin (the harness kills mcemu), calls
 * (expects -1 within the timeout), waits for a second line (mcemu restarted on the same
 * address), calls again (expects 0). Prints each code. */
#include <string.h>
#include "check.h"

int main(void) {
    HAND devHandle = 0, axisHandle = 0;
    short sts = 0, rc;
    char line[64];
    OK(NMC_DevOpen(0, &devHandle));
    OK(NMC_SetCommPara(devHandle, 500000, 0));
    OK(NMC_MtOpen(devHandle, 0, &axisHandle));
    OK(NMC_MtGetSts(axisHandle, &sts));
    printf("ready\n");
    fflush(stdout);
    if (!fgets(line, sizeof line, stdin)) return 2;
    rc = NMC_MtGetSts(axisHandle, &sts);
    printf("lost %d\n", rc);
    fflush(stdout);
    if (!fgets(line, sizeof line, stdin)) return 2;
    rc = NMC_MtGetSts(axisHandle, &sts);
    printf("back %d\n", rc);
    return 0;
}
