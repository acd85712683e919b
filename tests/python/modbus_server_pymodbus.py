#!/usr/bin/env python3
"""A plain pymodbus Modbus TCP server over memory: the baseline of the Modbus load benchmark
and the peer of the harness self-test (tests/tests/harness.rs). Not mcemu.

Every unit id is served by one device: 10 000 holding registers, input registers, coils and
discrete inputs at addresses 0..9999, all zero at start; address 10 000 and beyond answer
exception 02. FC 17 and FC 43/14 report a fixed identity.

    modbus_server_pymodbus.py [--host 127.0.0.1] [--port 0] [--framer socket|rtu]
    modbus_server_pymodbus.py --device /dev/pts/N [--baud 19200]

Over TCP, `--framer rtu` serves RTU over TCP. With --device it serves RTU on that serial
device instead (a pty end made by socat, in the harness self-test).

Prints `ready HOST:PORT` (the bound port when --port 0), or `ready DEVICE`, on stdout once it
listens, then
serves until SIGTERM/SIGINT, or until the thread that started it exits (Linux
PR_SET_PDEATHSIG), so a killed test leaves no server behind.
"""

from __future__ import annotations

import argparse
import asyncio
import ctypes
import logging
import signal
import sys

from pymodbus import FramerType, ModbusDeviceIdentification
from pymodbus.server import ModbusSerialServer, ModbusTcpServer
from pymodbus.simulator import DataType, SimData, SimDevice

SIZE = 10_000


IDENTITY = {"VendorName": "pymodbus-baseline", "ProductCode": "PM", "MajorMinorRevision": "3.16.1"}


def device() -> SimDevice:
    bits = lambda: [SimData(0, values=[False] * SIZE, datatype=DataType.BITS)]  # noqa: E731
    regs = lambda: [SimData(0, values=[0] * SIZE, datatype=DataType.REGISTERS)]  # noqa: E731
    # Separate blocks: coils and discrete inputs are addressed bit by bit, registers word by
    # word, as on most devices. id 0: every unit id.
    return SimDevice(0, simdata=(bits(), bits(), regs(), regs()))


def die_with_parent() -> None:
    """Ask Linux to send SIGTERM when the parent thread exits."""
    pr_set_pdeathsig = 1
    libc = ctypes.CDLL(None, use_errno=True)
    if libc.prctl(pr_set_pdeathsig, signal.SIGTERM, 0, 0, 0) != 0:
        print("modbus_server_pymodbus: prctl(PR_SET_PDEATHSIG) failed", file=sys.stderr)
        sys.exit(1)


async def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--host", default="127.0.0.1")
    parser.add_argument("--port", type=int, default=0)
    parser.add_argument("--framer", choices=["socket", "rtu"], default="socket")
    parser.add_argument("--device", help="serve RTU on this serial device instead of TCP")
    parser.add_argument("--baud", type=int, default=19200)
    args = parser.parse_args()
    die_with_parent()
    # pymodbus logs deprecation warnings and per-connection notes on stderr; keep it quiet.
    logging.getLogger("pymodbus").setLevel(logging.ERROR)

    identity = ModbusDeviceIdentification(info_name=IDENTITY)
    server: ModbusTcpServer | ModbusSerialServer
    if args.device:
        server = ModbusSerialServer(
            device(), port=args.device, baudrate=args.baud, identity=identity
        )
        await server.serve_forever(background=True)
        print(f"ready {args.device}", flush=True)
    else:
        framer = FramerType.SOCKET if args.framer == "socket" else FramerType.RTU
        server = ModbusTcpServer(
            device(), address=(args.host, args.port), framer=framer, identity=identity
        )
        await server.serve_forever(background=True)
        listener = server.transport
        sockets = getattr(listener, "sockets", None)
        if not sockets:
            print(f"modbus_server_pymodbus: no listening socket ({listener!r})", file=sys.stderr)
            sys.exit(1)
        host, port = sockets[0].getsockname()[:2]
        print(f"ready {host}:{port}", flush=True)

    loop = asyncio.get_running_loop()
    stop = asyncio.Event()
    for sig in (signal.SIGTERM, signal.SIGINT):
        loop.add_signal_handler(sig, stop.set)
    await stop.wait()
    await server.shutdown()


if __name__ == "__main__":
    asyncio.run(main())
