"""The pytest plugin (registered through the ``pytest11`` entry point, so installing the
package is enough).

Fixtures:

- ``mcemu``: a started :class:`mcemu.Machine` on the virtual clock with every port free,
  stopped at teardown. Which machine comes from the test's marker::

      @pytest.mark.mcemu(machine="himc")                # a shipped machine by name
      @pytest.mark.mcemu(config="rig.toml", set={"machine.period": 0.0005})
      @pytest.mark.mcemu(clock="scaled:10")

  and is the default machine without one. It has ``addresses``, ``client``, ``advance()``.
- ``mcemu_factory``: ``mcemu_factory(machine="himc", …)`` starts another machine (same
  arguments as :class:`mcemu.Machine`), several per test if needed, all stopped at teardown.

A failing test's report gets a section with each of its machines' logs (what mcemu printed).

Options: ``--mcemu-binary PATH`` (else ``$MCEMU_BIN``, else the installed one) and
``--mcemu-keep-output DIR`` (write every machine's log to ``DIR/<test>.log``, passed tests too).
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any, Callable, Iterator

import pytest

from .machine import Machine

_MACHINES = pytest.StashKey[list]()


def pytest_addoption(parser: pytest.Parser) -> None:
    group = parser.getgroup("mcemu")
    group.addoption(
        "--mcemu-binary",
        metavar="PATH",
        default=None,
        help="the mcemu executable (default: $MCEMU_BIN, else the one the package installed)",
    )
    group.addoption(
        "--mcemu-keep-output",
        metavar="DIR",
        default=None,
        help="write each machine's log (what mcemu printed) to DIR/<test>.log",
    )


def pytest_configure(config: pytest.Config) -> None:
    config.addinivalue_line(
        "markers",
        "mcemu(machine=None, config=None, set=None, clock='virtual', period=None): "
        "which machine the `mcemu` fixture starts",
    )


def _machines(item: pytest.Item) -> list:
    machines = item.stash.get(_MACHINES, None)
    if machines is None:
        machines = []
        item.stash[_MACHINES] = machines
    return machines


@pytest.fixture
def mcemu_factory(request: pytest.FixtureRequest) -> Iterator[Callable[..., Machine]]:
    """Start machines (arguments of :class:`mcemu.Machine`); all stopped at teardown."""
    started = _machines(request.node)
    binary = request.config.getoption("--mcemu-binary")

    def start(**kwargs: Any) -> Machine:
        kwargs.setdefault("binary", binary)
        machine = Machine(**kwargs)
        started.append(machine)
        return machine.start()

    yield start
    for machine in started:
        machine.stop()
    keep = request.config.getoption("--mcemu-keep-output")
    if keep:
        directory = Path(keep)
        directory.mkdir(parents=True, exist_ok=True)
        name = re.sub(r"[^A-Za-z0-9_.-]+", "_", request.node.nodeid)
        for i, machine in enumerate(started):
            suffix = f"-{i}" if len(started) > 1 else ""
            (directory / f"{name}{suffix}.log").write_text(machine.log() + "\n")


@pytest.fixture
def mcemu(request: pytest.FixtureRequest, mcemu_factory: Callable[..., Machine]) -> Machine:
    """A started machine: the marker's, else the default (virtual clock, free ports)."""
    marker = request.node.get_closest_marker("mcemu")
    kwargs = dict(marker.kwargs) if marker is not None else {}
    return mcemu_factory(**kwargs)


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item: pytest.Item, call: pytest.CallInfo) -> Iterator[None]:
    outcome = yield
    report = outcome.get_result()
    if not report.failed:
        return
    for i, machine in enumerate(item.stash.get(_MACHINES, [])):
        title = "mcemu log" + (f" ({i})" if i else "")
        command = " ".join(machine.argv)
        report.sections.append((title, f"$ {command}\n{machine.log()}"))
