/* What the laser and SHIO programs share: a 2-axis coordinate system (X = axis 0, Y = axis 1)
 * and a run of its buffer that watches one digital output along the path. */
#ifndef NMC_LASER_PATH_H
#define NMC_LASER_PATH_H

#include "check.h"

static HAND devHandle, crdHandle;

static short do_bit(short bit) {
    short v = -1;
    OK(NMC_GetDOBit(devHandle, bit, &v));
    return v;
}

/* Open the device, servo on axes 0 and 1, and make them coordinate system 0. */
static void open_xy(void) {
    TCrdConfig config = {0};
    TCrdPara para = {0};
    HAND ax;
    short i;
    OK(NMC_DevOpen(0, &devHandle));
    for (i = 0; i < 2; i++) {
        OK(NMC_MtOpen(devHandle, i, &ax));
        OK(NMC_MtClrError(ax));
        OK(NMC_MtSetSvOn(ax));
    }
    OK(NMC_CrdOpen(devHandle, &crdHandle));
    config.axCnts = 2;
    config.pAxArray[0] = 0;
    config.pAxArray[1] = 1;
    config.pAxArray[2] = -1;
    config.pAxArray[3] = -1;
    OK(NMC_CrdConfig(crdHandle, &config));
    para.orgFlag = 1;
    para.synAccMax = 50;
    para.synVelMax = 800;
    OK(NMC_CrdSetPara(crdHandle, &para));
    OK(NMC_CrdClrError(crdHandle));
    OK(NMC_CrdBufClr(crdHandle));
}

static void line_x(long seg, long x) {
    long tgt[2];
    tgt[0] = x;
    tgt[1] = 0;
    OK(NMC_CrdLineXYZEx(crdHandle, seg, 0x3, tgt, 0, 20, 1, 0));
}

/* What `level()` read along a path out to x = 10000 and back: on the way out and on the way
 * back (well inside each line: -1 if never seen there), and at the end. */
typedef struct { short out, back, end; } Seen;

static Seen run_out_and_back(short (*level)(void)) {
    Seen seen = {-1, -1, -1};
    short sts = 0;
    long pos[2], polls = 0, far = 0;
    OK(NMC_CrdEndMtn(crdHandle));
    OK(NMC_CrdStartMtn(crdHandle));
    do {
        /* The position first: what `level` reads then was switched before it. */
        OK(NMC_CrdGetSts(crdHandle, &sts));
        OK(NMC_CrdGetPrfPos(crdHandle, 2, pos));
        /* On the way back once the path has been near the far end (polls may miss it). */
        if (pos[0] > far) far = pos[0];
        if (far < 9900 && pos[0] > 1000 && pos[0] < 9000 && seen.out < 0) seen.out = level();
        if (far >= 9900 && pos[0] > 1000 && pos[0] < 9000 && seen.back < 0) seen.back = level();
        CHECK(!(sts & BIT_CORD_MVERR), "MVERR, sts %#x", sts);
        CHECK(++polls < 100000000L, "never finished, sts %#x", sts);
    } while (sts & BIT_CORD_BUSY);
    seen.end = level();
    return seen;
}

#endif
