/* What the coordinate-system programs share: the first axes servo on, and coordinate system 0
 * on the first of them. */
#ifndef NMC_CRD_OPEN_H
#define NMC_CRD_OPEN_H

#include <string.h>
#include "check.h"

/* Axes 0 … n-1 opened (into ax[] when it is not NULL), their errors cleared, servo on. */
static inline void servo_on_axes(HAND dev, short n, HAND *ax) {
    HAND h = 0;
    short i;
    for (i = 0; i < n; i++) {
        OK(NMC_MtOpen(dev, i, &h));
        OK(NMC_MtClrError(h));
        OK(NMC_MtSetSvOn(h));
        if (ax != NULL) ax[i] = h;
    }
}

/* Coordinate system 0 on axes 0 … axes-1, synAccMax 50 pulse/ms², synVelMax 800 pulse/ms,
 * origin flag orgFlag; its errors and buffer cleared. */
static inline HAND open_crd(HAND dev, short axes, short orgFlag) {
    TCrdConfig config;
    TCrdPara para;
    HAND crd = 0;
    short i;
    memset(&config, 0, sizeof config);
    config.axCnts = axes;
    for (i = 0; i < 4; i++) config.pAxArray[i] = i < axes ? i : -1;
    OK(NMC_CrdOpen(dev, &crd));
    OK(NMC_CrdConfig(crd, &config));
    memset(&para, 0, sizeof para);
    para.orgFlag = orgFlag;
    para.synAccMax = 50;
    para.synVelMax = 800;
    OK(NMC_CrdSetPara(crd, &para));
    OK(NMC_CrdClrError(crd));
    OK(NMC_CrdBufClr(crd));
    return crd;
}

/* Wait until coordinate system `crd` is still, failing on MVERR (a halted path's members stay
 * in synchronised motion: their own BUSY bit does not say). */
static inline void crd_still(HAND crd) {
    short sts = 0;
    do {
        OK(NMC_CrdGetSts(crd, &sts));
        CHECK(!(sts & BIT_CORD_MVERR), "MVERR, sts %#x", sts);
    } while (sts & BIT_CORD_BUSY);
}

#endif
