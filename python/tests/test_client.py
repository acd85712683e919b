"""mcemu.Client against every route of the control API, including its typed errors, on real
mcemu processes started by the plugin's fixtures."""

import pytest

import mcemu


def test_routes_lists_every_route_the_client_has_a_method_for(mcemu):
    paths = {r["path"] for r in mcemu.client.routes()}
    assert paths >= {
        "/api/v1", "/api/v1/state", "/api/v1/commands", "/api/v1/inputs", "/api/v1/faults",
        "/api/v1/time/advance", "/api/v1/trace/start", "/api/v1/trace/stop", "/api/v1/trace",
        "/api/v1/canopen/log/start", "/api/v1/canopen/log/stop",
    }


def test_state_and_axis(mcemu):
    state = mcemu.client.state()
    assert state["machine"] == "default"
    assert state["clock"] == "virtual"
    assert len(state["axes"]) == 4
    assert mcemu.client.axis(2) == state["axes"][2]
    assert mcemu.client.tick() == state["tick"] == 0


def test_one_command_a_list_and_an_atomic_list(mcemu):
    c = mcemu.client
    reply = c.command({"type": "enable", "axis": 0})
    assert reply == {"reply": "done"}
    replies = c.commands([{"type": "enable", "axis": 1}, {"type": "enable", "axis": 2}])
    assert [r["reply"] for r in replies] == ["done", "done"]
    moves = c.command(
        [
            {"type": "move_absolute", "axis": 0, "position": 1.0},
            {"type": "move_absolute", "axis": 1, "position": 2.0},
        ],
        atomic=True,
    )
    assert [m["reply"] for m in moves] == ["accepted", "accepted"]
    assert moves[0]["id"] != moves[1]["id"]
    mcemu.advance(ticks=1)
    axes = c.state()["axes"]
    assert axes[0]["state"] == axes[1]["state"] == "discrete_motion", "same tick"


def test_an_atomic_list_with_a_refused_command_applies_nothing(mcemu):
    with pytest.raises(__import__("mcemu").EngineRefused) as refused:
        mcemu.client.command(
            [{"type": "enable", "axis": 0}, {"type": "move_absolute", "axis": 3, "position": 1}],
            atomic=True,
        )
    assert refused.value["index"] == 1
    assert "enabled" not in mcemu.client.axis(0)["flags"]


def test_an_unknown_command_is_a_rejected_request_naming_the_variant(mcemu):
    with pytest.raises(__import__("mcemu").RequestRejected) as rejected:
        mcemu.client.command({"type": "fly", "axis": 0})
    assert rejected.value.status == 400
    assert rejected.value.code == "invalid_body"
    assert "fly" in rejected.value.message


def test_inputs_axis_digital_analog_and_release(mcemu):
    c = mcemu.client
    c.force_input(0, "limit_pos", True)
    c.force_di(3, True)
    c.force_ai(1, 2.5)
    mcemu.advance(ticks=1)
    state = c.state()
    assert "hw_limit_pos" in state["axes"][0]["flags"]
    assert state["io"]["di"][3] is True
    assert state["io"]["ai"][1] == 2.5
    c.force_input(0, "limit_pos", None)
    mcemu.advance(ticks=1)
    assert "hw_limit_pos" not in c.axis(0)["flags"]
    with pytest.raises(__import__("mcemu").ApiError) as bad:
        c.force_di(10_000, True)
    assert bad.value.code == "invalid_channel"


def test_faults_inject_and_clear(mcemu):
    c = mcemu.client
    c.command({"type": "enable", "axis": 0})
    c.inject_fault(0, "drive_alarm")
    mcemu.advance(ticks=2)
    assert c.axis(0)["state"] == "error_stop"
    c.clear_fault(0, "drive_alarm")
    mcemu.advance(ticks=1)
    c.command({"type": "reset", "axis": 0})
    mcemu.advance(ticks=1)
    assert c.axis(0)["state"] != "error_stop"


def test_advance_by_ticks_seconds_and_until(mcemu):
    c = mcemu.client
    assert mcemu.advance(ticks=10)["tick"] == 10
    assert mcemu.advance(seconds=0.5)["tick"] == 510
    c.command({"type": "enable", "axis": 0})
    c.command({"type": "move_relative", "axis": 0, "distance": 1.0})
    done = mcemu.advance(seconds=10, until={"axis": 0, "state": "standstill"})
    assert done["met"] and done["ticks_run"] < 10_000
    with pytest.raises(ValueError):
        c.advance()


def test_trace_rows_and_csv(mcemu):
    c = mcemu.client
    c.trace_start(axes=[1], max_rows=100)
    mcemu.advance(ticks=5)
    c.trace_stop()
    rows = c.trace()
    assert [r["axis"] for r in rows] == [1] * 5
    assert isinstance(rows[0]["time_s"], float) and rows[0]["state"] == "disabled"
    assert c.trace_csv().splitlines()[0].startswith("time_s,axis,state,")


def test_trace_frame_needs_pandas_only_when_called(mcemu):
    try:
        import pandas  # noqa: F401
    except ImportError:
        with pytest.raises(ImportError, match="pip install pandas"):
            mcemu.client.trace_frame()
    else:
        mcemu.client.trace_start()
        mcemu.advance(ticks=2)
        assert len(mcemu.client.trace_frame()) == 8


def test_can_log_on_a_machine_without_a_bus_is_a_typed_conflict(mcemu, tmp_path):
    with pytest.raises(__import__("mcemu").RequestRejected) as conflict:
        mcemu.client.can_log_start(tmp_path / "bus.log")
    assert (conflict.value.status, conflict.value.code) == (409, "no_can_bus")


@pytest.mark.mcemu(machine="cia402-can")
def test_can_log_start_and_stop(mcemu, tmp_path):
    log = tmp_path / "bus.log"
    assert mcemu.client.can_log_start(log)["logging"] is True
    mcemu.advance(ticks=10)
    stopped = mcemu.client.can_log_stop()
    assert stopped["logging"] is False and log.exists()


@pytest.mark.mcemu(clock="realtime")
def test_advance_on_a_realtime_clock_is_refused(mcemu):
    with pytest.raises(__import__("mcemu").RequestRejected) as refused:
        mcemu.advance(ticks=1)
    assert (refused.value.status, refused.value.code) == (409, "not_virtual_clock")
