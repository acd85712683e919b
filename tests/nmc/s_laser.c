/* S-LASER (digest 001 §5, C3§2.2.3 a–e, §2.3.3 b, §2.12): the laser channels' settings read
 * back, their echo on the machine's outputs (channel k's switch on DO 60 + k of the 64, or the
 * general output NMC_SetPWMPort names; LASER_DA's power on the analog output, NMC_GetDac), and
 * buffered on/off switching in path order; bad arguments. */
#include <string.h>
#include "laser_path.h"

static short laser0_on(void) {
    short on = -1;
    OK(NMC_LaserGetOnOff(devHandle, &on, 0));
    return on;
}

int main(void) {
    long onDelay = -1, offDelay = -1, minV = -1, maxV = -1, standby = -1;
    long xCmpPos[10], yCmpPos[10];
    unsigned long cmpPower[10][10];
    short on = -1, type = -1, idx = -1, d = 0, pAxisNo[2] = {0, 1}, i, j;
    double p = -1;
    TLaserPower lserPw;
    TTimeArrayPara timeAr;
    Seen seen;

    open_xy();

    /* a, b: basic mode, PWM duty at 1000 Hz (the examples' non-Ex form), power 10, on. */
    OK(NMC_LaserSetMode(devHandle, BASIC_OUTPUT_MODE, 0));
    OK(NMC_LaserSetOutputType(devHandle, LASER_PWM_DUTY, 0, 1000, 0));
    CHECK(laser0_on() == 0 && do_bit(60) == 0, "off at first");
    OK(NMC_LaserSetPowerEx(devHandle, 10, 0));
    OK(NMC_LaserOnOff(devHandle, 1, 0));
    OK(NMC_LaserGetPower(devHandle, &p, 0));
    CHECK(p == 10, "power %f", p);
    CHECK(laser0_on() == 1 && do_bit(60) == 1, "on: channel 0's switch is DO60 (%d)", do_bit(60));

    /* The PWM routed to general output 5, and back to its own pin. */
    OK(NMC_SetPWMPort(devHandle, 1, 5, 0));
    OK(NMC_GetPWMPort(devHandle, &type, &idx, 0));
    CHECK(type == 1 && idx == 5, "port %d %d", type, idx);
    CHECK(do_bit(5) == 1 && do_bit(60) == 0, "on DO5 now: %d %d", do_bit(5), do_bit(60));
    OK(NMC_LaserOnOff(devHandle, 0, 0));
    CHECK(laser0_on() == 0 && do_bit(5) == 0, "off");
    OK(NMC_SetPWMPort(devHandle, 0, 0, 0));
    OK(NMC_GetPWMPort(devHandle, &type, &idx, 0));
    CHECK(type == 0 && idx == 0, "default port %d %d", type, idx);

    /* Parameters read back. */
    OK(NMC_LaserSetParam(devHandle, 100, 200, 0, 80, 0, 0));
    OK(NMC_LaserGetParam(devHandle, &onDelay, &offDelay, &minV, &maxV, &standby, 0));
    CHECK(onDelay == 100 && offDelay == 200 && minV == 0 && maxV == 80 && standby == 0, "param %ld %ld %ld %ld %ld",
          onDelay, offDelay, minV, maxV, standby);

    /* LASER_DA on channel 1: analog output 1 carries the standby power while off, the power
     * (held to maxValue) while on. */
    OK(NMC_LaserSetModes(devHandle, BASIC_OUTPUT_MODE, 1));
    OK(NMC_LaserSetOutputTypeEx(devHandle, LASER_DA, 1, 0, 1));
    OK(NMC_LaserSetParam(devHandle, 0, 0, 0, 20000, 1000, 1));
    OK(NMC_GetDac(devHandle, 1, &d));
    CHECK(d == 1000, "standby power on the DAC: %d", d);
    OK(NMC_LaserSetPowerEx(devHandle, 16384, 1));
    OK(NMC_LaserOnOff(devHandle, 1, 1));
    OK(NMC_GetDac(devHandle, 1, &d));
    CHECK(d == 16384 && do_bit(61) == 1, "DAC %d, DO61 %d", d, do_bit(61));
    OK(NMC_LaserSetPowerEx(devHandle, 30000, 1));
    OK(NMC_GetDac(devHandle, 1, &d));
    CHECK(d == 20000, "held to maxValue: %d", d);
    OK(NMC_LaserOnOff(devHandle, 0, 1));
    OK(NMC_GetDac(devHandle, 1, &d));
    CHECK(d == 1000 && do_bit(61) == 0, "off: DAC %d", d);

    /* d, e: power following and the compensation table (stored). */
    OK(NMC_LaserSetFollowParam(devHandle, 16, 0, 0));
    for (i = 0; i < 10; i++) {
        xCmpPos[i] = yCmpPos[i] = 10000L * i;
        for (j = 0; j < 10; j++) cmpPower[i][j] = (unsigned long)(i * 10);
    }
    OK(NMC_SetLaserPowerCmpTable(devHandle, 0, xCmpPos, yCmpPos, 10, 10, 0, 1000, &cmpPower[0][0], 0));
    OK(NMC_StartLaserPowerComp(devHandle, pAxisNo, 0));
    OK(NMC_StopLaserPowerComp(devHandle, 0));

    /* The waveform (time-array) mode on channel 1: the 40-point ramp ends at 0, so the laser
     * is off after it; an array ending at 5000 leaves it on at 5000. */
    OK(NMC_LaserSetMode(devHandle, TIME_ARRAY_OUTPUT_MODE, 1));
    memset(&lserPw, 0, sizeof(TLaserPower));
    lserPw.count = 40;
    for (i = 0; i < 20; i++) {
        lserPw.time[i] = 100;
        lserPw.power[i] = i * 2;
        lserPw.time[i + 20] = 100;
        lserPw.power[i + 20] = (19 - i) * 2;
    }
    OK(NMC_LaserSetTimeArrayPower(devHandle, 0, &lserPw));
    OK(NMC_LaserTimeArrayExe(devHandle, 0, 1));
    OK(NMC_LaserGetOnOff(devHandle, &on, 1));
    CHECK(on == 0, "a ramp ending at 0 leaves the laser off");
    lserPw.count = 3;
    lserPw.power[2] = 5000;
    OK(NMC_LaserSetTimeArrayPower(devHandle, 1, &lserPw));
    OK(NMC_LaserTimeArrayExe(devHandle, 1, 1));
    OK(NMC_LaserGetOnOff(devHandle, &on, 1));
    OK(NMC_GetDac(devHandle, 1, &d));
    CHECK(on == 1 && d == 5000, "array ending at 5000: on %d, DAC %d", on, d);
    OK(NMC_LaserOnOff(devHandle, 0, 1));
    memset(&timeAr, 0, sizeof(timeAr));
    timeAr.axisMask = 0x3;
    timeAr.gateDistance = 20;
    timeAr.pwmEnable = 1;
    timeAr.pwmWidth = 1;
    timeAr.outputCh = 1;
    timeAr.pwmPeriod = 500000;
    OK(NMC_LaserSetTimeArrayPara(devHandle, &timeAr, 1));
    timeAr.gateDistance = 0;
    CHECK(NMC_LaserSetTimeArrayPara(devHandle, &timeAr, 1) == RTN_ARG_RANGE, "gateDistance 0 with pwmEnable");
    CHECK(NMC_LaserTimeArrayExe(devHandle, 0, 0) == RTN_INVALID_STATE, "time array in basic mode");
    CHECK(NMC_LaserTimeArrayExe(devHandle, 5, 1) == RTN_INVALID_STATE, "group never set");
    lserPw.count = 60; /* the manual's welding example: over LASET_POINT */
    CHECK(NMC_LaserSetTimeArrayPower(devHandle, 0, &lserPw) == RTN_ARG_RANGE, "count 60");

    /* Bad arguments. */
    CHECK(NMC_LaserSetMode(devHandle, 4, 0) == RTN_ARG_RANGE, "mode 4");
    CHECK(NMC_LaserOnOff(devHandle, 1, 2) == RTN_ARG_RANGE, "ch 2");
    CHECK(NMC_LaserOnOff(devHandle, 2, 0) == RTN_ARG_RANGE, "onOff 2");
    CHECK(NMC_LaserSetOutputTypeEx(devHandle, 5, 0, 0, 0) == RTN_ARG_RANGE, "type 5");
    CHECK(NMC_LaserSetOutputTypeEx(devHandle, LASER_DA, 256, 0, 0) == RTN_ARG_RANGE, "no analog output 256");
    CHECK(NMC_LaserSetOutputTypeEx(devHandle, LASER_PWM_FRQ, 0, 120, 0) == RTN_ARG_RANGE, "duty 120 %%");
    CHECK(NMC_LaserSetPowerEx(devHandle, 101, 0) == RTN_ARG_RANGE, "duty power 101");
    CHECK(NMC_LaserSetParam(devHandle, 70000, 0, 0, 0, 0, 0) == RTN_ARG_RANGE, "onDelay 70000");
    CHECK(NMC_LaserSetFollowParam(devHandle, 33, 0, 0) == RTN_ARG_RANGE, "filter 33");
    CHECK(NMC_SetLaserPowerCmpTable(devHandle, 20, xCmpPos, yCmpPos, 10, 10, 0, 1000, &cmpPower[0][0], 0) ==
              RTN_ARG_RANGE,
          "table 20");
    CHECK(NMC_SetLaserPowerCmpTable(devHandle, 0, xCmpPos, yCmpPos, 11, 10, 0, 1000, &cmpPower[0][0], 0) ==
              RTN_ARG_RANGE,
          "xCount 11");
    pAxisNo[1] = 9;
    CHECK(NMC_StartLaserPowerComp(devHandle, pAxisNo, 0) == RTN_ARG_RANGE, "axis 9");
    CHECK(NMC_LaserSetTimeArrayPower(devHandle, 12, &lserPw) == RTN_ARG_RANGE, "group 12");
    CHECK(NMC_SetPWMPort(devHandle, 1, 64, 0) == RTN_ARG_RANGE, "GPDO 64");
    CHECK(NMC_LaserGetPower(devHandle, NULL, 0) == RTN_NULL_POINTER, "NULL power");
    CHECK(NMC_LaserGetParam(devHandle, &onDelay, NULL, &minV, &maxV, &standby, 0) == RTN_NULL_POINTER, "NULL");

    /* c: buffered power and on/off around a line: the laser is on on the way out, off on the
     * way back, in path order. */
    OK(NMC_CrdBufClr(crdHandle));
    OK(NMC_CrdBufLaserPower(crdHandle, 100, 10, 0));
    OK(NMC_CrdBufLaserSetParam(crdHandle, 100, 10, 10, 0, 100, 0, 0));
    OK(NMC_CrdBufLaserSetFollow(crdHandle, 1, 5, 0, 0));
    OK(NMC_CrdBufLaserSetFollow(crdHandle, 1, 0, 0, 0));
    OK(NMC_CrdBufLaserOnOff(crdHandle, 101, 1, 0));
    line_x(154, 10000);
    OK(NMC_CrdBufLaserOnOff(crdHandle, 101, 0, 0));
    line_x(155, 0);
    CHECK(laser0_on() == 0, "nothing runs before NMC_CrdStartMtn");
    seen = run_out_and_back(laser0_on);
    CHECK(seen.out == 1 && seen.back == 0 && seen.end == 0, "laser out %d back %d end %d", seen.out, seen.back,
          seen.end);
    OK(NMC_LaserGetPower(devHandle, &p, 0));
    CHECK(p == 10, "buffered power %f", p);
    OK(NMC_LaserGetParam(devHandle, &onDelay, &offDelay, &minV, &maxV, &standby, 0));
    CHECK(onDelay == 10 && maxV == 100, "buffered param %ld %ld", onDelay, maxV);

    /* A buffered time array (channel 1, ending at 5000: on) and bad buffered arguments. */
    OK(NMC_CrdBufClr(crdHandle));
    OK(NMC_CrdBufLaserTimeArrayExe(crdHandle, 1, 1, 1));
    line_x(2, 100);
    OK(NMC_CrdEndMtn(crdHandle));
    OK(NMC_CrdStartMtn(crdHandle));
    do {
        OK(NMC_CrdGetSts(crdHandle, &d));
    } while (d & BIT_CORD_BUSY);
    OK(NMC_LaserGetOnOff(devHandle, &on, 1));
    OK(NMC_LaserGetPower(devHandle, &p, 1));
    CHECK(on == 1 && p == 5000, "after the buffered array: on %d, power %f", on, p);
    OK(NMC_CrdBufClr(crdHandle));
    CHECK(NMC_CrdBufLaserOnOff(crdHandle, 1, 2, 0) == RTN_ARG_RANGE, "buffered onOff 2");
    CHECK(NMC_CrdBufLaserSetFollow(crdHandle, 1, 5, 2, 0) == RTN_ARG_RANGE, "followType 2");
    CHECK(NMC_CrdBufLaserPower(crdHandle, 1, 40000, 1) == RTN_ARG_RANGE, "DA power 40000");
    CHECK(NMC_CrdBufLaserTimeArrayExe(crdHandle, 1, 0, 0) == RTN_INVALID_STATE, "buffered array in basic mode");
    CHECK(NMC_CrdBufLaserOnOff(devHandle, 1, 1, 0) == RTN_WRONG_HANDLE_KIND, "device handle");

    printf("ok\n");
    return 0;
}
