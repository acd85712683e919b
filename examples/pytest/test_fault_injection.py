"""Fault injection: the Modbus server answers a request with an exception on purpose, and the
HMI code under test must survive it (here a small polling routine with a retry).

Front-end faults go through the control API's `/faults` route, named by the front-end's config
section (`modbus_tcp`); `count` limits how many requests they hit. Everything else (the engine,
other clients) keeps running.
"""

import pytest
from pymodbus.client import ModbusTcpClient

import mcemu as mcemu_pkg

UNIT = 1
IR_TICK = 2000  # generic.toml: the machine tick, u32, high word first


def read_tick(hmi, attempts=3):
    """The code under test: read the machine tick, retrying on an exception response."""
    for _ in range(attempts):
        rr = hmi.read_input_registers(IR_TICK, count=2, device_id=UNIT)
        if not rr.isError():
            return (rr.registers[0] << 16) | rr.registers[1]
    raise IOError(f"no tick after {attempts} attempts: {rr}")


def test_the_hmi_survives_a_server_busy_exception(mcemu):
    host, port = mcemu.host_port("modbus-tcp")
    mcemu.advance(ticks=42)
    # Exception 06 (server device busy) for the next two FC 4 requests.
    mcemu.client.fault(
        {"frontend": "modbus_tcp", "fault": "exception", "code": 6, "function": 4, "count": 2}
    )
    with ModbusTcpClient(host, port=port, timeout=5, retries=0) as hmi:
        assert hmi.connect()
        first = hmi.read_input_registers(IR_TICK, count=2, device_id=UNIT)
        assert first.isError() and first.exception_code == 6
        assert read_tick(hmi) == 42  # one more busy reply, then the value

    modbus = next(f for f in mcemu.state()["frontends"] if f["name"] == "modbus_tcp")
    assert modbus["counters"]["faults_applied"]["exception"] == 2
    assert modbus["active_faults"] == []


def test_a_bad_fault_is_a_typed_error(mcemu):
    with pytest.raises(mcemu_pkg.RequestRejected) as refused:
        mcemu.client.fault({"frontend": "modbus_x", "fault": "clear"})
    assert refused.value.status == 400
    assert refused.value.code == "no_such_frontend"
