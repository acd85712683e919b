"""Exceptions: what the control API refused, and why a machine did not start."""

from __future__ import annotations

from typing import Any, Mapping


class McemuError(Exception):
    """Base of every error this package raises."""


class ApiError(McemuError):
    """The control API answered with an error.

    ``status`` is the HTTP status, ``code`` the error's code (``limit_active``,
    ``malformed_json``, ``not_virtual_clock`` …) and ``fields`` the whole JSON body, so that
    the typed error's fields (``axis``, ``direction``, ``index``, ``field`` …) can be read as
    ``err.fields["axis"]`` or ``err["axis"]``. ``message`` is the API's sentence.
    """

    def __init__(self, status: int, body: Mapping[str, Any], request: str):
        self.status = status
        self.fields = dict(body)
        # Request and runtime errors say {"error", "detail"}; engine refusals {"code", "message"}.
        self.code = str(body.get("code") or body.get("error") or f"http_{status}")
        self.message = str(body.get("message") or body.get("detail") or "")
        self.request = request
        super().__init__(f"{request}: {status} {self.code}: {self.message}")

    def __getitem__(self, key: str) -> Any:
        return self.fields[key]

    def get(self, key: str, default: Any = None) -> Any:
        return self.fields.get(key, default)


class EngineRefused(ApiError):
    """HTTP 422: the request was understood and the engine said no (an ``EngineError``)."""


class RequestRejected(ApiError):
    """HTTP 4xx other than 422: the request was malformed or meaningless."""


class Unavailable(ApiError):
    """HTTP 5xx: the runtime was busy, stopped, or its servo thread died."""


def api_error(status: int, body: Mapping[str, Any], request: str) -> ApiError:
    """The exception class for an error reply."""
    if status == 422:
        return EngineRefused(status, body, request)
    if status >= 500:
        return Unavailable(status, body, request)
    return RequestRejected(status, body, request)


class StartError(McemuError):
    """``mcemu run`` exited, or printed no ``listening: control`` line in time.

    The message carries what mcemu printed: a config error names file, key and reason; a taken
    port names the address.
    """

    def __init__(self, why: str, command: list[str], log: str):
        self.why = why
        self.command = command
        self.log = log
        super().__init__(f"mcemu did not start: {why}\n$ {' '.join(command)}\n{log}".rstrip())
