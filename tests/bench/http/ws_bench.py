#!/usr/bin/env python3
"""gimbald's CPU and memory with 50 WebSocket clients on /api/stream at 2 Hz for 60 s.

Starts gimbal-sim (TCP, free port) and gimbald connected to it with `http` enabled, opens
--clients WebSocket streams (spread over --stagger seconds, as browsers that open
independently do), reads them all, and after a warm-up measures over --window seconds: the
daemon's CPU time (utime + stime from /proc/PID/stat), its memory (anonymous memory RssAnon
sampled every second; VmRSS, VmHWM, Pss), and what each client received: every STATE due at 2 Hz must
arrive (count within one of rate x window, no gap over 1.5 periods), none dropped.

A benchmark, not a test (never run by ctest). Python 3 standard library only. Usage:

    ws_bench.py --gimbald build/release/daemon/gimbald \\
                --gimbal-sim build/release/tools/gimbal-sim [--clients 50] [--window 60]

Targets (issue 11): under 3 % of one core and under 30 MB - of anonymous memory (RssAnon, the
daemon's own; issue 25: VmRSS is mostly shared library pages now). A missed target is printed
as MISSED. The clients all come from 127.0.0.1, so the daemon's configuration raises
http.max_connections_per_client (default 16) with http.max_connections. --check
(scripts/bench-daemon.sh --smoke) makes the run fail (exit 1) unless every client got every
STATE.
"""

import argparse
import base64
import json
import os
import selectors
import socket
import struct
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "daemon"))
from load_bench import (cpu_seconds, free_udp_port, load_average, memory_kb,  # noqa: E402
                        memory_line, start_sim, stop, wait_connected)

CPU_TARGET_PCT = 3.0
ANON_TARGET_KB = 30 * 1024
RATE_HZ = 2.0


def parse_args():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--gimbald", required=True)
    p.add_argument("--gimbal-sim", required=True)
    p.add_argument("--clients", type=int, default=50)
    p.add_argument("--stagger", type=float, default=1.0)
    p.add_argument("--warmup", type=float, default=5.0)
    p.add_argument("--window", type=float, default=60.0)
    p.add_argument("--keep", action="store_true", help="keep the temp dir (config, logs)")
    p.add_argument("--check", action="store_true",
                   help="exit 1 unless every client got every STATE (none closed or dropped)")
    return p.parse_args()


def start_daemon(args, workdir, sim_port):
    config = os.path.join(workdir, "gimbald.json")
    with open(config, "w") as f:
        json.dump({"gimbals": [{"name": "main", "protocol": "orion",
                                "link": {"type": "tcp", "host": "127.0.0.1", "port": sim_port}}],
                   "command": {"bind": "127.0.0.1", "port": free_udp_port()},
                   # Every client is 127.0.0.1: the per-address cap must let them all in.
                   "http": {"port": 0, "max_connections": args.clients + 8,
                            "max_connections_per_client": args.clients + 8}}, f)
    log_path = os.path.join(workdir, "gimbald.log")
    proc = subprocess.Popen([args.gimbald, "-c", config], stdout=open(log_path, "wb"),
                            stderr=subprocess.STDOUT)
    deadline = time.monotonic() + 10
    while time.monotonic() < deadline:
        with open(log_path) as f:
            for line in f:
                try:
                    entry = json.loads(line)
                except ValueError:
                    continue
                if entry.get("event") == "start":
                    udp = entry["command"].rsplit(":", 1)
                    return proc, log_path, ("127.0.0.1", int(udp[1])), \
                        int(entry["http"].rsplit(":", 1)[1])
        time.sleep(0.05)
    stop(proc)
    sys.exit("ws_bench: gimbald did not start (see %s)" % log_path)


class Client:
    """One /api/stream WebSocket; parses frames as they arrive, times each STATE."""

    def __init__(self, port):
        # A bounded handshake: a refused upgrade (403, 503) is an error, never a hang.
        self.sock = socket.create_connection(("127.0.0.1", port), timeout=5.0)
        key = base64.b64encode(os.urandom(16)).decode()
        # Host must name gimbald (its DNS-rebinding check refuses anything else with 403).
        self.sock.sendall(("GET /api/stream HTTP/1.1\r\nHost: 127.0.0.1:%d\r\n"
                           "Upgrade: websocket\r\nConnection: Upgrade\r\n"
                           "Sec-WebSocket-Key: %s\r\nSec-WebSocket-Version: 13\r\n\r\n"
                           % (port, key)).encode())
        buf = b""
        while b"\r\n\r\n" not in buf:
            chunk = self.sock.recv(4096)
            if not chunk:
                raise ConnectionError("closed during the WebSocket handshake")
            buf += chunk
        head, self.buf = buf.split(b"\r\n\r\n", 1)
        if not head.startswith(b"HTTP/1.1 101"):
            raise ConnectionError("WebSocket upgrade refused: " +
                                  head.decode(errors="replace").splitlines()[0])
        self.sock.setblocking(False)
        self.states = []  # arrival times
        self.closed = False
        self.bytes = 0

    def on_readable(self):
        try:
            data = self.sock.recv(262144)
        except BlockingIOError:
            return
        if not data:
            self.closed = True
            return
        self.buf += data
        now = time.monotonic()
        while len(self.buf) >= 2:
            b0, b1 = self.buf[0], self.buf[1]
            n, head = b1 & 0x7F, 2
            if n == 126:
                if len(self.buf) < 4:
                    return
                n, head = struct.unpack(">H", self.buf[2:4])[0], 4
            elif n == 127:
                if len(self.buf) < 10:
                    return
                n, head = struct.unpack(">Q", self.buf[2:10])[0], 10
            if len(self.buf) < head + n:
                return
            payload, self.buf = self.buf[head:head + n], self.buf[head + n:]
            opcode = b0 & 0x0F
            if opcode == 0x8:
                self.closed = True
            elif opcode == 0x9:  # ping: pong, masked with a zero key
                self.sock.setblocking(True)
                self.sock.sendall(bytes([0x8A, 0x80 | len(payload)]) + b"\0\0\0\0" + payload)
                self.sock.setblocking(False)
            elif opcode == 0x1 and payload.endswith(b'"type":"state"}'):
                self.states.append(now)
                self.bytes += n


def main():
    args = parse_args()
    workdir = tempfile.mkdtemp(prefix="ws-bench-")
    sim, sim_port = start_sim(args.gimbal_sim, workdir)
    daemon = None
    clients = []
    complete = False
    try:
        daemon, log_path, udp, http_port = start_daemon(args, workdir, sim_port)
        wait_connected(udp, daemon)
        sel = selectors.DefaultSelector()

        def pump(seconds):
            end = time.monotonic() + seconds
            while True:
                left = end - time.monotonic()
                if left <= 0:
                    return
                for key, _ in sel.select(min(left, 0.1)):
                    key.data.on_readable()

        for i in range(args.clients):
            c = Client(http_port)
            clients.append(c)
            sel.register(c.sock, selectors.EVENT_READ, c)
            pump(args.stagger / max(1, args.clients))
        pump(args.warmup)

        t0 = time.monotonic()
        cpu0 = cpu_seconds(daemon.pid)
        anon = []
        while time.monotonic() - t0 < args.window:
            pump(1.0)
            anon.append(memory_kb(daemon.pid)["RssAnon"])
        t1 = time.monotonic()
        cpu1 = cpu_seconds(daemon.pid)
        mem = memory_kb(daemon.pid)

        window = t1 - t0
        expected = RATE_HZ * window
        counts, worst_gap = [], 0.0
        for c in clients:
            inside = [t for t in c.states if t0 <= t < t1]
            counts.append(len(inside))
            before = [t for t in c.states if t < t0][-1:]
            times = before + inside
            for a, b in zip(times, times[1:]):
                worst_gap = max(worst_gap, b - a)
        closed = sum(1 for c in clients if c.closed)
        with open(log_path) as f:
            dropped = sum(1 for line in f if '"websocket_dropped"' in line)
        complete = (closed == 0 and dropped == 0 and min(counts) >= expected - 1.5 and
                    worst_gap < 1.5 / RATE_HZ)
        cpu_pct = 100.0 * (cpu1 - cpu0) / window
        state_bytes = sum(c.bytes for c in clients) / max(1, sum(len(c.states) for c in clients))
        print("clients %d at %.0f Hz for %.1f s (load average %s, %d cores)" %
              (args.clients, RATE_HZ, window, load_average(), os.cpu_count()))
        print("STATE per client: min %d, max %d (expected %.0f), worst gap %.3f s, "
              "closed %d, dropped %d, mean message %.0f bytes" %
              (min(counts), max(counts), expected, worst_gap, closed, dropped, state_bytes))
        cpu_met = cpu_pct < CPU_TARGET_PCT
        anon_met = max(anon) < ANON_TARGET_KB
        print("gimbald CPU %.2f %% of a core (target < %.0f: %s)" %
              (cpu_pct, CPU_TARGET_PCT, "met" if cpu_met else "MISSED"))
        print("gimbald memory: %s; anonymous memory target < %d MB: %s" %
              (memory_line(mem, max(anon)), ANON_TARGET_KB // 1024,
               "met" if anon_met else "MISSED"))
        print("RESULT clients=%d window_s=%.1f min_states=%d max_states=%d expected=%.0f "
              "worst_gap_s=%.3f closed=%d dropped=%d complete=%s cpu_pct=%.2f cpu_met=%s "
              "anon_kb=%d anon_met=%s rss_kb=%d hwm_kb=%d pss_kb=%s"
              % (args.clients, window, min(counts), max(counts), expected, worst_gap, closed,
                 dropped, "yes" if complete else "no", cpu_pct, "yes" if cpu_met else "no",
                 max(anon), "yes" if anon_met else "no", mem["VmRSS"], mem["VmHWM"],
                 mem.get("Pss", 0)))
    except ConnectionError as e:
        complete = False
        print("ws_bench: %s" % e, file=sys.stderr)
    finally:
        for c in clients:
            c.sock.close()
        if daemon:
            stop(daemon)
        stop(sim)
        if args.keep:
            print("kept", workdir)
        else:
            import shutil
            shutil.rmtree(workdir, ignore_errors=True)
    if args.check and not complete:
        sys.exit("ws_bench: FAILED: a client missed STATE messages, was closed or dropped")


if __name__ == "__main__":
    main()
