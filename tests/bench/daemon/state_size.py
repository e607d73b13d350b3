#!/usr/bin/env python3
"""How large gimbald's STATE datagrams are (issue 8, "lean streams"; issue 17, delta streams).

Starts `gimbald --sim` (the embedded simulated Orion), asks the gimbal for every report and
settings packet it can be asked for (so every STATE key is filled), waits for the periodic
telemetry kinds, then measures the full STATE as a subscriber receives it, a subscription
restricted to `keys: ["telemetry"]`, and a delta stream (`changes: true`, contract section
14) at 10 Hz for --window seconds: how many of its patches fit one 1,472-byte UDP payload
(Ethernet MTU 1500 - IPv4 20 - UDP 8). The patches are merged as a receiver would and the
result compared with the full STATEs that follow.

A benchmark, not a test. Python 3 standard library only. Usage:

    state_size.py --gimbald build/release/daemon/gimbald [--window 60] [--check]

Targets: telemetry-only at most 1,200 bytes (issue 8) and, signed (contract section 10: the
push is a signed envelope, its payload escaped), at most 1,472 bytes - one UDP payload
(issue 25); the full STATE at most 9,000 bytes (issue 25); 99 % of the patches at most 1,472
bytes (issue 25; 95 % in issue 17). A missed target is printed as MISSED. --check
(scripts/bench-daemon.sh --smoke) fails the run when a push is missing, a patch does not
merge, or the stream does not start with a full STATE; sizes are not checked.
"""

import argparse
import hashlib
import hmac
import json
import os
import re
import secrets
import signal
import socket
import subprocess
import tempfile
import time

TELEMETRY_TARGET = 1200
UDP_PAYLOAD = 1472
FULL_TARGET = 9000
PATCH_SHARE_TARGET = 0.99
KEY_ID = "bench"


def verdict(met):
    return "met" if met else "MISSED"


def merge_patch(target, patch):
    """RFC 7396 section 2."""
    if not isinstance(patch, dict):
        return patch
    if not isinstance(target, dict):
        target = {}
    for name, value in patch.items():
        if value is None:
            target.pop(name, None)
        else:
            target[name] = merge_patch(target.get(name), value)
    return target


def without_ages(value):
    """A STATE without age_s members and null object members (as merged patches hold it)."""
    if isinstance(value, dict):
        return {k: without_ages(v) for k, v in value.items() if v is not None and k != "age_s"}
    if isinstance(value, list):
        return [without_ages(v) for v in value]
    return value


def measure_delta(port, rate_hz, window_s):
    """Subscribes with changes: true; returns (full sizes, patch sizes, pushes, problems)."""
    c = Client(port)
    c.request("subscribe", rate_hz=rate_hz, ttl_s=max(60, 2 * window_s), events=False,
              changes=True, full_every_s=10)
    fulls, patches, problems = [], [], []
    merged = None
    pushes = 0
    end = time.monotonic() + window_s
    while time.monotonic() < end:
        data = c.next_state()
        msg = json.loads(data)
        pushes += 1
        if msg["full"]:
            # The merged patches must have given what the next full STATE says, except what
            # changed in the last period: compare the keys that a full and a merge both hold.
            if merged is not None and set(without_ages(merged)) != set(without_ages(msg["state"])):
                problems.append("merged keys differ from the full STATE's")
            fulls.append(len(data))
            merged = msg["state"]
        else:
            patches.append(len(data))
            if merged is None:
                problems.append("a patch before the first full STATE")
            else:
                merged = merge_patch(merged, msg["state"])
    c.request("unsubscribe")
    return fulls, patches, pushes, problems


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

    def request(self, cmd, secret=None, **params):
        """Sends a request (signed with `secret` when given, contract section 10); returns its
        reply (a signed reply as its payload)."""
        self.n += 1
        params.update(cmd=cmd, id=self.n)
        data = json.dumps(params)
        if secret is not None:
            params.update(ts=int(time.time() * 1000), nonce=secrets.token_hex(8))
            payload = json.dumps(params)
            mac = hmac.new(secret, payload.encode(), hashlib.sha256).hexdigest()
            data = json.dumps({"signed": {"key": KEY_ID, "payload": payload, "mac": mac}})
        self.sock.sendto(data.encode(), ("127.0.0.1", self.port))
        while True:
            data = self.sock.recv(65536)
            msg = json.loads(data)
            if "signed" in msg:
                msg = json.loads(msg["signed"]["payload"])
            if msg.get("id") == self.n and "ok" in msg:
                return msg

    def next_state(self, timeout=3.0):
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            data = self.sock.recv(65536)
            msg = json.loads(data)
            if "signed" in msg:
                msg = json.loads(msg["signed"]["payload"])
            if msg.get("type") == "state":
                return data
        raise TimeoutError("no STATE datagram")


def wait_started(client, proc, timeout=15.0):
    """Until the daemon answers `ping` (a loaded machine may take seconds to start it)."""
    deadline = time.monotonic() + timeout
    client.sock.settimeout(0.2)
    while time.monotonic() < deadline:
        if proc.poll() is not None:
            raise SystemExit("state_size: gimbald exited (code %s)" % proc.returncode)
        try:
            client.request("ping")
            client.sock.settimeout(2.0)
            return
        except (TimeoutError, socket.timeout, ConnectionRefusedError):
            continue
    raise SystemExit("state_size: gimbald did not answer within %.0f s" % timeout)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--gimbald", required=True)
    p.add_argument("--settle", type=float, default=3.0,
                   help="seconds to wait for the requested packets and periodic reports")
    p.add_argument("--window", type=float, default=60.0,
                   help="seconds of the delta stream measured")
    p.add_argument("--rate", type=float, default=10.0, help="rate_hz of the delta stream")
    p.add_argument("--check", action="store_true",
                   help="exit 1 when the delta stream lost a push or did not merge")
    args = p.parse_args()

    port = free_port()
    tmp = tempfile.mkdtemp(prefix="state-size-")
    config = os.path.join(tmp, "c.json")
    secret = secrets.token_bytes(32)
    key_file = os.path.join(tmp, "bench.key")
    with open(os.open(key_file, os.O_WRONLY | os.O_CREAT, 0o600), "w") as f:
        f.write(secret.hex() + "\n")
    with open(config, "w") as f:
        json.dump({"command": {"port": port, "keys": [{"id": KEY_ID, "secret_file": key_file,
                                                       "roles": ["observe", "control"]}]},
                   "log": {"level": "warn"}}, f)
    proc = subprocess.Popen([args.gimbald, "-c", config, "--sim"], stdout=subprocess.DEVNULL)
    try:
        c = Client(port)
        wait_started(c, proc)
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
        signed = Client(port)
        signed.request("subscribe", secret=secret, rate_hz=2, ttl_s=30, events=False,
                       keys=["telemetry"])
        telemetry_signed = len(signed.next_state())
        signed.request("unsubscribe", secret=secret)

        fulls, patches, pushes, problems = measure_delta(port, args.rate, args.window)

        print("asked the gimbal for %d packet kinds; STATE keys still null: %s" %
              (len(asked), ", ".join(empty) or "none"))
        print("%-34s %8s %8s  %s" % ("datagram", "bytes", "target", "met"))
        print("%-34s %8d %8d  %s" % ("full STATE", full, FULL_TARGET, verdict(full <= FULL_TARGET)))
        print("%-34s %8d %8d  %s" % ("subscribe keys=[telemetry]", telemetry, TELEMETRY_TARGET,
                                     verdict(telemetry <= TELEMETRY_TARGET)))
        print("%-34s %8d %8d  %s" % ("the same, signed", telemetry_signed, UDP_PAYLOAD,
                                     verdict(telemetry_signed <= UDP_PAYLOAD)))
        biggest = sorted(((len(json.dumps(v, separators=(",", ":"))), k)
                          for k, v in state.items()), reverse=True)[:6]
        print("largest keys: " + ", ".join("%s %d" % (k, n) for n, k in biggest))
        patches.sort()
        fit = sum(1 for n in patches if n <= UDP_PAYLOAD)
        share = fit / len(patches) if patches else 0.0
        expected = int(args.rate * args.window)
        print("delta stream (changes: true, full_every_s 10) at %g Hz for %g s: %d pushes "
              "(expected about %d), %d full (%s bytes), %d patches" %
              (args.rate, args.window, pushes, expected, len(fulls),
               "/".join(str(n) for n in fulls), len(patches)))
        if patches:
            print("  patch bytes: median %d, p95 %d, max %d; %d of %d (%.1f %%) fit one %d-byte "
                  "UDP payload (target %.0f %%): %s" %
                  (patches[len(patches) // 2], patches[int(0.95 * (len(patches) - 1))],
                   patches[-1], fit, len(patches), 100 * share, UDP_PAYLOAD,
                   100 * PATCH_SHARE_TARGET, verdict(share >= PATCH_SHARE_TARGET)))
        complete = (not problems and fulls and pushes >= expected - 2)
        met = {"full": full <= FULL_TARGET, "telemetry": telemetry <= TELEMETRY_TARGET,
               "signed": telemetry_signed <= UDP_PAYLOAD, "patches": share >= PATCH_SHARE_TARGET}
        print("RESULT full_bytes=%d telemetry_bytes=%d telemetry_signed_bytes=%d pushes=%d "
              "expected=%d fulls=%d patches=%d patch_fit_pct=%.1f patch_median_bytes=%d "
              "patch_max_bytes=%d complete=%s missed=%s" %
              (full, telemetry, telemetry_signed, pushes, expected, len(fulls), len(patches),
               100 * share, patches[len(patches) // 2] if patches else 0,
               patches[-1] if patches else 0, "yes" if complete else "no",
               ",".join(k for k, v in met.items() if not v) or "none"))
        for problem in problems:
            print("problem: " + problem)
        if args.check and not complete:
            raise SystemExit("state_size: FAILED: the delta stream lost pushes or did not merge")
    finally:
        proc.send_signal(signal.SIGTERM)
        proc.wait(timeout=5)


if __name__ == "__main__":
    main()
