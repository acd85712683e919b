/* Coordinate-system buffered I/O, stops and packs, advanced buffered I/O (digest 001 §2.7,
 * §3.11, §3.12): NMC_CrdAdvBufIoOnAfterLen / OffBeforeLen switch their output where the path
 * crosses the distance, NMC_AdvBufIoGetPulseCnt counts the pulses put out, the buffered DO
 * pulse trains start and end in path order, NMC_CrdBufStopMtn halts the path where it reaches
 * it, NMC_CrdBufSetEstopDI / NMC_CrdBufEstopDIExOnOff arm inputs that E-stop the coordinate
 * system only from their place in the buffer, NMC_CrdBufBeforeAxSyncMove moves an outside axis
 * before the path goes on, NMC_CrdBufOut writes DA channel 0 (the harness reads it), and
 * NMC_CrdBufDataPack runs the manual's example. Bad arguments get their codes. The harness
 * (tests/tests/nmc_examples.rs) forces DI3 and DI4 high before the program starts. */
#include <string.h>
#include "check.h"

static HAND dev, crd, ax[4];

static void line_at(int at, long seg, long x, long y) {
    long tgt[3];
    short sts = 0, rc;
    tgt[0] = x;
    tgt[1] = y;
    tgt[2] = 0;
    rc = NMC_CrdLineXYZEx(crd, seg, 0x7, tgt, 0, 10, 0.5, 0);
    if (rc != 0) NMC_CrdGetSts(crd, &sts);
    CHECK(rc == 0, "line %ld (source line %d) returned %d, sts %#x", seg, at, rc, sts);
}
#define line(seg, x, y) line_at(__LINE__, seg, x, y)

static long x_now(void) {
    long pos[3];
    OK(NMC_CrdGetPrfPos(crd, 3, pos));
    return pos[0];
}

static short do_bit(short bit) {
    long v = 0;
    OK(NMC_GetDOGroup(dev, &v, 0));
    return (short)((v >> bit) & 1);
}

static void start(void) {
    OK(NMC_CrdEndMtn(crd));
    OK(NMC_CrdStartMtn(crd));
}

static short wait_idle(void) {
    short sts = 0;
    long polls = 0;
    do {
        OK(NMC_CrdGetSts(crd, &sts));
        CHECK(++polls < 100000000L, "never finished, sts %#x", sts);
    } while (sts & BIT_CORD_BUSY);
    return sts;
}

/* Run to the end, checking at every poll that DO `bit` is `before` while x is short of `edge`
 * and `after` once past it: pos read before the output when it still shows `before`, after
 * it when it shows `after` (one tick travels at most 10 pulses). */
static void run_watching_to(short bit, short before, short after, long edge, int ends_after) {
    short sts = 0;
    long polls = 0, seen = 0;
    start();
    do {
        long x0 = x_now();
        short v = do_bit(bit);
        long x1 = x_now();
        if (v == before) CHECK(x0 <= edge + 10, "DO%d still %d at x %ld (edge %ld)", bit, v, x0, edge);
        if (v == after) {
            CHECK(x1 >= edge, "DO%d already %d at x %ld (edge %ld)", bit, v, x1, edge);
            seen = 1;
        }
        OK(NMC_CrdGetSts(crd, &sts));
        CHECK(!(sts & BIT_CORD_MVERR), "MVERR, sts %#x", sts);
        CHECK(++polls < 100000000L, "never finished, sts %#x", sts);
    } while (sts & BIT_CORD_BUSY);
    CHECK(seen, "DO%d never became %d", bit, after);
    if (ends_after) CHECK(do_bit(bit) == after, "DO%d ends %d", bit, do_bit(bit));
}

static void run_watching(short bit, short before, short after, long edge) {
    run_watching_to(bit, before, after, edge, 1);
}

static void clear_errors(void) {
    short i;
    for (i = 0; i < 4; i++) OK(NMC_MtClrError(ax[i]));
    OK(NMC_CrdClrError(crd));
    OK(NMC_CrdBufClr(crd));
}

int main(void) {
    TCrdConfig cfg = {0};
    TCrdPara para = {0};
    TAdvBufIoParam p, back;
    TEstopExParam ex = {0};
    long cnt = -1, pos[4], enc = 0;
    short i, sts = 0;
    unsigned char buf[1024];
    short offset = 0, cmdType;

    OK(NMC_DevOpen(0, &dev));
    for (i = 0; i < 4; i++) {
        OK(NMC_MtOpen(dev, i, &ax[i]));
        OK(NMC_MtClrError(ax[i]));
        OK(NMC_MtSetSvOn(ax[i]));
    }
    OK(NMC_CrdOpen(dev, &crd));
    cfg.axCnts = 3;
    cfg.pAxArray[0] = 0;
    cfg.pAxArray[1] = 1;
    cfg.pAxArray[2] = 2;
    cfg.pAxArray[3] = -1;
    OK(NMC_CrdConfig(crd, &cfg));
    para.orgFlag = 1;
    para.synAccMax = 50;
    para.synVelMax = 800;
    OK(NMC_CrdSetPara(crd, &para));
    clear_errors();

    /* NMC_AdvBufIoSetParam / GetParam: channel 0 level mode on DO5 (active high), channel 1
     * pulse mode on DO6, 2 ms on / 2 ms off. */
    memset(&p, 0, sizeof p);
    p.outType = 0;
    p.outGroup = 0;
    p.outIndex = 5;
    p.outSns = 1;
    p.pulseMode = 0;
    OK(NMC_AdvBufIoSetParam(dev, &p, 0));
    p.outIndex = 6;
    p.pulseMode = 1;
    p.pulseOnTime = 2000;
    p.pulseOffTime = 2000;
    OK(NMC_AdvBufIoSetParam(dev, &p, 1));
    memset(&back, 0, sizeof back);
    OK(NMC_AdvBufIoGetParam(dev, &back, 1));
    CHECK(back.outIndex == 6 && back.pulseMode == 1 && back.pulseOnTime == 2000 && back.pulseOffTime == 2000,
          "param read back %d %d %ld", back.outIndex, back.pulseMode, back.pulseOnTime);
    CHECK(NMC_AdvBufIoSetParam(dev, &p, 2) == RTN_ARG_RANGE, "ch 2");
    CHECK(NMC_AdvBufIoGetParam(dev, &back, -1) == RTN_ARG_RANGE, "ch -1");
    CHECK(NMC_AdvBufIoGetParam(dev, NULL, 0) == RTN_NULL_POINTER, "NULL param");
    p.pulseOnTime = 0;
    CHECK(NMC_AdvBufIoSetParam(dev, &p, 1) == RTN_ARG_RANGE, "pulseOnTime 0");
    p.pulseOnTime = 2000;
    p.outSns = 2;
    CHECK(NMC_AdvBufIoSetParam(dev, &p, 1) == RTN_ARG_RANGE, "outSns 2");
    p.outSns = 1;

    /* NMC_AdvBufIoOut: level now; pulses counted. */
    OK(NMC_AdvBufIoOut(dev, 1, 0));
    EVENTUALLY(NMC_GetDOGroup(dev, &cnt, 0), (cnt >> 5) & 1);
    OK(NMC_AdvBufIoOut(dev, 0, 0));
    EVENTUALLY(NMC_GetDOGroup(dev, &cnt, 0), !((cnt >> 5) & 1));
    CHECK(NMC_AdvBufIoOut(dev, 2, 0) == RTN_ARG_RANGE, "level 2");
    OK(NMC_AdvBufIoOut(dev, 4, 1));
    EVENTUALLY(NMC_AdvBufIoGetPulseCnt(dev, &cnt, 1), cnt == 4);
    CHECK(NMC_AdvBufIoGetPulseCnt(dev, NULL, 1) == RTN_NULL_POINTER, "NULL count");
    CHECK(NMC_AdvBufIoGetPulseCnt(dev, &cnt, 5) == RTN_ARG_RANGE, "count ch 5");

    /* NMC_CrdAdvBufIoOnAfterLen: DO5 on 3000 pulses into the path. */
    CHECK(NMC_CrdAdvBufIoOnAfterLen(crd, 1, -1, 0, 0) == RTN_ARG_RANGE, "outLength -1");
    CHECK(NMC_CrdAdvBufIoOnAfterLen(crd, 1, 10, 0, 2) == RTN_ARG_RANGE, "OnAfterLen ch 2");
    CHECK(NMC_CrdAdvBufIoOnAfterLen(crd, 1, 10, 0, 1) == RTN_ARG_RANGE, "pulse mode needs a count");
    OK(NMC_CrdAdvBufIoOnAfterLen(crd, 1, 3000, 0, 0));
    line(2, 10000, 0);
    run_watching(5, 0, 1, 3000);

    /* NMC_CrdAdvBufIoOffBeforeLen: DO5 off 2000 pulses before the end of the two lines. */
    CHECK(NMC_CrdAdvBufIoOffBeforeLen(crd, 3, -5, 0) == RTN_ARG_RANGE, "OffBeforeLen -5");
    line(3, 0, 0);
    start();
    wait_idle();
    OK(NMC_CrdAdvBufIoOffBeforeLen(crd, 3, 2000, 0));
    line(4, 5000, 0);
    line(5, 10000, 0);
    /* 10000 of path in two lines: off 2000 before the end, at x = 8000. */
    run_watching(5, 1, 0, 8000);

    /* Pulse mode after a length: 3 pulses on DO6 once 1000 pulses are travelled. */
    OK(NMC_AdvBufIoGetPulseCnt(dev, &cnt, 1));
    CHECK(cnt == 4, "count before %ld", cnt);
    OK(NMC_CrdAdvBufIoOnAfterLen(crd, 6, 1000, 3, 1));
    line(7, 3000, 0);
    start();
    wait_idle();
    EVENTUALLY(NMC_AdvBufIoGetPulseCnt(dev, &cnt, 1), cnt == 7);

    /* NMC_CrdBufDoBitPulseEnable / Disable: an endless 1 ms / 1 ms train on DO7 for a 50 ms
     * dwell, ended in the buffer; channel 0 of the advanced I/O counts DO7's pulses. */
    p.outIndex = 7;
    p.pulseMode = 0;
    OK(NMC_AdvBufIoSetParam(dev, &p, 0));
    CHECK(NMC_CrdBufDoBitPulseEnable(crd, 8, 1, 7, 1000, 1000, 0, 1, 0) == RTN_ARG_RANGE, "doType 1");
    CHECK(NMC_CrdBufDoBitPulseEnable(crd, 8, 0, 7, 0, 1000, 0, 1, 0) == RTN_ARG_RANGE, "high 0");
    CHECK(NMC_CrdBufDoBitPulseEnable(crd, 8, 0, 7, 1000, 1000, 0, 1, 8) == RTN_ARG_RANGE, "ch 8");
    CHECK(NMC_CrdBufDoBitPulseDisable(crd, 8, -1) == RTN_ARG_RANGE, "disable ch -1");
    line(8, 5000, 0);
    OK(NMC_CrdBufDoBitPulseEnable(crd, 9, 0, 7, 1000, 1000, 0, 1, 0));
    OK(NMC_CrdBufDelay(crd, 10, 0, 50));
    OK(NMC_CrdBufDoBitPulseDisable(crd, 11, 0));
    OK(NMC_CrdBufDelay(crd, 12, 0, 50));
    /* Low until the path reaches x = 5000 (the train's level after that is either). */
    run_watching_to(7, 0, 1, 5000, 0);
    OK(NMC_AdvBufIoGetPulseCnt(dev, &cnt, 0));
    CHECK(cnt >= 24 && cnt <= 26, "pulses in 50 ms: %ld", cnt);

    /* NMC_CrdBufOut: DA 0 to 16384 (the harness reads +5 V); PWM takes its place. */
    CHECK(NMC_CrdBufOut(crd, 13, 2, 0, 0) == RTN_ARG_RANGE, "group 2");
    CHECK(NMC_CrdBufOut(crd, 13, 0, 9, 0) == RTN_ARG_RANGE, "DA ch 9");
    CHECK(NMC_CrdBufOut(crd, 13, 0, 0, 40000) == RTN_ARG_RANGE, "DA value 40000");
    OK(NMC_CrdBufOut(crd, 13, 0, 0, 16384));
    OK(NMC_CrdBufOut(crd, 14, 1, 0, 50));
    line(15, 0, 0);
    start();
    wait_idle();

    /* NMC_CrdBufBeforeAxSyncMove: axis 3 moves 1500 before the path goes on. */
    CHECK(NMC_CrdBufBeforeAxSyncMove(crd, 16, 0, 100, 10) == RTN_ARG_RANGE, "member axis");
    CHECK(NMC_CrdBufBeforeAxSyncMove(crd, 16, 3, 100, 0) == RTN_ARG_RANGE, "vel 0");
    OK(NMC_MtGetPrfPos(ax[3], &enc));
    OK(NMC_CrdBufBeforeAxSyncMove(crd, 16, 3, 1500, 20));
    line(17, 1000, 0);
    start();
    wait_idle();
    OK(NMC_MtGetPrfPos(ax[3], pos));
    CHECK(pos[0] == enc + 1500, "axis 3 at %ld, expected %ld", pos[0], enc + 1500);
    CHECK(x_now() == 1000, "path at %ld", x_now());

    /* NMC_CrdBufStopMtn: the path halts where it reaches it, StartMtn goes on. */
    CHECK(NMC_CrdBufStopMtn(crd, 18, 2) == RTN_ARG_RANGE, "crdIdx 2");
    line(18, 4000, 0);
    OK(NMC_CrdBufStopMtn(crd, 19, -1));
    line(20, 10000, 0);
    start();
    sts = wait_idle();
    {
        long x = x_now();
        CHECK(x >= 4000 && x < 10000, "halted at %ld", x);
    }
    OK(NMC_CrdStartMtn(crd));
    wait_idle();
    CHECK(x_now() == 10000, "went on to %ld", x_now());

    /* NMC_CrdBufEstopDIExOnOff on then off: DI4 is high, nothing stops. */
    ex.axMask = 0x8;
    ex.diType = 0;
    ex.diIndex = 4;
    ex.diSense = 1;
    OK(NMC_SetEstopDIEx(dev, &ex, 1));
    CHECK(NMC_CrdBufEstopDIExOnOff(crd, 21, 1, 4) == RTN_ARG_RANGE, "group 4");
    CHECK(NMC_CrdBufEstopDIExOnOff(crd, 21, 2, 1) == RTN_ARG_RANGE, "onOff 2");
    /* A started coordinate system takes what is pushed at once: both wait behind a long line. */
    line(21, 50000, 0);
    OK(NMC_CrdBufEstopDIExOnOff(crd, 22, 1, 1));
    OK(NMC_CrdBufEstopDIExOnOff(crd, 23, 0, 1));
    line(23, 6000, 0);
    start();
    sts = wait_idle();
    {
        short a0 = 0, a3 = 0;
        OK(NMC_MtGetSts(ax[0], &a0));
        OK(NMC_MtGetSts(ax[3], &a3));
        CHECK(!(sts & BIT_CORD_MVERR) && x_now() == 6000, "disarmed: sts %#x x %ld ax0 %#x ax3 %#x", sts, x_now(), a0, a3);
    }

    /* NMC_CrdBufEstopDIExOnOff on after a line: the coordinate system E-stops there. */
    line(24, 8000, 0);
    OK(NMC_CrdBufEstopDIExOnOff(crd, 25, 1, 1));
    line(26, 20000, 0);
    start();
    sts = wait_idle();
    CHECK((sts & BIT_CORD_MVERR) && x_now() >= 8000 && x_now() < 20000, "advanced E-stop: sts %#x x %ld", sts, x_now());
    clear_errors();
    OK(NMC_ClrEstopDIEx(dev, 1));

    /* NMC_CrdBufSetEstopDI: DI3 (high) arms only from its place. */
    CHECK(NMC_CrdBufSetEstopDI(crd, 27, 3, 3, 1) == RTN_ARG_RANGE, "axis 3 is not a member");
    CHECK(NMC_CrdBufSetEstopDI(crd, 27, 0, 3, 2) == RTN_ARG_RANGE, "sense 2");
    CHECK(NMC_CrdBufSetEstopDI(crd, 27, 0, 500, 1) == RTN_ARG_RANGE, "gpiIndex 500");
    OK(NMC_CrdGetPrfPos(crd, 3, pos));
    line(27, pos[0] + 3000, 0);
    OK(NMC_CrdBufSetEstopDI(crd, 28, 0, 3, 1));
    line(29, pos[0] + 20000, 0);
    start();
    sts = wait_idle();
    CHECK((sts & BIT_CORD_MVERR) && x_now() >= pos[0] + 3000 && x_now() < pos[0] + 20000,
          "E-stop DI: sts %#x x %ld", sts, x_now());
    clear_errors();

    /* NMC_CrdBufDataPack: the manual's example (C2§7.8.2), then a DO and a delay in the pack. */
    CHECK(NMC_CrdBufDataPack(crd, NULL, 4) == RTN_NULL_POINTER, "NULL pack");
    buf[0] = 99;
    buf[1] = 0;
    CHECK(NMC_CrdBufDataPack(crd, buf, 2) == RTN_ARG_RANGE, "unknown cmdType");
    CHECK(NMC_CrdBufDataPack(crd, buf, 1001) == RTN_ARG_RANGE, "1001 bytes");
    OK(NMC_CrdGetBufAllCmdCnt(crd, &enc));
    memset(buf, 0, sizeof(buf));
    for (i = 10; i >= 0; i--) {
        TCrdBufLine crdBufLine;
        cmdType = BUF_LINE;
        memset(&crdBufLine, 0, sizeof(crdBufLine));
        crdBufLine.segNo = i + 1;
        crdBufLine.tgPos[0] = (i + 1) * 2000;
        crdBufLine.tgPos[1] = (i + 1) * 1000;
        crdBufLine.tgPos[2] = 0;
        crdBufLine.endVel = 4;
        crdBufLine.vel = 10;
        crdBufLine.synAcc = 1;
        crdBufLine.mask = 0x3;
        crdBufLine.lookaheadDis = 0;
        if (offset + 2 + (short)sizeof(TCrdBufLine) > 1000) {
            OK(NMC_CrdBufDataPack(crd, buf, offset));
            memset(buf, 0, sizeof(buf));
            offset = 0;
        }
        memcpy(&buf[offset], &cmdType, sizeof(short));
        offset += sizeof(short);
        memcpy(&buf[offset], &crdBufLine, sizeof(TCrdBufLine));
        offset += sizeof(TCrdBufLine);
    }
    {
        TCrdBufDo d;
        memset(&d, 0, sizeof d);
        cmdType = BUF_DO;
        d.segNo = 30;
        d.doType = 3;
        d.ch = 9;
        d.value = 1;
        memcpy(&buf[offset], &cmdType, sizeof(short));
        offset += sizeof(short);
        memcpy(&buf[offset], &d, sizeof d);
        offset += sizeof d;
    }
    if (offset > 0) OK(NMC_CrdBufDataPack(crd, buf, offset));
    /* A bad entry after good ones: the whole pack is refused and nothing of it is kept. */
    {
        TCrdBufDelay bad;
        long before = 0, after = 0;
        OK(NMC_CrdGetBufAllCmdCnt(crd, &before));
        offset = 0;
        memset(&bad, 0, sizeof bad);
        cmdType = BUF_DELAY;
        bad.segNo = 31;
        bad.scale = 0;
        bad.count = 5;
        memcpy(&buf[offset], &cmdType, sizeof(short));
        offset += sizeof(short);
        memcpy(&buf[offset], &bad, sizeof bad);
        offset += sizeof bad;
        bad.scale = 7;
        memcpy(&buf[offset], &cmdType, sizeof(short));
        offset += sizeof(short);
        memcpy(&buf[offset], &bad, sizeof bad);
        offset += sizeof bad;
        CHECK(NMC_CrdBufDataPack(crd, buf, offset) == RTN_ARG_RANGE, "scale 7 in a pack");
        OK(NMC_CrdGetBufAllCmdCnt(crd, &after));
        CHECK(after == before, "a refused pack kept %ld commands", after - before);
    }
    OK(NMC_CrdGetBufAllCmdCnt(crd, &cnt));
    CHECK(cnt - enc == 12, "pack pushed %ld commands", cnt - enc);
    start();
    wait_idle();
    OK(NMC_CrdGetPrfPos(crd, 3, pos));
    CHECK(pos[0] == 2000 && pos[1] == 1000, "pack ends at (%ld,%ld)", pos[0], pos[1]);
    CHECK(do_bit(9) == 1, "the pack's DO");

    printf("ok\n");
    return 0;
}
