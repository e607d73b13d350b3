"""Attacks on MAVLink: junk senders that would evict a ground station (issue 25 item 8), a
flood of refused commands (item 9: `mavlink_refused` rolled up), absurd gimbal device limits
(item 13), and the held ones (262,600 requests; 11 kHz forged device attitudes). The
MAVLink side is tests/integration/mavlinktest.py (written from common.xml)."""

import math
import os
import random
import socket
import struct
import threading
import time

import attack_streams as S  # noqa: F401 (sys.path for mavlinktest)
import mavlinktest as mt

# CRC_EXTRA of the messages used here beyond mavlinktest's (common.xml).
mt.CRC_EXTRA.update({283: 74, 284: 99})
HEARTBEAT, COMMAND_LONG = 0, 76
MANAGER_INFORMATION, DEVICE_INFORMATION, ATTITUDE_STATUS = 280, 283, 285
ROLLUP_PER_S = 12  # contract section 14 v4: at most 10 a second, then one roll-up line
LIMIT_DEG = 360.0


def heartbeat(mav_type=6, autopilot=8):
    return struct.pack("<IBBBBB", 0, mav_type, autopilot, 0, 4, 3)


def write_key(path):
    with open(path, "w") as f:
        f.write(os.urandom(32).hex() + "\n")
    os.chmod(path, 0o600)
    with open(path) as f:
        return bytes.fromhex(f.read().strip())


class Gcs:
    """A ground station on its own thread: heartbeat every second, every frame it receives
    kept with its arrival time."""

    def __init__(self, port, key=None, sysid=255):
        self.peer = mt.Peer(port, sysid=sysid, key=key)
        self.peer.sock.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 1 << 21)
        self.lock = threading.Lock()
        self.running = True
        self.thread = threading.Thread(target=self._run, daemon=True)
        self.thread.start()

    def _run(self):
        last_beat = 0.0
        while self.running:
            if time.monotonic() - last_beat >= 1.0:
                with self.lock:
                    self.peer.send(HEARTBEAT, heartbeat())
                last_beat = time.monotonic()
            with self.lock:
                self.peer.pump(0.05)

    def send(self, msgid, payload):
        with self.lock:
            self.peer.send(msgid, payload)

    def arrivals(self, msgid, component=None):
        with self.lock:
            return [m for m in self.peer.received
                    if m[3] == msgid and (component is None or m[2] == component)]

    def close(self):
        self.running = False
        self.thread.join(timeout=2)
        self.peer.close()


def junk_peers(suite, f):
    """Item 8: under MAVLink signing, 24 senders of unsigned heartbeats and noise; the signed
    ground station must keep getting its streams (GIMBAL_DEVICE_ATTITUDE_STATUS at 10 Hz)."""
    rig_dir = suite.attack_dir(f.name)
    key_path = os.path.join(rig_dir, "mavlink.key")
    key = write_key(key_path)
    mavlink = {"signing_key_file": key_path,
               "signing_state_file": os.path.join(rig_dir, "signing.json")}
    with suite.rig(f, mavlink=mavlink) as rig:
        gcs = Gcs(rig.mavlink_port, key=key)
        began = {}

        def junk(stop):
            deadline = time.monotonic() + 3.0
            while not gcs.arrivals(ATTITUDE_STATUS) and time.monotonic() < deadline:
                time.sleep(0.05)
            socks = []
            for i in range(24):
                s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
                s.bind(("127.0.0.1", 0))
                socks.append(s)
            rng = random.Random(8)
            beats = [mt.frame(HEARTBEAT, heartbeat(), 100 + i, 190) for i in range(24)]
            began["t"] = time.monotonic()
            n = 0
            while not stop.is_set():
                for i, s in enumerate(socks):
                    data = beats[i] if n % 2 == 0 else bytes(rng.getrandbits(8)
                                                             for _ in range(rng.randint(1, 64)))
                    try:
                        s.sendto(data, ("127.0.0.1", rig.mavlink_port))
                    except OSError:
                        pass
                n += 1
                rig.count("junk datagrams", len(socks))
                time.sleep(0.005)
            began["end"] = time.monotonic()
            for s in socks:
                s.close()

        rig.measure([junk])
        got = [m[0] for m in gcs.arrivals(ATTITUDE_STATUS)]
        gcs.close()
        if "t" not in began:
            f.fail("the junk never started")
            return
        before = [t for t in got if t < began["t"]]
        during = [t for t in got if began["t"] + 0.5 <= t <= began["end"]]
        f.check(before, "the ground station got no stream even before the junk")
        gaps = [b - a for a, b in zip(during, during[1:])]
        longest = max(gaps, default=math.inf)
        f.note("attitude frames to the ground station: %d before, %d under junk (longest gap "
               "%s)" % (len(before), len(during), "-" if longest == math.inf else
                        "%.2f s" % longest))
        expected = 10 * max(0.0, began["end"] - began["t"] - 0.5)
        f.check(len(during) >= expected / 2 and longest < 0.5,
                "the ground station lost its streams under junk (%d frames, longest gap %s)"
                % (len(during), "-" if longest == math.inf else "%.2f s" % longest))


def refused_flood(suite, f):
    """Item 9: 1,600 unsupported commands a second from one ground station, each refused
    (`mavlink_refused`); lines rolled up, the laser's lines all present."""
    with suite.rig(f, mavlink={}) as rig:
        def flood(stop):
            peer = mt.Peer(rig.mavlink_port)
            frames = [mt.frame(COMMAND_LONG, mt.command_long(31010, [i % 7]), 255, 190, i)
                      for i in range(256)]
            state = {"i": 0}

            def produce(n):
                for _ in range(n):
                    peer.send_raw(frames[state["i"] % 256])
                    state["i"] += 1

            S.paced(stop, 1600, produce)
            rig.count("refused commands sent", state["i"])
            peer.close()

        rig.measure([flood])
        total, worst, rate = rig.log_rate("mavlink_refused")
        f.note("mavlink_refused lines: %d, at most %d in one second (%.0f/s)" % (total, worst,
                                                                                rate))
        f.check(total > 0, "no mavlink_refused line: the flood never reached a refusal")
        f.check(worst <= ROLLUP_PER_S, "mavlink_refused not rolled up: %d lines in one second"
                % worst)
        rig.check_safety_lines()


def requests_flood(suite, f):
    """Held: MAVLink requests at 6,565 a second (262,600 in 40 s): REQUEST_MESSAGE for the
    manager's, device's and camera's information, answered each time."""
    with suite.rig(f, mavlink={}) as rig:
        def flood(stop):
            peer = mt.Peer(rig.mavlink_port)
            peer.sock.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 1 << 16)
            frames = [mt.frame(COMMAND_LONG, mt.command_long(
                mt.MAV_CMD_REQUEST_MESSAGE, [(280, 283, 259, 269)[i % 4]], 1,
                (154, 100, 0)[i % 3]), 255, 190, i) for i in range(256)]
            state = {"i": 0}

            def produce(n):
                for _ in range(n):
                    peer.send_raw(frames[state["i"] % 256])
                    state["i"] += 1

            S.paced(stop, 6565, produce)
            rig.count("requests", state["i"])
            peer.close()

        rig.measure([flood])


class Device:
    """A MAVLink gimbal device on gimbald's device link: we are the device at
    127.0.0.1:device_port, gimbald's end is its configured local port."""

    def __init__(self, rig, limits_rad):
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.sock.bind(("127.0.0.1", rig.device_port))
        self.target = ("127.0.0.1", rig.device_local_port)
        self.limits = limits_rad
        self.seq = 0

    def frame(self, msgid, payload):
        self.seq += 1
        return mt.frame(msgid, payload, 1, 154, self.seq)

    def information(self):
        return struct.pack("<QIII6fHH32s32s32sB", 1, int(time.monotonic() * 1000) & 0xFFFFFFFF,
                           0x01020304, 1, *self.limits, 0x0FFF, 0, b"Attack", b"Forged", b"",
                           1)

    def attitude(self, rng):
        q = [rng.uniform(-1, 1) for _ in range(4)]
        n = math.sqrt(sum(x * x for x in q)) or 1.0
        return struct.pack("<I4ffffIHBBffB", int(time.monotonic() * 1000) & 0xFFFFFFFF,
                           *[x / n for x in q], 0.1, 0.2, 0.3, 0, 12, 1, 1, 0.0, 0.0, 1)

    def send(self, data):
        try:
            self.sock.sendto(data, self.target)
        except OSError:
            return False
        return True

    def close(self):
        self.sock.close()


def run_device(rig, stop, limits, attitude_hz):
    """Our device: heartbeat and information every second, attitudes at `attitude_hz`."""
    device = Device(rig, limits)
    rng = random.Random(13)
    last_info = 0.0
    sent = 0
    start = time.monotonic()
    while not stop.is_set():
        if time.monotonic() - last_info >= 1.0:
            device.send(device.frame(HEARTBEAT, heartbeat(26, 8)))
            device.send(device.frame(DEVICE_INFORMATION, device.information()))
            last_info = time.monotonic()
        due = int((time.monotonic() - start) * attitude_hz) - sent
        for _ in range(max(0, due)):
            device.send(device.frame(ATTITUDE_STATUS, device.attitude(rng)))
            sent += 1
        time.sleep(0.001)
    rig.count("attitudes", sent)
    device.close()


def device_attitudes(suite, f):
    """Held: a MAVLink gimbal device's attitude at 11 kHz (random orientations)."""
    sane = [-0.7, 0.7, -2.0, 0.5, -3.1, 3.1]
    with suite.rig(f, device=True) as rig:
        rig.measure([lambda stop: run_device(rig, stop, sane, 11000)])
        r = rig.client.request({"cmd": "state", "gimbal": "dev", "keys": ["device"]}, 2.0)
        device = (r or {}).get("state", {}).get("device") if r and r.get("ok") else None
        f.check(device is not None and device.get("attitude"),
                "the device's attitude never reached STATE (the attack did not land)")


def absurd(value):
    return value is not None and (not isinstance(value, (int, float)) or
                                  abs(value) > LIMIT_DEG)


def device_limits(suite, f):
    """Item 13: a device reporting roll/yaw limits of +-1e38 rad (+-5.7e39 deg) and inverted
    pitch limits: unknown (null) in STATE, never relayed to a ground station."""
    limits = [-1e38, 1e38, 1.0, -1.0, -1e38, 1e38]
    with suite.rig(f, device=True, mavlink={}) as rig:
        gcs = Gcs(rig.mavlink_port)

        def ask(stop):
            while not stop.wait(0.5):
                gcs.send(COMMAND_LONG, mt.command_long(mt.MAV_CMD_REQUEST_MESSAGE,
                                                       [MANAGER_INFORMATION], 1, 171))

        rig.measure([lambda stop: run_device(rig, stop, limits, 50), ask])
        r = rig.client.request({"cmd": "state", "gimbal": "dev", "keys": ["device"]}, 2.0)
        device = (r or {}).get("state", {}).get("device") if r and r.get("ok") else None
        got = (device or {}).get("limits") or {}
        f.note("STATE device.limits: %s" % got)
        f.check(device is not None, "STATE device never filled (the device was not heard)")
        bad = {k: v for k, v in got.items() if absurd(v)}
        for axis in ("roll", "pitch", "yaw"):
            lo, hi = got.get(axis + "_min"), got.get(axis + "_max")
            if lo is not None and hi is not None and lo > hi:
                bad[axis] = "inverted %s > %s" % (lo, hi)
        f.check(not bad, "STATE device.limits keeps absurd or inverted limits: %s" % bad)
        relayed = []
        for m in gcs.arrivals(MANAGER_INFORMATION, component=171):
            p = m[4] + b"\0" * (33 - len(m[4]))
            values = struct.unpack("<II6fB", p[:33])[2:8]
            relayed += [math.degrees(v) for v in values
                        if not math.isnan(v) and abs(math.degrees(v)) > LIMIT_DEG]
            for lo, hi in (values[0:2], values[2:4], values[4:6]):
                if not (math.isnan(lo) or math.isnan(hi)) and lo > hi:
                    relayed.append("inverted")
        f.note("GIMBAL_MANAGER_INFORMATION of the device's manager: %d" %
               len(gcs.arrivals(MANAGER_INFORMATION, component=171)))
        gcs.close()
        f.check(not relayed, "absurd limits relayed to the ground station: %s" % (
            ", ".join(str(v) if isinstance(v, str) else "%.3g deg" % v
                      for v in sorted(set(relayed), key=str)[:4])))
