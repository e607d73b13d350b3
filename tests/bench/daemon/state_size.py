#!/usr/bin/env python3
"""How large gimbald's STATE datagrams are (issue 8, "lean streams").

Starts `gimbald --sim` (the embedded simulated Orion), asks the gimbal for every report and
settings packet it can be asked for (so every STATE key is filled), waits for the periodic
telemetry kinds, then measures the full STATE as a subscriber receives it and a subscription
restricted to `keys: ["telemetry"]`.

A benchmark, not a test (never run by ctest). Python 3 standard library only. Usage:

    state_size.py --gimbald build/release/daemon/gimbald

Targets (issue 8): full STATE at most 6,000 bytes; telemetry-only at most 1,200 bytes.
"""

import argparse
import json
import os
import re
import signal
import socket
import subprocess
import tempfile
import time

FULL_TARGET = 6000
TELEMETRY_TARGET = 1200


def free_port():
    s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    s.bind(("127.0.0.1", 0))
    port = s.getsockname()[1]
    s.close()
    return port


class Client:
    def __init__(self, port):
        self.port = port
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.sock.bind(("127.0.0.1", 0))
        self.sock.settimeout(2.0)
        self.n = 0

    def request(self, cmd, **params):
        self.n += 1
        params.update(cmd=cmd, id=self.n)
        self.sock.sendto(json.dumps(params).encode(), ("127.0.0.1", self.port))
        while True:
            data = self.sock.recv(65536)
            msg = json.loads(data)
            if msg.get("id") == self.n and "ok" in msg:
                return msg

    def next_state(self, timeout=3.0):
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            data = self.sock.recv(65536)
            if json.loads(data).get("type") == "state":
                return data
        raise TimeoutError("no STATE datagram")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--gimbald", required=True)
    p.add_argument("--settle", type=float, default=3.0,
                   help="seconds to wait for the requested packets and periodic reports")
    args = p.parse_args()

    port = free_port()
    tmp = tempfile.mkdtemp(prefix="state-size-")
    config = os.path.join(tmp, "c.json")
    with open(config, "w") as f:
        json.dump({"command": {"port": port}, "log": {"level": "warn"}}, f)
    proc = subprocess.Popen([args.gimbald, "-c", config, "--sim"], stdout=subprocess.DEVNULL)
    try:
        time.sleep(1.0)
        c = Client(port)
        # The error message of an unknown name lists every packet that can be asked for.
        listing = c.request("request", packet="no_such_packet")["error"]["message"]
        names = re.findall(r"\b[a-z][a-z0-9_]+\b", listing.split("e.g.", 1)[1])
        # The message lists examples only: network_diagnostics is asked for by name, and a
        # staring geopoint makes the gimbal send StareStart (STATE `stare`).
        asked = ["versions", "network_diagnostics"] + names
        for name in asked:
            c.request("request", packet=name)
        c.request("geopoint", lat=45.71, lon=-121.47, alt=100, stare=True)
        time.sleep(args.settle)
        state = c.request("state")["state"]
        empty = sorted(k for k, v in state.items() if v is None)

        c.request("subscribe", rate_hz=2, ttl_s=30, events=False)
        full = len(c.next_state())
        c.request("unsubscribe")
        time.sleep(0.3)
        lean = Client(port)
        lean.request("subscribe", rate_hz=2, ttl_s=30, events=False, keys=["telemetry"])
        telemetry = len(lean.next_state())
        lean.request("unsubscribe")

        print("asked the gimbal for %d packet kinds; STATE keys still null: %s" %
              (len(asked), ", ".join(empty) or "none"))
        print("%-34s %8s %8s  %s" % ("datagram", "bytes", "target", "met"))
        for what, size, target in (("full STATE", full, FULL_TARGET),
                                   ("subscribe keys=[telemetry]", telemetry, TELEMETRY_TARGET)):
            print("%-34s %8d %8d  %s" % (what, size, target, "yes" if size <= target else "NO"))
        biggest = sorted(((len(json.dumps(v, separators=(",", ":"))), k)
                          for k, v in state.items()), reverse=True)[:6]
        print("largest keys: " + ", ".join("%s %d" % (k, n) for n, k in biggest))
    finally:
        proc.send_signal(signal.SIGTERM)
        proc.wait(timeout=5)


if __name__ == "__main__":
    main()
