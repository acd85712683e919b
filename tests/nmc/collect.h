/* What the data-collection programs share (s_collect.c, s_exe_time.c): a collection of
 * coordinate system 0's X, Y and velocity triggered on the velocity, and reading the collected
 * bytes back. */
#ifndef NMC_COLLECT_H
#define NMC_COLLECT_H

#include "crd_open.h"

static double fabs_(double v) { return v < 0 ? -v : v; }

/* Read dataLen bytes the way the manual does: 1440-byte chunks, then the rest. */
static double *read_all(HAND dev, long dataLen) {
    double *data = (double *)calloc((size_t)dataLen / 8 + 1, sizeof(double));
    short count = (short)(dataLen / 1440);
    int i;
    CHECK(data != NULL, "out of memory");
    for (i = 0; i < count; i++) OK(NMC_GetCollectData(dev, 1440, (unsigned char *)(data + i * 180)));
    OK(NMC_GetCollectData(dev, (short)(dataLen % 1440), (unsigned char *)(data + count * 180)));
    return data;
}

/* Collect coordinate system 0's X, Y and `velocity` (a COLLECT_ADDRESS_CRD_VEL* kind) every
 * planning period, from startDelay ms after the velocity rises through `from`; on. */
static void collect_crd(HAND dev, short velocity, double from, short startDelay) {
    TCollectCfg cfg;
    TCollectTrig trig;
    memset(&cfg, 0, sizeof cfg);
    cfg.count = 3;
    OK(NMC_GetCollectDataAddr(dev, 0, COLLECT_ADDRESS_CRD_POS0, &cfg.address[0], &cfg.length[0]));
    OK(NMC_GetCollectDataAddr(dev, 1, COLLECT_ADDRESS_CRD_POS0, &cfg.address[1], &cfg.length[1]));
    OK(NMC_GetCollectDataAddr(dev, 0, velocity, &cfg.address[2], &cfg.length[2]));
    memset(&trig, 0, sizeof trig);
    trig.mode = COLLECT_MODE_RISE;
    trig.source1 = 2;
    trig.value = from;
    trig.startDelay = startDelay;
    OK(NMC_ConfigCollect(dev, &cfg, &trig));
    OK(NMC_CollectOnOff(dev, 1));
}

#endif
