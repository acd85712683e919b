"""A typed client for mcemu's HTTP control API (`/api/v1`), standard library only.

Every method is one request; errors raise :class:`mcemu.errors.ApiError` subclasses carrying
the typed error's code and fields. Routes and shapes: the README and ``docs/decisions.md``
("Control API") of the mcemu repository.
"""

from __future__ import annotations

import csv
import io
import json
import urllib.error
import urllib.request
from typing import Any, Iterable, Mapping, Sequence

from .errors import api_error

Command = Mapping[str, Any]

# Trace CSV columns that are not numbers.
_TEXT_COLUMNS = {"state", "error"}


class Client:
    """The control API of one running mcemu.

    ``Client("http://127.0.0.1:8700")`` or ``Client("127.0.0.1:8700")``; ``timeout`` bounds
    each request in seconds.
    """

    def __init__(self, address: str, timeout: float = 60.0):
        if not address.startswith(("http://", "https://")):
            address = "http://" + address
        address = address.rstrip("/")
        if not address.endswith("/api/v1"):
            address += "/api/v1"
        self.base = address
        self.timeout = timeout

    def __repr__(self) -> str:
        return f"Client({self.base!r})"

    # --- transport -------------------------------------------------------------------------

    def _request(self, method: str, path: str, body: Any = None, raw: bool = False) -> Any:
        url = self.base + path
        data = None
        headers = {"Accept": "application/json"}
        if body is not None:
            data = json.dumps(body).encode()
            headers["Content-Type"] = "application/json"
        request = urllib.request.Request(url, data=data, method=method, headers=headers)
        what = f"{method} {path}" + (f" {json.dumps(body)}" if body is not None else "")
        try:
            with urllib.request.urlopen(request, timeout=self.timeout) as response:
                payload = response.read()
                if raw:
                    return payload.decode(), dict(response.headers)
                return json.loads(payload) if payload else None
        except urllib.error.HTTPError as e:
            payload = e.read()
            try:
                parsed = json.loads(payload)
            except ValueError:
                parsed = {"error": f"http_{e.code}", "detail": payload.decode(errors="replace")}
            if not isinstance(parsed, dict):
                parsed = {"error": f"http_{e.code}", "detail": str(parsed)}
            raise api_error(e.code, parsed, what) from None

    def get(self, path: str) -> Any:
        """``GET /api/v1{path}``: the JSON reply."""
        return self._request("GET", path)

    def post(self, path: str, body: Any = None) -> Any:
        """``POST /api/v1{path}`` with a JSON body: the JSON reply."""
        return self._request("POST", path, body)

    # --- state -----------------------------------------------------------------------------

    def routes(self) -> list[dict]:
        """``GET /api/v1``: the routes with their methods."""
        return self.get("")["routes"]

    def state(self) -> dict:
        """``GET /state``: machine, clock, tick, axes, I/O, drives, groups, front-ends, runtime."""
        return self.get("/state")

    def axis(self, axis: int) -> dict:
        """One axis's record from ``/state`` (``state``, ``flags``, ``cmd_pos``, ``act_pos`` …)."""
        return self.state()["axes"][axis]

    def tick(self) -> int:
        return int(self.state()["tick"])

    # --- commands --------------------------------------------------------------------------

    def command(self, command: Command | Sequence[Command], atomic: bool = False) -> Any:
        """``POST /commands``: one command (a dict with ``type``) or a list, in order.

        ``atomic=True`` applies a list between two servo ticks, all or none. Returns the reply
        (``{"reply": "accepted", "id": 3}``) or the list of replies.
        """
        path = "/commands?atomic=true" if atomic else "/commands"
        if not isinstance(command, Mapping):
            command = list(command)
        return self.post(path, command)

    def commands(self, commands: Iterable[Command], atomic: bool = False) -> list:
        """``command`` for a list, always answering a list."""
        return self.command(list(commands), atomic=atomic)

    # --- inputs and faults -----------------------------------------------------------------

    def force_input(self, axis: int, input: str, value: bool | None) -> Any:
        """Force an axis input (``limit_pos``, ``limit_neg``, ``home``, ``index``,
        ``drive_alarm``, ``encoder_loss``); ``None`` releases it to the simulation."""
        return self.post("/inputs", {"axis": axis, "input": input, "value": value})

    def force_di(self, channel: int, value: bool | None) -> Any:
        """Force a digital input; ``None`` releases it."""
        return self.post("/inputs", {"di": channel, "value": value})

    def force_ai(self, channel: int, value: float | None) -> Any:
        """Force an analog input; ``None`` releases it."""
        return self.post("/inputs", {"ai": channel, "value": value})

    def fault(self, body: Mapping[str, Any]) -> Any:
        """``POST /faults`` with any fault object (axis faults, or ``{"frontend": NAME, …}``)."""
        return self.post("/faults", dict(body))

    def inject_fault(
        self, axis: int, fault: str, amount: float | None = None, active: bool = True
    ) -> Any:
        """An axis fault: ``drive_alarm``, ``encoder_loss``, or ``following_error`` with an
        ``amount`` in user units. ``active=False`` clears it (a ``reset`` command then clears
        what latched)."""
        body: dict[str, Any] = {"axis": axis, "fault": fault, "active": active}
        if amount is not None:
            body["amount"] = amount
        return self.fault(body)

    def clear_fault(self, axis: int, fault: str) -> Any:
        return self.inject_fault(axis, fault, active=False)

    # --- virtual time ----------------------------------------------------------------------

    def advance(
        self,
        seconds: float | None = None,
        ticks: int | None = None,
        until: Mapping[str, Any] | None = None,
    ) -> dict:
        """``POST /time/advance`` on the virtual clock: run ``ticks`` or ``seconds``, ending
        early once ``until`` holds (``{"axis": 0, "state": "standstill"}`` or
        ``{"axis": 0, "flag": "in_position", "value": True}``). Answers ``tick``, ``time``,
        ``ticks_run`` and, with ``until``, ``met``."""
        if (seconds is None) == (ticks is None):
            raise ValueError("advance takes seconds= or ticks=, exactly one")
        body: dict[str, Any] = {"seconds": seconds} if ticks is None else {"ticks": ticks}
        if until is not None:
            body["until"] = dict(until)
        return self.post("/time/advance", body)

    # --- traces ----------------------------------------------------------------------------

    def trace_start(self, axes: Sequence[int] | None = None, max_rows: int | None = None) -> Any:
        """Start recording every tick of ``axes`` (all when ``None``)."""
        body: dict[str, Any] = {}
        if axes is not None:
            body["axes"] = list(axes)
        if max_rows is not None:
            body["max_rows"] = max_rows
        return self.post("/trace/start", body)

    def trace_stop(self) -> Any:
        return self.post("/trace/stop", {})

    def trace_csv(self) -> str:
        """``GET /trace``: the recording as CSV text."""
        text, _ = self._request("GET", "/trace", raw=True)
        return text

    def trace(self) -> list[dict[str, Any]]:
        """The recording as rows: one dict per tick per axis, numbers as ``int``/``float``."""
        return [_typed_row(row) for row in csv.DictReader(io.StringIO(self.trace_csv()))]

    def trace_frame(self):
        """The recording as a pandas ``DataFrame`` (needs pandas, which this package does not
        require)."""
        try:
            import pandas
        except ImportError as e:  # pragma: no cover - depends on the environment
            raise ImportError("trace_frame() needs pandas: pip install pandas") from e
        return pandas.read_csv(io.StringIO(self.trace_csv()))

    # --- CAN log ---------------------------------------------------------------------------

    def can_log_start(self, path: str) -> dict:
        """Start a ``candump -L`` log of the CAN bus into a new file ``path``."""
        return self.post("/canopen/log/start", {"path": str(path)})

    def can_log_stop(self) -> dict:
        """Stop the CAN log: ``lines`` and ``dropped``."""
        return self.post("/canopen/log/stop", {})


def _typed_row(row: Mapping[str, str]) -> dict[str, Any]:
    typed: dict[str, Any] = {}
    for key, text in row.items():
        if key in _TEXT_COLUMNS or text is None:
            typed[key] = text
            continue
        try:
            typed[key] = int(text)
        except ValueError:
            try:
                typed[key] = float(text)
            except ValueError:
                typed[key] = text
    return typed
