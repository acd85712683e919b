#!/usr/bin/env python3
"""Drive a real Modbus client library with a list of operations; print the results as JSON.

The external-client harness of mcemu's tests: the Rust tests (mcemu-tests,
`run_python_client`) run this with the venv's python, pass operations as JSON on stdin and
read one JSON array of results from stdout, one result per operation, in order.

    modbus_client.py --client pymodbus|minimalmodbus
                     --transport tcp|rtu|rtu-over-tcp
                     [--host 127.0.0.1 --port 502] [--device /dev/pts/N --baud 19200
                     --parity N|E|O] [--unit 1] [--timeout 1.0]

Clients and transports:
  pymodbus       tcp (ModbusTcpClient), rtu (ModbusSerialClient on --device), rtu-over-tcp
                 (ModbusTcpClient with the RTU framer). Sync client, no retries.
  minimalmodbus  rtu only (Instrument on --device). Operations minimalmodbus has no method for
                 (mask_write_register, readwrite_registers, report_server_id,
                 read_device_information, diag_echo) are framed and checked by its own
                 `_embed_payload`/`_extract_payload` (address, function, exception, CRC); the
                 driver reads their answers' length from their first bytes.

Operations (stdin: a JSON array of objects; "op" names the operation; addresses are PDU
addresses, from 0):
  {"op": "read_coils", "address": A, "count": N}                 -> [bool, ...]
  {"op": "read_discrete_inputs", "address": A, "count": N}       -> [bool, ...]
  {"op": "read_holding_registers", "address": A, "count": N}     -> [int, ...]
  {"op": "read_input_registers", "address": A, "count": N}       -> [int, ...]
  {"op": "write_coil", "address": A, "value": bool}              -> null
  {"op": "write_register", "address": A, "value": int}           -> null
  {"op": "write_coils", "address": A, "values": [bool, ...]}     -> null
  {"op": "write_registers", "address": A, "values": [int, ...]}  -> null
  {"op": "mask_write_register", "address": A, "and_mask": M, "or_mask": M} -> null
  {"op": "readwrite_registers", "read_address": A, "read_count": N,
   "write_address": A, "values": [int, ...]}                     -> [int, ...] (read part)
  {"op": "report_server_id"}                  -> {"id": "hex of the server id bytes", "running": bool}
  {"op": "read_device_information", "read_code": 1..4, "object_id": 0}
        -> {"conformity": int, "more_follows": bool, "next_object_id": int,
            "objects": {"0": "text", ...}}  (object values decoded as latin-1)
  {"op": "diag_echo", "data": "hex"}                             -> "hex" echoed
        (FC 8 sub-function 0; pymodbus's RTU framer assumes 2 data bytes)
  {"op": "read_float", "address": A, "word_order": "big"|"little", "function": 3|4} -> float
  {"op": "write_float", "address": A, "value": float, "word_order": "big"|"little"} -> null
        ("big": high word first; "little": low word first, as HIMC. FC 16.)
  Any operation may carry "unit" to override --unit for that request.

Each result is {"ok": value}, {"exception": code} (the Modbus exception code the server
answered, an int) or {"error": "text"} (no answer, timeout, bad CRC, malformed answer…).
A bad operation (unknown op, missing argument) is a usage error: exit status 2 and a message
on stderr, never a result. There is no sleep operation on purpose: tests wait for state
through the control API, not through time.
"""

from __future__ import annotations

import argparse
import json
import logging
import re
import struct
import sys
import time
from typing import Any, Callable

Result = dict[str, Any]


class UsageError(Exception):
    pass


def arg(op: dict, name: str, default: Any = ...) -> Any:
    if name in op:
        return op[name]
    if default is ...:
        raise UsageError(f"operation {op.get('op')!r} needs {name!r}: {json.dumps(op)}")
    return default


def word_order(op: dict) -> str:
    order = arg(op, "word_order", "big")
    if order not in ("big", "little"):
        raise UsageError(f"word_order must be 'big' or 'little', not {order!r}")
    return order


# ---------------------------------------------------------------------------------------------
# pymodbus


class PymodbusDriver:
    def __init__(self, args: argparse.Namespace) -> None:
        from pymodbus import FramerType
        from pymodbus.client import ModbusSerialClient, ModbusTcpClient

        logging.getLogger("pymodbus").setLevel(logging.CRITICAL)
        self.unit = args.unit
        if args.transport in ("tcp", "rtu-over-tcp"):
            framer = FramerType.SOCKET if args.transport == "tcp" else FramerType.RTU
            self.client = ModbusTcpClient(
                args.host, port=args.port, framer=framer, timeout=args.timeout, retries=0
            )
        else:
            if not args.device:
                raise UsageError("--transport rtu needs --device")
            self.client = ModbusSerialClient(
                args.device,
                framer=FramerType.RTU,
                baudrate=args.baud,
                parity=args.parity,
                bytesize=8,
                stopbits=1,
                timeout=args.timeout,
                retries=0,
            )
        if not self.client.connect():
            raise ConnectionError(f"pymodbus could not connect ({args.transport})")

    def close(self) -> None:
        self.client.close()

    def run(self, op: dict) -> Result:
        from pymodbus.exceptions import ModbusException

        name = op["op"]
        handler: Callable[[dict, int], Any] | None = getattr(self, "op_" + name, None)
        if handler is None:
            raise UsageError(f"unknown operation {name!r}")
        unit = int(arg(op, "unit", self.unit))
        try:
            return handler(op, unit)
        except UsageError:
            raise
        except _Exc as e:
            return {"exception": e.code}
        except ModbusException as e:
            return {"error": f"{type(e).__name__}: {e}"}
        except (OSError, ValueError, struct.error) as e:
            return {"error": f"{type(e).__name__}: {e}"}

    def call(self, method: str, *a: Any, **kw: Any) -> Any:
        """Run one request; an exception response becomes a result, a missing one an error."""
        rr = getattr(self.client, method)(*a, **kw)
        if rr is None:
            raise ValueError("no response")
        if rr.isError():
            code = getattr(rr, "exception_code", None)
            if code is None:
                raise ValueError(f"error response {rr!r}")
            raise _Exc(int(code))
        return rr

    def op_read_coils(self, op: dict, unit: int) -> Result:
        n = int(arg(op, "count"))
        rr = self.call("read_coils", int(arg(op, "address")), count=n, device_id=unit)
        return {"ok": [bool(b) for b in rr.bits[:n]]}

    def op_read_discrete_inputs(self, op: dict, unit: int) -> Result:
        n = int(arg(op, "count"))
        rr = self.call("read_discrete_inputs", int(arg(op, "address")), count=n, device_id=unit)
        return {"ok": [bool(b) for b in rr.bits[:n]]}

    def op_read_holding_registers(self, op: dict, unit: int) -> Result:
        n = int(arg(op, "count"))
        rr = self.call("read_holding_registers", int(arg(op, "address")), count=n, device_id=unit)
        return {"ok": list(rr.registers)}

    def op_read_input_registers(self, op: dict, unit: int) -> Result:
        n = int(arg(op, "count"))
        rr = self.call("read_input_registers", int(arg(op, "address")), count=n, device_id=unit)
        return {"ok": list(rr.registers)}

    def op_write_coil(self, op: dict, unit: int) -> Result:
        self.call("write_coil", int(arg(op, "address")), bool(arg(op, "value")), device_id=unit)
        return {"ok": None}

    def op_write_register(self, op: dict, unit: int) -> Result:
        self.call("write_register", int(arg(op, "address")), int(arg(op, "value")), device_id=unit)
        return {"ok": None}

    def op_write_coils(self, op: dict, unit: int) -> Result:
        values = [bool(v) for v in arg(op, "values")]
        self.call("write_coils", int(arg(op, "address")), values, device_id=unit)
        return {"ok": None}

    def op_write_registers(self, op: dict, unit: int) -> Result:
        values = [int(v) for v in arg(op, "values")]
        self.call("write_registers", int(arg(op, "address")), values, device_id=unit)
        return {"ok": None}

    def op_mask_write_register(self, op: dict, unit: int) -> Result:
        self.call(
            "mask_write_register",
            address=int(arg(op, "address")),
            and_mask=int(arg(op, "and_mask")),
            or_mask=int(arg(op, "or_mask")),
            device_id=unit,
        )
        return {"ok": None}

    def op_readwrite_registers(self, op: dict, unit: int) -> Result:
        rr = self.call(
            "readwrite_registers",
            read_address=int(arg(op, "read_address")),
            read_count=int(arg(op, "read_count")),
            write_address=int(arg(op, "write_address")),
            values=[int(v) for v in arg(op, "values")],
            device_id=unit,
        )
        return {"ok": list(rr.registers)}

    def op_report_server_id(self, op: dict, unit: int) -> Result:
        rr = self.call("report_device_id", device_id=unit)
        return {"ok": {"id": bytes(rr.identifier).hex(), "running": bool(rr.status)}}

    def op_read_device_information(self, op: dict, unit: int) -> Result:
        rr = self.call(
            "read_device_information",
            read_code=int(arg(op, "read_code", 1)),
            object_id=int(arg(op, "object_id", 0)),
            device_id=unit,
        )
        objects = {}
        for oid, value in rr.information.items():
            values = value if isinstance(value, list) else [value]
            objects[str(oid)] = "".join(bytes(v).decode("latin-1") for v in values)
        return {
            "ok": {
                "conformity": int(rr.conformity),
                "more_follows": bool(rr.more_follows),
                "next_object_id": int(rr.next_object_id),
                "objects": objects,
            }
        }

    def op_diag_echo(self, op: dict, unit: int) -> Result:
        data = bytes.fromhex(arg(op, "data"))
        rr = self.call("diag_query_data", data, device_id=unit)
        message = rr.message
        if isinstance(message, int):
            message = struct.pack(">H", message)
        elif isinstance(message, (list, tuple)):
            message = b"".join(struct.pack(">H", w) for w in message)
        return {"ok": bytes(message).hex()}

    def op_read_float(self, op: dict, unit: int) -> Result:
        function = int(arg(op, "function", 3))
        method = {3: "read_holding_registers", 4: "read_input_registers"}.get(function)
        if method is None:
            raise UsageError("read_float: function must be 3 or 4")
        rr = self.call(method, int(arg(op, "address")), count=2, device_id=unit)
        value = self.client.convert_from_registers(
            rr.registers, self.client.DATATYPE.FLOAT32, word_order=word_order(op)
        )
        return {"ok": float(value)}

    def op_write_float(self, op: dict, unit: int) -> Result:
        regs = self.client.convert_to_registers(
            float(arg(op, "value")), self.client.DATATYPE.FLOAT32, word_order=word_order(op)
        )
        self.call("write_registers", int(arg(op, "address")), regs, device_id=unit)
        return {"ok": None}


class _Exc(Exception):
    """A Modbus exception response (code)."""

    def __init__(self, code: int) -> None:
        super().__init__(code)
        self.code = code


# ---------------------------------------------------------------------------------------------
# minimalmodbus

# minimalmodbus raises one of a few classes per exception code, with a fixed message
# (`_check_response_slaveerrorcode`); the code is recovered from the message.
_MINIMALMODBUS_MESSAGES = {
    "Slave reported illegal function": 1,
    "Slave reported illegal data address": 2,
    "Slave reported illegal data value": 3,
    "Slave reported device failure": 4,
    "Slave reported device busy": 6,
    "Slave reported negative acknowledge": 7,
    "Slave reported memory parity error": 8,
    "Slave reported gateway path unavailable": 10,
    "Slave reported gateway target device failed to respond": 11,
}


class MinimalmodbusDriver:
    def __init__(self, args: argparse.Namespace) -> None:
        import minimalmodbus
        import serial

        if args.transport != "rtu":
            raise UsageError("minimalmodbus speaks RTU over a serial device only (--transport rtu)")
        if not args.device:
            raise UsageError("--transport rtu needs --device")
        self.mm = minimalmodbus
        self.unit = args.unit
        self.instrument = minimalmodbus.Instrument(args.device, args.unit, minimalmodbus.MODE_RTU)
        port = self.instrument.serial
        port.baudrate = args.baud
        port.parity = {"N": serial.PARITY_NONE, "E": serial.PARITY_EVEN, "O": serial.PARITY_ODD}[
            args.parity
        ]
        port.bytesize = 8
        port.stopbits = 1
        port.timeout = args.timeout
        self.instrument.clear_buffers_before_each_transaction = True

    def close(self) -> None:
        self.instrument.serial.close()

    def run(self, op: dict) -> Result:
        name = op["op"]
        handler = getattr(self, "op_" + name, None)
        if handler is None:
            raise UsageError(f"unknown operation {name!r}")
        self.instrument.address = int(arg(op, "unit", self.unit))
        try:
            return handler(op)
        except UsageError:
            raise
        except self.mm.SlaveReportedException as e:
            text = str(e)
            code = _MINIMALMODBUS_MESSAGES.get(text)
            if code is None:
                m = re.fullmatch(r"Slave reported error code (\d+)", text)
                if not m:
                    return {"error": f"unrecognised exception report: {text}"}
                code = int(m.group(1))
            return {"exception": code}
        except (self.mm.ModbusException, OSError, ValueError, TypeError) as e:
            return {"error": f"{type(e).__name__}: {e}"}

    def raw(self, function: int, payload: bytes) -> bytes:
        """One request for a function minimalmodbus has no method for. The frame is built and
        the answer checked (address, function, exception, CRC) by minimalmodbus's own
        `_embed_payload` and `_extract_payload`; the answer's length, which minimalmodbus cannot
        predict for these functions, is read from its first bytes as a server's would be."""
        mm = self.mm
        port = self.instrument.serial
        address = self.instrument.address
        request = mm._embed_payload(address, mm.MODE_RTU, function, payload)  # noqa: SLF001
        port.reset_input_buffer()
        # The 3.5-character silence before a request, kept as minimalmodbus keeps it.
        silence = mm._calculate_minimum_silent_period(port.baudrate)  # noqa: SLF001
        since_read = time.monotonic() - mm._latest_read_times.get(port.port, 0)  # noqa: SLF001
        if since_read < silence:
            time.sleep(silence - since_read)
        port.write(request)
        port.flush()
        answer = bytearray()

        def need(n: int) -> None:
            while len(answer) < n:
                chunk = port.read(n - len(answer))
                if not chunk:
                    if not answer:
                        raise mm.NoResponseError("No communication with the instrument (no answer)")
                    raise mm.InvalidResponseError(f"answer ends after {bytes(answer).hex()}")
                answer.extend(chunk)

        need(3)
        if answer[1] & 0x80:
            need(5)
        elif function in (0x11, 0x17):  # byte count at 2
            need(3 + answer[2] + 2)
        elif function == 0x08:  # echo
            need(len(request))
        elif function == 0x16:
            need(10)
        elif function == 0x2B:  # MEI header, then (id, length, value) objects
            need(8)
            at = 8
            for _ in range(answer[7]):
                need(at + 2)
                at += 2 + answer[at + 1]
            need(at + 2)
        else:
            raise UsageError(f"raw function {function} has no known answer length")
        mm._latest_read_times[port.port] = time.monotonic()  # noqa: SLF001
        return mm._extract_payload(bytes(answer), address, mm.MODE_RTU, function)  # noqa: SLF001

    def op_read_coils(self, op: dict) -> Result:
        bits = self.instrument.read_bits(int(arg(op, "address")), int(arg(op, "count")), 1)
        return {"ok": [bool(b) for b in bits]}

    def op_read_discrete_inputs(self, op: dict) -> Result:
        bits = self.instrument.read_bits(int(arg(op, "address")), int(arg(op, "count")), 2)
        return {"ok": [bool(b) for b in bits]}

    def op_read_holding_registers(self, op: dict) -> Result:
        regs = self.instrument.read_registers(int(arg(op, "address")), int(arg(op, "count")), 3)
        return {"ok": list(regs)}

    def op_read_input_registers(self, op: dict) -> Result:
        regs = self.instrument.read_registers(int(arg(op, "address")), int(arg(op, "count")), 4)
        return {"ok": list(regs)}

    def op_write_coil(self, op: dict) -> Result:
        self.instrument.write_bit(int(arg(op, "address")), int(bool(arg(op, "value"))), 5)
        return {"ok": None}

    def op_write_register(self, op: dict) -> Result:
        self.instrument.write_register(int(arg(op, "address")), int(arg(op, "value")), 0, 6)
        return {"ok": None}

    def op_write_coils(self, op: dict) -> Result:
        values = [int(bool(v)) for v in arg(op, "values")]
        self.instrument.write_bits(int(arg(op, "address")), values)
        return {"ok": None}

    def op_write_registers(self, op: dict) -> Result:
        self.instrument.write_registers(int(arg(op, "address")), [int(v) for v in arg(op, "values")])
        return {"ok": None}

    def op_mask_write_register(self, op: dict) -> Result:
        payload = struct.pack(
            ">HHH", int(arg(op, "address")), int(arg(op, "and_mask")), int(arg(op, "or_mask"))
        )
        answer = self.raw(0x16, payload)
        if answer != payload:
            return {"error": f"mask write echo {answer.hex()} != request {payload.hex()}"}
        return {"ok": None}

    def op_readwrite_registers(self, op: dict) -> Result:
        values = [int(v) for v in arg(op, "values")]
        payload = struct.pack(
            ">HHHHB",
            int(arg(op, "read_address")),
            int(arg(op, "read_count")),
            int(arg(op, "write_address")),
            len(values),
            2 * len(values),
        ) + b"".join(struct.pack(">H", v) for v in values)
        answer = self.raw(0x17, payload)
        if not answer or answer[0] != len(answer) - 1 or answer[0] % 2:
            return {"error": f"malformed FC 23 answer {answer.hex()}"}
        return {"ok": [int.from_bytes(answer[i : i + 2], "big") for i in range(1, len(answer), 2)]}

    def op_report_server_id(self, op: dict) -> Result:
        answer = self.raw(0x11, b"")
        if len(answer) < 2 or answer[0] != len(answer) - 1:
            return {"error": f"malformed FC 17 answer {answer.hex()}"}
        # Byte count, server id, run indicator (last byte), as pymodbus reads it.
        return {"ok": {"id": answer[1:-1].hex(), "running": answer[-1] == 0xFF}}

    def op_read_device_information(self, op: dict) -> Result:
        read_code = int(arg(op, "read_code", 1))
        answer = self.raw(0x2B, bytes([0x0E, read_code, int(arg(op, "object_id", 0))]))
        if len(answer) < 6 or answer[0] != 0x0E:
            return {"error": f"malformed FC 43 answer {answer.hex()}"}
        objects: dict[str, str] = {}
        at, count = 6, answer[5]
        for _ in range(count):
            if at + 2 > len(answer):
                return {"error": f"truncated FC 43 answer {answer.hex()}"}
            oid, length = answer[at], answer[at + 1]
            value = answer[at + 2 : at + 2 + length]
            if len(value) != length:
                return {"error": f"truncated FC 43 answer {answer.hex()}"}
            objects[str(oid)] = objects.get(str(oid), "") + value.decode("latin-1")
            at += 2 + length
        if at != len(answer):
            return {"error": f"trailing bytes in FC 43 answer {answer.hex()}"}
        return {
            "ok": {
                "conformity": answer[2],
                "more_follows": answer[3] == 0xFF,
                "next_object_id": answer[4],
                "objects": objects,
            }
        }

    def op_diag_echo(self, op: dict) -> Result:
        payload = b"\x00\x00" + bytes.fromhex(arg(op, "data"))
        answer = self.raw(0x08, payload)
        if answer[:2] != b"\x00\x00":
            return {"error": f"FC 8 answer for another sub-function: {answer.hex()}"}
        return {"ok": answer[2:].hex()}

    def byteorder(self, op: dict) -> int:
        return self.mm.BYTEORDER_BIG if word_order(op) == "big" else self.mm.BYTEORDER_LITTLE_SWAP

    def op_read_float(self, op: dict) -> Result:
        function = int(arg(op, "function", 3))
        if function not in (3, 4):
            raise UsageError("read_float: function must be 3 or 4")
        value = self.instrument.read_float(
            int(arg(op, "address")), function, 2, byteorder=self.byteorder(op)
        )
        return {"ok": float(value)}

    def op_write_float(self, op: dict) -> Result:
        self.instrument.write_float(
            int(arg(op, "address")), float(arg(op, "value")), 2, byteorder=self.byteorder(op)
        )
        return {"ok": None}


def main() -> int:
    parser = argparse.ArgumentParser(
        description=__doc__.splitlines()[0], formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--client", choices=["pymodbus", "minimalmodbus"], required=True)
    parser.add_argument("--transport", choices=["tcp", "rtu", "rtu-over-tcp"], required=True)
    parser.add_argument("--host", default="127.0.0.1")
    parser.add_argument("--port", type=int, default=502)
    parser.add_argument("--device", help="serial device for --transport rtu")
    parser.add_argument("--baud", type=int, default=19200)
    parser.add_argument("--parity", choices=["N", "E", "O"], default="N")
    parser.add_argument("--unit", type=int, default=1)
    parser.add_argument("--timeout", type=float, default=1.0, help="seconds per request")
    args = parser.parse_args()

    try:
        ops = json.load(sys.stdin)
        if not isinstance(ops, list) or not all(isinstance(o, dict) and "op" in o for o in ops):
            raise UsageError('stdin must be a JSON array of {"op": ...} objects')
        driver = (PymodbusDriver if args.client == "pymodbus" else MinimalmodbusDriver)(args)
        try:
            results = [driver.run(op) for op in ops]
        finally:
            driver.close()
    except (UsageError, json.JSONDecodeError) as e:
        print(f"modbus_client: {e}", file=sys.stderr)
        return 2
    except OSError as e:  # could not connect or open the device: nothing ran
        print(f"modbus_client: {type(e).__name__}: {e}", file=sys.stderr)
        return 1
    json.dump(results, sys.stdout)
    sys.stdout.write("\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
