"""Start an ``mcemu run`` process, read what listens where, stop it.

``Machine`` is what the pytest fixture yields and what a script uses directly::

    with mcemu.Machine(machine="himc") as m:        # virtual clock, every port free
        m.client.command({"type": "enable", "axis": 0})
        m.advance(seconds=0.01)
        print(m.addresses["modbus-tcp"])
"""

from __future__ import annotations

import os
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path
from typing import Any, Mapping, Sequence

from .client import Client
from .errors import McemuError, StartError

#: How long ``mcemu run`` may take to print ``listening: control``.
READY_TIMEOUT = 60.0
#: How long it may take to stop after SIGTERM before it is killed.
STOP_TIMEOUT = 30.0


def find_binary(binary: str | os.PathLike | None = None) -> Path:
    """The ``mcemu`` executable: ``binary`` if given, else ``$MCEMU_BIN``, else the one this
    package installed beside the running Python (the venv's ``bin/``), else ``mcemu`` on
    ``PATH``."""
    if binary is None:
        binary = os.environ.get("MCEMU_BIN") or None
    if binary is not None:
        path = Path(binary)
        if not path.is_file():
            raise McemuError(f"the mcemu binary {path} is not a file")
        return path
    scripts = Path(sys.executable).parent
    for name in ("mcemu", "mcemu.exe"):
        if (scripts / name).is_file():
            return scripts / name
    found = shutil.which("mcemu")
    if found is None:
        raise McemuError(
            "no mcemu binary: install the package (pip install ./python), set MCEMU_BIN, "
            "or pass --mcemu-binary"
        )
    return Path(found)


def _override(key: str, value: Any) -> str:
    """``--set key=value`` with the value as TOML."""
    if isinstance(value, bool):
        text = "true" if value else "false"
    elif isinstance(value, (int, float)):
        text = repr(value)
    elif isinstance(value, str):
        text = '"' + value.replace("\\", "\\\\").replace('"', '\\"') + '"'
    elif isinstance(value, (list, tuple)):
        text = "[" + ", ".join(_override("v", v).split("=", 1)[1] for v in value) + "]"
    else:
        raise TypeError(f"--set {key}: {value!r} is not a TOML scalar or array")
    return f"{key}={text}"


class Machine:
    """One ``mcemu run`` process.

    Which machine: ``config`` (a path), or ``machine`` (a shipped one by name: ``default``,
    ``himc``, ``gaochuan-gcn``, ``gaochuan-gcn-ecat``, ``hollysys-mc``, ``cpu226h``,
    ``cia402-can``), else the default. ``set`` overrides config keys (``{"machine.period": 0.0005}``). ``clock`` is
    ``virtual`` unless told (``realtime``, ``scaled:K``, or ``None`` for the config's own).
    Every TCP listener binds a free port (``mcemu run --any-port``), and the state directory is
    a fresh temporary one unless ``state_dir`` is given, so machines run side by side.

    After :meth:`start`: ``addresses`` maps each ``listening:`` name (``modbus-tcp``,
    ``modbus-rtu``, ``control`` …) to the address or path printed, ``client`` is the control
    API's :class:`Client`, and :meth:`log` is everything mcemu printed.
    """

    def __init__(
        self,
        config: str | os.PathLike | None = None,
        machine: str | None = None,
        set: Mapping[str, Any] | None = None,
        clock: str | None = "virtual",
        period: str | float | None = None,
        state_dir: str | os.PathLike | None = None,
        binary: str | os.PathLike | None = None,
        args: Sequence[str] = (),
        ready_timeout: float = READY_TIMEOUT,
    ):
        if config is not None and machine is not None:
            raise ValueError("give config= or machine=, not both")
        self.config = Path(config) if config is not None else None
        self.machine = machine
        self.overrides = dict(set or {})
        self.clock = clock
        self.period = period
        self.binary = find_binary(binary)
        self.extra_args = list(args)
        self.ready_timeout = ready_timeout
        self._state_dir = Path(state_dir) if state_dir is not None else None
        self._temp: tempfile.TemporaryDirectory | None = None
        self.process: subprocess.Popen | None = None
        self.addresses: dict[str, str] = {}
        self.client: Client | None = None
        self.argv: list[str] = []
        self._lines: list[str] = []
        self._stderr: list[str] = []
        self._ready = threading.Event()
        self._lock = threading.Lock()
        self._readers: list[threading.Thread] = []

    # --- lifecycle -------------------------------------------------------------------------

    def start(self) -> "Machine":
        """Start mcemu and return once its control API listens (its line is printed last, so
        every front-end listens too). Raises :class:`StartError` with mcemu's own message if it
        exits or stays silent."""
        if self.process is not None:
            raise McemuError("this machine was started already")
        command = [str(self.binary), "run", "--any-port"]
        if self.config is not None:
            command += ["--config", str(self.config)]
        if self.machine is not None:
            command += ["--machine", self.machine]
        if self.clock is not None:
            command += ["--clock", self.clock]
        if self.period is not None:
            command += ["--period", str(self.period)]
        if self._state_dir is None:
            self._temp = tempfile.TemporaryDirectory(prefix="mcemu-state-")
            self._state_dir = Path(self._temp.name)
        command += ["--state-dir", str(self._state_dir)]
        for key, value in self.overrides.items():
            command += ["--set", _override(key, value)]
        command += self.extra_args
        self.argv = command
        try:
            self.process = subprocess.Popen(
                command,
                stdin=subprocess.DEVNULL,
                stdout=subprocess.PIPE,
                stderr=subprocess.PIPE,
                text=True,
                bufsize=1,
            )
        except OSError as e:
            raise StartError(f"cannot run {self.binary}: {e}", command, "") from None
        self._readers = [
            threading.Thread(target=self._read_stdout, daemon=True),
            threading.Thread(target=self._read_stderr, daemon=True),
        ]
        for reader in self._readers:
            reader.start()
        deadline = time.monotonic() + self.ready_timeout
        while not self._ready.wait(0.05):
            code = self.process.poll()
            if code is not None:
                for reader in self._readers:
                    reader.join(5)
                raise StartError(f"mcemu exited with status {code}", command, self.log())
            if time.monotonic() > deadline:
                self._kill()
                raise StartError(
                    f"no `listening: control` line within {self.ready_timeout:g} s",
                    command,
                    self.log(),
                )
        self.client = Client(self.addresses["control"])
        return self

    def _read_stdout(self) -> None:
        assert self.process is not None and self.process.stdout is not None
        for line in self.process.stdout:
            line = line.rstrip("\n")
            with self._lock:
                self._lines.append(line)
            if line.startswith("listening: "):
                name, _, address = line[len("listening: ") :].partition(" ")
                self.addresses[name] = address.strip()
                if name == "control":
                    self._ready.set()

    def _read_stderr(self) -> None:
        assert self.process is not None and self.process.stderr is not None
        for line in self.process.stderr:
            with self._lock:
                self._stderr.append(line.rstrip("\n"))

    def stop(self, timeout: float = STOP_TIMEOUT) -> int | None:
        """SIGTERM, wait for mcemu to stop its axes and exit (killed after ``timeout``); its
        exit status. Idempotent."""
        process = self.process
        if process is None:
            return None
        if process.poll() is None:
            process.send_signal(signal.SIGTERM)
            try:
                process.wait(timeout)
            except subprocess.TimeoutExpired:
                self._kill()
        for reader in self._readers:
            reader.join(5)
        if self._temp is not None:
            self._temp.cleanup()
            self._temp = None
        return process.returncode

    def _kill(self) -> None:
        if self.process is not None and self.process.poll() is None:
            self.process.kill()
            self.process.wait()

    def __enter__(self) -> "Machine":
        return self.start()

    def __exit__(self, *exc: object) -> None:
        self.stop()

    # --- what it printed -------------------------------------------------------------------

    def log(self) -> str:
        """Everything mcemu printed so far: stdout, then stderr."""
        with self._lock:
            out = "\n".join(self._lines)
            err = "\n".join(self._stderr)
        return out + ("\n--- stderr\n" + err if err else "")

    @property
    def running(self) -> bool:
        return self.process is not None and self.process.poll() is None

    # --- conveniences ----------------------------------------------------------------------

    def address(self, name: str) -> str:
        """The address printed for listener ``name``; a clear error naming the ones there are."""
        try:
            return self.addresses[name]
        except KeyError:
            raise McemuError(
                f"this machine has no `{name}` listener (it has {sorted(self.addresses)})"
            ) from None

    def host_port(self, name: str) -> tuple[str, int]:
        """A TCP listener's address as ``(host, port)``."""
        host, _, port = self.address(name).rpartition(":")
        return host, int(port)

    def advance(
        self,
        seconds: float | None = None,
        ticks: int | None = None,
        until: Mapping[str, Any] | None = None,
    ) -> dict:
        """Run the virtual clock (see :meth:`Client.advance`)."""
        return self._client().advance(seconds=seconds, ticks=ticks, until=until)

    def command(self, command, atomic: bool = False):
        """Apply one command or a list (see :meth:`Client.command`)."""
        return self._client().command(command, atomic=atomic)

    def state(self) -> dict:
        return self._client().state()

    def _client(self) -> Client:
        if self.client is None:
            raise McemuError("the machine is not started")
        return self.client
