"""python-can on vcan0 (part of tests/vcan/selftest, run through tests/vcan/run).

Two socketcan buses on vcan0: one sends a standard frame with a random payload, the other
must receive it; then a BCM periodic send (python-can's `send_periodic` on socketcan, which
needs the can-bcm module) of an extended frame every 10 ms, of which the receiver must see
five. Prints one line per check; with --out FILE, also writes what it received as JSON.
Exits 1 with the reason on any failure.
"""

import argparse
import json
import os
import sys
import time

import can

TIMEOUT = 10.0


def fail(why: str) -> None:
    print(f"python-can: FAILED: {why}", file=sys.stderr)
    sys.exit(1)


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--out", help="write the received frames to this JSON file")
    args = parser.parse_args()

    payload = os.urandom(4)
    periodic_id = 0x18FF0001
    filters = [
        {"can_id": 0x124, "can_mask": 0x7FF, "extended": False},
        {"can_id": periodic_id, "can_mask": 0x1FFFFFFF, "extended": True},
    ]
    result = {"interface": "socketcan", "channel": "vcan0", "python_can": can.__version__}
    with can.Bus(interface="socketcan", channel="vcan0", can_filters=filters) as rx, can.Bus(
        interface="socketcan", channel="vcan0"
    ) as tx:
        tx.send(can.Message(arbitration_id=0x124, data=payload, is_extended_id=False))
        deadline = time.monotonic() + TIMEOUT
        got = None
        while got is None and time.monotonic() < deadline:
            msg = rx.recv(timeout=deadline - time.monotonic())
            if msg is not None and msg.arbitration_id == 0x124 and bytes(msg.data) == payload:
                got = msg
        if got is None:
            fail(f"no frame 124#{payload.hex().upper()} received within {TIMEOUT} s")
        frame = f"124#{bytes(got.data).hex().upper()}"
        print(f"python-can: received {frame}")
        result["frame"] = frame

        task = tx.send_periodic(
            can.Message(arbitration_id=periodic_id, data=b"\x01\x02", is_extended_id=True),
            period=0.01,
        )
        seen = 0
        deadline = time.monotonic() + TIMEOUT
        while seen < 5 and time.monotonic() < deadline:
            msg = rx.recv(timeout=deadline - time.monotonic())
            if msg is not None and msg.arbitration_id == periodic_id and msg.is_extended_id:
                seen += 1
        task.stop()
        if seen < 5:
            fail(f"periodic send: {seen} of 5 frames {periodic_id:08X}#0102 within {TIMEOUT} s")
        print(f"python-can: periodic send, received 5 frames {periodic_id:08X}#0102")
        result["periodic"] = {"id": f"{periodic_id:08X}", "received": seen}

    if args.out:
        with open(args.out, "w", encoding="utf-8") as f:
            json.dump(result, f)


if __name__ == "__main__":
    main()
