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

import skipping

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


# --- Viewpro framing (viewpro-target-gps-protocol.md) ---------------------------------------

VP_OUT_SIZES = {0xFB: 23, 0xFC: 76, 0xFD: 60}  # OUT1, OUT2, OUT3/OUT4 by id


def vp_sum(data):
    return sum(data) % 256


def vp_mode(mode_byte):
    return bytes([0xAA, 0x55, 0x0F, mode_byte, 0xFF])


def vp_in2(lat, lon, alt_msl, yaw_deg, vel=(0.0, 0.0, 0.0), when=(2024, 7, 1, 12, 0, 0)):
    year, month, day, hour, minute, second = when
    body = bytes([0xF9, 0xFC]) + struct.pack("<H", year) + bytes([month, day, hour, minute, second])
    body += struct.pack("<fff", 0.0, 0.0, math.radians(yaw_deg))
    body += struct.pack("<iii", round(lat * 1e7), round(lon * 1e7), round(alt_msl * 1000))
    body += struct.pack("<hhh", *(round(v * 100) for v in vel))
    return body + bytes([vp_sum(body)])


class ViewproDeframer:
    """Streaming parser of the gimbal's OUTx frames: (format, bytes) out, resync after junk."""

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
            if self.buf[i] != 0xFE:
                i += 1
                self.dropped += 1
                continue
            if n - i < 2:
                break
            size = VP_OUT_SIZES.get(self.buf[i + 1])
            if size is None:
                i += 1
                self.dropped += 1
                continue
            if n - i < size:
                break
            raw = bytes(self.buf[i:i + size])
            if vp_sum(raw[:-1]) != raw[-1]:
                self.bad_checksums += 1
                self.dropped += 1
                i += 1
                continue
            fmt = {0xFB: "out1", 0xFC: "out2", 0xFD: "out3"}[raw[1]]
            if fmt == "out3" and raw[3] == 0xFF:
                fmt = "out4"
            frames.append((fmt, raw))
            i += size
        del self.buf[:i]
        return frames


def decode_out3(raw):
    uav_lat, uav_lon, target_lat, target_lon = struct.unpack("<iiii", raw[43:59])
    return {
        "zoom": struct.unpack("<H", raw[9:11])[0],
        "gimbal_pitch": math.degrees(struct.unpack("<f", raw[15:19])[0]),
        "lrf": struct.unpack("<f", raw[23:27])[0],
        "uav_yaw": math.degrees(struct.unpack("<f", raw[35:39])[0]),
        "uav_alt": struct.unpack("<i", raw[39:43])[0] / 1000.0,
        "uav_lat": uav_lat / 1e7, "uav_lon": uav_lon / 1e7,
        "target_lat": target_lat / 1e7, "target_lon": target_lon / 1e7,
    }


def north_east_m(lat0, lon0, lat1, lon1):
    """Small offsets between two points, metres north and east (spherical earth is enough)."""
    r = 6371000.0
    return (math.radians(lat1 - lat0) * r,
            math.radians(lon1 - lon0) * r * math.cos(math.radians(lat0)))


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

    def test_help_gives_each_protocol_its_own_start_position(self):
        # Each model's own start (docs/simulator.md): the help must not hand the Viewpro the
        # Orion's position, nor the other way round.
        text = " ".join(subprocess.run([SIM, "--help"], capture_output=True,
                                       text=True).stdout.split())
        orion = text[text.index("--protocol orion:"):text.index("--protocol viewpro:")]
        viewpro = text[text.index("--protocol viewpro:"):]
        self.assertIn("45.7 N, 121.5 W, 1500 m", orion)
        self.assertIn("6.9428789 N, 79.8812446 E, 300 m", viewpro)
        self.assertNotIn("45.7 N", viewpro.split("Options:")[0])

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


class GimbalSimViewpro(unittest.TestCase):
    """--protocol viewpro: the Viewpro model over a pty (its serial port) and TCP."""

    def open_pty(self, sim):
        fd = os.open(sim.endpoints["pty"], os.O_RDWR | os.O_NOCTTY)
        tty.setraw(fd)
        return fd

    def read_vp(self, fd, seconds, deframer=None, until=None):
        return read_frames(fd, seconds, deframer or ViewproDeframer(), until)

    def test_pty_silent_until_mode_then_out3_at_10hz_and_in2_moves_the_target(self):
        with tempfile.TemporaryDirectory() as tmp:
            log_path = os.path.join(tmp, "rx.jsonl")
            sim = Sim("--protocol", "viewpro", "--no-tcp", "--pty", "--rx-log", log_path,
                      want=("pty",))
            try:
                self.assertNotIn("discovery", sim.endpoints)
                fd = self.open_pty(sim)
                try:
                    self.assertEqual(self.read_vp(fd, 1.0), [])  # default mode 0x01: no output
                    os.write(fd, vp_mode(0x51))  # target on OSD, serial, OUT3
                    self.read_vp(fd, 0.3)  # settle
                    deframer = ViewproDeframer()
                    frames = self.read_vp(fd, 3.0, deframer)
                    self.assertAlmostEqual(len(frames), 30, delta=5)
                    self.assertEqual(deframer.bad_checksums, 0)
                    self.assertEqual(deframer.dropped, 0)
                    self.assertEqual({fmt for _, fmt, _ in frames}, {"out3"})
                    before = decode_out3(frames[-1][2])
                    self.assertAlmostEqual(before["gimbal_pitch"], -45, places=3)

                    sent_in2 = vp_in2(47.3977419, 8.5455938, 600.0, 90.0, vel=(0, 20, 0))
                    os.write(fd, sent_in2[:7])  # split across writes
                    time.sleep(0.05)
                    os.write(fd, sent_in2[7:])
                    moved = lambda fs: any(abs(decode_out3(d)["uav_lat"] - 47.3977419) < 1e-6
                                           for _, _, d in fs)
                    frames = self.read_vp(fd, 2.0, until=moved)
                    self.assertTrue(moved(frames))
                    out = decode_out3(frames[-1][2])
                finally:
                    os.close(fd)
                time.sleep(0.2)
                with open(log_path) as f:
                    lines = [json.loads(line) for line in f]
            finally:
                self.assertEqual(sim.stop(), 0, sim.errors())

        self.assertAlmostEqual(out["uav_lon"], 8.5455938, places=6)
        self.assertAlmostEqual(out["uav_alt"], 600.0, places=2)
        self.assertAlmostEqual(out["uav_yaw"], 90.0, places=3)
        self.assertGreater(abs(out["target_lat"] - before["target_lat"]), 1.0)  # it moved
        # Heading east, gimbal 45 degrees down: the target is about 600 m east on 0 m terrain.
        north, east = north_east_m(out["uav_lat"], out["uav_lon"],
                                   out["target_lat"], out["target_lon"])
        self.assertAlmostEqual(north, 0.0, delta=5.0)
        self.assertAlmostEqual(east, 600.0, delta=5.0)
        self.assertAlmostEqual(out["lrf"], 600.0 * math.sqrt(2), delta=2.0)

        self.assertEqual([l["kind"] for l in lines], ["mode", "in2"])
        self.assertEqual(lines[0]["hex"], vp_mode(0x51).hex())
        self.assertEqual(lines[0]["len"], 5)
        self.assertEqual(lines[0]["src"], "pty")
        self.assertEqual(lines[0]["frame"], {"osd": "target", "network": False,
                                             "serial": True, "format": "out3"})
        self.assertEqual(lines[1]["hex"], sent_in2.hex())
        self.assertEqual(lines[1]["len"], 40)
        self.assertAlmostEqual(lines[1]["frame"]["lat"], 47.3977419, places=7)
        self.assertAlmostEqual(lines[1]["frame"]["yaw"], 90.0, places=4)
        self.assertEqual(lines[1]["frame"]["vel_ned"], [0.0, 20.0, 0.0])
        self.assertEqual(lines[1]["frame"]["time"], "2024-07-01T12:00:00Z")
        self.assertGreater(lines[1]["t"], lines[0]["t"])

    def test_tcp_serves_each_format_and_network_only_is_silent(self):
        sim = Sim("--protocol", "viewpro", "--port", "0", "--zoom", "77")
        try:
            self.assertNotIn("discovery", sim.endpoints)
            with sim.connect() as s:
                for mode_byte, fmt, size in ((0x11, "out1", 23), (0x31, "out2", 76),
                                             (0x51, "out3", 60), (0x71, "out4", 60)):
                    s.sendall(vp_mode(mode_byte))
                    read_frames(s, 0.3, ViewproDeframer())  # the switch, then steady output
                    frames = read_frames(s, 1.0, ViewproDeframer())
                    self.assertGreaterEqual(len(frames), 7, fmt)
                    self.assertEqual({f for _, f, _ in frames}, {fmt})
                    self.assertEqual({len(d) for _, _, d in frames}, {size})
                    if fmt == "out3":
                        self.assertEqual(decode_out3(frames[0][2])["zoom"], 77)
                s.sendall(vp_mode(0x69))  # RJ45 only (ICD 1.5's text): not on this port
                read_frames(s, 0.3, ViewproDeframer())
                self.assertEqual(read_frames(s, 1.0, ViewproDeframer()), [])
        finally:
            self.assertEqual(sim.stop(), 0, sim.errors())

    def test_corrupt_fraction_and_junk_apply_to_viewpro_frames(self):
        sim = Sim("--protocol", "viewpro", "--port", "0", "--corrupt-fraction", "0.3",
                  "--junk-every", "3")
        try:
            with sim.connect() as s:
                s.sendall(vp_mode(0x11))
                deframer = ViewproDeframer()
                frames = read_frames(s, 2.5, deframer)
        finally:
            self.assertEqual(sim.stop(), 0)
        self.assertGreater(deframer.bad_checksums, 3)
        self.assertGreater(deframer.dropped, 10)
        self.assertGreater(len(frames), 8)

    def test_unknown_protocol_exits_1(self):
        result = subprocess.run([SIM, "--protocol", "gremsy"], capture_output=True)
        self.assertEqual(result.returncode, 1)


if __name__ == "__main__":
    if not SIM:
        skipping.need_for_file("GIMBAL_SIM is not set")
    unittest.main(verbosity=2)
