/* S-LASER's SHIO examples (digest 001 §5, C3§2.4.3 a, b; §2.12): the gate pin is the machine's
 * DO62 (of 64, the HSIO compare group 0's GATE drives too), on while the gate is on; the
 * immediate gate, the buffered gate around lines in path order, pulse trains (continuous:
 * high; counted: low when done), the PWM mapped to the gate pin; bad arguments. */
#include <string.h>
#include "laser_path.h"

static short gate(void) { return do_bit(62); }

int main(void) {
    TSHIOPara shioPrm;
    Seen seen;

    open_xy();

    /* a: immediate gate. NMC_NMC_SHIOGateOn [sic] is the manual's example's typo: the
     * vendor's header has only NMC_SHIOGateOn. */
    OK(NMC_LaserSetMode(devHandle, SHIO_OUTPUT_MODE, 0));
    memset(&shioPrm, 0, sizeof(shioPrm));
    shioPrm.isArray = 0;
    shioPrm.outMode = 1;
    shioPrm.posSrc = 1;
    shioPrm.axisMask = 0x1;
    shioPrm.delay = 0;
    shioPrm.gateTime = 0.0008;
    shioPrm.gateDistance = 20;
    OK(NMC_SHIOConfigPara(devHandle, &shioPrm, 0));
    CHECK(gate() == 0, "gate off at first");
    OK(NMC_SHIOGateOn(devHandle, 0));
    CHECK(gate() == 1, "gate on");
    OK(NMC_SHIOGateOff(devHandle, 0));
    CHECK(gate() == 0, "gate off");

    /* Minimum frequency, axes, trigger (stored), with the summary table's Frg spellings. */
    OK(NMC_SHIOEnableMinFrq(devHandle, 1000, 0));
    OK(NMC_SHIODisableMinFrq(devHandle, 0));
    OK(NMC_SHIOEnableMinFrg(devHandle, 1000, 0));
    OK(NMC_SHIODisableMinFrg(devHandle, 0));
    OK(NMC_SHIOChangeAxisMask(devHandle, 0x3, 0));
    OK(NMC_SHIOTriggerOn(devHandle, 1000, 0.0001, 0));
    OK(NMC_SHIOTriggerOff(devHandle, 0));

    /* Pulse trains: continuous holds the pin high, a counted one ends low. */
    OK(NMC_SHIOGatePulse(devHandle, 10, 1000, 0, 0));
    CHECK(gate() == 1, "continuous gate pulses");
    OK(NMC_SHIOGatePulse(devHandle, 10, 1000, 5, 0));
    CHECK(gate() == 0, "5 gate pulses done");
    OK(NMC_PwmPulseOut(devHandle, 10, 1000, 0, 0));
    CHECK(do_bit(60) == 1, "continuous PWM on the PWM pin DO60");
    OK(NMC_PwmPulseOut(devHandle, 10, 1000, 3, 0));
    CHECK(do_bit(60) == 0, "3 PWM pulses done");

    /* The PWM of the basic mode mapped to the gate pin. */
    OK(NMC_LaserSetMode(devHandle, BASIC_OUTPUT_MODE, 0));
    CHECK(NMC_SHIOGatePulse(devHandle, 10, 1000, 0, 0) == RTN_INVALID_STATE, "gate pulse outside SHIO mode");
    CHECK(NMC_PwmPulseOut(devHandle, 10, 1000, 0, 0) == RTN_INVALID_STATE, "PWM pulse outside SHIO mode");
    OK(NMC_LaserSetOutputTypeEx(devHandle, LASER_PWM_DUTY, 0, 1000, 0));
    OK(NMC_SetPwmToGate(devHandle, 0, 0, 1));
    OK(NMC_LaserOnOff(devHandle, 1, 0));
    CHECK(gate() == 1 && do_bit(60) == 0, "PWM on the gate pin: %d %d", gate(), do_bit(60));
    OK(NMC_SetPwmToGate(devHandle, 0, 0, 0));
    CHECK(gate() == 0 && do_bit(60) == 1, "PWM back on its pin: %d %d", gate(), do_bit(60));
    OK(NMC_LaserOnOff(devHandle, 0, 0));
    OK(NMC_LaserSetOutputTypeEx(devHandle, LASER_NONE, 0, 0, 0));

    /* Bad arguments. */
    OK(NMC_LaserSetMode(devHandle, SHIO_OUTPUT_MODE, 0));
    CHECK(NMC_SHIOGateOn(devHandle, 1) == RTN_ARG_RANGE, "ch 1");
    shioPrm.gateTime = 0.001;
    CHECK(NMC_SHIOConfigPara(devHandle, &shioPrm, 0) == RTN_ARG_RANGE, "gateTime 0.001");
    shioPrm.gateTime = 0.0008;
    shioPrm.outMode = 5;
    CHECK(NMC_SHIOConfigPara(devHandle, &shioPrm, 0) == RTN_ARG_RANGE, "outMode 5");
    shioPrm.outMode = 1;
    shioPrm.isArray = 1;
    CHECK(NMC_SHIOConfigPara(devHandle, &shioPrm, 0) == RTN_ARG_RANGE, "isArray 1");
    CHECK(NMC_SHIOConfigPara(devHandle, NULL, 0) == RTN_NULL_POINTER, "NULL");
    CHECK(NMC_SHIOEnableMinFrq(devHandle, 0, 0) == RTN_ARG_RANGE, "minFrq 0");
    CHECK(NMC_SHIOChangeAxisMask(devHandle, 0x100, 0) == RTN_ARG_RANGE, "axis 8");
    CHECK(NMC_SHIOTriggerOn(devHandle, 0, 0.0001, 0) == RTN_ARG_RANGE, "freq 0");
    CHECK(NMC_SHIOTriggerOn(devHandle, 1000, 0.01, 0) == RTN_ARG_RANGE, "width over the period");
    CHECK(NMC_SHIOGatePulse(devHandle, 10, 1000, -1, 0) == RTN_ARG_RANGE, "outCount -1");
    CHECK(NMC_SHIOGatePulse(devHandle, 0, 1000, 1, 0) == RTN_ARG_RANGE, "gateTime 0");
    CHECK(NMC_SetPwmToGate(devHandle, 1, 0, 1) == RTN_ARG_RANGE, "pwmCh 1");
    CHECK(NMC_SetPwmToGate(devHandle, 0, 0, 2) == RTN_ARG_RANGE, "onOff 2");
    CHECK(NMC_SetPWMPort(devHandle, 2, 0, 0) == RTN_ARG_RANGE, "portType 2");

    /* b: the gate by travel, switched on and off in the buffer around lines; buffered
     * parameters, axes and minimum frequency; a continuous buffered gate pulse at the end. */
    shioPrm.isArray = 0;
    shioPrm.outMode = 2;
    shioPrm.posSrc = 0;
    shioPrm.axisMask = 0x3;
    shioPrm.gateTime = 0.00001;
    shioPrm.gateDistance = 20;
    OK(NMC_SHIOConfigPara(devHandle, &shioPrm, 0));
    OK(NMC_CrdBufClr(crdHandle));
    OK(NMC_CrdBufSHIOSetParam(crdHandle, 1, 0, 0.0005, 40, 0));
    OK(NMC_CrdBufSHIOChangeAxisMask(crdHandle, 1, 0x3, 0));
    OK(NMC_CrdBufSHIOSetMinFrq(crdHandle, 1, 500, 0));
    OK(NMC_CrdBufSHIOClrMinFrq(crdHandle, 1, 0));
    OK(NMC_CrdBufSHIOSetMinFrg(crdHandle, 1, 500, 0));
    OK(NMC_CrdBufSHIOClrMinFrg(crdHandle, 1, 0));
    OK(NMC_BufSHIOGateOn(crdHandle, 1, 0));
    line_x(154, 10000);
    OK(NMC_BufSHIOGateOff(crdHandle, 1, 0));
    line_x(155, 0);
    OK(NMC_CrdBufSHIOGatePulse(crdHandle, 156, 10, 1000, 0, 0));
    CHECK(gate() == 0, "nothing runs before NMC_CrdStartMtn");
    seen = run_out_and_back(gate);
    CHECK(seen.out == 1 && seen.back == 0 && seen.end == 1, "gate out %d back %d end %d", seen.out, seen.back,
          seen.end);

    OK(NMC_CrdBufClr(crdHandle));
    CHECK(NMC_CrdBufSHIOSetParam(crdHandle, 1, 0, 0.001, 40, 0) == RTN_ARG_RANGE, "buffered gateTime 0.001");
    CHECK(NMC_CrdBufSHIOSetParam(crdHandle, 1, 0, 0.0005, 0, 0) == RTN_ARG_RANGE, "gateDistance 0");
    CHECK(NMC_CrdBufSHIOSetMinFrq(crdHandle, 1, -5, 0) == RTN_ARG_RANGE, "buffered minFrq -5");
    CHECK(NMC_CrdBufSHIOChangeAxisMask(crdHandle, 1, -1, 0) == RTN_ARG_RANGE, "buffered mask -1");
    CHECK(NMC_BufSHIOGateOn(crdHandle, 1, 1) == RTN_ARG_RANGE, "buffered ch 1");
    CHECK(NMC_BufSHIOGateOn(devHandle, 1, 0) == RTN_WRONG_HANDLE_KIND, "device handle");
    OK(NMC_LaserSetMode(devHandle, BASIC_OUTPUT_MODE, 0));
    CHECK(NMC_CrdBufSHIOGatePulse(crdHandle, 1, 10, 1000, 0, 0) == RTN_INVALID_STATE, "buffered pulse outside SHIO");

    printf("ok\n");
    return 0;
}
