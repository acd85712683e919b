/* The polar machine on a coordinate system's own X and Y axes (NMC_CrdSetTransPolar, digest 001
 * C3§10.5 "极坐标转换: 用户数据是按照直角坐标描述, 实际机械机构是一个旋转轴和一个进给轴"): axis 0
 * turns (10000 pulses a turn), axis 1 moves along the radius, the crd motions are Cartesian.
 * While a line and an arc run, every polled (r cos θ, r sin θ) of the two axes lies on the
 * programmed geometry; the ends are atan2 and hypot of the programmed points, the manual's
 * (5000, 5000) → 45°, √2·5000 included; a path through the pole is refused. GCN400 fixture,
 * scaled clock. */
#include <math.h>
#include <string.h>
#include "crd_open.h"

#define PI_ 3.14159265358979
#define EQUIV (2 * PI_ / 10000)

static HAND devHandle, crdHandle, ax[2];

static void near(short k, long want, long tol, const char *what) {
    long p = 0;
    OK(NMC_MtGetPrfPos(ax[k], &p));
    CHECK(labs(p - want) <= tol, "%s: axis %d at %ld, expected %ld", what, k, p, want);
}

/* The two axes' point (one snapshot: NMC_CrdGetAxisPos), and how far a whole pulse of each
 * can put it from the exact one. */
static double machine_point(double *x, double *y) {
    long m[2];
    double theta, r;
    OK(NMC_CrdGetAxisPos(crdHandle, 2, m));
    theta = m[0] * EQUIV;
    r = (double)m[1];
    *x = r * cos(theta);
    *y = r * sin(theta);
    return r * EQUIV + 1.0;
}

/* Start what was pushed; until the coordinate system is still, `on_path` of every polled
 * point must be within its tolerance. */
static void run_checked(double (*off_path)(double, double), const char *what) {
    short sts = 0;
    long polls = 0;
    double x, y, tol, worst = 0;
    OK(NMC_CrdEndMtn(crdHandle));
    OK(NMC_CrdStartMtn(crdHandle));
    do {
        tol = machine_point(&x, &y);
        CHECK(off_path(x, y) <= tol, "%s: (%.1f, %.1f) is %.2f off the path", what, x, y, off_path(x, y));
        if (off_path(x, y) > worst) worst = off_path(x, y);
        polls++;
        OK(NMC_CrdGetSts(crdHandle, &sts));
        CHECK(!(sts & BIT_CORD_MVERR), "MVERR, sts %#x", sts);
    } while (sts & BIT_CORD_BUSY);
    CHECK(polls > 3, "%s: only %ld polls while moving", what, polls);
    printf("%s: %ld polls, worst %.2f pulses off\n", what, polls, worst);
}

/* The line (5000, 5000) → (12000, −3000). */
static double off_line(double x, double y) {
    double dx = 7000, dy = -8000;
    return fabs((x - 5000) * dy - (y - 5000) * dx) / hypot(dx, dy);
}

/* The circle about (10000, 0) through (12000, −3000) and (13000, 2000). */
static double off_arc(double x, double y) {
    return fabs(hypot(x - 10000, y) - hypot(2000, 3000));
}

int main(void) {
    TCrdConfig cfg;
    long p[4] = {0, 0, 0, 0}, center[2], user[2];
    short rc;

    OK(NMC_DevOpen(0, &devHandle));
    servo_on_axes(devHandle, 2, ax);
    OK(NMC_CrdOpen(devHandle, &crdHandle));
    memset(&cfg, 0, sizeof cfg);
    cfg.axCnts = 2;
    cfg.pAxArray[0] = 0;
    cfg.pAxArray[1] = 1;
    cfg.pAxArray[2] = cfg.pAxArray[3] = -1;
    OK(NMC_CrdConfig(crdHandle, &cfg));
    OK(NMC_CrdClrError(crdHandle));
    OK(NMC_CrdBufClr(crdHandle));

    OK(NMC_CrdSetTransPolar(crdHandle, 0, 1, EQUIV));
    /* The manual's case: the rotary axis to 45° (1250 pulses), the feed axis to √2·5000. */
    OK(NMC_CrdRunToPolarPos(crdHandle, 5000, 5000, 10, 10));
    crd_still(crdHandle);
    near(0, 1250, 0, "45°");
    near(1, 7071, 0, "√2·5000");
    OK(NMC_CrdGetPrfPos(crdHandle, 2, user));
    CHECK(labs(user[0] - 5000) <= 2 && labs(user[1] - 5000) <= 2, "program point (%ld, %ld)", user[0], user[1]);

    /* A Cartesian line across θ = 0: the rotary axis goes to −14.04° (−390 pulses), not a
     * turn further. */
    p[0] = 12000;
    p[1] = -3000;
    OK(NMC_CrdLineXYZEx(crdHandle, 1, 0x3, p, 0, 20, 0.5, 0));
    run_checked(off_line, "line");
    near(0, (long)lround(atan2(-3000.0, 12000.0) / EQUIV), 0, "θ of (12000, −3000)");
    near(1, (long)lround(hypot(12000.0, 3000.0)), 0, "r of (12000, −3000)");
    OK(NMC_CrdGetPrfPos(crdHandle, 2, user));
    CHECK(labs(user[0] - 12000) <= 2 && labs(user[1] + 3000) <= 2, "program point (%ld, %ld)", user[0], user[1]);
    OK(NMC_CrdGetAxisPos(crdHandle, 2, user));
    CHECK(user[0] == -390 && user[1] == 12369, "machine point (%ld, %ld)", user[0], user[1]);

    /* A counter-clockwise quarter arc about (10000, 0) to (13000, 2000). */
    p[0] = 13000;
    p[1] = 2000;
    center[0] = -2000;
    center[1] = 3000;
    OK(NMC_CrdArcCenterEx(crdHandle, 2, p, center, 1, 0, 20, 0.5, 0));
    run_checked(off_arc, "arc");
    near(0, (long)lround(atan2(2000.0, 13000.0) / EQUIV), 0, "θ of (13000, 2000)");
    near(1, (long)lround(hypot(13000.0, 2000.0)), 0, "r of (13000, 2000)");

    /* Through the pole: the rotary axis would turn half a turn at once. */
    p[0] = -13000;
    p[1] = -2000;
    rc = NMC_CrdLineXYZEx(crdHandle, 3, 0x3, p, 0, 20, 0.5, 0);
    if (rc == 0) rc = NMC_CrdStartMtn(crdHandle);
    CHECK(rc == RTN_INVALID_ARGUMENT, "a line through the pole: %d", rc);
    crd_still(crdHandle);
    near(0, 243, 0, "θ stays");

    /* Changed only with nothing pushed: those segments were given in the other coordinates. */
    OK(NMC_CrdBufClr(crdHandle));
    OK(NMC_CrdLineXYZEx(crdHandle, 4, 0x3, p, 0, 20, 0.5, 0));
    rc = NMC_CrdDelTransPolar(crdHandle);
    CHECK(rc == RTN_GROUP_STATE, "DelTransPolar with a segment pushed: %d", rc);
    /* Deleted: the members are X and Y again. */
    OK(NMC_CrdBufClr(crdHandle));
    OK(NMC_CrdDelTransPolar(crdHandle));
    p[0] = 1000;
    p[1] = 2000;
    OK(NMC_CrdLineXYZEx(crdHandle, 5, 0x3, p, 0, 20, 0.5, 0));
    OK(NMC_CrdEndMtn(crdHandle));
    OK(NMC_CrdStartMtn(crdHandle));
    crd_still(crdHandle);
    near(0, 1000, 0, "X after DelTransPolar");
    near(1, 2000, 0, "Y after DelTransPolar");
    OK(NMC_CrdClose(&crdHandle));
    printf("ok\n");
    return 0;
}
