/* Test vectors of digest 001 §6 on the axis inputs, which the harness (tests/tests/nmc_examples.rs)
 * forces through the control API: for each line "post {json}" this program prints, it posts
 * the JSON to /api/v1/commands and answers "done". A forced switch input is its electrical
 * level (the fixture's switches are wired plain, high when actuated).
 * TV40 (NMC_MtGetMotionIO bits: the inputs' live levels), TV21 (a low-active + limit: stop,
 * same direction refused, reverse allowed, cleared once released), TV23 (a high-active drive
 * alarm), TV24 (following error: actions 0 flag only, 2 stop, 1 servo off), TV26
 * (NMC_MtClrStsByBits clears only the masked latched bits). */
#include <string.h>
#include "check.h"

static void post(const char *json) {
    char line[64];
    printf("post %s\n", json);
    fflush(stdout);
    if (!fgets(line, sizeof line, stdin)) exit(2);
}

/* Force `input` of `axis` to `value` ("true", "false"; "null" gives it back to the switches). */
static void force(int axis, const char *input, const char *value) {
    char json[160];
    snprintf(json, sizeof json, "{\"type\":\"force_input\",\"axis\":%d,\"input\":\"%s\",\"value\":%s}",
             axis, input, value);
    post(json);
}

/* |prf − enc| of `axis` grows by `amount` pulses ("null" removes it). */
static void following_error(int axis, const char *amount) {
    char json[160];
    snprintf(json, sizeof json, "{\"type\":\"inject_following_error\",\"axis\":%d,\"amount\":%s}",
             axis, amount);
    post(json);
}

/* A move the axis must not make: refused, or accepted and never moving. */
static void no_motion(HAND ax, short rc, const char *what) {
    long before = 0, after = 0;
    OK(NMC_MtGetPrfPos(ax, &before));
    if (rc == 0) {
        wait_still(ax);
        OK(NMC_MtGetPrfPos(ax, &after));
        CHECK(after == before, "%s: moved from %ld to %ld", what, before, after);
    }
}

/* Poll until the axis has been moving for a while: its planned position passes `beyond`. */
static void wait_past(HAND ax, long beyond) {
    long pos = 0, polls = 0;
    short sts = 0;
    do {
        OK(NMC_MtGetPrfPos(ax, &pos));
        OK(NMC_MtGetSts(ax, &sts));
        CHECK(sts & BIT_AXIS_BUSY, "stopped at %ld before %ld: sts %#x", pos, beyond, sts);
        CHECK(++polls < 10000000L, "never past %ld: at %ld", beyond, pos);
    } while (beyond >= 0 ? pos <= beyond : pos >= beyond);
}

/* NMC_MtClrError until it succeeds (the engine has seen every cause go). */
static void clear_errors(HAND ax) {
    long polls = 0;
    while (NMC_MtClrError(ax) != 0) CHECK(++polls < 1000000L, "errors never cleared");
}

/* A released input: its motion-I/O bit `io_bit` drops at once (the live level), while the
 * status bit `sts_bit` it latched stays until NMC_MtClrError. */
static void released(HAND ax, long io_bit, short sts_bit) {
    long io = 0;
    short sts = 0;
    EVENTUALLY(NMC_MtGetMotionIO(ax, &io), !(io & io_bit));
    OK(NMC_MtGetSts(ax, &sts));
    CHECK((sts & sts_bit) == sts_bit, "TV40: latched %#x gone with the input: %#x", sts_bit, sts);
    clear_errors(ax);
}

int main(void) {
    HAND dev = 0, ax0 = 0, ax1 = 0, ax2 = 0, ax3 = 0;
    long io = 0, pos = 0, pos2 = 0;
    short sts = 0, rc = 0;

    OK(NMC_DevOpen(0, &dev));
    OK(NMC_MtOpen(dev, 0, &ax0));
    OK(NMC_MtOpen(dev, 1, &ax1));
    OK(NMC_MtOpen(dev, 2, &ax2));
    OK(NMC_MtOpen(dev, 3, &ax3));

    /* TV40 on axis 0 (fresh: limits and home high-active): each input active sets its bit. */
    force(0, "home", "false");
    EVENTUALLY(NMC_MtGetMotionIO(ax0, &io), !(io & BIT_AXMTIO_HOME));
    force(0, "home", "true");
    EVENTUALLY(NMC_MtGetMotionIO(ax0, &io), io & BIT_AXMTIO_HOME);
    CHECK(!(io & (BIT_AXMTIO_LMTP | BIT_AXMTIO_LMTN | BIT_AXMTIO_ALM)), "TV40: home only: %#lx", io);
    force(0, "limit_pos", "true");
    EVENTUALLY(NMC_MtGetMotionIO(ax0, &io), io & BIT_AXMTIO_LMTP);
    CHECK(!(io & BIT_AXMTIO_LMTN), "TV40: + limit shows as - too: %#lx", io);
    /* The bits are the inputs' levels, not the status word's latched limits (TV40). */
    force(0, "limit_pos", "null");
    released(ax0, BIT_AXMTIO_LMTP, BIT_AXIS_LMTP);
    force(0, "limit_neg", "true");
    EVENTUALLY(NMC_MtGetMotionIO(ax0, &io), io & BIT_AXMTIO_LMTN);
    CHECK(!(io & BIT_AXMTIO_LMTP), "TV40: - limit shows as + too: %#lx", io);
    force(0, "limit_neg", "null");
    released(ax0, BIT_AXMTIO_LMTN, BIT_AXIS_LMTN);
    OK(NMC_MtSetAlarmCfg(ax0, 1, 1));
    force(0, "drive_alarm", "true");
    EVENTUALLY(NMC_MtGetMotionIO(ax0, &io), io & BIT_AXMTIO_ALM);
    force(0, "drive_alarm", "null");
    released(ax0, BIT_AXMTIO_ALM, BIT_AXIS_ALM);
    force(0, "home", "null");

    /* TV26 on axis 0: ESTP and a latched LMTP (the + limit pressed and released): the mask
     * 0x1000 clears ESTP and leaves LMTP; LMTP's own bit then clears it. */
    force(0, "limit_pos", "true");
    EVENTUALLY(NMC_MtGetSts(ax0, &sts), sts & BIT_AXIS_LMTP);
    force(0, "limit_pos", "null");
    EVENTUALLY(NMC_MtGetMotionIO(ax0, &io), !(io & BIT_AXMTIO_LMTP));
    OK(NMC_MtEstp(ax0));
    OK(NMC_MtGetSts(ax0, &sts));
    CHECK((sts & (BIT_AXIS_ESTP | BIT_AXIS_LMTP)) == (BIT_AXIS_ESTP | BIT_AXIS_LMTP),
          "TV26: before: %#x", sts);
    OK(NMC_MtClrStsByBits(ax0, 0x1000));
    OK(NMC_MtGetSts(ax0, &sts));
    CHECK(!(sts & BIT_AXIS_ESTP), "TV26: ESTP stays: %#x", sts);
    CHECK(sts & BIT_AXIS_LMTP, "TV26: LMTP cleared by the ESTP mask: %#x", sts);
    OK(NMC_MtClrStsByBits(ax0, BIT_AXIS_LMTP));
    OK(NMC_MtGetSts(ax0, &sts));
    CHECK(!(sts & BIT_AXIS_LMTP), "TV26: LMTP stays: %#x", sts);

    /* TV21 on axis 2, limits enabled low-active: both inputs held high (inactive) first. */
    force(2, "limit_pos", "true");
    force(2, "limit_neg", "true");
    OK(NMC_MtSetLmtCfg(ax2, 1, 1, 0, 0));
    /* Either sense latched a limit on the way: clear once the forced levels are seen. */
    for (io = 0;; io++) {
        rc = NMC_MtClrError(ax2);
        OK(NMC_MtGetSts(ax2, &sts));
        if (rc == 0 && !(sts & (BIT_AXIS_LMTP | BIT_AXIS_LMTN))) break;
        CHECK(io < 1000000L, "TV21: limits before: rc %d sts %#x", rc, sts);
    }
    OK(NMC_MtSetSvOn(ax2));
    OK(NMC_MtMoveJog(ax2, 0.5, 0.5, 5, 0, 0));
    wait_past(ax2, 100);
    force(2, "limit_pos", "false"); /* the + limit input goes low: active */
    sts = wait_still(ax2);
    CHECK(sts & BIT_AXIS_LMTP, "TV21: no LMTP: %#x", sts);
    OK(NMC_MtGetPrfPos(ax2, &pos));
    rc = NMC_MtMoveJog(ax2, 0.5, 0.5, 5, 0, 0);
    no_motion(ax2, rc, "TV21: jog + into the limit");

    /* TV21 continued: jog − is allowed and moves off the limit, which releases; then
     * NMC_MtClrError clears LMTP. */
    OK(NMC_MtMoveJog(ax2, 0.5, 0.5, -5, 0, 0));
    wait_past(ax2, pos - 100);
    force(2, "limit_pos", "true");
    OK(NMC_MtStop(ax2));
    wait_still(ax2);
    OK(NMC_MtGetPrfPos(ax2, &pos2));
    CHECK(pos2 < pos, "TV21: jog - from %ld ended at %ld", pos, pos2);
    OK(NMC_MtClrError(ax2));
    OK(NMC_MtGetSts(ax2, &sts));
    CHECK(!(sts & BIT_AXIS_LMTP), "TV21: LMTP after ClrError: %#x", sts);
    OK(NMC_MtMoveJog(ax2, 0.5, 0.5, 5, 0, 0));
    wait_past(ax2, pos2 + 100);
    OK(NMC_MtStop(ax2));
    wait_still(ax2);

    /* TV23 on axis 1: alarm enabled high-active, input high: ALM, motion refused until the
     * input clears and NMC_MtClrError. */
    OK(NMC_MtSetSvOn(ax1));
    OK(NMC_MtSetAlarmCfg(ax1, 1, 1));
    force(1, "drive_alarm", "true");
    EVENTUALLY(NMC_MtGetSts(ax1, &sts), sts & BIT_AXIS_ALM);
    rc = NMC_MtMovePtpRel(ax1, 1, 1, 0, 0, 10, 0, 1000);
    no_motion(ax1, rc, "TV23: move with the alarm");
    CHECK(NMC_MtClrError(ax1) != 0, "TV23: ClrError with the input high");
    OK(NMC_MtGetSts(ax1, &sts));
    CHECK(sts & BIT_AXIS_ALM, "TV23: ALM cleared with the input high: %#x", sts);
    force(1, "drive_alarm", "false");
    rc = NMC_MtMovePtpRel(ax1, 1, 1, 0, 0, 10, 0, 1000);
    no_motion(ax1, rc, "TV23: move before ClrError");
    /* NMC_MtClrError succeeds once the engine has seen the input clear. */
    for (io = 0; NMC_MtClrError(ax1) != 0; io++) CHECK(io < 1000000L, "TV23: never cleared");
    OK(NMC_MtGetSts(ax1, &sts));
    CHECK(!(sts & BIT_AXIS_ALM), "TV23: ALM after ClrError: %#x", sts);
    OK(NMC_MtSetSvOn(ax1));
    OK(NMC_MtGetPrfPos(ax1, &pos));
    OK(NMC_MtMovePtpRel(ax1, 1, 1, 0, 0, 10, 0, 1000));
    wait_still(ax1);
    OK(NMC_MtGetPrfPos(ax1, &pos2));
    CHECK(pos2 == pos + 1000, "TV23: move after clearing from %ld to %ld", pos, pos2);

    /* TV24 on axis 3: limit 100, |prf − enc| = 150 while jogging sets POSERR; what follows is
     * the action's alone. Action 0: the jog goes on, servo on. */
    OK(NMC_MtSetSvOn(ax3));
    OK(NMC_MtSetPosErrLmt(ax3, 100));
    OK(NMC_MtSetPosErrAction(ax3, 0));
    OK(NMC_MtMoveJog(ax3, 0.5, 0.5, 2, 0, 0));
    wait_past(ax3, 50);
    OK(NMC_MtGetSts(ax3, &sts));
    CHECK(!(sts & BIT_AXIS_POSERR), "TV24: POSERR before: %#x", sts);
    following_error(3, "150");
    EVENTUALLY(NMC_MtGetSts(ax3, &sts), sts & BIT_AXIS_POSERR);
    OK(NMC_MtGetPrfPos(ax3, &pos));
    wait_past(ax3, pos + 200);
    OK(NMC_MtGetSts(ax3, &sts));
    CHECK(sts & BIT_AXIS_SVON, "TV24 action 0: servo off: %#x", sts);
    following_error(3, "null");
    OK(NMC_MtStop(ax3));
    wait_still(ax3);
    clear_errors(ax3);

    /* Action 2: the axis stops and stays stopped, servo on. */
    OK(NMC_MtSetPosErrAction(ax3, 2));
    OK(NMC_MtMoveJog(ax3, 0.5, 0.5, 2, 0, 0));
    OK(NMC_MtGetPrfPos(ax3, &pos));
    wait_past(ax3, pos + 50);
    following_error(3, "150");
    EVENTUALLY(NMC_MtGetSts(ax3, &sts), sts & BIT_AXIS_POSERR);
    sts = wait_still(ax3);
    CHECK(sts & BIT_AXIS_SVON, "TV24 action 2: servo off: %#x", sts);
    OK(NMC_MtGetPrfPos(ax3, &pos));
    OK(NMC_MtGetSts(ax3, &sts));
    OK(NMC_MtGetPrfPos(ax3, &pos2));
    CHECK(pos2 == pos && !(sts & BIT_AXIS_BUSY), "TV24 action 2: moving %ld -> %ld, sts %#x",
          pos, pos2, sts);
    following_error(3, "null");
    clear_errors(ax3);

    /* Action 1: servo off. */
    OK(NMC_MtSetPosErrAction(ax3, 1));
    OK(NMC_MtMoveJog(ax3, 0.5, 0.5, 2, 0, 0));
    OK(NMC_MtGetPrfPos(ax3, &pos));
    wait_past(ax3, pos + 50);
    following_error(3, "150");
    EVENTUALLY(NMC_MtGetSts(ax3, &sts), !(sts & BIT_AXIS_SVON));
    CHECK(sts & BIT_AXIS_POSERR, "TV24 action 1: %#x", sts);
    following_error(3, "null");
    printf("ok\n");
    return 0;
}
