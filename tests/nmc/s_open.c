/* S-OPEN (digest 001 §5, C2§2.3) with TV01–TV03, TV25: open the device three ways, each axis,
 * clear its errors, servo on; SVON set on every axis and cleared by servo off. */
#include <string.h>
#include "check.h"
#include "mtn_lib20_ext.h"

int main(void) {
    HAND devHandle = 0, byId = 0, byIp = 0, axisHandle = 0;
    short sts = 0, i;
    unsigned char ip[4] = {192, 168, 1, 110};
    char id[] = "CARD1";
    TCardInfo info;

    OK(NMC_DevOpen(0, &devHandle));                      /* TV01 */
    OK(NMC_DevOpenByID(id, &byId));                      /* TV02 */
    OK(NMC_DevOpenByIP(ip, &byIp));                      /* TV03 (network card) */
    CHECK(devHandle != byId, "each open is its own handle");
    OK(NMC_GetCardInfo(byIp, &info));
    CHECK(info.axisNum == 4 && strcmp(info.idStr, "CARD1") == 0, "card %d axes, id %s", info.axisNum, info.idStr);
    CHECK(info.diNum == 64 && info.doNum == 64, "io %d/%d", info.diNum, info.doNum);
    for (i = 0; i < 4; i++) {
        OK(NMC_MtOpen(devHandle, i, &axisHandle));
        OK(NMC_MtClrError(axisHandle));
        OK(NMC_MtSetSvOn(axisHandle));
        OK(NMC_MtGetSts(axisHandle, &sts));
        CHECK(sts & BIT_AXIS_SVON, "axis %d sts %#x", i, sts);
    }
    OK(NMC_MtSetSvOff(axisHandle));                       /* TV25 */
    OK(NMC_MtGetSts(axisHandle, &sts));
    CHECK(!(sts & BIT_AXIS_SVON), "after servo off sts %#x", sts);
    /* Bad input: a handle of the wrong kind, an axis that does not exist, NULL. */
    CHECK(NMC_MtGetSts(devHandle, &sts) == RTN_WRONG_HANDLE_KIND, "device handle as axis");
    CHECK(NMC_MtOpen(devHandle, 4, &axisHandle) == RTN_ARG_RANGE, "itemNo 4");
    CHECK(NMC_GetLastErr() == RTN_ARG_RANGE, "last error");
    CHECK(NMC_MtGetSts(axisHandle, NULL) == RTN_NULL_POINTER, "NULL");
    CHECK(NMC_MtGetSts(0, &sts) == RTN_INVALID_HANDLE, "handle 0");
    OK(NMC_DevClose(&byId));
    CHECK(byId == 0, "DevClose zeroes the handle");
    printf("ok\n");
    return 0;
}
