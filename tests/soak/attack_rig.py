"""The rig every runtime attack of the attack suite (attack.py) runs on, and its measures.

One rig = one gimbal-sim Orion over TCP (with --rx-log: every packet it receives, timed on
its own steady clock) + one fresh gimbald whose configuration allows the laser with
`laser.fire_timeout_s` 2 and adds what the attack needs (video input, HTTP, the MAVLink
endpoint, a MAVLink gimbal device, terrain). While the attack's traffic runs, the rig:

- fires the laser (index 0) once and never renews it, then waits for the cease-fire at the
  simulated Orion; in a longer run, fires again after each cease. The delay is measured from
  the moment the client sent the fire to the moment the cease packet reached the simulator:
  gimbal-sim's rx-log times are CLOCK_MONOTONIC seconds since its start (std::chrono::
  steady_clock), the same clock as Python's time.monotonic(); the offset is calibrated once
  before the attack with a harmless laser command (index 1, all off) on a quiet link;
- pings gimbald from another address (127.0.0.2) every 20 ms, in its own process
  (attack_pinger.py);
- samples gimbald's VmRSS every 50 ms and its anonymous memory (smaps_rollup) every 250 ms.

Targets (issue 25, contract section 14 v4): cease-fire within fire_timeout + 0.25 s, ping p99
under 50 ms, RSS under 128 MB and back within 16 MB of its start after the attack; and
gimbald stops within 5 s of SIGTERM.
"""

import json
import math
import os
import signal
import socket
import subprocess
import threading
import time

from attack_figures import CEASE_LIMIT_S, FIRE_TIMEOUT_S, RSS_RETURN_MB, STOP_LIMIT_S
from attack_process import MemorySampler, Pinger, proc_anon_kb, proc_rss_kb


class AttackSkipped(Exception):
    """A tool the attack needs is missing (a failure under CI=true)."""


def free_port(kind=socket.SOCK_DGRAM, host="127.0.0.1"):
    with socket.socket(socket.AF_INET, kind) as s:
        s.bind((host, 0))
        return s.getsockname()[1]


def read_json_lines(path, offset=0):
    """(objects, new offset) of the complete JSON lines of a file from `offset`."""
    try:
        with open(path, "rb") as f:
            f.seek(offset)
            chunk = f.read()
    except OSError:
        return [], offset
    end = chunk.rfind(b"\n") + 1
    out = []
    for line in chunk[:end].splitlines():
        try:
            out.append(json.loads(line))
        except ValueError:
            continue
    return out, offset + end


class Client:
    """A JSON command socket client on its own address; replies collected by a thread."""

    def __init__(self, port, source="127.0.0.1"):
        self.port = port
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.sock.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 1 << 21)
        self.sock.bind((source, 0))
        self.replies = {}  # id -> (arrival, reply)
        self.pushes = []  # (arrival, datagram) without an id: subscription pushes
        self.cond = threading.Condition()
        self.serial = 0
        self.running = True
        self.thread = threading.Thread(target=self._run, daemon=True)
        self.thread.start()

    def _run(self):
        self.sock.settimeout(0.1)
        while self.running:
            try:
                data = self.sock.recv(65536)
            except socket.timeout:
                continue
            except OSError:
                if not self.running:
                    return
                continue
            now = time.monotonic()
            try:
                msg = json.loads(data)
            except ValueError:
                continue
            with self.cond:
                if isinstance(msg, dict) and msg.get("id") is not None and "type" not in msg:
                    self.replies[msg["id"]] = (now, msg)
                else:
                    self.pushes.append((now, msg))
                self.cond.notify_all()

    def send(self, request):
        """Sends and returns the request's id (one is given when missing)."""
        if "id" not in request:
            self.serial += 1
            request = dict(request, id="r%d" % self.serial)
        self.sock.sendto(json.dumps(request).encode(), ("127.0.0.1", self.port))
        return request["id"]

    def reply(self, request_id, timeout):
        deadline = time.monotonic() + timeout
        with self.cond:
            while request_id not in self.replies:
                left = deadline - time.monotonic()
                if left <= 0:
                    return None
                self.cond.wait(left)
            return self.replies[request_id][1]

    def request(self, request, timeout=3.0):
        return self.reply(self.send(request), timeout)

    def close(self):
        self.running = False
        self.sock.close()
        self.thread.join(timeout=1)


class Rig:
    """gimbal-sim + a fresh gimbald configured for one attack."""

    def __init__(self, suite, figures, video=None, video_extra=None, http=False, mavlink=None,
                 device=False, terrain=None, command=None, start_timeout=None):
        self.suite, self.figures = suite, figures
        self.dir = suite.attack_dir(figures.name)
        self.children = []
        self.sim_port = None
        self.command_port = free_port()
        self.video_port = free_port() if video == "udp" else None
        self.video, self.video_extra = video, video_extra or {}
        self.http_port = free_port(socket.SOCK_STREAM) if http else None
        self.mavlink_port = free_port() if mavlink is not None else None
        self.device_port = free_port() if device else None
        self.device_local_port = free_port() if device else None
        self.mavlink, self.device, self.terrain = mavlink, device, terrain
        self.command = command or {}
        self.start_timeout = start_timeout or (3.0 if suite.brief else 8.0)
        self.log_path = os.path.join(self.dir, "gimbald.log")
        self.rx_path = os.path.join(self.dir, "sim-rx.jsonl")
        self.stats = {}  # counters the attack's traffic keeps (shown in the notes)
        self.stats_lock = threading.Lock()
        self.fires = []  # (send time, request id)
        self.epoch = None
        # How far the epoch may be off: half the calibrating exchange's round trip (a loaded
        # machine's can be tens of ms), or the simulator's start's few ms.
        self.epoch_error = 0.005
        self.daemon = None
        self.client = None
        self.ready = False

    # --- set-up --------------------------------------------------------------------------
    def config(self):
        # reconnect_min_s: gimbald may start before the simulator listens; it then retries
        # soon instead of after the default 0.2 s (the suite starts a hundred of them).
        orion = {"name": "orion", "protocol": "orion",
                 "link": {"type": "tcp", "host": "127.0.0.1", "port": self.sim_port,
                          "reconnect_min_s": 0.05}}
        config = {"gimbals": [orion],
                  "command": dict({"port": self.command_port}, **self.command),
                  "laser": {"allow_fire": True, "fire_timeout_s": FIRE_TIMEOUT_S},
                  "log": {"level": "info"}}
        if self.video == "udp":
            orion["video"] = dict({"input": "udp://127.0.0.1:%d" % self.video_port},
                                  **self.video_extra)
        elif self.video is not None:
            orion["video"] = dict({"input": self.video}, **self.video_extra)
        if self.http_port:
            config["http"] = {"bind": "127.0.0.1", "port": self.http_port}
        if self.mavlink is not None:
            orion["feed"] = {"autopilot": False}
            config["vehicle"] = {"source": {"type": "udp", "bind": "127.0.0.1",
                                            "port": self.mavlink_port}}
            config["mavlink"] = dict({"gimbal_manager": True, "system_id": 1}, **self.mavlink)
        if self.device:
            config["gimbals"].append({"name": "dev", "protocol": "mavlink",
                                      "link": {"type": "udp", "host": "127.0.0.1",
                                               "port": self.device_port,
                                               "local_port": self.device_local_port}})
        if self.terrain is not None:
            config["terrain"] = {"files": list(self.terrain), "geoid": "none"}
        return config

    def start(self):
        self.start_sim()
        path = os.path.join(self.dir, "gimbald.json")
        with open(path, "w") as f:
            json.dump(self.config(), f, indent=1)
        self.config_path = path
        self.daemon = subprocess.Popen([self.suite.gimbald, "-c", path],
                                       stdout=open(self.log_path, "wb"), stderr=subprocess.STDOUT,
                                       stdin=subprocess.DEVNULL)
        self.children.append(self.daemon)
        self.client = Client(self.command_port)
        self.ready = self.wait_ready()
        if self.sim.poll() is not None:
            raise RuntimeError("gimbal-sim exited at start: " + self.sim_errors())
        if self.daemon.poll() is not None:
            self.figures.fail("gimbald exited at start (code %s): %s" % (
                self.daemon.returncode, self.log_tail()))
            return False
        if not self.ready:
            # Hung at start (a terrain read, say): the attack is measured all the same, with
            # the simulator's start as its clock's origin (a few ms early at most).
            self.figures.fail("gimbald not ready within %.0f s of its start" % self.start_timeout)
            self.epoch = self.sim_started
            return True
        self.calibrate()
        return True

    def start_sim(self):
        """gimbal-sim on a port picked here, so gimbald can start at once beside it (it
        connects as soon as the simulator listens)."""
        self.sim_port = free_port(socket.SOCK_STREAM)
        self.sim_started = time.monotonic()
        self.sim = subprocess.Popen(
            [self.suite.gimbal_sim, "--no-discovery", "--port", str(self.sim_port), "--rx-log",
             self.rx_path], stdout=subprocess.DEVNULL,
            stderr=open(os.path.join(self.dir, "sim.stderr"), "wb"), stdin=subprocess.DEVNULL)
        self.children.append(self.sim)

    def sim_errors(self):
        try:
            with open(os.path.join(self.dir, "sim.stderr"), errors="replace") as f:
                return " ".join(f.read().split())[-300:]
        except OSError:
            return ""

    def wait_ready(self):
        """The Orion's link is up and its telemetry reached STATE."""
        deadline = time.monotonic() + self.start_timeout
        while time.monotonic() < deadline:
            if self.daemon.poll() is not None:
                return False
            r = self.client.request({"cmd": "state", "gimbal": "orion", "keys": ["telemetry"]},
                                    timeout=0.5)
            if r and r.get("ok") and r["state"]["link"].get("connected") and \
                    r["state"].get("telemetry"):
                return True
            if self.sim.poll() is not None:
                return False
            time.sleep(0.05)
        return False

    def calibrate(self):
        """The simulator's clock offset: a laser command for index 1 (all off) on a quiet
        link; its arrival at the simulator lies between our send and the reply."""
        best = None
        for _ in range(3):
            sent = time.monotonic()
            r = self.client.request({"cmd": "laser", "gimbal": "orion", "index": 1,
                                     "enable": False, "arm": False, "fire": False}, timeout=2.0)
            replied = time.monotonic()
            if not r or not r.get("ok"):
                continue
            line = None
            deadline = time.monotonic() + 1.0
            while line is None and time.monotonic() < deadline:
                entries = [e for e in self.rx_laser() if e[1] == 1]
                line = entries[-1] if entries else None
                if line is None:
                    time.sleep(0.01)
            if line is None:
                continue
            offset = (sent + replied) / 2.0 - line[0]
            spread = replied - sent
            if best is None or spread < best[1]:
                best = (offset, spread)
        if best is None:
            self.figures.note("clock not calibrated (no laser command at the simulator): "
                              "the simulator's start is used")
            self.epoch = self.sim_started
            return
        self.epoch = best[0]
        # Capped: a fire is still told from the one before it (fires are seconds apart).
        self.epoch_error = min(best[1] / 2.0, 0.25)
        if best[1] > 0.1:
            self.figures.note("clock calibrated within %.3f s only (a loaded machine): cease-fire "
                              "times are that uncertain" % (best[1] / 2.0))

    def rx_laser(self):
        """(sim time, index, fire) of every laser command the simulator received."""
        out = []
        lines, _ = read_json_lines(self.rx_path)
        for e in lines:
            if e.get("name") != "laser_cmd":
                continue
            p = e.get("packet") or {}
            out.append((e["t"], int(p.get("index", 0)), bool(p.get("fire"))))
        return out

    # --- under attack --------------------------------------------------------------------
    def count(self, key, n=1):
        with self.stats_lock:
            self.stats[key] = self.stats.get(key, 0) + n

    def fire(self):
        n = len(self.fires) + 1
        sent = time.monotonic()
        rid = self.client.send({"cmd": "laser", "gimbal": "orion", "id": "fire-%d" % n,
                                "index": 0, "enable": True, "arm": True, "fire": True})
        self.fires.append((sent, rid))
        return sent

    def laser_events(self, since):
        """The first fire-on at the simulator after `since` (our clock) and the first
        fire-off after it: (fire_at, cease_at) in our clock, None where missing."""
        fire_at = cease_at = None
        for t, index, firing in self.rx_laser():
            if index != 0:
                continue
            at = t + self.epoch
            if fire_at is None:
                # A fire sent at `since` arrives after it, give or take the epoch's error.
                if firing and at >= since - self.epoch_error - 0.002:
                    fire_at = at
            elif not firing and at > fire_at:
                cease_at = at
                break
        return fire_at, cease_at

    def ceased(self, sent):
        return self.laser_events(sent)[1] is not None

    def measure(self, traffic, seconds=None, ramp=None, during=None):
        """Runs the traffic functions (each `fn(stop_event)`, in a thread) for `seconds`, fires
        the laser and measures. `during(elapsed)` is called about every 100 ms, for attacks
        that watch something while they run."""
        f = self.figures
        if self.daemon is None or self.daemon.poll() is not None:
            return
        seconds = self.suite.seconds if seconds is None else seconds
        ramp = (0.2 if self.suite.brief else 1.0) if ramp is None else ramp
        grace = 1.5 if self.suite.brief else 4.0
        pid = self.daemon.pid
        f.rss_start_kb, f.anon_start_kb = proc_rss_kb(pid), proc_anon_kb(pid)
        sampler = MemorySampler(pid)
        pinger = Pinger(self.command_port)
        time.sleep(0.05)  # the pinger's first pings land before the attack
        stop = threading.Event()
        errors = []

        def guarded(fn):
            def run():
                try:
                    fn(stop)
                except Exception as e:  # the attack could not run: say so, never pass quietly
                    errors.append("%s: %s: %s" % (getattr(fn, "__name__", "traffic"),
                                                  type(e).__name__, e))
            return run

        threads = [threading.Thread(target=guarded(fn), daemon=True) for fn in traffic]
        t0 = time.monotonic()
        for t in threads:
            t.start()
        self.sleep_watching(ramp, during, t0)
        while True:
            sent = self.fire()
            ceased = self.wait_watching(sent, CEASE_LIMIT_S + grace, during, t0)
            if not ceased or self.daemon.poll() is not None:
                break
            if time.monotonic() - t0 + 0.3 + CEASE_LIMIT_S + 0.2 > seconds:
                break
            self.sleep_watching(0.3, during, t0)
        self.sleep_watching(max(0.0, seconds - (time.monotonic() - t0)), during, t0)
        stop.set()
        for t in threads:
            t.join(timeout=10)
        f.elapsed_s = time.monotonic() - t0
        if errors:
            for e in errors:
                f.fail("attack traffic failed: " + e)
        alive = self.daemon.poll() is None
        if not alive:
            f.fail("gimbald exited during the attack (code %s)" % self.daemon.returncode)
        # Settle: memory should come back within 16 MB of the start.
        settle = 1.5 if self.suite.brief else 4.0
        deadline = time.monotonic() + settle
        while alive and time.monotonic() < deadline:
            rss = proc_rss_kb(pid)
            if rss is not None and rss - f.rss_start_kb <= RSS_RETURN_MB * 1024:
                break
            time.sleep(0.1)
        # A cease-fire that is late comes once gimbald has worked off what the attack left
        # it: wait for it a while, so the row shows how late it was.
        late_cap = 8.0 if self.suite.brief else 20.0
        while alive and self.daemon.poll() is None:
            waiting = [sent for sent, _ in self.fires
                       if self.laser_events(sent)[0] is not None and
                       self.laser_events(sent)[1] is None and
                       time.monotonic() < sent + late_cap]
            if not waiting:
                break
            time.sleep(0.1)
        f.ping = pinger.stop()
        sampler.stop()
        f.rss_end_kb, f.anon_end_kb = proc_rss_kb(pid), proc_anon_kb(pid)
        f.rss_peak_kb = max(x or 0 for x in (sampler.peak_kb, f.rss_start_kb, f.rss_end_kb))
        f.anon_peak_kb = max(x or 0 for x in (sampler.peak_anon_kb, f.anon_start_kb,
                                               f.anon_end_kb))
        for sent, rid in self.fires:
            fire_at, cease_at = self.laser_events(sent)
            reply = self.client.reply(rid, 0.01)
            if fire_at is None:
                # What the simulator logged, for the reader: a fire-on just before `since`
                # would mean a clock calibration further off than its round trip says.
                ons = [t + self.epoch - sent for t, index, firing in self.rx_laser()
                       if index == 0 and firing]
                f.fail("the fire never reached the gimbal (reply: %s; fire-on at the simulator: "
                       "%s s from the send, clock within %.3f s)" % (
                           "none" if reply is None else
                           "ok" if reply.get("ok") else reply.get("error", {}).get("code"),
                           ", ".join("%+.3f" % d for d in ons) or "none", self.epoch_error))
                continue
            f.cease_s.append(None if cease_at is None else cease_at - sent)
        if self.stats:
            f.note(", ".join("%s %s" % (k, human(v)) for k, v in sorted(self.stats.items())))

    def sleep_watching(self, seconds, during, t0):
        end = time.monotonic() + seconds
        while True:
            left = end - time.monotonic()
            if left <= 0:
                return
            if during:
                during(time.monotonic() - t0)
            time.sleep(min(0.1, left))

    def wait_watching(self, sent, timeout, during, t0):
        """Waits for the cease-fire of the fire sent at `sent` (True), at most until
        sent + timeout, polling the rx-log every 20 ms and `during` every 100 ms."""
        end = sent + timeout
        next_during = time.monotonic()
        while time.monotonic() < end:
            if self.ceased(sent):
                return True
            if self.daemon.poll() is not None:
                return False
            if during and time.monotonic() >= next_during:
                during(time.monotonic() - t0)
                next_during = time.monotonic() + 0.1
            time.sleep(0.02)
        return self.ceased(sent)

    def note_shutdown_ceases(self):
        """A fire that was never ceased in time may still be ceased by the shutdown."""
        if self.epoch is None or None not in self.figures.cease_s:
            return
        time.sleep(0.1)
        for sent, _ in self.fires:
            fire_at, cease_at = self.laser_events(sent)
            late = self.suite.brief and 8.0 or 20.0
            if fire_at is not None and cease_at is not None and cease_at - sent > late:
                self.figures.note("fire at %.1f s: ceased only by the shutdown, %.1f s after "
                                  "the fire" % (sent - self.fires[0][0], cease_at - sent))

    # --- logs and stop -------------------------------------------------------------------
    def logs(self):
        lines, _ = read_json_lines(self.log_path)
        return lines

    def accepted_fires(self):
        n = 0
        for _, rid in self.fires:
            r = self.client.reply(rid, 0.01) if self.client else None
            n += 1 if r and r.get("ok") else 0
        return n

    def check_safety_lines(self):
        """Under a log flood, every accepted fire still has its `laser_fire` and `audit` lines
        and every cease its `laser_deadman` line (contract section 14 v4: never rolled up)."""
        f = self.figures
        logs = self.logs()
        fired = self.accepted_fires()
        ceased = sum(1 for d in f.cease_s if d is not None)
        laser_fire = sum(1 for e in logs if e.get("event") == "laser_fire")
        audit = sum(1 for e in logs if e.get("event") == "audit" and e.get("cmd") == "laser"
                    and e.get("fire") is True)
        deadman = sum(1 for e in logs if e.get("event") == "laser_deadman")
        f.note("fires accepted %d: laser_fire lines %d, audit (fire) %d, laser_deadman %d"
               % (fired, laser_fire, audit, deadman))
        f.check(laser_fire >= fired, "%d laser_fire lines for %d fires" % (laser_fire, fired))
        f.check(audit >= fired, "%d audit lines for %d fires" % (audit, fired))
        f.check(deadman >= ceased, "%d laser_deadman lines for %d cease-fires"
                % (deadman, ceased))

    def log_rate(self, event):
        """(lines of `event`, most in one second, lines per second over the run)."""
        seconds = {}
        for e in self.logs():
            if e.get("event") == event and isinstance(e.get("ts"), str):
                key = e["ts"][:19]
                seconds[key] = seconds.get(key, 0) + 1
        total = sum(seconds.values())
        span = max(1, len(seconds))
        return total, max(seconds.values(), default=0), total / span

    def log_tail(self, n=600):
        try:
            with open(self.log_path, "rb") as f:
                f.seek(0, 2)
                size = f.tell()
                f.seek(max(0, size - n))
                return f.read().decode(errors="replace").strip().replace("\n", " | ")
        except OSError:
            return ""

    def stop(self):
        """SIGTERM gimbald and time its exit (math.inf: still running after STOP_LIMIT_S,
        then killed); then the simulator (its rx-log is flushed line by line)."""
        if self.client:
            self.client.close()
        if self.daemon is not None and self.daemon.poll() is None:
            t0 = time.monotonic()
            self.daemon.send_signal(signal.SIGTERM)
            try:
                self.daemon.wait(timeout=STOP_LIMIT_S)
                self.figures.stop_s = time.monotonic() - t0
            except subprocess.TimeoutExpired:
                self.daemon.kill()
                self.daemon.wait()
                self.figures.stop_s = math.inf
            self.note_shutdown_ceases()
        for p in self.children:
            if p.poll() is None:
                p.kill()
            p.wait()


def human(v):
    return "%.1f" % v if isinstance(v, float) else "{:,}".format(v)
