/* Helpers of the NMC example programs: each check prints what failed and exits 1; the harness
 * (tests/tests/nmc_examples.rs) runs each program against `mcemu run` and expects "ok". */
#ifndef NMC_CHECK_H
#define NMC_CHECK_H

#include <stdio.h>
#include <stdlib.h>
#include "mtn_lib20.h"

#define CHECK(cond, ...)                                                    \
    do {                                                                    \
        if (!(cond)) {                                                      \
            fprintf(stderr, "%s:%d: check failed: %s: ", __FILE__, __LINE__, #cond); \
            fprintf(stderr, __VA_ARGS__);                                   \
            fprintf(stderr, "\n");                                          \
            exit(1);                                                        \
        }                                                                   \
    } while (0)

/* A call that must succeed; on failure prints the library's description. */
#define OK(call)                                                            \
    do {                                                                    \
        short rc_ = (call);                                                 \
        if (rc_ != 0) {                                                     \
            char d_[256];                                                   \
            NMC_GetErrDesc(rc_, d_);                                        \
            fprintf(stderr, "%s:%d: %s returned %d: %s\n", __FILE__, __LINE__, #call, rc_, d_); \
            exit(1);                                                        \
        }                                                                   \
    } while (0)

/* Poll `call` (which sets what `cond` reads) until `cond` holds: a value the server shows from
 * its next snapshot on. */
#define EVENTUALLY(call, cond)                                              \
    do {                                                                    \
        long n_ = 0;                                                        \
        for (;;) {                                                          \
            OK(call);                                                       \
            if (cond) break;                                                \
            CHECK(++n_ < 1000000L, "never: %s", #cond);                    \
        }                                                                   \
    } while (0)

/* Poll until the axis is still (the status word's BUSY bit clears). */
static inline short wait_still(HAND ax) {
    short sts = 0;
    long polls = 0;
    do {
        OK(NMC_MtGetSts(ax, &sts));
        CHECK(++polls < 10000000L, "axis never stopped, sts %#x", sts);
    } while (sts & BIT_AXIS_BUSY);
    return sts;
}

#endif
