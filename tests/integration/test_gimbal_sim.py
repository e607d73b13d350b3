#!/usr/bin/env python3
"""Integration tests of the real gimbal-sim binary over loopback TCP, UDP and a pty.

Python standard library only. Needs GIMBAL_SIM (the binary's path); exits 77 (skipped)
without it.
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
import tty
import unittest

SIM = os.environ.get("GIMBAL_SIM")

# Packet ids (OrionPktType_t).
CMD, LASER_STATES, CROWN_VERSION, CAMERAS = 1, 6, 40, 99
PERFORMANCE, DIAGNOSTICS = 67, 65
GPS_DATA, INS_QUALITY, GEOLOCATE, GEOPOINT = 209, 211, 212, 213


# --- OrionPublic framing -------------------------------------------------------------------

def fletcher251(data):
    a = b = 0
    for i, byte in enumerate(data):
        if i == 0:
            a = b = (byte + 1) % 251
        else:
            a = (a + byte) % 251
            b = (b + a) % 251
    return (a << 8) | b


def frame(pkt_id, data=b""):
    head = bytes([0xD0, 0x0D, pkt_id, len(data)]) + bytes(data)
    return head + struct.pack(">H", fletcher251(head))


class Deframer:
    """Streaming parser: complete frames out, bad checksums counted, resync after junk."""

    def __init__(self):
        self.buf = bytearray()
        self.bad_checksums = 0
        self.dropped = 0

    def push(self, data):
        self.buf += data
        frames = []
        i = 0
        n = len(self.buf)
        while i < n:
            if self.buf[i] != 0xD0:
                i += 1
                self.dropped += 1
                continue
            if n - i < 4:
                break
            if self.buf[i + 1] != 0x0D or self.buf[i + 3] > 140:
                i += 1
                self.dropped += 1
                continue
            length = self.buf[i + 3]
            total = 6 + length
            if n - i < total:
                break
            body = bytes(self.buf[i:i + 4 + length])
            (checksum,) = struct.unpack(">H", self.buf[i + 4 + length:i + total])
            if fletcher251(body) != checksum:
                self.bad_checksums += 1
                self.dropped += 1
                i += 1
                continue
            frames.append((self.buf[i + 2], bytes(self.buf[i + 4:i + 4 + length])))
            i += total
        del self.buf[:i]
        return frames


# --- packets the tests read or write ---------------------------------------------------------

RAD_TO_I32 = 1e7 * 180 / math.pi


def decode_telemetry(data):
    lat, lon, alt = struct.unpack(">iii", data[12:24])
    pan, tilt = struct.unpack(">hh", data[38:42])
    los = struct.unpack(">hhh", data[46:52]) if len(data) >= 52 else (0, 0, 0)
    mode = data[56] if len(data) > 56 else 255
    return {
        "lat": lat / RAD_TO_I32, "lon": lon / RAD_TO_I32, "alt": alt / 1e4,
        "pan": pan * math.pi / 32767, "tilt": tilt * math.pi / 32767,
        "los": los, "mode": mode,
    }


def geopoint_cmd(lat_deg, lon_deg, alt_m):
    data = struct.pack(">iii", round(math.radians(lat_deg) * RAD_TO_I32),
                       round(math.radians(lon_deg) * RAD_TO_I32), round(alt_m * 1e4))
    data += struct.pack(">hhhHB", 0, 0, 0, 0, 0)
    return frame(GEOPOINT, data)


def orion_cmd(mode, pan=0.0, tilt=0.0):
    return frame(CMD, struct.pack(">hhBBB", round(pan * 1000), round(tilt * 1000), mode, 0, 0))


def ecef(lat, lon, alt):
    """WGS84 geodetic (radians, metres) to ECEF metres."""
    a, f = 6378137.0, 1 / 298.257223563
    e2 = f * (2 - f)
    n = a / math.sqrt(1 - e2 * math.sin(lat) ** 2)
    return ((n + alt) * math.cos(lat) * math.cos(lon),
            (n + alt) * math.cos(lat) * math.sin(lon),
            (n * (1 - e2) + alt) * math.sin(lat))


def angle_between(u, v):
    dot = sum(a * b for a, b in zip(u, v))
    nu = math.sqrt(sum(a * a for a in u))
    nv = math.sqrt(sum(b * b for b in v))
    return math.degrees(math.acos(max(-1.0, min(1.0, dot / (nu * nv)))))


# --- running the simulator -------------------------------------------------------------------

class Sim:
    """A gimbal-sim process; endpoints parsed from its stdout lines ("tcp: host:port")."""

    def __init__(self, *args, want=("tcp",)):
        self.stderr = tempfile.TemporaryFile()
        self.proc = subprocess.Popen([SIM, *args], stdout=subprocess.PIPE, stderr=self.stderr)
        self.endpoints = {}
        # Raw reads, not readline(): a buffered reader can hold a line select() cannot see.
        pending = b""
        deadline = time.monotonic() + 10
        while not all(w in self.endpoints for w in want):
            if time.monotonic() > deadline or self.proc.poll() is not None:
                self.stop()
                raise RuntimeError("gimbal-sim did not print %s; stderr: %s" % (want, self.errors()))
            ready, _, _ = select.select([self.proc.stdout], [], [], 0.5)
            if ready:
                pending += os.read(self.proc.stdout.fileno(), 4096)
                *lines, pending = pending.split(b"\n")
                for line in lines:
                    key, _, value = line.decode().strip().partition(": ")
                    if value:
                        self.endpoints[key] = value

    def address(self, key="tcp"):
        host, port = self.endpoints[key].rsplit(":", 1)
        return host, int(port)

    def connect(self):
        s = socket.create_connection(self.address(), timeout=5)
        s.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        return s

    def errors(self):
        if self.stderr.closed:
            return self._errors
        self.stderr.seek(0)
        return self.stderr.read().decode(errors="replace")

    def stop(self):
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGTERM)
            try:
                self.proc.wait(timeout=5)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        if not self.stderr.closed:
            self._errors = self.errors()
            self.stderr.close()
            self.proc.stdout.close()
        return self.proc.returncode


def read_frames(fd_or_sock, seconds, deframer=None, until=None):
    """Collects (time, id, data) for `seconds`, or until until(frames) is true."""
    deframer = deframer or Deframer()
    frames = []
    end = time.monotonic() + seconds
    is_socket = isinstance(fd_or_sock, socket.socket)
    while time.monotonic() < end:
        ready, _, _ = select.select([fd_or_sock], [], [], max(0.0, end - time.monotonic()))
        if not ready:
            continue
        data = fd_or_sock.recv(65536) if is_socket else os.read(fd_or_sock, 65536)
        if not data:
            break
        now = time.monotonic()
        frames += [(now, i, d) for i, d in deframer.push(data)]
        if until and until(frames):
            break
    return frames


def closed_by_peer(sock, seconds):
    """True when the other side closes sock within `seconds` (data before that is skipped)."""
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        ready, _, _ = select.select([sock], [], [], max(0.0, end - time.monotonic()))
        if ready:
            try:
                if not sock.recv(65536):
                    return True
            except ConnectionResetError:
                return True
    return False


def count(frames, pkt_id):
    return sum(1 for _, i, _ in frames if i == pkt_id)


# --- tests -----------------------------------------------------------------------------------

class GimbalSimTcp(unittest.TestCase):
    def setUp(self):
        self.sim = Sim("--port", "0", "--no-discovery")

    def tearDown(self):
        self.assertEqual(self.sim.stop(), 0, self.sim.errors())

    def test_prints_a_free_loopback_port(self):
        host, port = self.sim.address()
        self.assertEqual(host, "127.0.0.1")
        self.assertGreater(port, 0)

    def test_periodic_rates(self):
        with self.sim.connect() as s:
            read_frames(s, 0.3)  # settle
            deframer = Deframer()
            frames = read_frames(s, 4.0, deframer)
        self.assertEqual(deframer.bad_checksums, 0)
        # The model runs on the wall clock, so only scheduling jitter at the window's ends counts.
        self.assertAlmostEqual(count(frames, GEOLOCATE), 40, delta=5)
        self.assertAlmostEqual(count(frames, PERFORMANCE), 16, delta=3)
        self.assertAlmostEqual(count(frames, INS_QUALITY), 4, delta=1)
        self.assertAlmostEqual(count(frames, GPS_DATA), 4, delta=1)
        self.assertIn(count(frames, DIAGNOSTICS), (1, 2))

    def test_orion_cmd_is_echoed(self):
        cmd = orion_cmd(80, 0.5, -0.3)
        with self.sim.connect() as s:
            read_frames(s, 0.2)
            s.sendall(cmd)
            frames = read_frames(s, 2.0, until=lambda f: count(f, CMD) > 0)
        echoes = [d for _, i, d in frames if i == CMD]
        self.assertEqual(echoes, [cmd[4:-2]])

    def test_geopoint_turns_the_gimbal(self):
        target = (45.712, -121.47, 100.0)
        with self.sim.connect() as s:
            read_frames(s, 0.3)
            s.sendall(geopoint_cmd(*target))
            read_frames(s, 5.0)  # slew and settle
            frames = read_frames(s, 1.0)
        telemetry = [decode_telemetry(d) for _, i, d in frames if i == GEOLOCATE]
        self.assertGreaterEqual(len(telemetry), 8)
        goal = ecef(math.radians(target[0]), math.radians(target[1]), target[2])
        for t in telemetry:
            self.assertEqual(t["mode"], 96)  # geopoint
            here = ecef(t["lat"], t["lon"], t["alt"])
            wanted = tuple(g - h for g, h in zip(goal, here))
            self.assertLess(angle_between(t["los"], wanted), 0.5)

    def test_a_new_client_replaces_the_old_and_the_model_keeps_running(self):
        first = self.sim.connect()
        try:
            read_frames(first, 0.3)
            first.sendall(orion_cmd(16))  # rate mode
            read_frames(first, 0.3)
            with self.sim.connect() as second:
                frames = read_frames(second, 1.0)
            self.assertTrue(closed_by_peer(first, 2.0))
        finally:
            first.close()
        telemetry = [decode_telemetry(d) for _, i, d in frames if i == GEOLOCATE]
        self.assertGreater(len(telemetry), 5)
        self.assertEqual(telemetry[-1]["mode"], 16)  # the state outlived the connection


class GimbalSimRequests(unittest.TestCase):
    def test_zero_length_requests_and_rx_log(self):
        with tempfile.TemporaryDirectory() as tmp:
            log_path = os.path.join(tmp, "rx.jsonl")
            sim = Sim("--port", "0", "--no-discovery", "--rx-log", log_path)
            try:
                sent_geopoint = geopoint_cmd(45.71, -121.49, 120.0)
                with sim.connect() as s:
                    read_frames(s, 0.2)
                    # Split across writes, with junk in front: the log must still be exact.
                    s.sendall(b"\x00\xd0\x13" + sent_geopoint[:5])
                    time.sleep(0.05)
                    s.sendall(sent_geopoint[5:] + frame(CAMERAS) + frame(CROWN_VERSION))
                    frames = read_frames(s, 2.0, until=lambda f: count(f, CAMERAS) > 0 and
                                         count(f, 37) > 0 and count(f, 249) > 0)
                self.assertEqual(count(frames, CAMERAS), 1)
                for version_id in (37, 40, 41, 44, 248, 249):  # every version packet
                    self.assertEqual(count(frames, version_id), 1, version_id)
                time.sleep(0.2)
                with open(log_path) as f:
                    lines = [json.loads(line) for line in f]
            finally:
                self.assertEqual(sim.stop(), 0)
        self.assertEqual([l["name"] for l in lines], ["geopoint_cmd", "cameras", "crown_version"])
        geo = lines[0]
        self.assertEqual(geo["id"], GEOPOINT)
        self.assertEqual(geo["len"], 21)
        self.assertEqual(geo["hex"], sent_geopoint.hex())
        self.assertEqual(geo["src"], "tcp")
        self.assertAlmostEqual(geo["packet"]["lat"], 45.71, places=6)
        self.assertAlmostEqual(geo["packet"]["alt"], 120.0, places=3)
        self.assertGreater(geo["t"], 0)
        self.assertEqual(lines[1]["len"], 0)
        self.assertNotIn("packet", lines[1])
        self.assertEqual(lines[1]["hex"], frame(CAMERAS).hex())


class GimbalSimPty(unittest.TestCase):
    def test_serves_a_pty_that_can_be_reopened(self):
        with tempfile.TemporaryDirectory() as tmp:
            link = os.path.join(tmp, "orion")
            sim = Sim("--no-tcp", "--pty", "--pty-link", link, "--no-discovery", want=("pty",))
            try:
                self.assertTrue(sim.endpoints["pty"].startswith("/dev/"))
                self.assertEqual(os.path.realpath(link), os.path.realpath(sim.endpoints["pty"]))
                for attempt in range(2):  # open, close, open again
                    fd = os.open(link, os.O_RDWR | os.O_NOCTTY)
                    try:
                        tty.setraw(fd)
                        frames = read_frames(fd, 1.5)
                        self.assertGreater(count(frames, GEOLOCATE), 8, "attempt %d" % attempt)
                        cmd = orion_cmd(48)  # scene
                        os.write(fd, cmd)
                        frames = read_frames(fd, 1.0, until=lambda f: count(f, CMD) > 0)
                        self.assertIn(cmd[4:-2], [d for _, i, d in frames if i == CMD])
                    finally:
                        os.close(fd)
                    time.sleep(0.3)
            finally:
                self.assertEqual(sim.stop(), 0, sim.errors())
            self.assertFalse(os.path.lexists(link))  # removed on exit


class GimbalSimDiscovery(unittest.TestCase):
    def test_answers_crown_version_requests(self):
        listener = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        listener.bind(("127.0.0.1", 0))
        reply_port = listener.getsockname()[1]
        sim = Sim("--port", "0", "--discovery-port", "0", "--discovery-reply-port",
                  str(reply_port), want=("tcp", "discovery"))
        try:
            port = sim.address("discovery")[1]
            asker = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
            asker.settimeout(3)
            asker.sendto(b"\xd0\x0d\x28\x00\x0b\xca", ("127.0.0.1", port))
            listener.settimeout(3)
            reply, sender = listener.recvfrom(512)
            frames = Deframer().push(reply)
            self.assertEqual(len(frames), 1)
            self.assertEqual(frames[0][0], CROWN_VERSION)
            self.assertEqual(len(frames[0][1]), 36)
            self.assertEqual(sender[0], "127.0.0.1")
            # The request's source port hears it too.
            reply2, _ = asker.recvfrom(512)
            self.assertEqual(reply2, reply)
            # Anything else gets no answer.
            asker.sendto(frame(CAMERAS), ("127.0.0.1", port))
            asker.settimeout(0.5)
            with self.assertRaises(socket.timeout):
                asker.recvfrom(512)
            asker.close()
        finally:
            listener.close()
            self.assertEqual(sim.stop(), 0, sim.errors())


class GimbalSimFaults(unittest.TestCase):
    def test_drop_after_closes_each_client(self):
        sim = Sim("--port", "0", "--no-discovery", "--drop-after", "1.0")
        try:
            for _ in range(2):
                with sim.connect() as s:
                    start = time.monotonic()
                    frames = read_frames(s, 4.0)
                    elapsed = time.monotonic() - start
                self.assertGreater(count(frames, GEOLOCATE), 5)
                self.assertGreater(elapsed, 0.8)
                self.assertLess(elapsed, 2.5)  # read_frames ended because the server closed
        finally:
            self.assertEqual(sim.stop(), 0, sim.errors())

    def test_corrupt_fraction_shows_bad_checksums(self):
        sim = Sim("--port", "0", "--no-discovery", "--corrupt-fraction", "0.3")
        try:
            with sim.connect() as s:
                deframer = Deframer()
                frames = read_frames(s, 2.0, deframer)
        finally:
            self.assertEqual(sim.stop(), 0)
        self.assertGreater(deframer.bad_checksums, 5)
        self.assertGreater(len(frames), 20)

    def test_junk_between_frames(self):
        sim = Sim("--port", "0", "--no-discovery", "--junk-every", "3")
        try:
            with sim.connect() as s:
                deframer = Deframer()
                frames = read_frames(s, 2.0, deframer)
        finally:
            self.assertEqual(sim.stop(), 0)
        self.assertGreater(deframer.dropped, 10)
        self.assertGreater(count(frames, GEOLOCATE), 15)  # no telemetry lost to the junk

    def test_stall_goes_silent_then_resumes(self):
        sim = Sim("--port", "0", "--no-discovery", "--stall-after", "1.0", "--stall-for", "1.5")
        try:
            with sim.connect() as s:
                frames = read_frames(s, 4.0)
        finally:
            self.assertEqual(sim.stop(), 0)
        times = [t for t, i, _ in frames if i == GEOLOCATE]
        gaps = [b - a for a, b in zip(times, times[1:])]
        self.assertGreater(max(gaps), 1.2)
        self.assertLess(max(gaps), 2.6)
        self.assertGreater(times[-1] - times[0], 3.0)  # talking again after the stall


class GimbalSimLifecycle(unittest.TestCase):
    def test_bad_command_line_exits_1(self):
        result = subprocess.run([SIM, "--no-tcp"], capture_output=True)
        self.assertEqual(result.returncode, 1)
        result = subprocess.run([SIM, "--corrupt-fraction", "2"], capture_output=True)
        self.assertEqual(result.returncode, 1)

    def test_help_is_a_manual(self):
        result = subprocess.run([SIM, "--help"], capture_output=True, text=True)
        self.assertEqual(result.returncode, 0)
        for section in ("NAME", "SYNOPSIS", "DESCRIPTION", "EXIT STATUS", "--drop-after"):
            self.assertIn(section, result.stdout)

    def test_busy_port_exits_2(self):
        blocker = socket.socket()
        blocker.bind(("127.0.0.1", 0))
        blocker.listen()
        port = blocker.getsockname()[1]
        result = subprocess.run([SIM, "--port", str(port), "--no-discovery"],
                                capture_output=True, timeout=10)
        blocker.close()
        self.assertEqual(result.returncode, 2)

    def test_sigint_stops_cleanly(self):
        sim = Sim("--port", "0", "--no-discovery")
        with sim.connect() as s:
            read_frames(s, 0.3)
            sim.proc.send_signal(signal.SIGINT)
            self.assertEqual(sim.proc.wait(timeout=5), 0)
        sim.stop()


if __name__ == "__main__":
    if not SIM:
        print("GIMBAL_SIM is not set: skipped")
        sys.exit(77)
    unittest.main(verbosity=2)
