#!/usr/bin/env python3
"""gimbald's CPU per viewer of GET /api/video/{gimbal} (contract section 18), 10 viewers.

gimbal-sim (its own process, so its rendering and encoding are not gimbald's CPU) sends the
simulated Orion's H.264 in MPEG-TS to gimbald's video input; gimbald relays it. The
daemon's CPU time (utime + stime, /proc/PID/stat) is measured over --window seconds with no
viewer, then again with --viewers WebSocket viewers reading everything; the difference
divided by the viewers is one viewer's cost. Every viewer must keep up: within the span all of them were counting, each
got the same frames (by timestamp) - none skipped, none dropped. The stream's own rate is
printed (a loaded machine's simulator may send fewer than --fps frames a second).

A benchmark, not a test. Python 3 standard library only. Usage:

    video_viewers_bench.py --gimbald build/release/daemon/gimbald \\
                           --gimbal-sim build/release/tools/gimbal-sim [--viewers 10] [--window 30]

Target (issue 21): under 0.5 % of a core per viewer (release build). --check (the smoke run)
makes the run fail (exit 1) unless every viewer kept up.
"""

import argparse
import json
import os
import re
import select
import shutil
import socket
import struct
import subprocess
import sys
import tempfile
import threading
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "integration"))
sys.path.insert(0, os.path.join(HERE, "..", "daemon"))
import httptest as ht  # noqa: E402
from load_bench import cpu_seconds, free_udp_port, load_average, stop  # noqa: E402

TARGET_PCT = 0.5


def parse_args():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--gimbald", required=True)
    p.add_argument("--gimbal-sim", required=True)
    p.add_argument("--viewers", type=int, default=10)
    p.add_argument("--warmup", type=float, default=3.0)
    p.add_argument("--window", type=float, default=30.0)
    p.add_argument("--fps", type=int, default=15)
    p.add_argument("--check", action="store_true",
                   help="exit 1 unless every viewer got every frame of the window")
    return p.parse_args()


def free_tcp_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def start_sim(args, workdir, video_port):
    err = open(os.path.join(workdir, "gimbal-sim.err"), "wb")
    proc = subprocess.Popen([args.gimbal_sim, "--port", "0", "--no-discovery", "--video",
                             "udp://127.0.0.1:%d" % video_port, "--video-fps", str(args.fps)],
                            stdout=subprocess.PIPE, stderr=err, text=True)
    deadline = time.monotonic() + 10
    while time.monotonic() < deadline:
        ready, _, _ = select.select([proc.stdout], [], [], 0.5)
        if ready:
            m = re.match(r"tcp: ([\d.]+):(\d+)", proc.stdout.readline())
            if m:
                return proc, int(m.group(2))
    sys.exit("video_viewers_bench: gimbal-sim did not start")


class Viewer(threading.Thread):
    """Reads one video WebSocket; keeps the frames' timestamps while `counting`."""

    def __init__(self, port, period_us):
        super().__init__(daemon=True)
        self.ws = ht.WebSocket(port, "/api/video/main", timeout=10)
        self.period_us = period_us
        self.counting = False
        self.stamps = []
        self.error = None
        self.running = True

    def run(self):
        try:
            while self.running:
                opcode, payload = self.ws.recv_frame(timeout=5)
                if opcode == 0x8:
                    self.error = "closed by gimbald"
                    return
                if opcode != 0x2:
                    continue
                if self.counting:
                    self.stamps.append(struct.unpack(">Q", payload[:8])[0])
        except (OSError, ConnectionError) as e:
            if self.running:
                self.error = str(e)


def main():
    args = parse_args()
    workdir = tempfile.mkdtemp(prefix="video-viewers-bench-")
    video_port = free_udp_port()
    http_port = free_tcp_port()
    sim, sim_port = start_sim(args, workdir, video_port)
    config = os.path.join(workdir, "gimbald.json")
    with open(config, "w") as f:
        json.dump({"gimbals": [{"name": "main", "protocol": "orion",
                                "link": {"type": "tcp", "host": "127.0.0.1", "port": sim_port},
                                "video": {"input": "udp://127.0.0.1:%d" % video_port}}],
                   "command": {"bind": "127.0.0.1", "port": free_udp_port()},
                   "http": {"bind": "127.0.0.1", "port": http_port}}, f)
    log = open(os.path.join(workdir, "gimbald.log"), "wb")
    daemon = subprocess.Popen([args.gimbald, "-c", config, "--log-level", "warn"],
                              stdout=subprocess.DEVNULL, stderr=log)
    viewers = []
    try:
        deadline = time.monotonic() + 15
        while time.monotonic() < deadline:
            try:
                _, st = ht.get_json(http_port, "/api/state")
                if st["gimbals"]["main"]["video"]["connected"]:
                    break
            except (OSError, ValueError, KeyError, TypeError):
                pass
            time.sleep(0.2)
        else:
            sys.exit("video_viewers_bench: gimbald's video never came up")
        time.sleep(args.warmup)
        c0 = cpu_seconds(daemon.pid)
        time.sleep(args.window)
        idle_pct = (cpu_seconds(daemon.pid) - c0) / args.window * 100

        period_us = 1e6 / args.fps
        viewers = [Viewer(http_port, period_us) for _ in range(args.viewers)]
        for v in viewers:
            v.start()
        time.sleep(args.warmup)
        for v in viewers:
            v.counting = True
        c0 = cpu_seconds(daemon.pid)
        t0 = time.monotonic()
        time.sleep(args.window)
        for v in viewers:
            v.counting = False
        window = time.monotonic() - t0
        busy_pct = (cpu_seconds(daemon.pid) - c0) / window * 100
        per_viewer = (busy_pct - idle_pct) / args.viewers
        # The span every viewer was counting in: the same frames for all.
        first = max(v.stamps[0] for v in viewers if v.stamps) if all(v.stamps for v in viewers) else 0
        last = min(v.stamps[-1] for v in viewers if v.stamps) if all(v.stamps for v in viewers) else -1
        spans = [[t for t in v.stamps if first <= t <= last] for v in viewers]
        counts = [len(s) for s in spans]
        union = sorted(set(t for s in spans for t in s))
        kept_up = all(v.error is None for v in viewers) and counts and min(counts) > 0 and \
            all(s == union for s in spans)
        stream_fps = (len(union) - 1) / ((last - first) / 1e6) if last > first else 0
        print("video viewers: %d viewers x %.1f s, load average %s" %
              (args.viewers, window, load_average()))
        print("  gimbald CPU: %.2f %% of a core with no viewer, %.2f %% with %d viewers" %
              (idle_pct, busy_pct, args.viewers))
        print("  per viewer: %.3f %% of a core (target < %.1f %%: %s)" %
              (per_viewer, TARGET_PCT, "met" if per_viewer < TARGET_PCT else "MISSED"))
        print("  frames per viewer in their common span: %s of the %d sent (%.1f frames/s; "
              "errors %s)" % (counts, len(union), stream_fps,
                              [v.error for v in viewers if v.error]))
        print("  every viewer kept up: %s" % ("yes" if kept_up else "NO"))
        if args.check and not kept_up:
            return 1
        return 0
    finally:
        for v in viewers:
            v.running = False
            v.ws.sock.close()
        stop(daemon)
        stop(sim)
        log.close()
        shutil.rmtree(workdir, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
