/* Full circles through three points (NMC_CrdCirclePPP in XY, NMC_CrdCircle3DEx in space) and
 * the pushed path length (NMC_CrdSetBufLengthFlag / NMC_CrdGetBufLength), digest 001 §2.7, on
 * the GCN400 fixture on a scaled clock. */
#include "crd_open.h"

static HAND devHandle, crdHandle, ax[4];

static double dabs(double v) { return v < 0 ? -v : v; }

/* Extremes of X, Y and Z while the coordinate system runs, the longest chord between two
 * polls, and how many polled points were on the circle about `center` of radius `radius`. */
typedef struct {
    long lo[3], hi[3], last[3];
    double max_step2; /* the longest chord between two polls, squared */
    const long *center;
    double radius;
    long off_circle;
} Box;

static void widen(Box *box, const long *pos, int first) {
    double step = 0, d2 = 0, r = box->radius;
    long k;
    for (k = 0; k < 3; k++) {
        double dk = (double)(pos[k] - box->last[k]), ck = (double)(pos[k] - box->center[k]);
        step += dk * dk;
        d2 += ck * ck;
        if (pos[k] < box->lo[k]) box->lo[k] = pos[k];
        if (pos[k] > box->hi[k]) box->hi[k] = pos[k];
        box->last[k] = pos[k];
    }
    if (!first && step > box->max_step2) box->max_step2 = step;
    /* Off the circle by more than 30 pulses, and not on the lead-in line along y = z = 0
     * (radius 0: no circle to check). */
    if (r > 0 && (d2 < (r - 30) * (r - 30) || d2 > (r + 30) * (r + 30)) && !(pos[1] == 0 && pos[2] == 0 && pos[0] <= 1000))
        box->off_circle++;
}

/* The start and end positions are in the box whatever the polling saw: on a loaded host the
 * first poll may come after the path has left its start, and polls may be far apart. */
static void run(Box *box, const long *center, double radius) {
    short sts = 0;
    long pos[3], k;
    for (k = 0; k < 3; k++) {
        box->lo[k] = 2147483647L;
        box->hi[k] = -2147483647L;
    }
    box->max_step2 = 0;
    box->center = center;
    box->radius = radius;
    box->off_circle = 0;
    OK(NMC_CrdGetPrfPos(crdHandle, 3, pos));
    widen(box, pos, 1);
    OK(NMC_CrdEndMtn(crdHandle));
    OK(NMC_CrdStartMtn(crdHandle));
    do {
        OK(NMC_CrdGetSts(crdHandle, &sts));
        OK(NMC_CrdGetPrfPos(crdHandle, 3, pos));
        widen(box, pos, 0);
        CHECK(!(sts & BIT_CORD_MVERR), "MVERR at (%ld,%ld,%ld)", pos[0], pos[1], pos[2]);
    } while (sts & BIT_CORD_BUSY);
    OK(NMC_CrdGetPrfPos(crdHandle, 3, pos));
    widen(box, pos, 0);
    CHECK(box->off_circle == 0, "%ld polled points off the circle", box->off_circle);
}

static void at(long x, long y, long z) {
    long pos[3];
    OK(NMC_CrdGetPrfPos(crdHandle, 3, pos));
    CHECK(pos[0] == x && pos[1] == y && pos[2] == z, "at (%ld,%ld,%ld), expected (%ld,%ld,%ld)", pos[0], pos[1],
          pos[2], x, y, z);
}

/* lo/hi of coordinate k within 30 pulses of the expected values, plus what polls a chord c
 * apart can miss of a circle of radius R at its extreme: R(1 − cos(c/2R)) ≤ c²/8R. */
static void spans(const Box *b, int k, long lo, long hi) {
    long tol = 30 + (long)(b->max_step2 / (8 * b->radius));
    CHECK(labs(b->lo[k] - lo) <= tol && labs(b->hi[k] - hi) <= tol,
          "coordinate %d in [%ld, %ld], expected [%ld, %ld] within %ld", k, b->lo[k], b->hi[k], lo, hi, tol);
}

int main(void) {
    long st[2] = {1000, 0}, mid[2] = {2000, 1000}, tg[2] = {3000, 0}, line[2] = {5000, 0};
    long center2[3] = {2000, 0, 0}, center3[3] = {1000, 0, 1000};
    long origin[3] = {0, 0, 0}, mid3[3] = {2000, 0, 1000}, tg3[3] = {1000, 0, 2000}, on_line[3] = {2000, 0, 0}, end3[3] = {3000, 0, 0};
    double len = -1, circle = 2 * 3.14159265358979 * 1000;
    Box box;

    OK(NMC_DevOpen(0, &devHandle));
    servo_on_axes(devHandle, 4, ax);
    crdHandle = open_crd(devHandle, 3, 1);
    /* From the origin. */
    OK(NMC_CrdLineXYZEx(crdHandle, 0, 0x7, origin, 0, 50, 1, 0));
    run(&box, origin, 0);
    at(0, 0, 0);
    OK(NMC_CrdBufClr(crdHandle));

    /* Bad arguments. */
    CHECK(NMC_CrdCirclePPP(crdHandle, 1, 1, st, mid, tg, 0, 10, 1, 0) == RTN_ARG_RANGE, "planeIdx 1 (YZ)");
    CHECK(NMC_CrdCirclePPP(crdHandle, 1, 0, st, line, tg, 0, 10, 1, 0) == RTN_ARG_RANGE, "three points on a line");
    CHECK(NMC_CrdCirclePPP(crdHandle, 1, 0, NULL, mid, tg, 0, 10, 1, 0) == RTN_NULL_POINTER, "NULL pStPos");
    CHECK(NMC_CrdCirclePPP(crdHandle, 1, 0, st, mid, tg, 0, 0, 1, 0) == RTN_ARG_RANGE, "vel 0");
    CHECK(NMC_CrdCircle3DEx(crdHandle, 1, on_line, end3, 0, 10, 1, 0) == RTN_ARG_RANGE, "3-D: points on a line");
    CHECK(NMC_CrdCircle3DEx(crdHandle, 1, NULL, tg3, 0, 10, 1, 0) == RTN_NULL_POINTER, "3-D: NULL pMidPos");
    CHECK(NMC_CrdSetBufLengthFlag(crdHandle, 2) == RTN_ARG_RANGE, "flag 2");
    CHECK(NMC_CrdGetBufLength(crdHandle, NULL) == RTN_NULL_POINTER, "NULL pLen");
    OK(NMC_CrdBufClr(crdHandle));

    /* Flag 0 (the default): nothing is summed. */
    OK(NMC_CrdCirclePPP(crdHandle, 1, 0, st, mid, tg, 0, 10, 1, 0));
    OK(NMC_CrdGetBufLength(crdHandle, &len));
    CHECK(len == 0, "flag 0: length %f", len);
    OK(NMC_CrdBufClr(crdHandle));

    /* PPP: a line (0,0) → (1000,0), then the clockwise circle about (2000,0) through (2000,1000)
     * and (3000,0) back to (1000,0): 1000 + 2π·1000 pulses. */
    OK(NMC_CrdSetBufLengthFlag(crdHandle, 1));
    OK(NMC_CrdCirclePPP(crdHandle, 1, 0, st, mid, tg, 0, 10, 1, 0));
    OK(NMC_CrdGetBufLength(crdHandle, &len));
    CHECK(dabs(len - (1000 + circle)) < 1, "PPP length %f", len);
    run(&box, center2, 1000);
    at(1000, 0, 0);
    spans(&box, 0, 0, 3000);
    spans(&box, 1, -1000, 1000);
    spans(&box, 2, 0, 0);

    /* 3-D: from (1000,0,0) through (2000,0,1000) and (1000,0,2000): the circle about (1000,0,1000)
     * in the XZ plane. */
    OK(NMC_CrdBufClr(crdHandle));
    OK(NMC_CrdGetBufLength(crdHandle, &len));
    CHECK(len == 0, "after BufClr: length %f", len);
    OK(NMC_CrdCircle3DEx(crdHandle, 2, mid3, tg3, 0, 10, 1, 0));
    OK(NMC_CrdGetBufLength(crdHandle, &len));
    CHECK(dabs(len - circle) < 1, "3-D length %f", len);
    run(&box, center3, 1000);
    at(1000, 0, 0);
    spans(&box, 0, 0, 2000);
    spans(&box, 1, 0, 0);
    spans(&box, 2, 0, 2000);
    OK(NMC_CrdSetBufLengthFlag(crdHandle, 0));

    OK(NMC_CrdClose(&crdHandle));
    printf("ok\n");
    return 0;
}
