"""The plugin's fixtures: machines by name, config and overrides; side by side; what a failure
to start says."""

import socket
import subprocess
import sys
import textwrap

import pytest

import mcemu as mcemu_pkg


@pytest.mark.mcemu(machine="himc", set={"machine.period": 0.0005})
def test_the_marker_chooses_the_machine_and_overrides(mcemu):
    state = mcemu.state()
    assert state["machine"] == "hiwin-himc"
    assert state["period"] == 0.0005
    assert set(mcemu.addresses) >= {"modbus-tcp", "control"}


def test_two_machines_side_by_side_without_port_clashes(mcemu, mcemu_factory):
    other = mcemu_factory()
    assert mcemu.addresses["control"] != other.addresses["control"]
    assert mcemu.addresses["modbus-tcp"] != other.addresses["modbus-tcp"]
    mcemu.client.command({"type": "enable", "axis": 0})
    mcemu.advance(ticks=1)
    assert "enabled" in mcemu.client.axis(0)["flags"]
    assert "enabled" not in other.client.axis(0)["flags"], "separate engines"


def test_a_config_file(mcemu_factory, tmp_path):
    config = tmp_path / "rig.toml"
    config.write_text(
        textwrap.dedent(
            """
            [machine]
            name = "rig"
            [[axes]]
            name = "spindle"
            [frontends.control]
            bind = "127.0.0.1:8700"
            """
        )
    )
    m = mcemu_factory(config=config)
    assert m.state()["machine"] == "rig"
    assert list(m.addresses) == ["control"]


def test_a_config_that_does_not_validate_fails_with_mcemus_message(mcemu_factory, tmp_path):
    config = tmp_path / "bad.toml"
    config.write_text("[machine]\nperiod = -1\n")
    with pytest.raises(mcemu_pkg.StartError) as failed:
        mcemu_factory(config=config)
    text = str(failed.value)
    assert "exited with status" in text
    assert "bad.toml" in text and "period" in text


def test_an_unknown_machine_names_the_shipped_ones(mcemu_factory):
    with pytest.raises(mcemu_pkg.StartError, match="gaochuan-gcn"):
        mcemu_factory(machine="gcn")


def test_a_port_already_taken_names_the_address(mcemu_factory):
    with socket.socket() as taken:
        taken.bind(("127.0.0.1", 0))
        taken.listen()
        address = "%s:%d" % taken.getsockname()
        with pytest.raises(mcemu_pkg.StartError) as failed:
            mcemu_factory(set={"frontends.modbus_tcp.bind": address})
    assert address in str(failed.value)


def test_a_binary_that_exits_at_start_fails_at_once(mcemu_factory, tmp_path):
    fake = tmp_path / "mcemu"
    fake.write_text("#!/bin/sh\necho 'mcemu: broken on purpose' >&2\nexit 3\n")
    fake.chmod(0o755)
    with pytest.raises(mcemu_pkg.StartError) as failed:
        mcemu_factory(binary=fake)
    assert "status 3" in str(failed.value)
    assert "broken on purpose" in str(failed.value)


def test_a_failing_test_report_carries_the_mcemu_log(tmp_path):
    # A test made to fail on purpose, in its own pytest run: its report shows mcemu's output.
    (tmp_path / "test_fails.py").write_text(
        "def test_fails(mcemu):\n"
        "    mcemu.client.command({'type': 'enable', 'axis': 0})\n"
        "    assert False, 'on purpose'\n"
    )
    run = subprocess.run(
        [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", str(tmp_path)],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert run.returncode == 1, run.stdout + run.stderr
    assert "mcemu log" in run.stdout
    assert "listening: control 127.0.0.1:" in run.stdout
    assert "mcemu: machine default, 4 axes" in run.stdout


def test_keep_output_writes_each_log(tmp_path):
    (tmp_path / "test_passes.py").write_text("def test_passes(mcemu):\n    pass\n")
    logs = tmp_path / "logs"
    run = subprocess.run(
        [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider",
         f"--mcemu-keep-output={logs}", str(tmp_path)],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert run.returncode == 0, run.stdout + run.stderr
    (log,) = logs.iterdir()
    assert "mcemu: stopped" in log.read_text()
