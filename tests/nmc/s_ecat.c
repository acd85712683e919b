/* S-ECAT-START (digest 001 §5, C2§1.3) with TV33 on an EtherCAT card (device.kind = "ecat"),
 * and what mcemu answers for the drives and slaves it does not have. With the argument "pulse"
 * the device is a network card, where every EtherCAT call is refused. */
#include <string.h>
#include "check.h"

int main(int argc, char **argv) {
    HAND devHandle = 0, axisHandle = 0;
    unsigned short mstSts = 0;
    short slaves = -1, drives = -1, io = -1;
    unsigned char val[4] = {0}, home = 0;
    unsigned int abort_code = 0;
    char gml[] = "test.gml";
    int i;

    OK(NMC_DevOpen(0, &devHandle));
    OK(NMC_MtOpen(devHandle, 0, &axisHandle));
    if (argc > 1 && strcmp(argv[1], "pulse") == 0) {
        CHECK(NMC_EcatGetSts(devHandle, &mstSts) == RTN_NOT_ON_THIS_CARD, "not a bus card");
        CHECK(NMC_EcatStart(devHandle) == RTN_NOT_ON_THIS_CARD, "not a bus card");
        printf("ok\n");
        return 0;
    }

    /* S-ECAT-START / TV33 (the example's body runs only when the master is not started). */
    OK(NMC_EcatGetSts(devHandle, &mstSts));
    CHECK(mstSts != 0, "TV33: started before NMC_EcatStart");
    OK(NMC_EcatStop(devHandle));
    OK(NMC_EcatLoadConfigFromFile(devHandle, gml, 0));
    OK(NMC_EcatStart(devHandle));
    for (i = 0; i < 5000; i++) {
        OK(NMC_EcatGetSts(devHandle, &mstSts));
        if (mstSts == 0) break;
    }
    CHECK(mstSts == 0, "TV33: master not started");
    OK(NMC_MtClrError(axisHandle));

    OK(NMC_EcatGetResource(devHandle, &slaves, &drives, &io));
    CHECK(slaves == 0 && drives == 0 && io == 0, "slaves %d %d %d", slaves, drives, io);
    CHECK(NMC_EcatSdoRead(devHandle, 0, 0x6041, 0, 2, val, &abort_code) == RTN_INVALID_SLAVE, "no slave 0");
    CHECK(NMC_EcatSdoWrite(devHandle, 0, 0x6040, 0, 2, val, &abort_code) == RTN_INVALID_SLAVE, "no slave 0");
    CHECK(NMC_EcatSdoRead(devHandle, 0, 0x6041, 0, 2, NULL, &abort_code) == RTN_NULL_POINTER, "NULL val");
    CHECK(NMC_EcatStartHome(axisHandle, 21, 10, 1, 1, 0) == RTN_NOT_ON_THIS_CARD, "pulse axis homing");
    CHECK(NMC_EcatGetHomeSts(axisHandle, &home) == RTN_NOT_ON_THIS_CARD, "pulse axis home status");
    CHECK(NMC_EcatLoadConfigFromFile(devHandle, gml, 1) == RTN_ARG_RANGE, "masterIdx 1");
    OK(NMC_EcatStop(devHandle));
    OK(NMC_EcatGetSts(devHandle, &mstSts));
    CHECK(mstSts != 0, "stopped");
    printf("ok\n");
    return 0;
}
