/* Interference protection between the two coordinate systems (NMC_SetMvProtect,
 * TmvProtectPara; digest 001 §2.7, §3.7, §4.4) on the GCN400 fixture on a scaled clock:
 * coordinate system 0 is axis 0, coordinate system 1 axis 1, and their X axes face each other
 * on one rail, 50000 pulses apart at 0, to be kept 10000 apart. */
#include <string.h>
#include "check.h"

static HAND devHandle, crd[2], ax[2];

static void configure(short n) {
    TCrdConfig cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.axCnts = 1;
    cfg.pAxArray[0] = n;
    cfg.pAxArray[1] = cfg.pAxArray[2] = cfg.pAxArray[3] = -1;
    OK(NMC_CrdConfig(crd[n], &cfg));
    OK(NMC_CrdClrError(crd[n]));
    OK(NMC_CrdBufClr(crd[n]));
}

static short sts(void) {
    short s = -1;
    OK(NMC_GetMvProtectSts(devHandle, 0, &s));
    return s;
}

/* Coordinate system 0's X to `x` at 20 pulse/ms; whether the protection showed interference
 * (2) while it ran. */
static int move0(long x) {
    short s = 0;
    int seen = 0;
    OK(NMC_CrdBufClr(crd[0]));
    OK(NMC_CrdLineXYZEx(crd[0], 1, 0x1, &x, 0, 20, 0.5, 0));
    OK(NMC_CrdStartMtn(crd[0]));
    do {
        if (sts() == 2) seen = 1;
        OK(NMC_CrdGetSts(crd[0], &s));
    } while (s & BIT_CORD_BUSY);
    if (sts() == 2) seen = 1;
    return seen;
}

static long x0(void) {
    long p = 0;
    OK(NMC_MtGetPrfPos(ax[0], &p));
    return p;
}

int main(void) {
    TmvProtectPara p, back;
    TMvProtectPara *same = &p; /* the manual's other spelling names the same struct */
    char d[512];
    short i, rc;
    int seen;

    OK(NMC_DevOpen(0, &devHandle));
    for (i = 0; i < 2; i++) {
        OK(NMC_MtOpen(devHandle, i, &ax[i]));
        OK(NMC_MtClrError(ax[i]));
        OK(NMC_MtSetSvOn(ax[i]));
        OK(NMC_MtMovePtpAbs(ax[i], 1, 1, 0, 0, 50, 0, 0)); /* both X at 0 */
        wait_still(ax[i]);
        OK(NMC_CrdOpenEx(devHandle, i, &crd[i]));
        configure(i);
    }

    CHECK(sts() == 0, "not enabled: 0");
    rc = NMC_SetMvProtect(devHandle, 0, 0);
    CHECK(rc == RTN_INVALID_STATE, "no parameters yet: %d", rc);
    NMC_GetErrDesc(rc, d);
    CHECK(strstr(d, "NMC_SetMvProtectMode01Para") != NULL, "description: %s", d);

    memset(&p, 0, sizeof p);
    p.crdNo[0] = 0;
    p.crdNo[1] = 1;
    p.crdAxNo[0] = 0;
    p.crdAxNo[1] = 0;
    p.moveDir[0] = 1;  /* coordinate system 0 closes the gap moving + */
    p.moveDir[1] = -1; /* coordinate system 1 moving − */
    p.orgDis = 50000;
    p.mvProtectDis = 10000;
    p.safeWaitPos = -5000;
    p.mvToSafeAcc = 0.5; /* the retreat: 0.5 pulse/ms², 20 pulse/ms */
    p.mvToSafeVel = 20;
    p.stopCrdNo = 0;

    /* Bad arguments: each its code, nothing stored. */
    CHECK(NMC_SetMvProtectMode01Para(devHandle, 1, same) == RTN_ARG_RANGE, "groupNo 1");
    CHECK(NMC_SetMvProtectMode01Para(devHandle, 0, NULL) == RTN_NULL_POINTER, "NULL");
    CHECK(NMC_SetMvProtectMode01Para(crd[0], 0, &p) == RTN_WRONG_HANDLE_KIND, "a crd handle");
    back = p;
    back.crdNo[1] = 0;
    CHECK(NMC_SetMvProtectMode01Para(devHandle, 0, &back) == RTN_ARG_RANGE, "crdNo twice 0");
    back = p;
    back.crdAxNo[0] = 3;
    CHECK(NMC_SetMvProtectMode01Para(devHandle, 0, &back) == RTN_ARG_RANGE, "crdAxNo 3");
    back = p;
    back.moveDir[1] = 2;
    rc = NMC_SetMvProtectMode01Para(devHandle, 0, &back);
    CHECK(rc == RTN_ARG_RANGE, "moveDir 2: %d", rc);
    NMC_GetErrDesc(rc, d);
    CHECK(strstr(d, "moveDir[1]") != NULL, "description: %s", d);
    back = p;
    back.mvProtectDis = -1;
    CHECK(NMC_SetMvProtectMode01Para(devHandle, 0, &back) == RTN_ARG_RANGE, "mvProtectDis −1");

    /* Y (coordinate 1) of a one-axis coordinate system: refused when enabled. */
    back = p;
    back.crdAxNo[0] = 1;
    OK(NMC_SetMvProtectMode01Para(devHandle, 0, &back));
    CHECK(NMC_SetMvProtect(devHandle, 0, 0) == RTN_ARG_RANGE, "crdAxNo 1 of a one-axis crd");
    CHECK(sts() == 0, "still not enabled");

    OK(NMC_SetMvProtectMode01Para(devHandle, 0, &p));
    memset(&back, 0, sizeof back);
    OK(NMC_GetMvProtectMode01Para(devHandle, 0, &back));
    CHECK(back.crdNo[0] == 0 && back.crdNo[1] == 1 && back.crdAxNo[0] == 0 && back.crdAxNo[1] == 0 &&
              back.moveDir[0] == 1 && back.moveDir[1] == -1 && back.orgDis == 50000 && back.mvProtectDis == 10000 &&
              back.safeWaitPos == -5000 && back.mvToSafeAcc == 0.5 && back.mvToSafeVel == 20 && back.stopCrdNo == 0,
          "TmvProtectPara read back");
    CHECK(NMC_SetMvProtect(devHandle, 0, 2) == RTN_ARG_RANGE, "mode 2");
    CHECK(NMC_SetMvProtect(devHandle, 1, 0) == RTN_ARG_RANGE, "groupNo 1");

    /* Mode 0: coordinate system 0 heads for 100000; the gap 50000 − x must stay ≥ 10000, so it
     * stops short of 40000 (both stop; coordinate system 1 is at rest). */
    OK(NMC_SetMvProtect(devHandle, 0, 0));
    CHECK(sts() == 1, "enabled, far apart: 1");
    seen = move0(100000);
    /* It stops before the gap falls below mvProtectDis (40000), at most a tick's travel
     * (20 pulses) off: at 20 pulse/ms it brakes at its synAcc (0.5 pulse/ms², the crd's stop
     * deceleration being synAccMax), 400 pulses, from the last tick that leaves room for it. */
    CHECK(x0() <= 40000 && x0() >= 40000 - 2 * 20, "stopped at %ld", x0());
    CHECK(seen, "interference (2) was never reported while stopping");
    /* Moving apart is never stopped. */
    move0(0);
    CHECK(x0() == 0, "moved back to %ld", x0());
    CHECK(sts() == 1, "apart again: 1");

    /* Mode 1 needs stopCrdNo to be one of the pair. */
    back = p;
    back.stopCrdNo = 5;
    OK(NMC_SetMvProtectMode01Para(devHandle, 0, &p));
    CHECK(NMC_SetMvProtectMode01Para(devHandle, 0, &back) == 0, "mode 0 ignores stopCrdNo");
    rc = NMC_SetMvProtect(devHandle, 0, 1);
    CHECK(rc == RTN_ARG_RANGE, "mode 1 with stopCrdNo 5: %d", rc);
    NMC_GetErrDesc(rc, d);
    CHECK(strstr(d, "stopCrdNo") != NULL, "description: %s", d);
    OK(NMC_SetMvProtectMode01Para(devHandle, 0, &p));

    /* Mode 1 ("laser"): coordinate system 0 stops, then its X retreats to safeWaitPos. */
    OK(NMC_SetMvProtect(devHandle, 0, 1));
    move0(100000);
    {
        short s = 0;
        long polls = 0;
        /* The retreat is queued once the path is at rest: wait for it to end at −5000. */
        do {
            OK(NMC_CrdGetSts(crd[0], &s));
            CHECK(++polls < 10000000L, "no retreat: at %ld", x0());
        } while ((s & BIT_CORD_BUSY) || x0() != -5000);
    }

    /* Deleted: 0, and nothing stops the path any more. */
    OK(NMC_DelMvProtect(devHandle, 0));
    CHECK(sts() == 0, "deleted: 0");
    OK(NMC_DelMvProtect(devHandle, 0)); /* twice: still 0 */
    move0(45000);
    CHECK(x0() == 45000, "unguarded: at %ld", x0());
    move0(0);

    /* NMC_CrdConfig re-makes a coordinate system: the protection guarding it ends. */
    OK(NMC_SetMvProtect(devHandle, 0, 0));
    CHECK(sts() == 1, "enabled again");
    configure(1);
    CHECK(sts() == 0, "after NMC_CrdConfig of coordinate system 1: %d", sts());

    printf("ok\n");
    return 0;
}
