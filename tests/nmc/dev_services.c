/* Controller services (digest 001 §2.20, §4.9): DevWriteID / DevReadID, DevSetPara /
 * DevGetPara, the RTC behind a system password, the password itself, backed variables. */
#include <string.h>
#include "check.h"

int main(void) {
    HAND dev = 0, ax = 0;
    char id[32];
    long v = 0;
    short en = -1;
    TNMCTime t, now;
    TBackGroup2 back;
    char pw[] = "123456", wrong[] = "654321", fresh[] = "s3cret", toolong[] = "0123456789abcdef";
    char card2[] = "CARD2";

    OK(NMC_DevOpen(0, &dev));
    OK(NMC_MtOpen(dev, 1, &ax));

    /* ID: written for the next power-up, read back now. */
    OK(NMC_DevWriteID(dev, card2));
    OK(NMC_DevReadID(dev, id));
    CHECK(strcmp(id, "CARD2") == 0, "ID %s", id);
    CHECK(NMC_DevWriteID(dev, toolong) == RTN_ARG_RANGE, "16-byte ID");
    CHECK(NMC_DevWriteID(dev, NULL) == RTN_NULL_POINTER, "NULL ID");

    /* System parameters: the IP reads 192.168.1.110 until written. */
    OK(NMC_DevGetPara(dev, PARA_IP_ADDRESS, &v));
    CHECK(v == ((192L << 24) | (168L << 16) | (1L << 8) | 110L), "IP para %#lx", v);
    OK(NMC_DevSetPara(dev, PARA_IP_ADDRESS, 0xC0A80165L));
    OK(NMC_DevSetPara(dev, PARA_WRITE_EN, 1));
    OK(NMC_DevGetPara(dev, PARA_IP_ADDRESS, &v));
    CHECK(v == 0xC0A80165L, "IP para written %#lx", v);
    OK(NMC_DevGetPara(dev, PARA_WRITE_EN, &v));
    CHECK(v == 1, "PARA_WRITE_EN %ld", v);
    CHECK(NMC_DevSetPara(dev, PARA_WRITE_EN, 2) == RTN_ARG_RANGE, "PARA_WRITE_EN 2");

    /* RTC. */
    OK(NMC_GetTime(dev, &now));
    CHECK(now.ear >= 2024 && now.mon >= 1 && now.mon <= 12, "RTC %d-%d", now.ear, now.mon);
    t.ear = 2030; t.mon = 5; t.day = 6; t.hour = 7; t.min = 8; t.second = 9;
    CHECK(NMC_SetTime(dev, &t, wrong) == RTN_PASSWORD, "wrong password");
    OK(NMC_SetTime(dev, &t, pw));
    OK(NMC_GetTime(dev, &now));
    CHECK(now.ear == 2030 && now.mon == 5 && now.day == 6 && now.hour == 7 && now.min == 8 &&
          now.second >= 9 && now.second <= 20, "RTC %d-%d-%d %d:%d:%d", now.ear, now.mon, now.day,
          now.hour, now.min, now.second);
    t.mon = 2; t.day = 30;
    CHECK(NMC_SetTime(dev, &t, pw) == RTN_ARG_RANGE, "30 February");
    t.day = 28; t.ear = 2100;
    CHECK(NMC_SetTime(dev, &t, pw) == RTN_ARG_RANGE, "year 2100");

    /* Password. */
    OK(NMC_VerifyPassword(dev, pw));
    CHECK(NMC_VerifyPassword(dev, wrong) == RTN_PASSWORD, "verify wrong");
    CHECK(NMC_ChangePassword(dev, wrong, fresh) == RTN_PASSWORD, "change with wrong");
    CHECK(NMC_ChangePassword(dev, pw, toolong) == RTN_ARG_RANGE, "16-char password");
    OK(NMC_ChangePassword(dev, pw, fresh));
    CHECK(NMC_VerifyPassword(dev, pw) == RTN_PASSWORD, "old password");
    OK(NMC_VerifyPassword(dev, fresh));

    /* Backed variables: off by default; on, what a power failure would save. */
    OK(NMC_GetBackedVarOnOff(dev, &en));
    CHECK(en == 0, "backed default %d", en);
    CHECK(NMC_GetBackedVarGroup2(dev, &back) == RTN_INVALID_STATE, "read while off");
    OK(NMC_SetBackedVarOnOff(dev, 1));
    OK(NMC_GetBackedVarOnOff(dev, &en));
    CHECK(en == 1, "backed on %d", en);
    OK(NMC_MtSetSvOn(ax));
    OK(NMC_MtMovePtpAbs(ax, 1, 1, 0, 0, 50, 0, 3000));
    wait_still(ax);
    OK(NMC_GetBackedVarGroup2(dev, &back));
    CHECK(back.axPrfPos[1] == 3000 && back.axisPos[1] == 3000, "backed axis 1 %ld %ld",
          back.axPrfPos[1], back.axisPos[1]);
    CHECK(back.encPos[1] > 2900 && back.encPos[1] <= 3000, "backed encoder 1 %ld", back.encPos[1]);
    CHECK(back.axPrfPos[0] == 0 && back.axPrfPos[11] == 0, "other axes %ld %ld", back.axPrfPos[0],
          back.axPrfPos[11]);
    CHECK(NMC_SetBackedVarOnOff(dev, 2) == RTN_ARG_RANGE, "en 2");

    printf("ok\n");
    return 0;
}
