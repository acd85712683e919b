/* The coordinate system's documented refusals (digest 001 §6): TV51 the override's open range
 * (0, 10), TV52 at most 4 axes (C2§7.1.1(1) "最多支持 4 个轴"), TV53 NMC_CrdLineXYZD8Pack's
 * count ∈ [1, 18]. Each refusal is RTN_ARG_RANGE with a description naming the argument and
 * the range, and leaves the coordinate system as it was. */
#include <math.h>
#include <string.h>
#include "check.h"

static HAND devHandle, crdHandle;

static void names(short rc, const char *argument, const char *range) {
    char d[512];
    NMC_GetErrDesc(rc, d);
    CHECK(strstr(d, argument) != NULL && strstr(d, range) != NULL, "description \"%s\" (wanted %s and %s)", d,
          argument, range);
}

int main(void) {
    TCrdConfig cfg, back;
    TCrdLineXYZD8Unit pack[19];
    short counts[] = {5, 0, -1, 32767}, packs[] = {19, 0, -1, 1000}, rc;
    double overrides[] = {10, 0, -0.5, 10.5, NAN, INFINITY}, ov = 0;
    long used = -1;
    unsigned k;
    short i;

    OK(NMC_DevOpen(0, &devHandle));
    OK(NMC_CrdOpen(devHandle, &crdHandle));
    memset(&cfg, 0, sizeof cfg);
    cfg.axCnts = 3;
    for (i = 0; i < 4; i++) cfg.pAxArray[i] = i < 3 ? i : -1;
    OK(NMC_CrdConfig(crdHandle, &cfg));

    /* TV52: axCnts outside [1, 4]; the configuration stays. */
    for (k = 0; k < sizeof counts / sizeof counts[0]; k++) {
        back = cfg;
        back.axCnts = counts[k];
        rc = NMC_CrdConfig(crdHandle, &back);
        CHECK(rc == RTN_ARG_RANGE, "TV52: axCnts %d gave %d", counts[k], rc);
        CHECK(NMC_GetLastErr() == RTN_ARG_RANGE, "TV52: last error");
        names(rc, "axCnts", "[1, 4]");
    }
    memset(&back, 0, sizeof back);
    OK(NMC_CrdGetConfig(crdHandle, &back));
    CHECK(back.axCnts == 3 && back.pAxArray[2] == 2, "TV52: the configuration is unchanged (%d axes)", back.axCnts);
    /* 4 axes is the most, and allowed. */
    back = cfg;
    back.axCnts = 4;
    back.pAxArray[3] = 3;
    OK(NMC_CrdConfig(crdHandle, &back));
    /* An axis twice is no fifth axis, but still out of range. */
    back.pAxArray[3] = 0;
    CHECK(NMC_CrdConfig(crdHandle, &back) == RTN_ARG_RANGE, "an axis twice");
    CHECK(NMC_CrdConfig(crdHandle, NULL) == RTN_NULL_POINTER, "NULL config");
    OK(NMC_CrdConfig(crdHandle, &cfg));

    /* TV53: count outside [1, 18]; nothing is pushed. */
    OK(NMC_CrdBufClr(crdHandle));
    memset(pack, 0, sizeof pack);
    for (i = 0; i < 19; i++) {
        pack[i].segNo = i;
        pack[i].crdAxMask = 0x7;
        pack[i].tgPos[0] = 100 * (i + 1); /* none where the path already is (not queued) */
        pack[i].vel = 10;
        pack[i].acc = 1;
    }
    for (k = 0; k < sizeof packs / sizeof packs[0]; k++) {
        rc = NMC_CrdLineXYZD8Pack(crdHandle, packs[k], pack);
        CHECK(rc == RTN_ARG_RANGE, "TV53: count %d gave %d", packs[k], rc);
        names(rc, "count", "[1, 18]");
    }
    OK(NMC_CrdBufGetUsed(crdHandle, &used));
    CHECK(used == 0, "TV53: %ld commands pushed by refused packs", used);
    OK(NMC_CrdLineXYZD8Pack(crdHandle, 18, pack));
    OK(NMC_CrdBufGetUsed(crdHandle, &used));
    CHECK(used == 18, "18 units: %ld used", used);
    OK(NMC_CrdBufClr(crdHandle));

    /* TV51: the override's range is open at both ends; the factor stays. */
    OK(NMC_CrdSetOverride(crdHandle, 0.5));
    for (k = 0; k < sizeof overrides / sizeof overrides[0]; k++) {
        rc = NMC_CrdSetOverride(crdHandle, overrides[k]);
        CHECK(rc == RTN_ARG_RANGE, "TV51: override %f gave %d", overrides[k], rc);
        names(rc, "override", "(0, 10)");
    }
    OK(NMC_CrdGetOverride(crdHandle, &ov));
    CHECK(ov == 0.5, "TV51: override now %f", ov);
    OK(NMC_CrdSetOverRide(crdHandle, 9.99));
    OK(NMC_CrdGetOverRide(crdHandle, &ov));
    CHECK(ov == 9.99, "the alias: %f", ov);
    OK(NMC_CrdSetOverride(crdHandle, 1));

    printf("ok\n");
    return 0;
}
