"""python-canopen's SDO client timing transfers of a DOMAIN, for emulator/benches/canopen_sdo.rs.

    canopen_bench_sdo.py --interface socketcan --channel vcan0 --node 1 --index 0x2F00 \
        --reps 3 --transfer block:102400 --transfer segmented:1024
    canopen_bench_sdo.py --interface socketcand --host 127.0.0.1 --port 29536 --channel vcan0 ...

For each --transfer MODE:SIZE (MODE block or segmented), REPS times: a download of SIZE random
bytes, then an upload of the object, compared with what was written. Block transfers use
`sdo.open(..., block_transfer=True)` (CRC on), segmented ones `sdo.download`/`sdo.upload`
(python-canopen segments anything above 4 bytes). Each transfer is timed from the call to its
return with `time.perf_counter`.

Prints one JSON object a line on stdout:
    {"mode": "block", "size": 102400, "direction": "down", "ms": [..], "error": null}
one for "down" and one for "up" per transfer; "error" is the first failure's text (an
SdoAbortedError names its abort code as "abort 0x05040001"), after which that transfer's
remaining repetitions are not run. A wrong upload is an error ("upload differs ..."). After a
failed download the upload is still tried once (unverified), so that a server's answer to
both directions shows. Exit status
0 unless the bus could not be opened.

--tcp-tune on|off: python-can's socketcand `tcp_tune` (TCP_NODELAY and TCP_QUICKACK on the
client socket; python-can's default is off). --timeout: python-canopen's SDO response timeout
(its default, 0.3 s, is too short for a TCG VM).
"""

import argparse
import json
import logging
import os
import sys
import time

import canopen
from canopen.objectdictionary import DOMAIN, ODVariable


def connect(args, tcp_tune):
    network = canopen.Network()
    if args.interface == "socketcand":
        network.connect(
            interface="socketcand",
            host=args.host,
            port=args.port,
            channel=args.channel,
            tcp_tune=tcp_tune,
        )
    else:
        network.connect(interface=args.interface, channel=args.channel)
    return network


def dictionary(index):
    od = canopen.ObjectDictionary()
    var = ODVariable("benchmark domain", index, 0)
    var.data_type = DOMAIN
    var.access_type = "rw"
    od.add_object(var)
    return od


def describe(exc):
    if isinstance(exc, canopen.SdoAbortedError):
        return f"abort 0x{exc.code:08X}"
    return f"{type(exc).__name__}: {exc}"


def transfer(node, index, mode, size, reps):
    down = {"mode": mode, "size": size, "direction": "down", "ms": [], "error": None}
    up = {"mode": mode, "size": size, "direction": "up", "ms": [], "error": None}
    for _ in range(reps):
        data = os.urandom(size)
        try:
            start = time.perf_counter()
            if mode == "block":
                with node.sdo.open(index, 0, "wb", size=size, block_transfer=True) as f:
                    f.write(data)
            else:
                node.sdo.download(index, 0, data)
            down["ms"].append((time.perf_counter() - start) * 1e3)
        except Exception as exc:  # noqa: BLE001 - reported to the bench, which judges it
            down["error"] = describe(exc)
            data = None
        # The upload runs even after a failed download (it then reads what an earlier transfer
        # left, unverified), so that a server's refusal of either direction shows.
        try:
            start = time.perf_counter()
            if mode == "block":
                with node.sdo.open(index, 0, "rb", block_transfer=True) as f:
                    back = f.read()
            else:
                back = node.sdo.upload(index, 0)
            elapsed = (time.perf_counter() - start) * 1e3
        except Exception as exc:  # noqa: BLE001
            up["error"] = describe(exc)
            break
        if data is None:
            up["error"] = f"unverified: the download failed ({len(back)} bytes read)"
            up["ms"].append(elapsed)
            break
        if back != data:
            up["error"] = f"upload differs from the download ({len(back)} of {size} bytes)"
            break
        up["ms"].append(elapsed)
    return [down, up]


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--interface", choices=["socketcan", "socketcand"], required=True)
    p.add_argument("--channel", default="vcan0")
    p.add_argument("--host", default="127.0.0.1")
    p.add_argument("--port", type=int, default=29536)
    p.add_argument("--tcp-tune", choices=["on", "off"], default="on")
    p.add_argument("--node", type=int, required=True)
    p.add_argument("--index", type=lambda s: int(s, 0), default=0x2F00)
    p.add_argument("--reps", type=int, default=3)
    p.add_argument("--timeout", type=float, default=5.0)
    p.add_argument("--transfer", action="append", required=True, help="MODE:SIZE")
    args = p.parse_args()
    # python-can logs a warning for every socketcand read that ends inside a frame, and
    # python-canopen an error for every abort: the JSON says what failed.
    logging.basicConfig(level=logging.CRITICAL)

    network = connect(args, args.tcp_tune == "on")
    try:
        node = canopen.RemoteNode(args.node, dictionary(args.index))
        network.add_node(node)
        node.sdo.RESPONSE_TIMEOUT = args.timeout
        for spec in args.transfer:
            mode, size = spec.split(":")
            if mode not in ("block", "segmented"):
                sys.exit(f"--transfer {spec}: mode is block or segmented")
            for result in transfer(node, args.index, mode, int(size), args.reps):
                print(json.dumps(result), flush=True)
    finally:
        network.disconnect()


if __name__ == "__main__":
    main()
