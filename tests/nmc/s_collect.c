/* S-COLLECT (digest 001 §5, C3§10.4.3; §2.20 data collection, §3.19): the manual's example —
 * stop, clear, the addresses of axis 0's planned position and command velocity, count 2,
 * interval 0, no trigger, start, MtMovePtpAbs(ax,1,1,0,0,10,0,10000), wait, stop, read in
 * 1440-byte chunks into a double array — then what the data say: one sample per planning
 * period (1 ms), positions 0 … 10000, velocity 10 pulse/ms in the cruise. Then a rising
 * trigger, clearing, and the documented codes of bad arguments; then coordinate system 0's
 * position and path velocity, recorded startDelay ms after a rising trigger on the velocity. */
#include "collect.h"

/* Coordinate system 0 on axes 0 and 1 runs a diagonal from (20000, 0) to (30000, 10000) at
 * 10 pulse/ms, 1 pulse/ms²; channels X, Y and the path velocity, triggered when the velocity
 * rises through 0.5 pulse/ms, the first sample startDelay = 100 ms later. */
static void crd_collect(HAND dev) {
    HAND ax[2], crd;
    unsigned long a = 0;
    short l = 0, sts = 0;
    long dataLen = 0, k, tgt[3] = {30000, 10000, 0};
    double *data;

    servo_on_axes(dev, 2, ax);
    crd = open_crd(dev, 2, 0);
    CHECK(NMC_GetCollectDataAddr(dev, 2, COLLECT_ADDRESS_CRD_POS0, &a, &l) == RTN_ARG_RANGE, "coordinate 2 of 2");
    CHECK(NMC_GetCollectDataAddr(dev, 1, COLLECT_ADDRESS_CRD_VELO, &a, &l) == RTN_ARG_RANGE, "velocity index 1");
    CHECK(NMC_GetCollectDataAddr(dev, 0, COLLECT_ADDRESS_CRD_POS1, &a, &l) == RTN_INVALID_STATE, "crd 1 unconfigured");
    OK(NMC_ClearCollectSts(dev));
    collect_crd(dev, COLLECT_ADDRESS_CRD_VELO, 0.5, 100);
    OK(NMC_CrdLineXYZEx(crd, 1, 0x3, tgt, 0, 10, 1, 1));
    OK(NMC_CrdStartMtn(crd));
    do {
        OK(NMC_CrdGetSts(crd, &sts));
        CHECK(!(sts & BIT_CORD_MVERR), "MVERR %#x", sts);
    } while (sts & BIT_CORD_BUSY);
    wait_still(ax[1]);
    OK(NMC_CollectOnOff(dev, 0));
    OK(NMC_GetCollectSts(dev, &sts, &dataLen));
    CHECK(sts & COLLECT_STS_TRIGGERED, "triggered %#x", sts);
    CHECK(dataLen % 24 == 0 && dataLen / 24 > 1000, "crd samples %ld", dataLen / 24);
    data = read_all(dev, dataLen);
    /* 100 ms after the first tick at 1 pulse/ms: 50 pulses of ramp, then 90 ms at 10. */
    CHECK(data[2] == 10, "first sample's path velocity %g", data[2]);
    CHECK(fabs_((data[0] - 20000) * 1.41421356 - 950) <= 15, "first sample at %g, %g", data[0], data[1]);
    for (k = 0; k < dataLen / 24; k++) {
        double x = data[3 * k], y = data[3 * k + 1], v = data[3 * k + 2];
        CHECK(fabs_((x - 20000) - y) <= 1, "sample %ld off the diagonal: %g, %g", k, x, y);
        CHECK(v >= 0 && v <= 10 + 1e-9, "sample %ld: path velocity %g", k, v);
    }
    CHECK(data[dataLen / 8 - 3] == 30000 && data[dataLen / 8 - 2] == 10000, "last sample %g, %g",
          data[dataLen / 8 - 3], data[dataLen / 8 - 2]);
    free(data);
}

int main(void) {
    HAND devHandle = 0, axisHandle = 0;
    unsigned long addr[8];
    short len[8], cltSts = 0;
    long dataLen = 0, k, cruise = 0;
    TCollectCfg g_cltCfg, bad;
    TCollectTrig cltTrig, badTrig;
    double *data, vmax = 0;
    unsigned char one[8];

    OK(NMC_DevOpen(0, &devHandle));
    OK(NMC_MtOpen(devHandle, 0, &axisHandle));
    OK(NMC_MtSetSvOn(axisHandle));

    /* Nothing configured yet: nothing to start; stopping is harmless (the example does). */
    CHECK(NMC_CollectOnOff(devHandle, 1) == RTN_INVALID_STATE, "start before ConfigCollect");
    OK(NMC_ClearCollectSts(devHandle));
    OK(NMC_GetCollectSts(devHandle, &cltSts, &dataLen));
    CHECK(cltSts == 0 && dataLen == 0, "fresh status %#x %ld", cltSts, dataLen);

    OK(NMC_GetCollectDataAddr(devHandle, 0, COLLECT_ADDRESS_PRF_POS, &addr[0], &len[0]));
    OK(NMC_GetCollectDataAddr(devHandle, 0, COLLECT_ADDRESS_CMD_VEL, &addr[1], &len[1]));
    CHECK(len[0] == 8 && len[1] == 8, "lengths %d %d", len[0], len[1]);
    CHECK(addr[0] != addr[1] && addr[0] != 0, "addresses %#lx %#lx", addr[0], addr[1]);

    /* Bad addresses. */
    CHECK(NMC_GetCollectDataAddr(devHandle, 0, 16, &addr[2], &len[2]) == RTN_ARG_RANGE, "dataType 16");
    CHECK(NMC_GetCollectDataAddr(devHandle, 0, -1, &addr[2], &len[2]) == RTN_ARG_RANGE, "dataType -1");
    CHECK(NMC_GetCollectDataAddr(devHandle, 4, COLLECT_ADDRESS_PRF_POS, &addr[2], &len[2]) == RTN_ARG_RANGE, "axis 4");
    CHECK(NMC_GetCollectDataAddr(devHandle, 0, COLLECT_ADDRESS_CRD_POS, &addr[2], &len[2]) == RTN_INVALID_STATE,
          "crd pos before NMC_CrdConfig");
    CHECK(NMC_GetCollectDataAddr(devHandle, 0, COLLECT_ADDRESS_LASER_POWER, &addr[2], &len[2]) == RTN_UNSUPPORTED, "laser");
    CHECK(NMC_GetCollectDataAddr(devHandle, 0, COLLECT_ADDRESS_PRF_POS, NULL, &len[2]) == RTN_NULL_POINTER, "NULL pAddr");
    CHECK(NMC_GetCollectDataAddr(axisHandle, 0, COLLECT_ADDRESS_PRF_POS, &addr[2], &len[2]) == RTN_WRONG_HANDLE_KIND, "axis handle");

    memset(&g_cltCfg, 0, sizeof(TCollectCfg));
    g_cltCfg.count = 2;
    g_cltCfg.interval = 0;
    g_cltCfg.address[0] = addr[0];
    g_cltCfg.length[0] = len[0];
    g_cltCfg.address[1] = addr[1];
    g_cltCfg.length[1] = len[1];
    memset(&cltTrig, 0, sizeof(TCollectTrig));
    cltTrig.mode = COLLECT_MODE_NONE;

    /* Bad configurations. */
    bad = g_cltCfg; bad.count = 0;
    CHECK(NMC_ConfigCollect(devHandle, &bad, &cltTrig) == RTN_ARG_RANGE, "count 0");
    bad = g_cltCfg; bad.count = COLLECT_LIST_MAX + 1;
    CHECK(NMC_ConfigCollect(devHandle, &bad, &cltTrig) == RTN_ARG_RANGE, "count 9");
    bad = g_cltCfg; bad.address[1] = 0x1234;
    CHECK(NMC_ConfigCollect(devHandle, &bad, &cltTrig) == RTN_ARG_RANGE, "foreign address");
    bad = g_cltCfg; bad.length[0] = 4;
    CHECK(NMC_ConfigCollect(devHandle, &bad, &cltTrig) == RTN_ARG_RANGE, "length 4");
    bad = g_cltCfg; bad.interval = -1;
    CHECK(NMC_ConfigCollect(devHandle, &bad, &cltTrig) == RTN_ARG_RANGE, "interval -1");
    badTrig = cltTrig; badTrig.mode = 7;
    CHECK(NMC_ConfigCollect(devHandle, &g_cltCfg, &badTrig) == RTN_ARG_RANGE, "mode 7");
    badTrig = cltTrig; badTrig.mode = COLLECT_MODE_RISE; badTrig.source1 = 2;
    CHECK(NMC_ConfigCollect(devHandle, &g_cltCfg, &badTrig) == RTN_ARG_RANGE, "source1 2 of 2 channels");
    badTrig = cltTrig; badTrig.startDelay = -1;
    CHECK(NMC_ConfigCollect(devHandle, &g_cltCfg, &badTrig) == RTN_ARG_RANGE, "startDelay -1");
    CHECK(NMC_ConfigCollect(devHandle, NULL, &cltTrig) == RTN_NULL_POINTER, "NULL pCollect");

    /* The manual's example. */
    OK(NMC_CollectOnOff(devHandle, 0));
    OK(NMC_ClearCollectSts(devHandle));
    OK(NMC_ConfigCollect(devHandle, &g_cltCfg, &cltTrig));
    CHECK(NMC_CollectOnOff(devHandle, 2) == RTN_ARG_RANGE, "en 2");
    OK(NMC_CollectOnOff(devHandle, 1));
    EVENTUALLY(NMC_GetCollectSts(devHandle, &cltSts, &dataLen), (cltSts & COLLECT_STS_TRIGGERED) != 0);
    CHECK(cltSts & COLLECT_STS_ON, "running %#x", cltSts);
    OK(NMC_MtMovePtpAbs(axisHandle, 1, 1, 0, 0, 10, 0, 10000));
    wait_still(axisHandle);
    OK(NMC_CollectOnOff(devHandle, 0));
    OK(NMC_GetCollectSts(devHandle, &cltSts, &dataLen));
    CHECK(!(cltSts & COLLECT_STS_ON) && (cltSts & COLLECT_STS_TRIGGERED), "stopped %#x", cltSts);
    CHECK(dataLen % 16 == 0, "dataLen %ld is whole samples", dataLen);
    /* 10 ms up, 990 cruising, 10 down: at least 1010 samples of 1 ms. */
    CHECK(dataLen / 16 >= 1010, "samples %ld", dataLen / 16);
    CHECK(NMC_GetCollectData(devHandle, 1441, one) == RTN_ARG_RANGE, "len 1441");

    data = read_all(devHandle, dataLen);
    CHECK(data[0] >= 0 && data[0] < 1, "first position %g", data[0]);
    CHECK(data[dataLen / 8 - 2] == 10000, "last position %g", data[dataLen / 8 - 2]);
    for (k = 0; k + 1 < dataLen / 16; k++) {
        double p0 = data[2 * k], v0 = data[2 * k + 1], p1 = data[2 * k + 2], v1 = data[2 * k + 3];
        CHECK(p1 >= p0, "position falls at sample %ld: %g → %g", k, p0, p1);
        CHECK(v1 >= -1e-9 && v1 <= 10 + 1e-9, "velocity %g at sample %ld", v1, k);
        /* One planning period between samples: the step is the mean velocity × 1 ms. */
        CHECK(fabs_((p1 - p0) - (v0 + v1) / 2) <= 0.5 + 1e-9, "sample %ld: step %g, velocities %g %g",
              k, p1 - p0, v0, v1);
        if (v1 > vmax) vmax = v1;
        if (fabs_(v1 - 10) < 1e-9) cruise++;
    }
    CHECK(fabs_(vmax - 10) < 1e-9, "top velocity %g", vmax);
    CHECK(cruise >= 980, "cruise samples %ld", cruise);
    free(data);
    /* Everything is read: one byte more is refused. */
    CHECK(NMC_GetCollectData(devHandle, 1, one) == RTN_ARG_RANGE, "read past the end");

    OK(NMC_ClearCollectSts(devHandle));
    OK(NMC_GetCollectSts(devHandle, &cltSts, &dataLen));
    CHECK(cltSts == 0 && dataLen == 0, "cleared %#x %ld", cltSts, dataLen);

    /* A rising trigger on channel 0 (the planned position) at 15000: nothing before it. */
    cltTrig.mode = COLLECT_MODE_RISE;
    cltTrig.source1 = 0;
    cltTrig.value = 15000;
    g_cltCfg.interval = 2;
    OK(NMC_ConfigCollect(devHandle, &g_cltCfg, &cltTrig));
    OK(NMC_CollectOnOff(devHandle, 1));
    OK(NMC_GetCollectSts(devHandle, &cltSts, &dataLen));
    CHECK(cltSts == COLLECT_STS_ON && dataLen == 0, "armed %#x %ld", cltSts, dataLen);
    OK(NMC_MtMovePtpAbs(axisHandle, 1, 1, 0, 0, 10, 0, 20000));
    wait_still(axisHandle);
    OK(NMC_CollectOnOff(devHandle, 0));
    OK(NMC_GetCollectSts(devHandle, &cltSts, &dataLen));
    CHECK(cltSts & COLLECT_STS_TRIGGERED, "triggered %#x", cltSts);
    /* 5000 pulses at 10 pulse/ms every 2 ms: about 250 samples. */
    CHECK(dataLen / 16 >= 250 && dataLen / 16 < 400, "samples %ld", dataLen / 16);
    data = read_all(devHandle, dataLen);
    CHECK(data[0] >= 15000 && data[0] < 15010, "first sample %g", data[0]);
    CHECK(fabs_((data[2] - data[0]) - 20) < 1e-9, "2 ms between samples: %g", data[2] - data[0]);
    free(data);

    crd_collect(devHandle);
    printf("ok\n");
    return 0;
}
