/* The plain I/O aliases, bit inversion, timed outputs on the virtual clock, DI filters, DI edge
 * counters and the DIO mapping table (digest 001 §2.8, §3.12, §4.8). */
#include <string.h>
#include "check.h"

static HAND dev;

/* The controller clock in ms (125 µs ticks). */
static double now_ms(void) {
    unsigned long clock = 0, loop = 0;
    OK(NMC_GetClock(dev, &clock, &loop));
    return clock / 8.0;
}

/* Level changes of DO `bit` seen while polling for `ms` of controller time; its last level. */
static int transitions(short bit, double ms, short *last) {
    short b = 0, prev = -1;
    int n = 0;
    double end = now_ms() + ms;
    while (now_ms() < end) {
        OK(NMC_GetDOBit(dev, bit, &b));
        if (prev >= 0 && b != prev) n++;
        prev = b;
    }
    *last = prev;
    return n;
}

static void move_z(HAND z, long pos) {
    OK(NMC_MtMovePtpAbs(z, 0.2, 0.2, 0, 0, 20, 0, pos));
    wait_still(z);
}

int main(void) {
    HAND z = 0;
    long v = 0, w = 0;
    short b = -1, c = -1, last = -1;
    unsigned short u16 = 0;
    unsigned long counts[2] = {0, 0};
    double t0, t1;
    int n;
    TDioMappingCfg map[MAX_DIO_MAPPING], one;

    OK(NMC_DevOpen(0, &dev));
    OK(NMC_MtOpen(dev, 2, &z));
    OK(NMC_MtSetSvOn(z));

    /* GetDI / GetDO / SetDO are the group functions. */
    OK(NMC_SetDO(dev, 0x55, 0));
    OK(NMC_GetDO(dev, &v, 0));
    OK(NMC_GetDOGroup(dev, &w, 0));
    CHECK(v == 0x55 && w == 0x55, "SetDO/GetDO %#lx %#lx", v, w);
    OK(NMC_GetDI(dev, &v, 0));
    OK(NMC_GetDIGroup(dev, &w, 0));
    CHECK(v == w, "GetDI %#lx GetDIGroup %#lx", v, w);
    CHECK(NMC_GetDI(dev, &v, 2) == RTN_ARG_RANGE, "GetDI group 2 before its module");

    /* DI inversion: what is read flips, the raw level does not. */
    OK(NMC_GetDIBit(dev, 0, &b));
    OK(NMC_SetDIBitRevs(dev, 0, 1));
    OK(NMC_GetDIBitRevs(dev, 0, &c));
    CHECK(c == 1, "DI revs %d", c);
    OK(NMC_GetDIBit(dev, 0, &c));
    CHECK(c == !b, "inverted DI0 %d was %d", c, b);
    OK(NMC_GetDIGroup(dev, &v, 0));
    OK(NMC_GetDIEx(dev, DI_TYPE_GPI, 0, &w));
    CHECK((v & 1) == c && (w & 1) == c, "inverted group %#lx / Ex %#lx", v, w);
    OK(NMC_GetDIRaw(dev, DI_TYPE_GPI, 0, &w));
    CHECK((w & 1) == b, "raw DI0 %ld", w & 1);
    OK(NMC_SetDIBitRevs(dev, 0, 0));
    OK(NMC_GetDIBit(dev, 0, &c));
    CHECK(c == b, "DI0 back %d", c);
    CHECK(NMC_SetDIBitRevs(dev, 0, 2) == RTN_ARG_RANGE, "revs 2");
    CHECK(NMC_SetDIBitRevs(dev, 96, 1) == RTN_ARG_RANGE, "DI 96");

    /* DO inversion: the bit reads what was written; the terminal (module 2's) drives the opposite. */
    OK(NMC_IOModuleSetEn(dev, 2, IOMODULE_TYPE_IO64));
    OK(NMC_SetDOBit(dev, 64, 1));
    EVENTUALLY(NMC_IOModuleRdOut16Bit(dev, 2, 0, &u16), (u16 & 1) == 1);
    OK(NMC_SetDOBitRevs(dev, 64, 1));
    EVENTUALLY(NMC_IOModuleRdOut16Bit(dev, 2, 0, &u16), (u16 & 1) == 0);
    OK(NMC_GetDOBit(dev, 64, &b));
    OK(NMC_GetDOBitRevs(dev, 64, &c));
    CHECK(b == 1 && c == 1, "inverted DO64 reads %d revs %d", b, c);
    OK(NMC_SetDOBit(dev, 64, 0));
    EVENTUALLY(NMC_IOModuleRdOut16Bit(dev, 2, 0, &u16), (u16 & 1) == 1);
    OK(NMC_GetDOGroup(dev, &v, 2));
    CHECK((v & 1) == 0, "DO group 2 %#lx", v);
    OK(NMC_SetDOBitRevsEx(dev, DO_TYPE_GPDO, 2, 1, 1));
    OK(NMC_GetDOBitRevs(dev, 65, &c));
    CHECK(c == 1, "RevsEx general DO65 %d", c);
    EVENTUALLY(NMC_IOModuleRdOut16Bit(dev, 2, 0, &u16), (u16 & 2) == 2);
    OK(NMC_SetDOBitRevsEx(dev, DO_TYPE_MOTOR_ENABLE, 0, 3, 1));
    OK(NMC_GetDOBitRevsEx(dev, DO_TYPE_MOTOR_ENABLE, 0, 3, &c));
    CHECK(c == 1, "RevsEx enable axis 3 %d", c);
    OK(NMC_GetDOBitRevsEx(dev, DO_TYPE_MOTOR_CLEAR, 0, 3, &c));
    CHECK(c == 0, "RevsEx alarm clear axis 3 %d", c);
    CHECK(NMC_SetDOBitRevsEx(dev, 4, 0, 0, 1) == RTN_ARG_RANGE, "doType 4");
    CHECK(NMC_SetDOBitRevsEx(dev, DO_TYPE_MOTOR_ENABLE, 0, 4, 1) == RTN_ARG_RANGE, "axis 4");
    CHECK(NMC_GetDOBitRevsEx(dev, DO_TYPE_GPDO, 0, 32, &c) == RTN_ARG_RANGE, "bit 32");

    /* Auto reverse: 1 now, 0 after 50 ms of controller time. */
    OK(NMC_SetDOBit(dev, 5, 0));
    t0 = now_ms();
    OK(NMC_SetDOBitAutoReverse(dev, 5, 1, 50));
    EVENTUALLY(NMC_GetDOBit(dev, 5, &b), b == 1);
    EVENTUALLY(NMC_GetDOBit(dev, 5, &b), b == 0);
    t1 = now_ms();
    CHECK(t1 - t0 >= 49.0, "reversed after %f ms", t1 - t0);
    CHECK(NMC_SetDOBitAutoReverse(dev, 5, 1, 0) == RTN_ARG_RANGE, "reverseTime 0");
    CHECK(NMC_SetDOBitAutoReverse(dev, 5, 2, 10) == RTN_ARG_RANGE, "value 2");

    /* A train of 3 pulses, 150 ms high / 150 ms low from high: 6 changes, ends high (levels
     * long enough for a poller on a loaded host to see each). */
    OK(NMC_SetDOBit(dev, 6, 0));
    OK(NMC_DoBitPulseEnable(dev, 0, 6, 150000, 150000, 3, 1, 0));
    EVENTUALLY(NMC_GetDOBit(dev, 6, &b), b == 1);
    n = transitions(6, 1200, &last);
    CHECK(n == 6 && last == 1, "3 pulses: %d changes, last %d", n, last);
    /* Continuous until disabled; then it holds. */
    OK(NMC_DoBitPulseEnable(dev, 0, 7, 100000, 100000, 0, 0, 1));
    n = transitions(7, 700, &last);
    CHECK(n >= 3, "continuous train: %d changes", n);
    OK(NMC_DoBitPulseDisable(dev, 1));
    OK(NMC_GetDOBit(dev, 7, &b));
    n = transitions(7, 300, &last);
    CHECK(n == 0, "disabled train changed %d times", n);
    CHECK(NMC_DoBitPulseEnable(dev, 0, 7, 1000, 1000, 1, 0, MAX_NUM_DOBIT_PULSE) == RTN_ARG_RANGE, "ch");
    CHECK(NMC_DoBitPulseEnable(dev, 1, 7, 1000, 1000, 1, 0, 0) == RTN_ARG_RANGE, "doType 1");
    CHECK(NMC_DoBitPulseEnable(dev, 0, 7, 0, 1000, 1, 0, 0) == RTN_ARG_RANGE, "high 0");
    CHECK(NMC_DoBitPulseEnable(dev, 0, 7, 1000, 1000, -1, 0, 0) == RTN_ARG_RANGE, "count -1");
    CHECK(NMC_DoBitPulseDisable(dev, -1) == RTN_ARG_RANGE, "disable ch -1");

    /* DI filters: default 3 ms (TV74: GPI group 0 bit 0), [0, 32]. */
    OK(NMC_GetDIFilter(dev, 0, 0, 0, &c));
    CHECK(c == 3, "TV74: default filter of DI0 %d", c);
    OK(NMC_GetDIFilter(dev, 0, 0, 5, &c));
    CHECK(c == 3, "default filter %d", c);
    OK(NMC_SetDIFilter(dev, 0, 0, 5, 10));
    OK(NMC_GetDIFilter(dev, 0, 0, 5, &c));
    CHECK(c == 10, "filter %d", c);
    OK(NMC_SetDIFilter(dev, DI_TYPE_HOME, 0, 1, 0));
    OK(NMC_GetDIFilter(dev, DI_TYPE_HOME, 0, 1, &c));
    CHECK(c == 0, "home filter %d", c);
    CHECK(NMC_SetDIFilter(dev, 0, 0, 5, 33) == RTN_ARG_RANGE, "33 ms");
    CHECK(NMC_SetDIFilter(dev, 5, 0, 0, 1) == RTN_ARG_RANGE, "diType 5");
    CHECK(NMC_SetDIFilter(dev, DI_TYPE_LMTP, 0, 4, 1) == RTN_ARG_RANGE, "axis 4");

    /* Edge counters: DI15 is z's home sensor (the fixture's wiring, on while z is in [0, 2000]). */
    move_z(z, 1000);
    counts[0] = 100;
    OK(NMC_SetDiReverseCount(dev, 0, 15, counts, 1));
    OK(NMC_GetDiReverseCount(dev, 0, 15, counts, 1));
    CHECK(counts[0] == 100, "counter set %lu", counts[0]);
    move_z(z, 3000);
    move_z(z, 1000);
    OK(NMC_GetDiReverseCount(dev, 0, 14, counts, 2));
    CHECK(counts[1] == 102, "DI15 changes %lu", counts[1]);
    CHECK(NMC_GetDiReverseCount(dev, 0, 15, counts, 2) == RTN_ARG_RANGE, "index 15 + 2 > 16");
    CHECK(NMC_GetDiReverseCount(dev, 0, 0, counts, 0) == RTN_ARG_RANGE, "count 0");
    CHECK(NMC_GetDiReverseCount(dev, 5, 0, counts, 1) == RTN_ARG_RANGE, "diType 5");
    CHECK(NMC_SetDiReverseCount(dev, 0, 0, NULL, 1) == RTN_NULL_POINTER, "NULL");

    /* DIO mappings: up to 8, read back, cleared. */
    memset(&one, 0, sizeof one);
    one.enable = 1; one.pinGrp = 0; one.pinIndex = 3; one.outEnable = 1; one.newGrp = 1; one.newIndex = 7;
    OK(NMC_SetDioMapping(dev, &one));
    memset(map, 0xFF, sizeof map);
    OK(NMC_GetAllDioMapping(dev, map));
    CHECK(map[0].pinIndex == 3 && map[0].newIndex == 7 && map[1].enable == 0, "mapping %d %d %d",
          map[0].pinIndex, map[0].newIndex, map[1].enable);
    for (n = 1; n < MAX_DIO_MAPPING; n++) OK(NMC_SetDioMapping(dev, &one));
    CHECK(NMC_SetDioMapping(dev, &one) == RTN_QUEUE_FULL, "9th mapping");
    OK(NMC_ClrAllDioMapping(dev));
    OK(NMC_GetAllDioMapping(dev, map));
    CHECK(map[0].enable == 0, "cleared");

    printf("ok\n");
    return 0;
}
