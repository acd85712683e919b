"""A CiA 402 profile-position move with python-canopen's BaseNode402, over socketcand (no
SocketCAN needed), against the shipped `cia402-can` machine: four CiA 402 servos, node ids 1–4,
described by fixtures/canopen/cia402-drive.eds. The clock is real time here: BaseNode402 waits
for PDOs in its own threads, so the drive must run while the test waits.

Two things trip up a first attempt, as they would on a real drive with the CiA 402 default
PDO mapping (mcemu behaves as the drive does; the tests below show both):

1. `node.state = "OPERATION ENABLED"` waits until it times out unless SYNC runs: the TPDO that
   maps the statusword (0x6041) is synchronous, so without SYNC no statusword ever arrives.
   Start SYNC (`network.sync.start(0.01)`) or give that TPDO an event timer.
2. `node.op_mode = …` sends RPDO2 whole, and RPDO2 also carries the controlword, as 0 ("disable
   voltage"): an enabled drive drops to SWITCH ON DISABLED. Write 0x6060 by SDO instead (or
   remap RPDO2 to 0x6060 alone), or set the mode before enabling.
"""

import time
from pathlib import Path

import canopen
import pytest
from canopen.profiles.p402 import BaseNode402

EDS = str(Path(__file__).resolve().parents[2] / "fixtures/canopen/cia402-drive.eds")
INC_PER_MM = 10_000  # the fixture's drives: 10 000 increments per mm


def wait_until(what, timeout, probe, interval=0.01):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        value = probe()
        if value:
            return value
        time.sleep(interval)
    raise AssertionError(f"timed out after {timeout} s waiting for {what}")


@pytest.fixture
def network(mcemu):
    host, port = mcemu.host_port("socketcand")
    net = canopen.Network()
    net.connect(interface="socketcand", host=host, port=port, channel="vcan0")
    yield net
    net.sync.stop()
    net.disconnect()


def drive(network, node_id):
    node = BaseNode402(node_id, EDS)
    network.add_node(node)
    node.nmt.state = "PRE-OPERATIONAL"
    node.setup_402_state_machine()  # reads the PDO mapping over SDO
    network.sync.start(0.01)  # pitfall 1: the statusword TPDO is synchronous
    node.nmt.state = "OPERATIONAL"
    return node


@pytest.mark.mcemu(machine="cia402-can", clock="realtime")
def test_profile_position_move(mcemu, network):
    node = drive(network, 1)
    node.sdo[0x6060].raw = 1  # pitfall 2: profile position, by SDO
    node.state = "OPERATION ENABLED"
    assert node.state == "OPERATION ENABLED"

    node.sdo[0x6081].raw = 200_000  # profile velocity: 20 mm/s
    node.sdo[0x607A].raw = 100_000  # target: 10 mm
    node.controlword = 0x000F
    node.controlword = 0x001F  # bit 4 rising: new set-point
    wait_until("set-point acknowledge", 2, lambda: node.sdo[0x6041].raw & 0x1000)
    node.controlword = 0x000F
    wait_until(
        "target reached at 100 000 increments",
        10,
        lambda: node.sdo[0x6041].raw & 0x0400 and node.sdo[0x6064].raw == 100_000,
    )
    # The engine behind the drive agrees: axis 0 (node 1) is at 10 mm.
    axis = wait_until("axis 0 at rest", 2, lambda: (a := mcemu.client.axis(0))["act_vel"] == 0 and a)
    assert round(axis["act_pos"] * INC_PER_MM) == 100_000


@pytest.mark.mcemu(machine="cia402-can", clock="realtime")
def test_op_mode_on_an_enabled_drive_sends_controlword_0(mcemu, network):
    node = drive(network, 2)
    node.state = "OPERATION ENABLED"
    node.op_mode = "PROFILED POSITION"  # RPDO2: controlword 0 + mode 1
    wait_until(
        "switch on disabled",
        2,
        lambda: mcemu.state()["drives"][1]["state"] == "switch_on_disabled",
    )
