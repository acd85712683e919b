"""python-can's real `socketcand` interface against mcemu's socketcand server.

Frames are JSON objects {"id": int, "ext": bool, "data": "hex"}.

    can_socketcand.py exchange --host H --port P --channel vcan0 --expect N --send JSON --out FILE
        One client: prints "ready" once connected (raw mode), receives N frames, then sends the
        frames of JSON; writes {"received": [...]} to FILE.

    can_socketcand.py pair --host H --port P --channel vcan0 --send-a JSON --send-b JSON
        Two clients A and B: A sends, B receives; B sends, A receives; each also checks that it
        does not get its own frames. Prints {"b_got": [...], "a_got": [...], "a_own": n,
        "b_own": n} on stdout.

Exit status 0 unless something could not run (the JSON says what was received; the Rust test
judges it).
"""

import argparse
import json
import sys
import time

import can

RECV_TIMEOUT = 5.0


def to_json(msg):
    return {
        "id": msg.arbitration_id,
        "ext": msg.is_extended_id,
        "data": bytes(msg.data).hex(),
        "timestamp": msg.timestamp,
        "error": msg.is_error_frame,
    }


def to_message(frame):
    return can.Message(
        arbitration_id=frame["id"],
        is_extended_id=frame["ext"],
        data=bytes.fromhex(frame["data"]),
    )


def receive(bus, count, timeout=RECV_TIMEOUT):
    got = []
    deadline = time.monotonic() + timeout
    while len(got) < count and time.monotonic() < deadline:
        msg = bus.recv(timeout=max(0.0, deadline - time.monotonic()))
        if msg is not None:
            got.append(to_json(msg))
    return got


def drain(bus, quiet=0.3):
    """Frames that arrive within `quiet` seconds (should be none)."""
    got = []
    while True:
        msg = bus.recv(timeout=quiet)
        if msg is None:
            return got
        got.append(to_json(msg))


def open_bus(args):
    return can.Bus(
        interface="socketcand", host=args.host, port=args.port, channel=args.channel
    )


def exchange(args):
    bus = open_bus(args)
    try:
        print("ready", flush=True)
        received = receive(bus, args.expect)
        for frame in json.loads(args.send):
            bus.send(to_message(frame))
        # Let the frames leave before the socket closes.
        time.sleep(0.2)
    finally:
        bus.shutdown()
    with open(args.out, "w") as out:
        json.dump({"received": received}, out)


def pair(args):
    a = open_bus(args)
    b = open_bus(args)
    try:
        send_a = json.loads(args.send_a)
        send_b = json.loads(args.send_b)
        # Both clients are in raw mode once the constructors return; frames are held for the
        # server's settle time after that, so give them a moment before sending.
        time.sleep(0.1)
        for frame in send_a:
            a.send(to_message(frame))
        b_got = receive(b, len(send_a))
        for frame in send_b:
            b.send(to_message(frame))
        a_got = receive(a, len(send_b))
        a_own = drain(a)
        b_own = drain(b)
    finally:
        a.shutdown()
        b.shutdown()
    json.dump(
        {"b_got": b_got, "a_got": a_got, "a_own": len(a_own), "b_own": len(b_own)},
        sys.stdout,
    )


def main():
    parser = argparse.ArgumentParser()
    sub = parser.add_subparsers(dest="scenario", required=True)
    for name in ("exchange", "pair"):
        p = sub.add_parser(name)
        p.add_argument("--host", default="127.0.0.1")
        p.add_argument("--port", type=int, required=True)
        p.add_argument("--channel", default="vcan0")
        if name == "exchange":
            p.add_argument("--expect", type=int, default=0)
            p.add_argument("--send", default="[]")
            p.add_argument("--out", required=True)
        else:
            p.add_argument("--send-a", default="[]")
            p.add_argument("--send-b", default="[]")
    args = parser.parse_args()
    {"exchange": exchange, "pair": pair}[args.scenario](args)


if __name__ == "__main__":
    main()
