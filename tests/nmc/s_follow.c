/* S-FOLLOW (digest 001 §5, C3§7.3) with TV59: master axis 0 jogs at 50 pulse/ms; slave axis 1
 * follows FIFO 0 ((20000,10000), (40000,30000), (60000,40000), for ever) once the master
 * crosses 50000 moving positive: still before, then 40000 of slave per 60000 of master. Both
 * positions are read from one packed status (one snapshot). FIFO 1 holds the same points and
 * the Follow switches to it after the first pass; the getters and bad arguments besides. */
#include "check.h"

/* The packed status once the master has passed `master`: the slave's position. */
static long slave_at(HAND first, long master, long *masterSeen) {
    TAxisStsPack12Ex p;
    long polls = 0;
    do {
        OK(NMC_MtGetStsPack12Ex(first, &p));
        CHECK(++polls < 100000000L, "master never reached %ld", master);
        if (p.mtPrfPos[0] < 50000 - 500) {
            CHECK(p.mtPrfPos[1] == 0, "slave moved to %ld with the master at %ld", p.mtPrfPos[1],
                  p.mtPrfPos[0]);
        }
    } while (p.mtPrfPos[0] < master);
    *masterSeen = p.mtPrfPos[0];
    return p.mtPrfPos[1];
}

int main(void) {
    HAND dev = 0, ax0 = 0, ax1 = 0;
    short no = 0, type = 0, ev = 0, dir = 0, space = 0, mode = 0, bad[1] = {9};
    long pos = 0, loops = 0, seen = 0, slave = 0;
    long masterPos[3] = {20000, 40000, 60000};
    double slavePos[3] = {10000, 30000, 40000};
    int i, f;

    OK(NMC_DevOpen(0, &dev));
    OK(NMC_MtOpen(dev, 0, &ax0));
    OK(NMC_MtOpen(dev, 1, &ax1));
    OK(NMC_MtSetSvOn(ax0));
    OK(NMC_MtSetSvOn(ax1));
    OK(NMC_MtGetPrfPos(ax0, &pos));
    CHECK(pos == 0, "master starts at %ld", pos);

    OK(NMC_MtSetPrfMode(ax1, MT_FOLLOW_PRF_MODE));
    OK(NMC_MtFollowGetMaster(ax1, &no, &type));
    CHECK(no == -1 && type == PROFILE_FOLLOW_MASTER_NONE, "master before set %d %d", no, type);
    OK(NMC_MtFollowClear(ax1, 0));
    OK(NMC_MtFollowClear(ax1, 1));
    CHECK(NMC_MtFollowClear(ax1, 2) == RTN_ARG_RANGE, "FIFO 2 accepted");
    CHECK(NMC_MtFollowSetMaster(ax1, 1, PROFILE_FOLLOW_MASTER_AXIS_PRF) == RTN_ARG_RANGE,
          "the slave as its own master");
    CHECK(NMC_MtFollowSetMaster(ax1, 0, 4) == RTN_ARG_RANGE, "master type 4");
    OK(NMC_MtFollowSetMaster(ax1, 0, PROFILE_FOLLOW_MASTER_AXIS_PRF));
    OK(NMC_MtFollowGetMaster(ax1, &no, &type));
    CHECK(no == 0 && type == PROFILE_FOLLOW_MASTER_AXIS_PRF, "master %d %d", no, type);
    for (f = 0; f < 2; f++)
        for (i = 0; i < 3; i++) OK(NMC_MtFollowPushData(ax1, masterPos[i], slavePos[i], 0, (short)f));
    CHECK(NMC_MtFollowPushData(ax1, 80000, 50000, 4, 0) == RTN_ARG_RANGE, "type 4");
    OK(NMC_MtFollowGetSpace(ax1, &space, 0));
    CHECK(space == 29, "FIFO 0 space %d after 3 points", space);
    OK(NMC_MtFollowSetLoopCount(ax1, 0));
    CHECK(NMC_MtFollowSetLoopCount(ax1, -1) == RTN_ARG_RANGE, "loop count -1");
    OK(NMC_MtFollowGetLoopCount(ax1, &loops));
    CHECK(loops == 0, "loop count %ld", loops);
    CHECK(NMC_MtFollowSetEvent(ax1, 3, 1, 50000) == RTN_ARG_RANGE, "event 3");
    OK(NMC_MtFollowSetEvent(ax1, 2, 1, 50000));
    OK(NMC_MtFollowGetEvent(ax1, &ev, &dir, &pos));
    CHECK(ev == 2 && dir == 1 && pos == 50000, "event %d %d %ld", ev, dir, pos);
    OK(NMC_MtFollowSetDir(ax1, 0));
    OK(NMC_MtFollowGetDir(ax1, &dir));
    CHECK(dir == 0, "dir %d", dir);
    CHECK(NMC_MtFollowStart(ax1, 1, bad) == RTN_ARG_RANGE, "axis 9 started");
    OK(NMC_MtFollowStart(ax1, 0, 0));
    OK(NMC_MtGetPrfMode(ax1, &mode));
    CHECK(mode == MT_FOLLOW_PRF_MODE, "slave mode %d", mode);

    /* The master (as in the manual, after the slave is set up here: the start position is
     * 1 s of jog away either way). */
    OK(NMC_MtMoveJog(ax0, 1, 1, 50, 0, 1));
    slave = slave_at(ax0, 50000 + 60000, &seen);
    CHECK(slave > 40000 - 600 && slave < 40000 + 600, "TV59 k=1: slave %ld at master %ld", slave,
          seen);
    OK(NMC_MtFollowGetLoopCount(ax1, &loops));
    CHECK(loops == 1, "passes done %ld after one", loops);
    OK(NMC_MtFollowSwitch(ax1, 0, 0));
    slave = slave_at(ax0, 50000 + 2 * 60000, &seen);
    CHECK(slave > 80000 - 600 && slave < 80000 + 600, "TV59 k=2: slave %ld at master %ld", slave,
          seen);

    OK(NMC_MtStop(ax0));
    wait_still(ax0);
    OK(NMC_MtStop(ax1));
    wait_still(ax1);
    printf("ok\n");
    return 0;
}
