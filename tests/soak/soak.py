#!/usr/bin/env python3
"""Soak under faults (issue 8): gimbald with two gimbal-sim Orions whose links flap and carry
junk and bad checksums, 100 subscribers that come and go, 200 requests/s (a third invalid or
badly signed), and a laser fire every ~10 s left to the dead-man timer.

Prints a row every --report-every seconds (RSS, fds, requests, replies, lost, reconnects) and
checks at the end: every fire ceased at the simulator, 0 replies lost, RSS growth under 1 MB
after the first minute, no fd growth, every reconnect under 2 s. Exit 0 when all pass.
Python 3 standard library only; everything on 127.0.0.1; bounded in time.

    soak.py --gimbald G --gimbalctl C --gimbal-sim S [--seconds N] [--report-every S]
"""

import argparse
import hashlib
import hmac
import json
import os
import random
import secrets
import select
import signal
import socket
import subprocess
import sys
import tempfile
import time

FIRE_TIMEOUT_S = 1.5
RATE_HZ = 200
SUBSCRIBERS = 100


def free_udp_port():
    s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    s.bind(("127.0.0.1", 0))
    port = s.getsockname()[1]
    s.close()
    return port


def start_sim(path, workdir, name, drop_after):
    rx_log = os.path.join(workdir, name + "-rx.jsonl")
    proc = subprocess.Popen(
        [path, "--no-discovery", "--port", "0", "--rx-log", rx_log, "--drop-after",
         str(drop_after), "--junk-every", "50", "--corrupt-fraction", "0.01", "--seed",
         str(drop_after)],
        stdout=subprocess.PIPE, stderr=open(os.path.join(workdir, name + ".stderr"), "wb"))
    deadline = time.monotonic() + 10
    pending = b""
    while time.monotonic() < deadline:
        ready, _, _ = select.select([proc.stdout], [], [], 0.2)
        if ready:
            pending += os.read(proc.stdout.fileno(), 4096)
            for line in pending.decode(errors="replace").splitlines():
                if line.startswith("tcp: "):
                    return proc, int(line.rsplit(":", 1)[1]), rx_log
    proc.kill()
    raise RuntimeError("gimbal-sim did not start")


def proc_rss_kb(pid):
    with open("/proc/%d/status" % pid) as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    return 0


def proc_fds(pid):
    return len(os.listdir("/proc/%d/fd" % pid))


class Signer:
    def __init__(self, key_id, secret):
        self.key_id, self.secret = key_id, secret

    def sign(self, request, secret=None, key_id=None, nonce=None):
        payload = dict(request, ts=int(time.time() * 1000), nonce=nonce or secrets.token_hex(8))
        text = json.dumps(payload)
        mac = hmac.new(secret or self.secret, text.encode(), hashlib.sha256).hexdigest()
        return json.dumps({"signed": {"key": key_id or self.key_id, "payload": text,
                                      "mac": mac}}).encode()


class Soak:
    def __init__(self, args):
        self.args = args
        self.tmp = tempfile.mkdtemp(prefix="gimbald-soak-")
        self.children = []
        self.sent = self.replies = 0
        self.fires = []  # (time, gimbal) of fires the daemon accepted
        self.rows = []
        self.failures = []

    # --- set-up ---------------------------------------------------------------------------
    def start(self):
        a = self.args
        key = os.path.join(self.tmp, "ops.key")
        subprocess.run([a.gimbalctl, "keygen", key], check=True)
        with open(key) as f:
            self.signer = Signer("ops", bytes.fromhex(f.read().strip()))
        self.sims = {}
        for name, drop in (("a", 7), ("b", 13)):
            proc, port, rx = start_sim(a.gimbal_sim, self.tmp, name, drop)
            self.children.append(proc)
            self.sims[name] = (port, rx)
        self.port = free_udp_port()
        config = {
            "gimbals": [{"name": n, "protocol": "orion",
                         "link": {"type": "tcp", "host": "127.0.0.1", "port": p}}
                        for n, (p, _) in self.sims.items()],
            "command": {"port": self.port, "auth": "signed", "max_subscribers": 128,
                        "max_subscribers_per_host": 128,
                        "keys": [{"id": "ops", "secret_file": key,
                                  "roles": ["observe", "control", "laser"]}],
                        "rate_limit": {"per_source_hz": 5000, "burst": 5000}},
            "laser": {"allow_fire": True, "fire_timeout_s": FIRE_TIMEOUT_S},
            "log": {"level": "info"}}
        path = os.path.join(self.tmp, "gimbald.json")
        with open(path, "w") as f:
            json.dump(config, f)
        self.log_path = os.path.join(self.tmp, "gimbald.log")
        self.daemon = subprocess.Popen([a.gimbald, "-c", path], stdout=open(self.log_path, "wb"),
                                       stderr=subprocess.STDOUT)
        self.children.append(self.daemon)
        time.sleep(1.5)
        if self.daemon.poll() is not None:
            raise RuntimeError("gimbald exited: " + open(self.log_path).read()[-2000:])
        self.load = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.load.bind(("127.0.0.1", 0))
        self.load.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 1 << 22)
        self.load.setblocking(False)
        self.subs = []
        for _ in range(SUBSCRIBERS):
            s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
            s.bind(("127.0.0.1", 0))
            s.setblocking(False)
            self.subs.append(s)

    def stop(self):
        for p in reversed(self.children):
            if p.poll() is None:
                p.send_signal(signal.SIGTERM)
        for p in self.children:
            try:
                p.wait(timeout=5)
            except subprocess.TimeoutExpired:
                p.kill()

    # --- traffic --------------------------------------------------------------------------
    def request_bytes(self, n):
        """One of the 200/s: two thirds valid, one third invalid or badly signed."""
        gimbal = "a" if n % 2 else "b"
        kind = n % 9
        if kind == 0:
            return b'{"cmd": "state", "id": '  # bad JSON
        if kind == 1:
            return json.dumps({"cmd": "fly", "id": n}).encode()  # unknown command, unsigned
        if kind == 2:
            return self.signer.sign({"cmd": "position", "id": n, "gimbal": gimbal,
                                     "pan": 999, "tilt": 0})  # out of range
        if kind == 3:
            return self.signer.sign({"cmd": "state", "id": n, "gimbal": gimbal},
                                    secret=b"\0" * 32)  # wrong MAC
        if kind == 4:
            return self.signer.sign({"cmd": "ping", "id": n}, key_id="nobody")
        if kind == 5:
            return self.signer.sign({"cmd": "ping", "id": n}, nonce="replayed-nonce-1")
        if kind == 6:
            return self.signer.sign({"cmd": "position", "id": n, "gimbal": gimbal,
                                     "pan": random.uniform(-90, 90),
                                     "tilt": random.uniform(-60, 0)})
        if kind == 7:
            return self.signer.sign({"cmd": "state", "id": n, "gimbal": gimbal,
                                     "keys": ["telemetry"]})
        return self.signer.sign({"cmd": "ping", "id": n})

    def churn_subscribers(self, now):
        for s in random.sample(self.subs, 10):
            r = random.random()
            if r < 0.5:
                req = {"cmd": "subscribe", "id": "s", "rate_hz": random.choice([1, 2, 5]),
                       "ttl_s": random.choice([1, 2, 5]), "keys": ["telemetry"]}
            elif r < 0.8:
                req = {"cmd": "unsubscribe", "id": "s"}
            else:
                continue  # left alone: its subscription expires by itself
            s.sendto(self.signer.sign(req), ("127.0.0.1", self.port))

    def fire(self, n):
        gimbal = "a" if n % 2 else "b"
        self.load.sendto(self.signer.sign({"cmd": "laser", "id": "fire-%d" % n, "gimbal": gimbal,
                                           "enable": True, "arm": True, "fire": True}),
                         ("127.0.0.1", self.port))
        self.sent += 1
        self.pending_fire = ("fire-%d" % n, gimbal, time.time())

    def on_reply(self, data):
        self.replies += 1
        try:
            msg = json.loads(data)
        except ValueError:
            return
        if "signed" in msg:
            msg = json.loads(msg["signed"]["payload"])
        pf = getattr(self, "pending_fire", None)
        if pf and msg.get("id") == pf[0]:
            if msg.get("ok"):
                self.fires.append((pf[2], pf[1]))
            self.pending_fire = None

    def drain(self, timeout):
        socks = [self.load] + self.subs
        ready, _, _ = select.select(socks, [], [], timeout)
        for s in ready:
            while True:
                try:
                    data = s.recv(65536)
                except (BlockingIOError, ConnectionRefusedError):
                    break
                if s is self.load:
                    self.on_reply(data)

    # --- measurements ---------------------------------------------------------------------
    def link_events(self):
        """(reconnects, [durations]) from gimbald's JSON log, read incrementally: the log grows
        by megabytes a minute and re-reading it would stall this client (and overflow its
        socket buffer)."""
        if not hasattr(self, "_log_offset"):
            self._log_offset, self._down, self._durations, self._ups = 0, {}, [], 0
        with open(self.log_path, "rb") as f:
            f.seek(self._log_offset)
            chunk = f.read()
        complete = chunk.rfind(b"\n") + 1
        self._log_offset += complete
        for line in chunk[:complete].decode(errors="replace").splitlines():
            if '"link_' not in line:
                continue
            try:
                e = json.loads(line)
            except ValueError:
                continue
            g = e.get("gimbal")
            if e.get("event") == "link_down":
                self._down.setdefault(g, e["ts"])
            elif e.get("event") == "link_up":
                self._ups += 1
                if g in self._down:
                    self._durations.append(iso_seconds(e["ts"]) - iso_seconds(self._down.pop(g)))
        return max(0, self._ups - len(self.sims)), self._durations

    def row(self, elapsed):
        pid = self.daemon.pid
        reconnects, durations = self.link_events()
        r = {"t": elapsed, "rss_kb": proc_rss_kb(pid), "fds": proc_fds(pid), "sent": self.sent,
             "replies": self.replies, "lost": max(0, self.sent - self.replies - self.in_flight()),
             "reconnects": reconnects, "max_reconnect_s": max(durations, default=0.0),
             "fires": len(self.fires)}
        self.rows.append(r)
        print("%7.0f %8d %5d %9d %9d %6d %10d %14.3f %6d" % (
            elapsed, r["rss_kb"], r["fds"], r["sent"], r["replies"], r["lost"], r["reconnects"],
            r["max_reconnect_s"], r["fires"]), flush=True)

    def in_flight(self):
        return 50  # requests sent within the last ~0.25 s may still be on their way

    # --- the run --------------------------------------------------------------------------
    def run(self):
        a = self.args
        print("%7s %8s %5s %9s %9s %6s %10s %14s %6s" % (
            "t_s", "rss_kb", "fds", "sent", "replies", "lost", "reconnects", "max_reconn_s",
            "fires"), flush=True)
        start = time.monotonic()
        next_req = next_churn = start
        next_fire = start + 3
        next_row = start + a.report_every
        n = fires = 0
        while True:
            now = time.monotonic()
            if now - start >= a.seconds:
                break
            if self.daemon.poll() is not None:
                self.failures.append("gimbald exited during the soak")
                break
            while next_req <= now:
                n += 1
                self.load.sendto(self.request_bytes(n), ("127.0.0.1", self.port))
                self.sent += 1
                next_req += 1.0 / RATE_HZ
            if now >= next_churn:
                self.churn_subscribers(now)
                next_churn = now + 0.5
            if now >= next_fire:
                fires += 1
                self.fire(fires)
                next_fire = now + 10
            if now >= next_row:
                self.row(now - start)
                next_row += a.report_every
            self.drain(max(0.0, min(next_req, next_row) - time.monotonic()))
        deadline = time.monotonic() + 3
        while time.monotonic() < deadline:
            self.drain(0.1)
        self.row(time.monotonic() - start)

    def check(self):
        rows = self.rows
        lost = self.sent - self.replies
        self.verdict("replies lost", lost == 0, "%d of %d requests unanswered" %
                     (lost, self.sent))
        warm = next((r for r in rows if r["t"] >= 60), rows[0])
        growth = rows[-1]["rss_kb"] - warm["rss_kb"]
        if self.args.seconds >= 120:
            self.verdict("RSS growth after the first minute < 1 MB", growth < 1024,
                         "%+d kB (%d -> %d)" % (growth, warm["rss_kb"], rows[-1]["rss_kb"]))
        else:
            print("RSS growth after warm-up: %+d kB (reported only in a short run)" % growth)
        self.verdict("no fd growth", rows[-1]["fds"] <= rows[0]["fds"] + 2,
                     "%d -> %d" % (rows[0]["fds"], rows[-1]["fds"]))
        _, durations = self.link_events()
        self.verdict("every reconnect under 2 s", all(d < 2.0 for d in durations),
                     "%d reconnects, longest %.3f s" % (len(durations),
                                                        max(durations, default=0.0)))
        ceased, total = self.cease_fires()
        self.verdict("every dead-man cease-fire reached the simulator", ceased == total and
                     total > 0, "%d of %d fires ceased (%d accepted by gimbald)" %
                     (ceased, total, len(self.fires)))

    def cease_fires(self):
        """Fires seen by each simulator, and how many were followed by a fire-0 command."""
        total = ceased = 0
        for _, (_, rx) in self.sims.items():
            entries = []
            with open(rx, errors="replace") as f:
                for line in f:
                    try:
                        e = json.loads(line)
                    except ValueError:
                        continue
                    if e.get("name") == "laser_cmd":
                        entries.append(bool(e.get("packet", {}).get("fire")))
            for i, firing in enumerate(entries):
                if firing:
                    total += 1
                    if any(not later for later in entries[i + 1:]):
                        ceased += 1
        return ceased, total

    def verdict(self, what, ok, detail):
        print("%-50s %s  %s" % (what, "PASS" if ok else "FAIL", detail))
        if not ok:
            self.failures.append(what)


def iso_seconds(ts):
    # "2026-11-24T18:52:51.880123Z"
    t = time.strptime(ts[:19], "%Y-%m-%dT%H:%M:%S")
    return time.mktime(t) + float("0" + ts[19:-1])


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--gimbald", default=os.environ.get("GIMBALD"))
    p.add_argument("--gimbalctl", default=os.environ.get("GIMBALCTL"))
    p.add_argument("--gimbal-sim", default=os.environ.get("GIMBAL_SIM"))
    p.add_argument("--seconds", type=float, default=1800)
    p.add_argument("--report-every", type=float, default=60)
    a = p.parse_args()
    if not (a.gimbald and a.gimbalctl and a.gimbal_sim):
        p.error("--gimbald, --gimbalctl and --gimbal-sim (or GIMBALD, GIMBALCTL, GIMBAL_SIM)")
    random.seed(1)
    soak = Soak(a)
    try:
        soak.start()
        soak.run()
        soak.check()
    finally:
        soak.stop()
    print("soak: %s" % ("PASS" if not soak.failures else "FAIL: " + ", ".join(soak.failures)))
    sys.exit(0 if not soak.failures else 1)


if __name__ == "__main__":
    main()
