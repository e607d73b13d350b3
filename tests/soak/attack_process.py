"""Measuring gimbald as a process: its memory (VmRSS, VmHWM, the anonymous memory of
smaps_rollup), a concurrent ping from another address in a process of its own
(attack_pinger.py), and a command run under a deadline with its peak memory."""

import json
import os
import subprocess
import sys
import threading
import time

PING_INTERVAL_S = 0.02
PING_SOURCE = "127.0.0.2"
HERE = os.path.dirname(os.path.abspath(__file__))


def proc_rss_kb(pid):
    try:
        with open("/proc/%d/status" % pid) as f:
            for line in f:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1])
    except OSError:
        pass
    return None


def proc_anon_kb(pid):
    try:
        with open("/proc/%d/smaps_rollup" % pid) as f:
            for line in f:
                if line.startswith("Anonymous:"):
                    return int(line.split()[1])
    except OSError:
        pass
    return None


class MemorySampler(threading.Thread):
    def __init__(self, pid):
        super().__init__(daemon=True)
        self.pid = pid
        self.running = True
        self.peak_kb = 0
        self.peak_anon_kb = 0
        self.start()

    def run(self):
        n = 0
        while self.running:
            rss = proc_rss_kb(self.pid)
            if rss is None:
                return
            self.peak_kb = max(self.peak_kb, rss)
            if n % 5 == 0:
                self.peak_anon_kb = max(self.peak_anon_kb, proc_anon_kb(self.pid) or 0)
            n += 1
            time.sleep(0.05)

    def stop(self):
        self.running = False
        self.join(timeout=2)


class Pinger:
    def __init__(self, port):
        self.proc = subprocess.Popen(
            [sys.executable, os.path.join(HERE, "attack_pinger.py"), str(port), PING_SOURCE,
             str(PING_INTERVAL_S)], stdin=subprocess.PIPE, stdout=subprocess.PIPE)

    def stop(self):
        try:
            out, _ = self.proc.communicate(input=b"stop\n", timeout=10)
            return json.loads(out)
        except (OSError, ValueError, subprocess.TimeoutExpired):
            self.proc.kill()
            return {"sent": 0, "rtts_ms": [], "lost": 0}


def proc_hwm_kb(pid):
    try:
        with open("/proc/%d/status" % pid) as f:
            for line in f:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1])
    except OSError:
        pass
    return None


def run_measured(args, timeout, stdin=subprocess.DEVNULL):
    """Runs a command with a deadline; (exit code or None when killed at the deadline,
    seconds, peak RSS in kB, output). The peak is the child's VmHWM read every 5 ms while it
    runs (wait4's ru_maxrss would count the suite's own memory: Linux carries the parent's
    high-water mark over fork and exec)."""
    out_path = "/tmp/attack-run-%d.out" % os.getpid()
    peak = 0
    with open(out_path, "wb") as out:
        t0 = time.monotonic()
        proc = subprocess.Popen(args, stdout=out, stderr=subprocess.STDOUT, stdin=stdin)
        code = None
        while True:
            hwm = proc_hwm_kb(proc.pid)
            if hwm is not None:
                peak = max(peak, hwm)
            try:
                code = proc.wait(timeout=0.005)
                break
            except subprocess.TimeoutExpired:
                pass
            if time.monotonic() - t0 > timeout:
                proc.kill()
                proc.wait()
                code = None
                break
        elapsed = time.monotonic() - t0
    with open(out_path, "rb") as f:
        text = f.read().decode(errors="replace")
    os.unlink(out_path)
    return code, elapsed, peak, text
