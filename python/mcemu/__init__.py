"""mcemu for test suites: start a machine, drive its control API, advance virtual time.

``Machine`` starts ``mcemu run`` (virtual clock, every port free) and parses what listens
where; ``Client`` is the typed control-API client; installing the package also installs the
``mcemu`` command and a pytest plugin with the ``mcemu`` fixture (see ``mcemu.pytest_plugin``).
"""

from .client import Client
from .errors import (
    ApiError,
    EngineRefused,
    McemuError,
    RequestRejected,
    StartError,
    Unavailable,
)
from .machine import Machine, find_binary

__all__ = [
    "ApiError",
    "Client",
    "EngineRefused",
    "Machine",
    "McemuError",
    "RequestRejected",
    "StartError",
    "Unavailable",
    "find_binary",
]
