"""python-canopen's LocalNode serving a DOMAIN: the baseline server of emulator/benches/canopen_sdo.rs.

    canopen_bench_localnode.py --interface socketcan --channel vcan0 --node 2 --index 0x2F00
    canopen_bench_localnode.py --interface socketcand --host 127.0.0.1 --port P --channel vcan0 ...

Serves node NODE with one read-write DOMAIN at INDEX:0 (python-canopen's SdoServer: expedited
and segmented transfers; it refuses block downloads and answers block uploads as segmented).
Prints "ready" once on the bus, then serves until its stdin ends (the bench holds it open).
"""

import argparse
import logging
import sys

import canopen

from canopen_bench_sdo import connect, dictionary


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--interface", choices=["socketcan", "socketcand"], required=True)
    p.add_argument("--channel", default="vcan0")
    p.add_argument("--host", default="127.0.0.1")
    p.add_argument("--port", type=int, default=29536)
    p.add_argument("--node", type=int, required=True)
    p.add_argument("--index", type=lambda s: int(s, 0), default=0x2F00)
    args = p.parse_args()
    logging.basicConfig(level=logging.CRITICAL)

    # Same TCP tuning as the client, so neither side waits on Nagle's algorithm.
    network = connect(args, tcp_tune=True)
    try:
        network.add_node(canopen.LocalNode(args.node, dictionary(args.index)))
        print("ready", flush=True)
        sys.stdin.read()
    finally:
        network.disconnect()


if __name__ == "__main__":
    main()
