"""An HMI's Modbus flow against the default machine, with pymodbus: enable axis 0, write a
target and a velocity, start the move with a rising edge, and read the actual position back.

The register map is fixtures/modbus/generic.toml (per-axis blocks; f64 values big-endian, high
word first). Time is virtual: nothing moves until the test advances it, so the checks are
exact and the test takes the same path on a loaded CI machine as on a laptop.
"""

import struct

from pymodbus.client import ModbusTcpClient

UNIT = 1
# generic.toml: coils 0 enable, 1 start; holding registers 0 target (f64), 4 velocity (f64);
# input registers 0 actual position (f64), 16 state; discrete input 2 in position.
COIL_ENABLE, COIL_START = 0, 1
HR_TARGET, HR_VELOCITY = 0, 4
IR_ACT_POS, IR_STATE = 0, 16
DI_IN_POSITION = 2
STANDSTILL = 1


def f64_registers(value):
    return list(struct.unpack(">4H", struct.pack(">d", value)))


def f64_from(registers):
    return struct.unpack(">d", struct.pack(">4H", *registers))[0]


def test_an_hmi_enables_moves_and_reads_back_axis_0(mcemu):
    host, port = mcemu.host_port("modbus-tcp")
    with ModbusTcpClient(host, port=port, timeout=5, retries=0) as hmi:
        assert hmi.connect()
        assert not hmi.write_coil(COIL_ENABLE, True, device_id=UNIT).isError()
        mcemu.advance(ticks=1)
        assert hmi.read_coils(COIL_ENABLE, count=1, device_id=UNIT).bits[0], "enabled"

        hmi.write_registers(HR_TARGET, f64_registers(25.0), device_id=UNIT)
        hmi.write_registers(HR_VELOCITY, f64_registers(50.0), device_id=UNIT)
        hmi.write_coil(COIL_START, False, device_id=UNIT)
        hmi.write_coil(COIL_START, True, device_id=UNIT)  # the rising edge starts the move

        # The move takes 0.5 s at 50 mm/s plus its ramps: run virtual time until it is done.
        done = mcemu.advance(seconds=5, until={"axis": 0, "state": "standstill"})
        assert done["met"], done
        assert done["time"] > 0.5, "a 25 mm move at 50 mm/s cannot end sooner"

        position = f64_from(hmi.read_input_registers(IR_ACT_POS, count=4, device_id=UNIT).registers)
        assert position == 25.0
        assert hmi.read_input_registers(IR_STATE, count=1, device_id=UNIT).registers[0] == STANDSTILL
        assert hmi.read_discrete_inputs(DI_IN_POSITION, count=1, device_id=UNIT).bits[0]

    # The control API sees the same engine.
    assert mcemu.client.axis(0)["act_pos"] == 25.0
