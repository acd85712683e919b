/* Closed loop (digest 001 §2.15, S-CLOSED-LOOP's calls) and profile configuration (§2.20):
 * control mode, PID sets and the active one, the DAC settings and NMC_SetCloseLoopDac (the
 * manual's other name), TV70 (startPos offsets the axis position), TV67 (the planning
 * coefficient's range), the encoder coefficient scaling the encoder reading. */
#include "check.h"

int main(void) {
    HAND dev = 0, ax0 = 0, ax2 = 0;
    short mode = 9, index = 9, map = 9, port = 9;
    long pos = 0, start = 0, enc0 = 0, enc = 0;
    double coe = 0;
    TPidPara pid = {5, 1, 0, 0, 1000, 0, 32767}, back;
    TDacMotor dac = {0, 0, 500}, dacBack;

    OK(NMC_DevOpen(0, &dev));
    OK(NMC_MtOpen(dev, 0, &ax0));
    OK(NMC_MtOpen(dev, 2, &ax2));

    OK(NMC_MtGetCtrlMode(ax0, &mode));
    CHECK(mode == 0, "default control mode %d", mode);
    OK(NMC_MtSetCloseLoopDac(ax0, &dac));
    OK(NMC_MtGetCloseLoopDac(ax0, &dacBack));
    CHECK(dacBack.dacLmt == 500 && dacBack.inverse == 0, "DAC %d %d", dacBack.dacLmt,
          dacBack.inverse);
    dac.inverse = 1;
    dac.bias = -20;
    dac.dacLmt = 400;
    OK(NMC_SetCloseLoopDac(ax0, &dac));
    OK(NMC_MtGetCloseLoopDac(ax0, &dacBack));
    CHECK(dacBack.dacLmt == 400 && dacBack.inverse == 1 && dacBack.bias == -20,
          "DAC through the alias %d %d %d", dacBack.dacLmt, dacBack.inverse, dacBack.bias);
    dac.dacLmt = -1;
    CHECK(NMC_MtSetCloseLoopDac(ax0, &dac) == RTN_ARG_RANGE, "dacLmt -1 accepted");
    OK(NMC_MtSetCtrlMode(ax0, 1));
    OK(NMC_MtGetCtrlMode(ax0, &mode));
    CHECK(mode == 1, "control mode %d", mode);
    CHECK(NMC_MtSetCtrlMode(ax0, 2) == RTN_ARG_RANGE, "mode 2 accepted");
    OK(NMC_MtSetCtrlMode(ax0, 0));

    OK(NMC_MtSetPIDPara(ax0, 1, &pid));
    OK(NMC_MtGetPIDPara(ax0, 1, &back));
    CHECK(back.kp == 5.0f && back.ki == 1.0f && back.integralLimit == 1000 &&
              back.outLimit == 32767,
          "PID 1: %f %f %ld %d", back.kp, back.ki, back.integralLimit, back.outLimit);
    OK(NMC_MtGetPIDPara(ax0, 0, &back));
    CHECK(back.kp == 0.0f, "PID 0 kp %f", back.kp);
    CHECK(NMC_MtSetPIDPara(ax0, 3, &pid) == RTN_ARG_RANGE, "PID index 3 accepted");
    CHECK(NMC_MtGetPIDPara(ax0, -1, &back) == RTN_ARG_RANGE, "PID index -1 accepted");
    CHECK(NMC_MtSetPIDPara(ax0, 0, NULL) == RTN_NULL_POINTER, "NULL accepted");
    OK(NMC_MtGetPIDIndex(ax0, &index));
    CHECK(index == 0, "default PID index %d", index);
    OK(NMC_MtSetPIDIndex(ax0, 1));
    OK(NMC_MtGetPIDIndex(ax0, &index));
    CHECK(index == 1, "PID index %d", index);
    CHECK(NMC_MtSetPIDIndex(ax0, 3) == RTN_ARG_RANGE, "PID index 3 accepted");

    /* TV70: startPos 1000; PTP to 5000 ⇒ prfPos 5000, axisPos 6000. */
    OK(NMC_MtGetPrfConfig(ax0, &map, &port, &start));
    CHECK(map == 0 && port == 0 && start == 0, "default prf config %d %d %ld", map, port, start);
    OK(NMC_MtPrfConfig(ax0, 0, 0, 1000));
    OK(NMC_MtGetPrfConfig(ax0, &map, &port, &start));
    CHECK(start == 1000, "startPos %ld", start);
    CHECK(NMC_MtPrfConfig(ax0, 0, 2, 0) == RTN_ARG_RANGE, "port 2 accepted");
    CHECK(NMC_MtPrfConfig(ax0, 9, 0, 0) == RTN_ARG_RANGE, "axis 9 accepted");
    OK(NMC_MtSetSvOn(ax0));
    OK(NMC_MtMovePtpAbs(ax0, 1, 1, 0, 0, 20, 0, 5000));
    wait_still(ax0);
    OK(NMC_MtGetPrfPos(ax0, &pos));
    CHECK(pos == 5000, "TV70 prfPos %ld", pos);
    OK(NMC_MtGetAxisPos(ax0, &pos));
    CHECK(pos == 6000, "TV70 axisPos %ld", pos);

    /* TV67. */
    CHECK(NMC_MtSetPrfCoe(ax0, 1.5) == RTN_ARG_RANGE, "TV67: 1.5 accepted");
    CHECK(NMC_MtSetPrfCoe(ax0, 0) == RTN_ARG_RANGE, "0 accepted");
    OK(NMC_MtGetPrfCoe(ax0, &coe));
    CHECK(coe == 1.0, "default prf coefficient %f", coe);
    OK(NMC_MtSetPrfCoe(ax0, 0.5));
    OK(NMC_MtGetPrfCoe(ax0, &coe));
    CHECK(coe == 0.5, "prf coefficient %f", coe);

    /* The encoder coefficient on axis 2 (a stepper counting its own pulses): 1000 pulses read
     * 4000 with 4 (the manual's example), and the reading does not jump at the change. */
    OK(NMC_MtSetSvOn(ax2));
    OK(NMC_MtGetEncPos(ax2, &enc0));
    OK(NMC_MtSetEncCoe(ax2, 4));
    OK(NMC_MtGetEncCoe(ax2, &coe));
    CHECK(coe == 4.0, "encoder coefficient %f", coe);
    OK(NMC_MtGetEncPos(ax2, &enc));
    CHECK(enc == enc0, "the reading jumped from %ld to %ld", enc0, enc);
    OK(NMC_MtMovePtpRel(ax2, 1, 1, 0, 0, 20, 0, 1000));
    wait_still(ax2);
    OK(NMC_MtGetEncPos(ax2, &enc));
    CHECK(enc == enc0 + 4000, "1000 pulses read %ld (from %ld)", enc - enc0, enc0);
    CHECK(NMC_MtSetEncCoe(ax2, 0) == RTN_ARG_RANGE, "0 accepted");
    CHECK(NMC_MtSetEncCoe(ax2, -1) == RTN_ARG_RANGE, "-1 accepted");
    printf("ok\n");
    return 0;
}
