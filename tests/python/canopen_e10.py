"""python-canopen (a real CANopen master) against a node of mcemu, over socketcand.

    canopen_e10.py --host H --port P --channel vcan0 --node 2 --eds FILE < ops.json

Reads a JSON list of operations on stdin, runs them in order on one connection and prints one
JSON result per operation on stdout:

    {"op": "sdo_read", "index": 0x20CC, "sub": 0}           -> {"ok": "hex bytes"} | {"abort": code}
    {"op": "sdo_write", "index": I, "sub": S, "data": "hex"} -> {"ok": true} | {"abort": code}
    {"op": "nmt", "state": "OPERATIONAL"}                   -> {"ok": true}
    {"op": "read_pdo_config"}                                -> {"ok": {"rpdo1": [names], "tpdo1": …}}
        (python-canopen's PdoMaps.read(): the mapping read back over SDO)
    {"op": "frames", "cob_id": 0x182}                        -> {"ok": ["hex", …]}
        (every frame with that identifier received since the connection opened)
    {"op": "wait_frame", "cob_id": 0x182, "timeout": 5}     -> {"ok": "hex"} | {"timeout": true}
        (the first frame with that identifier received from now on)
    {"op": "send", "cob_id": 0x202, "data": "hex"}          -> {"ok": true}
    {"op": "sleep", "seconds": 0.2}                          -> {"ok": true}
    {"op": "stamps", "cob_id": 0x702}                        -> {"ok": [seconds, …]}
        (the bus timestamps of those frames, as socketcand gives them: mcemu's bus time)
    {"op": "clear"} / {"op": "clear", "cob_id": 0x702}      -> {"ok": true}
        (forget the frames received so far, of every identifier or of one)
    {"op": "wait_count", "cob_id": 0x702, "count": 1, "timeout": 5}
                                                             -> {"ok": ["hex", …]} | {"timeout": [...]}
        (every frame with that identifier since the last clear, once there are `count`)
    {"op": "advance", "body": {"ticks": 1000}, "repeat": 1}  -> {"ok": last reply}
        (POST /time/advance to the control API of --control, `repeat` times in a row)

Frames from mcemu reach this process in the order mcemu sent them (one hub, one socketcand
connection): an SDO answer received means every frame the node sent before it was recorded.

Exit status 0 unless something could not run; the Rust test judges the results.
"""

import argparse
import json
import sys
import threading
import time
import urllib.request

import canopen


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--host", default="127.0.0.1")
    p.add_argument("--port", type=int, required=True)
    p.add_argument("--channel", default="vcan0")
    p.add_argument("--node", type=int, required=True)
    p.add_argument("--eds", required=True)
    p.add_argument("--control", help="the control API, http://HOST:PORT/api/v1 (for advance)")
    args = p.parse_args()
    ops = json.load(sys.stdin)

    network = canopen.Network()
    received = {}
    stamps = {}
    lock = threading.Lock()
    cond = threading.Condition(lock)

    def record(cob_id, data, timestamp):
        with cond:
            received.setdefault(cob_id, []).append(bytes(data).hex())
            stamps.setdefault(cob_id, []).append(timestamp)
            cond.notify_all()

    network.connect(
        interface="socketcand", host=args.host, port=args.port, channel=args.channel
    )
    # python-can's socketcand interface needs a moment in raw mode before frames flow.
    time.sleep(0.3)
    node = canopen.RemoteNode(args.node, args.eds)
    node.sdo.RESPONSE_TIMEOUT = 3.0
    network.add_node(node)
    subscribed = set()

    def subscribe(cob_id):
        if cob_id not in subscribed:
            network.subscribe(cob_id, record)
            subscribed.add(cob_id)

    # The TPDOs and EMCY of the node, from the start.
    for cob_id in (0x180, 0x280, 0x380, 0x480, 0x80, 0x700):
        subscribe(cob_id + args.node)

    results = []
    for op in ops:
        kind = op["op"]
        try:
            if kind == "sdo_read":
                data = node.sdo.upload(op["index"], op.get("sub", 0))
                results.append({"ok": bytes(data).hex()})
            elif kind == "sdo_write":
                node.sdo.download(op["index"], op.get("sub", 0), bytes.fromhex(op["data"]))
                results.append({"ok": True})
            elif kind == "nmt":
                node.nmt.state = op["state"]
                results.append({"ok": True})
            elif kind == "read_pdo_config":
                node.rpdo.read()
                node.tpdo.read()
                out = {}
                for prefix, maps in (("rpdo", node.rpdo), ("tpdo", node.tpdo)):
                    for n, m in maps.map.items():
                        if m.enabled:
                            out[f"{prefix}{n}"] = [v.od.index for v in m.map]
                results.append({"ok": out})
            elif kind == "frames":
                subscribe(op["cob_id"])
                with cond:
                    results.append({"ok": list(received.get(op["cob_id"], []))})
            elif kind == "stamps":
                subscribe(op["cob_id"])
                with cond:
                    results.append({"ok": list(stamps.get(op["cob_id"], []))})
            elif kind == "wait_frame":
                cob_id = op["cob_id"]
                subscribe(cob_id)
                deadline = time.monotonic() + op.get("timeout", 5.0)
                with cond:
                    start = len(received.get(cob_id, []))
                    while len(received.get(cob_id, [])) <= start:
                        left = deadline - time.monotonic()
                        if left <= 0:
                            break
                        cond.wait(left)
                    got = received.get(cob_id, [])
                    if len(got) > start:
                        results.append({"ok": got[start]})
                    else:
                        results.append({"timeout": True})
            elif kind == "send":
                network.send_message(op["cob_id"], bytes.fromhex(op["data"]))
                results.append({"ok": True})
            elif kind == "sleep":
                time.sleep(op["seconds"])
                results.append({"ok": True})
            elif kind == "clear":
                with cond:
                    if "cob_id" in op:
                        received.pop(op["cob_id"], None)
                        stamps.pop(op["cob_id"], None)
                    else:
                        received.clear()
                        stamps.clear()
                results.append({"ok": True})
            elif kind == "wait_count":
                cob_id = op["cob_id"]
                subscribe(cob_id)
                deadline = time.monotonic() + op.get("timeout", 5.0)
                with cond:
                    while len(received.get(cob_id, [])) < op["count"]:
                        left = deadline - time.monotonic()
                        if left <= 0:
                            break
                        cond.wait(left)
                    got = list(received.get(cob_id, []))
                    results.append({"ok": got} if len(got) >= op["count"] else {"timeout": got})
            elif kind == "advance":
                body = json.dumps(op["body"]).encode()
                reply = None
                for _ in range(op.get("repeat", 1)):
                    request = urllib.request.Request(
                        args.control + "/time/advance", data=body, method="POST",
                        headers={"content-type": "application/json"})
                    with urllib.request.urlopen(request, timeout=60) as r:
                        reply = json.loads(r.read())
                results.append({"ok": reply})
            else:
                results.append({"error": f"unknown op {kind}"})
        except canopen.SdoAbortedError as e:
            results.append({"abort": e.code})
        except canopen.SdoCommunicationError as e:
            results.append({"error": f"SDO: {e}"})
    network.disconnect()
    json.dump(results, sys.stdout)
    sys.stdout.write("\n")


if __name__ == "__main__":
    main()
