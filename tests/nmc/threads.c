/* 8 threads call on one device handle at once: every call gets its own reply. */
#include <pthread.h>
#include "check.h"

static HAND axes_[4];
static HAND dev_;

static void *worker(void *arg) {
    long id = (long)arg;
    int i;
    for (i = 0; i < 200; i++) {
        short sts = 0;
        long pos = -1;
        TPtpPara p;
        HAND spare = 0;
        OK(NMC_MtGetSts(axes_[id % 4], &sts));
        OK(NMC_MtGetPrfPos(axes_[id % 4], &pos));
        CHECK(pos == 0, "thread %ld: pos %ld", id, pos);
        OK(NMC_MtGetPtpPara(axes_[id % 4], &p));
        CHECK(p.acc > 0, "thread %ld: acc %f", id, p.acc);
        CHECK(NMC_MtOpen(dev_, 9, &spare) == RTN_ARG_RANGE, "thread %ld: bad itemNo accepted", id);
        CHECK(NMC_GetLastErr() == RTN_ARG_RANGE, "thread %ld: last error is per thread", id);
    }
    return NULL;
}

int main(void) {
    pthread_t t[8];
    long i;
    OK(NMC_DevOpen(0, &dev_));
    for (i = 0; i < 4; i++) OK(NMC_MtOpen(dev_, (short)i, &axes_[i]));
    for (i = 0; i < 8; i++) CHECK(pthread_create(&t[i], NULL, worker, (void *)i) == 0, "thread");
    for (i = 0; i < 8; i++) pthread_join(t[i], NULL);
    printf("ok\n");
    return 0;
}
