"""A deterministic test: command a move, advance virtual time, and assert on the trace (every
servo tick of the axis, as the CSV export has it)."""

import pytest

import mcemu as mcemu_pkg


def test_a_move_traced_tick_by_tick(mcemu):
    c = mcemu.client
    c.command({"type": "enable", "axis": 0})
    c.trace_start(axes=[0])
    c.command(
        {"type": "move_absolute", "axis": 0, "position": 10.0, "velocity": 20.0,
         "acceleration": 200.0, "deceleration": 200.0}
    )
    mcemu.advance(seconds=2)
    c.trace_stop()
    rows = c.trace()

    period = mcemu.state()["period"]
    assert len(rows) == round(2 / period), "one row per tick"
    assert rows[-1]["cmd_pos"] == 10.0
    assert rows[-1]["state"] == "standstill"
    assert max(r["cmd_vel"] for r in rows) == pytest.approx(20.0)
    # A trapezoid with 0.1 s ramps: 10 mm at 20 mm/s takes 0.5 + 0.1 s.
    moving = [r for r in rows if r["cmd_vel"] > 0]
    assert len(moving) * period == pytest.approx(0.6, abs=2 * period)
    # The commanded position never goes back.
    assert all(b["cmd_pos"] >= a["cmd_pos"] for a, b in zip(rows, rows[1:]))


def test_the_engine_refuses_with_a_typed_error(mcemu):
    # Axis 1 is not enabled: the engine refuses, and the exception carries its fields.
    with pytest.raises(mcemu_pkg.EngineRefused) as refused:
        mcemu.client.command({"type": "move_absolute", "axis": 1, "position": 5.0})
    assert refused.value.status == 422
    assert refused.value["axis"] == 1
    assert refused.value.code == "axis_disabled"
