"""Shared helpers of the gimbald integration tests (tests/integration/test_gimbald_*.py).

Real binaries only: gimbald, gimbalctl and gimbal-sim, named by the environment variables
GIMBALD, GIMBALCTL and GIMBAL_SIM (ctest sets them). Python 3 standard library only.

Rules every helper keeps: every wait has a deadline, every child process is killed on
cleanup (also when a test fails), and every port is picked free (bind to port 0) so tests
can run beside other daemons and simulators.
"""

import json
import math
import os
import select
import signal
import socket
import struct
import subprocess
import sys
import tempfile
import time
import unittest

import skipping

GIMBALD = os.environ.get("GIMBALD")
GIMBALCTL = os.environ.get("GIMBALCTL")
GIMBAL_SIM = os.environ.get("GIMBAL_SIM")
SKIP = 77

# Generous bounds for a busy 2-core machine; tests assert behaviour, not speed.
START_TIMEOUT_S = 10.0
STOP_TIMEOUT_S = 5.0
REPLY_TIMEOUT_S = 3.0


def main():
    """unittest.main(), or exit 77 (skipped; on CI a failure, skipping.py) when a binary is
    not named in the environment."""
    missing = [name for name, path in (("GIMBALD", GIMBALD), ("GIMBALCTL", GIMBALCTL),
                                       ("GIMBAL_SIM", GIMBAL_SIM)) if not path]
    if missing:
        skipping.need_for_file("%s not set" % ", ".join(missing))
    unittest.main(verbosity=2)


# --- waiting ---------------------------------------------------------------------------------

def wait_for(predicate, timeout, interval=0.05):
    """Calls predicate() until it returns something truthy or `timeout` seconds pass.

    Returns the last value predicate() returned (falsy on timeout)."""
    deadline = time.monotonic() + timeout
    while True:
        value = predicate()
        if value or time.monotonic() >= deadline:
            return value
        time.sleep(interval)


# --- ports and files -------------------------------------------------------------------------

def settled_projection(client, gimbal, point, within=0.1, timeout=20, still=0.005):
    """`project`'s reply for point once it lies within `within` of the picture's centre and
    the camera has settled: two replies 0.2 s apart agree to `still` (a box drawn while the
    gimbal still slews is drawn on a picture that no longer shows it there). None on timeout."""
    previous = [None]

    def settled():
        reply = client.request("project", gimbal=gimbal, **point)
        if not (reply and reply.get("ok") and reply["visible"] and
                abs(reply["x"]) < within and abs(reply["y"]) < within):
            previous[0] = None
            return None
        before, previous[0] = previous[0], reply
        if before and abs(reply["x"] - before["x"]) < still and \
                abs(reply["y"] - before["y"]) < still:
            return reply
        return None
    return wait_for(settled, timeout, 0.2)


def free_port(kind=socket.SOCK_DGRAM):
    """A port nobody listens on right now (the kernel's pick for port 0)."""
    with socket.socket(socket.AF_INET, kind) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def closed_tcp_port():
    """A TCP port with no listener: connecting to it is refused."""
    return free_port(socket.SOCK_STREAM)


_serial = [0]


def unique_path(workdir, prefix, suffix):
    """A new file name in the test's private directory."""
    _serial[0] += 1
    return os.path.join(workdir, "%s%d%s" % (prefix, _serial[0], suffix))


def read_json_lines(path):
    """Every complete JSON line of a file (a half-written last line is left for later)."""
    try:
        with open(path, "rb") as f:
            data = f.read()
    except FileNotFoundError:
        return []
    out = []
    for line in data.split(b"\n")[:-1]:
        line = line.strip()
        if not line:
            continue
        try:
            out.append(json.loads(line))
        except ValueError:
            out.append({"unparsed": line.decode(errors="replace")})
    return out


def read_line(pipe, timeout):
    """One line from a child's binary stdout pipe, or what arrived before `timeout` passed.
    Reads byte by byte from the descriptor so no buffered data hides from select()."""
    line = b""
    deadline = time.monotonic() + timeout
    while not line.endswith(b"\n"):
        ready, _, _ = select.select([pipe], [], [], max(0.0, deadline - time.monotonic()))
        if not ready:
            break
        byte = os.read(pipe.fileno(), 1)
        if not byte:
            break
        line += byte
    return line.decode(errors="replace")


def stop_process(proc, sig=signal.SIGTERM, timeout=STOP_TIMEOUT_S):
    """Sends `sig`, waits up to `timeout`, then kills. Returns the exit code."""
    if proc.poll() is None:
        try:
            proc.send_signal(sig)
            proc.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait(timeout=timeout)
    return proc.returncode


def run(args, timeout=20.0, **kwargs):
    """subprocess.run with a deadline; returns the CompletedProcess (text mode)."""
    return subprocess.run(args, capture_output=True, text=True, timeout=timeout, **kwargs)


# --- configuration ---------------------------------------------------------------------------

def orion_tcp(name, port, host="127.0.0.1", **link):
    """An Orion gimbal over TCP; `link` adds keys such as reconnect_max_s."""
    return {"name": name, "protocol": "orion",
            "link": dict({"type": "tcp", "host": host, "port": port}, **link)}


def orion_serial(name, device, baud=115200, **link):
    return {"name": name, "protocol": "orion",
            "link": dict({"type": "serial", "device": device, "baud": baud}, **link)}


# --- Orion wire and geodesy, computed independently of the product ---------------------------

def fletcher251(data):
    """The OrionPublic checksum (ICD: Fletcher-16 modulo 251, seeded with the first byte)."""
    a = b = 0
    for i, byte in enumerate(data):
        if i == 0:
            a = b = (byte + 1) % 251
        else:
            a = (a + byte) % 251
            b = (b + a) % 251
    return (a << 8) | b


def frame(pkt_id, data=b""):
    """A whole OrionPublic frame: sync D0 0D, id, length, data, checksum."""
    head = bytes([0xD0, 0x0D, pkt_id, len(data)]) + bytes(data)
    return head + struct.pack(">H", fletcher251(head))


def scaled(value, scale):
    """The contract's encoding rule: value x scale rounded half away from zero."""
    v = value * scale
    return int(math.floor(abs(v) + 0.5)) * (1 if v >= 0 else -1)


WGS84_A = 6378137.0
WGS84_F = 1 / 298.257223563
WGS84_E2 = WGS84_F * (2 - WGS84_F)


def lla_to_ecef(lat_deg, lon_deg, alt_m):
    lat, lon = math.radians(lat_deg), math.radians(lon_deg)
    n = WGS84_A / math.sqrt(1 - WGS84_E2 * math.sin(lat) ** 2)
    return ((n + alt_m) * math.cos(lat) * math.cos(lon),
            (n + alt_m) * math.cos(lat) * math.sin(lon),
            (n * (1 - WGS84_E2) + alt_m) * math.sin(lat))


def ecef_to_lla(x, y, z):
    """Geodetic degrees/metres from ECEF metres (fixed-point iteration; mm after 5 rounds)."""
    lon = math.atan2(y, x)
    p = math.hypot(x, y)
    lat = math.atan2(z, p * (1 - WGS84_E2))
    alt = 0.0
    for _ in range(8):
        n = WGS84_A / math.sqrt(1 - WGS84_E2 * math.sin(lat) ** 2)
        alt = p / math.cos(lat) - n
        lat = math.atan2(z, p * (1 - WGS84_E2 * n / (n + alt)))
    return math.degrees(lat), math.degrees(lon), alt


def ground_distance_m(lat1, lon1, lat2, lon2):
    """Horizontal distance, metres (equirectangular: fine over a few km)."""
    north = math.radians(lat2 - lat1) * 6371000.0
    east = math.radians(lon2 - lon1) * 6371000.0 * math.cos(math.radians((lat1 + lat2) / 2))
    return math.hypot(north, east)


def angle_diff_deg(a, b):
    """|a - b| for angles in degrees, wrapped to 0..180."""
    return abs((a - b + 180.0) % 360.0 - 180.0)


# --- Viewpro wire, computed independently of the product (viewpro-target-gps-protocol.md) ---

VIEWPRO_FORMATS = ("out1", "out2", "out3", "out4")


def viewpro_serial(name, device, baud=115200, output=None, **link):
    """A Viewpro gimbal on a serial device; `output` is gimbals[].viewpro.output."""
    gimbal = {"name": name, "protocol": "viewpro",
              "link": dict({"type": "serial", "device": device, "baud": baud}, **link)}
    if output is not None:
        gimbal["viewpro"] = {"output": output}
    return gimbal


def viewpro_tcp(name, port, host="127.0.0.1", output=None, **link):
    gimbal = {"name": name, "protocol": "viewpro",
              "link": dict({"type": "tcp", "host": host, "port": port}, **link)}
    if output is not None:
        gimbal["viewpro"] = {"output": output}
    return gimbal


def viewpro_mode_byte(osd, serial, network, format):
    """ICD section 1: bit 0 OSD shows the target, bit 3 network, bit 4 serial, bits 5-7 OUTx."""
    return ((VIEWPRO_FORMATS.index(format) << 5) | (0x01 if osd == "target" else 0) |
            (0x08 if network else 0) | (0x10 if serial else 0))


def viewpro_command(set_id, value):
    """An `AA 55 ID XX FF` command; a negative value is its int8 byte."""
    return bytes([0xAA, 0x55, set_id, value & 0xFF, 0xFF])


def viewpro_mode(osd="target", serial=True, network=False, format="out3"):
    return viewpro_command(0x0F, viewpro_mode_byte(osd, serial, network, format))


def sum8(data):
    """The Viewpro checksum: the low byte of the sum of the bytes before it."""
    return sum(data) & 0xFF


def by_kind(kind):
    """An rx-log predicate for gimbal-sim --protocol viewpro lines."""
    return lambda entry: entry.get("kind") == kind


# --- gimbal-sim ------------------------------------------------------------------------------

class Sim:
    """A gimbal-sim process with an rx log; endpoints read from its stdout ("tcp: H:P")."""

    def __init__(self, workdir, *args, port=0, tcp=True, pty_link=None, want=None):
        self.rx_log = unique_path(workdir, "rx-", ".jsonl")
        cmd = [GIMBAL_SIM, "--no-discovery", "--rx-log", self.rx_log]
        cmd += ["--port", str(port)] if tcp else ["--no-tcp"]
        if pty_link:
            cmd += ["--pty", "--pty-link", pty_link]
        cmd += list(args)
        want = want or (("tcp",) if tcp else ("pty",))
        self.stderr_path = self.rx_log.replace(".jsonl", ".stderr")
        self._stderr = open(self.stderr_path, "wb")
        self.proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=self._stderr)
        self.endpoints = {}
        pending = b""
        deadline = time.monotonic() + START_TIMEOUT_S
        # Raw reads, not readline(): a buffered reader can hold a line select() cannot see.
        while not all(w in self.endpoints for w in want):
            if time.monotonic() > deadline or self.proc.poll() is not None:
                self.kill()
                raise RuntimeError("gimbal-sim did not print %s: %s" % (want, self.errors()))
            ready, _, _ = select.select([self.proc.stdout], [], [], 0.2)
            if ready:
                chunk = os.read(self.proc.stdout.fileno(), 4096)
                pending += chunk
                *lines, pending = pending.split(b"\n")
                for line in lines:
                    key, _, value = line.decode().strip().partition(": ")
                    if value:
                        self.endpoints[key] = value

    @property
    def port(self):
        return int(self.endpoints["tcp"].rsplit(":", 1)[1])

    def errors(self):
        try:
            with open(self.stderr_path, "rb") as f:
                return f.read().decode(errors="replace")
        except OSError:
            return ""

    def rx(self):
        """Every packet gimbal-sim received so far (rx log entries)."""
        return read_json_lines(self.rx_log)

    def wait_rx(self, predicate, timeout=REPLY_TIMEOUT_S, start=0):
        """The first rx entry at index >= start for which predicate(entry) is true, or None."""
        def find():
            for entry in self.rx()[start:]:
                if predicate(entry):
                    return entry
            return None
        return wait_for(find, timeout)

    def running(self):
        return self.proc.poll() is None

    def stop(self, sig=signal.SIGTERM):
        code = stop_process(self.proc, sig)
        if self.proc.stdout and not self.proc.stdout.closed:
            self.proc.stdout.close()
        if not self._stderr.closed:
            self._stderr.close()
        return code

    def kill(self):
        return self.stop(signal.SIGKILL)


def by_name(name):
    return lambda entry: entry.get("name") == name


# --- gimbald ---------------------------------------------------------------------------------

class Daemon:
    """A gimbald process on a free UDP command port; its JSON log lines read from stdout."""

    def __init__(self, workdir, config, args=(), wait_started=True):
        self.workdir = workdir
        self.config = json.loads(json.dumps(config))
        self.args = list(args)
        for _ in range(3):
            # The free port may be taken between our pick and gimbald's bind: retry.
            self.config.setdefault("command", {})
            if "port" not in config.get("command", {}):
                self.config["command"]["port"] = free_port()
            self.port = self.config["command"]["port"]
            self._launch()
            if not wait_started:
                return
            if self.wait_log(lambda e: e.get("event") == "start", START_TIMEOUT_S,
                             until_exit=True):
                return
            code = self.stop(signal.SIGKILL)
            if code != 2 or "port" in config.get("command", {}):
                break
        raise RuntimeError("gimbald did not start (exit %s): %s\n%s" %
                           (self.proc.returncode, self.errors(), self.log_text()))

    def _launch(self):
        self.stopped = False  # set once stop() was called: a later exit is expected
        self.config_path = unique_path(self.workdir, "gimbald-", ".json")
        with open(self.config_path, "w") as f:
            json.dump(self.config, f)
        self.stdout_path = self.config_path.replace(".json", ".stdout")
        self.stderr_path = self.config_path.replace(".json", ".stderr")
        self._stdout = open(self.stdout_path, "wb")
        self._stderr = open(self.stderr_path, "wb")
        self.proc = subprocess.Popen([GIMBALD, "-c", self.config_path, *self.args],
                                     stdout=self._stdout, stderr=self._stderr,
                                     stdin=subprocess.DEVNULL)

    def logs(self):
        return read_json_lines(self.stdout_path)

    def log_text(self):
        with open(self.stdout_path, "rb") as f:
            return f.read().decode(errors="replace")

    def errors(self):
        with open(self.stderr_path, "rb") as f:
            return f.read().decode(errors="replace")

    def events(self, name):
        return [e for e in self.logs() if e.get("event") == name]

    def wait_log(self, predicate, timeout=REPLY_TIMEOUT_S, until_exit=False):
        """The first log entry with predicate(entry) true, or None (also when gimbald exits
        first and until_exit is set)."""
        def find():
            for e in self.logs():
                if predicate(e):
                    return e
            if until_exit and self.proc.poll() is not None:
                return "exited"
            return None
        found = wait_for(find, timeout)
        return None if found == "exited" else found

    def client(self):
        return Client(self.port)

    def running(self):
        return self.proc.poll() is None

    def stop(self, sig=signal.SIGTERM):
        self.stopped = True
        code = stop_process(self.proc, sig)
        for f in (self._stdout, self._stderr):
            if not f.closed:
                f.close()
        return code


# --- the JSON command socket -----------------------------------------------------------------

class Client:
    """A UDP client of gimbald's command socket, bound to its own ephemeral port."""

    def __init__(self, port, host="127.0.0.1"):
        self.address = (host, port)
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.sock.bind(("127.0.0.1", 0))
        self.backlog = []  # datagrams that arrived while waiting for a reply
        self._next_id = 0

    def close(self):
        self.sock.close()

    def send_raw(self, data):
        self.sock.sendto(data, self.address)

    def send(self, request):
        self.send_raw(json.dumps(request).encode())

    def _receive(self, timeout):
        ready, _, _ = select.select([self.sock], [], [], max(0.0, timeout))
        if not ready:
            return None
        try:
            data = self.sock.recv(65536)
        except ConnectionRefusedError:  # ICMP from an earlier send; nothing to read
            return None
        try:
            return json.loads(data)
        except ValueError:
            return {"unparsed": data.decode(errors="replace")}

    def recv(self, timeout=REPLY_TIMEOUT_S):
        """The next datagram (backlog first) as an object, or None after `timeout`."""
        if self.backlog:
            return self.backlog.pop(0)
        return self._receive(timeout)

    def reply_to(self, request_id, timeout=REPLY_TIMEOUT_S):
        """The reply carrying `request_id` (a datagram with "ok"); others go to the backlog."""
        deadline = time.monotonic() + timeout
        while True:
            msg = self._receive(deadline - time.monotonic())
            if msg is None:
                return None
            if isinstance(msg, dict) and "ok" in msg and msg.get("id") == request_id:
                return msg
            self.backlog.append(msg)

    def request(self, cmd, timeout=REPLY_TIMEOUT_S, **params):
        """Sends {"cmd": cmd, "id": <fresh>, **params}; returns the reply (None on timeout)."""
        self._next_id += 1
        request = {"cmd": cmd, "id": params.pop("id", "req-%d" % self._next_id)}
        request.update(params)
        self.send(request)
        return self.reply_to(request["id"], timeout)

    def collect(self, seconds, predicate=lambda m: True):
        """Every datagram (backlog first) received within `seconds` that predicate accepts."""
        out = [m for m in self.backlog if predicate(m)]
        self.backlog = []
        deadline = time.monotonic() + seconds
        while time.monotonic() < deadline:
            msg = self._receive(deadline - time.monotonic())
            if msg is not None and predicate(msg):
                out.append(msg)
        return out

    def wait_message(self, predicate, timeout):
        """The first datagram (backlog first) predicate accepts, or None after `timeout`.
        Datagrams it skips are dropped."""
        while self.backlog:
            msg = self.backlog.pop(0)
            if predicate(msg):
                return msg
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            msg = self._receive(deadline - time.monotonic())
            if msg is not None and predicate(msg):
                return msg
        return None


def is_state(msg):
    return isinstance(msg, dict) and msg.get("type") == "state"


def is_event(kind=None):
    return lambda m: (isinstance(m, dict) and m.get("type") == "event" and
                      (kind is None or m.get("event") == kind))


def finish_daemon(daemon):
    """Cleanup of every daemon a test started: unless the test stopped it (and checked the
    exit code itself), it must still be running and must exit 0 on SIGTERM."""
    if daemon.stopped:
        return
    if not daemon.running():
        code = daemon.stop()
        raise AssertionError("gimbald died during the test (exit %s): %s\n%s" %
                             (code, daemon.errors()[-2000:], daemon.log_text()[-2000:]))
    code = daemon.stop(signal.SIGTERM)
    if code != 0:
        raise AssertionError("gimbald exited %s on SIGTERM: %s" % (code, daemon.errors()[-2000:]))


# --- test base -------------------------------------------------------------------------------

class GimbaldTestCase(unittest.TestCase):
    """Per-test temp directory; every process and client started through it is stopped
    on cleanup, also when the test fails."""

    # Class-wide fixtures (one simulator and daemon shared by a class's read-mostly tests).
    @classmethod
    def setUpClass(cls):
        cls._class_tmp = tempfile.TemporaryDirectory(prefix="gimbald-it-")
        cls.addClassCleanup(cls._class_tmp.cleanup)
        cls.class_workdir = cls._class_tmp.name

    @classmethod
    def start_class_sim(cls, *args, **kwargs):
        sim = Sim(cls.class_workdir, *args, **kwargs)
        cls.addClassCleanup(sim.kill)
        return sim

    @classmethod
    def start_class_daemon(cls, config, args=()):
        daemon = Daemon(cls.class_workdir, config, args)
        cls.addClassCleanup(finish_daemon, daemon)
        return daemon

    def setUp(self):
        self._tmp = tempfile.TemporaryDirectory(prefix="gimbald-it-")
        self.addCleanup(self._tmp.cleanup)
        self.workdir = self._tmp.name

    def start_sim(self, *args, **kwargs):
        sim = Sim(self.workdir, *args, **kwargs)
        self.addCleanup(sim.kill)
        return sim

    def start_daemon(self, config, args=(), wait_started=True):
        daemon = Daemon(self.workdir, config, args, wait_started)
        self.addCleanup(self._dump_on_failure, daemon)
        self.addCleanup(finish_daemon, daemon)
        return daemon

    def client(self, daemon_or_port):
        port = daemon_or_port if isinstance(daemon_or_port, int) else daemon_or_port.port
        c = Client(port)
        self.addCleanup(c.close)
        return c

    def wait_connected(self, client, gimbal=None, timeout=START_TIMEOUT_S, telemetry=True):
        """Waits until STATE shows the link up (and telemetry, unless told otherwise)."""
        params = {"gimbal": gimbal} if gimbal else {}

        def ready():
            reply = client.request("state", **params)
            if not reply or not reply.get("ok"):
                return None
            state = reply["state"]
            if state["link"]["connected"] and (not telemetry or state.get("telemetry")):
                return state
            return None
        state = wait_for(ready, timeout, interval=0.1)
        self.assertTrue(state, "gimbal never connected with telemetry")
        return state

    def _dump_on_failure(self, daemon):
        # Only on failure: the daemon's log is the first thing one wants to read.
        outcome = getattr(self, "_outcome", None)
        result = getattr(outcome, "result", None)
        recorded = (getattr(result, "failures", []) + getattr(result, "errors", []) +
                    getattr(outcome, "errors", []))  # the last: Python < 3.11
        if any(test is self and exc for test, exc in recorded):
            sys.stderr.write("--- gimbald log (%s) ---\n%s%s\n" %
                             (self.id(), daemon.log_text()[-4000:], daemon.errors()[-2000:]))

    def assertOk(self, reply, msg=None):
        self.assertIsNotNone(reply, "no reply")
        self.assertTrue(reply.get("ok"), msg or reply)

    def assertError(self, reply, code, request_id=None):
        self.assertIsNotNone(reply, "no reply")
        self.assertIs(reply.get("ok"), False, reply)
        self.assertEqual(reply["error"]["code"], code, reply)
        self.assertIsInstance(reply["error"]["message"], str)
        if request_id is not None:
            self.assertEqual(reply["id"], request_id)
