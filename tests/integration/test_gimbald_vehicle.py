"""The vehicle feed (issue 5): MAVLink datagrams sent to gimbald's vehicle port reach the
gimbals as OrionAutopilotData / GPS_DATA, Viewpro IN2 / IN1, or forwarded MAVLink v1 frames.

MAVLink frames are built here with struct and CRC-16/MCRF4XX (X.25) plus CRC_EXTRA,
independently of the C++ codec. What the gimbals receive is read from gimbal-sim's rx log,
and for the MAVLink forward from a plain TCP server standing in for the Viewpro.
"""

import math
import os
import socket
import struct
import tempfile
import threading
import time
import tty
import unittest

import gimbaltest as gt

# --- MAVLink, independent of lib/mavlink -------------------------------------------------------

HEARTBEAT, SYSTEM_TIME, ATTITUDE, GLOBAL_POSITION_INT = 0, 2, 30, 33
CRC_EXTRA = {HEARTBEAT: 50, SYSTEM_TIME: 137, ATTITUDE: 39, GLOBAL_POSITION_INT: 104}
MAV_STATE_STANDBY, MAV_STATE_ACTIVE = 3, 4
ARMED = 128


def x25(data, crc=0xFFFF):
    for b in data:
        tmp = b ^ (crc & 0xFF)
        tmp = (tmp ^ (tmp << 4)) & 0xFF
        crc = ((crc >> 8) ^ (tmp << 8) ^ (tmp << 3) ^ (tmp >> 4)) & 0xFFFF
    return crc


def mavlink_v2(msgid, payload, seq=0, sysid=1, compid=1):
    body = struct.pack("<BBBBBB", len(payload), 0, 0, seq, sysid, compid)
    body += struct.pack("<I", msgid)[:3] + payload
    crc = x25(body + bytes([CRC_EXTRA[msgid]]))
    return b"\xfd" + body + struct.pack("<H", crc)


def mavlink_v1(msgid, payload, seq=0, sysid=1, compid=1):
    body = struct.pack("<BBBBB", len(payload), seq, sysid, compid, msgid) + payload
    crc = x25(body + bytes([CRC_EXTRA[msgid]]))
    return b"\xfe" + body + struct.pack("<H", crc)


def parse_v1(data):
    """Every CRC-valid MAVLink v1 frame in `data`: [(msgid, sysid, payload)]."""
    frames, i = [], 0
    while i + 8 <= len(data):
        if data[i] != 0xFE:
            i += 1
            continue
        length = data[i + 1]
        end = i + 6 + length + 2
        msgid = data[i + 5]
        if end <= len(data) and msgid in CRC_EXTRA:
            crc = x25(data[i + 1:end - 2] + bytes([CRC_EXTRA[msgid]]))
            if crc == struct.unpack_from("<H", data, end - 2)[0]:
                frames.append((msgid, data[i + 3], data[i + 6:end - 2]))
                i = end
                continue
        i += 1
    return frames


def heartbeat(armed, state):
    # custom_mode, type (quadrotor), autopilot (ArduPilot), base_mode, system_status, version
    return struct.pack("<IBBBBB", 0, 2, 3, ARMED if armed else 0, state, 3)


def attitude(roll_deg, pitch_deg, yaw_deg):
    return struct.pack("<I6f", 5000, math.radians(roll_deg), math.radians(pitch_deg),
                       math.radians(yaw_deg), 0.0, 0.0, 0.0)


def global_position(lat, lon, alt_msl, rel_alt, vel_ned):
    return struct.pack("<IiiiihhhH", 5000, round(lat * 1e7), round(lon * 1e7),
                       round(alt_msl * 1000), round(rel_alt * 1000),
                       *(round(v * 100) for v in vel_ned), 9000)


def system_time(unix_s):
    return struct.pack("<QI", int(unix_s * 1e6), 5000)


class Vehicle:
    """An autopilot streaming HEARTBEAT (2 Hz) and ATTITUDE, GLOBAL_POSITION_INT and
    SYSTEM_TIME (10 Hz) to a UDP port, in MAVLink 2, until paused or closed."""

    def __init__(self, port, sysid=1):
        self.port, self.sysid = port, sysid
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.lock = threading.Lock()
        self.armed, self.state = True, MAV_STATE_ACTIVE
        self.att = (2.5, -4.0, 135.0)
        self.pos = dict(lat=45.7123456, lon=-121.4987654, alt_msl=850.25, rel_alt=120.0,
                        vel_ned=(12.5, -3.0, 0.5))
        self.unix_s = 1767225600.0  # 2026-01-01T00:00:00Z at start
        self.sending = threading.Event()
        self.closed = False
        self.seq = 0
        self.thread = threading.Thread(target=self._run, daemon=True)
        self.thread.start()

    def payloads(self):
        with self.lock:
            return (heartbeat(self.armed, self.state), attitude(*self.att),
                    global_position(**self.pos), system_time(self.unix_s))

    def set(self, **kw):
        with self.lock:
            for k, v in kw.items():
                if k in ("armed", "state", "att"):
                    setattr(self, k, v)
                else:
                    self.pos[k] = v

    def _send(self, msgid, payload):
        self.sock.sendto(mavlink_v2(msgid, payload, self.seq & 0xFF, self.sysid),
                         ("127.0.0.1", self.port))
        self.seq += 1

    def _run(self):
        n = 0
        while not self.closed:
            if self.sending.wait(0.05) and not self.closed:
                hb, att, pos, st = self.payloads()
                if n % 5 == 0:
                    self._send(HEARTBEAT, hb)
                self._send(ATTITUDE, att)
                self._send(GLOBAL_POSITION_INT, pos)
                self._send(SYSTEM_TIME, st)
                with self.lock:
                    self.unix_s += 0.1
                n += 1
                time.sleep(0.1)

    def start(self):
        self.sending.set()

    def pause(self):
        self.sending.clear()

    def close(self):
        self.closed = True
        self.sending.set()
        self.thread.join(2)
        self.sock.close()


class PtyVehicle(Vehicle):
    """The same autopilot on a serial line: a pseudo-terminal whose slave the daemon opens
    through a symlink, as it would a USB telemetry radio."""

    def __init__(self, link_path, sysid=1):
        self.master, self.slave = os.openpty()
        tty.setraw(self.slave)
        os.symlink(os.ttyname(self.slave), link_path)
        self.link_path = link_path
        super().__init__(port=0, sysid=sysid)

    def _send(self, msgid, payload):
        try:
            os.write(self.master, mavlink_v2(msgid, payload, self.seq & 0xFF, self.sysid))
        except OSError:
            pass  # nobody has the line open yet: a radio talks into the void too
        self.seq += 1

    def close(self):
        super().close()
        os.close(self.master)
        os.close(self.slave)
        if os.path.islink(self.link_path):
            os.unlink(self.link_path)


class RawTcpGimbal:
    """A TCP server that records every byte a client sends (a Viewpro fed MAVLink)."""

    def __init__(self):
        self.server = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
        self.server.bind(("127.0.0.1", 0))
        self.server.listen(1)
        self.port = self.server.getsockname()[1]
        self.data = bytearray()
        self.lock = threading.Lock()
        self.closed = False
        self.thread = threading.Thread(target=self._run, daemon=True)
        self.thread.start()

    def _run(self):
        self.server.settimeout(0.2)
        conn = None
        while not self.closed:
            if conn is None:
                try:
                    conn, _ = self.server.accept()
                    conn.settimeout(0.2)
                except OSError:
                    continue
            try:
                chunk = conn.recv(4096)
            except socket.timeout:
                continue
            except OSError:
                break
            if not chunk:
                conn.close()
                conn = None
                continue
            with self.lock:
                self.data += chunk
        if conn:
            conn.close()

    def received(self):
        with self.lock:
            return bytes(self.data)

    def close(self):
        self.closed = True
        self.thread.join(2)
        self.server.close()


def rate_hz(entries, window_s):
    """Rate of entries (rx log, field t) over their last `window_s` seconds."""
    if not entries:
        return 0.0
    end = entries[-1]["t"]
    return len([e for e in entries if e["t"] > end - window_s]) / window_s


class VehicleFeedTest(gt.GimbaldTestCase):
    def vehicle(self, port):
        v = Vehicle(port)
        self.addCleanup(v.close)
        return v

    def state(self, client, gimbal):
        reply = client.request("state", gimbal=gimbal)
        self.assertOk(reply)
        return reply["state"]

    def wait_state(self, client, gimbal, predicate, what, timeout=gt.START_TIMEOUT_S):
        found = gt.wait_for(lambda: (lambda s: s if predicate(s) else None)(
            self.state(client, gimbal)), timeout, interval=0.1)
        self.assertTrue(found, "STATE never showed " + what)
        return found

    def test_orion_and_viewpro_in2_fed_lost_and_recovered(self):
        orion = self.start_sim()
        viewpro = self.start_sim("--protocol", "viewpro")
        vport = gt.free_port()
        orion_cfg = gt.orion_tcp("main", orion.port)
        orion_cfg["feed"] = {"autopilot": True, "gps": True}
        daemon = self.start_daemon({
            "gimbals": [orion_cfg, gt.viewpro_tcp("nose", viewpro.port)],
            "vehicle": {"source": {"type": "udp", "bind": "127.0.0.1", "port": vport},
                        "timeout_s": 1.0}})
        client = self.client(daemon)
        events = self.client(daemon)
        self.assertOk(events.request("subscribe", rate_hz=0.1, events=True))
        self.wait_connected(client, "main")

        # No vehicle yet: STATE says so, nothing but CommGood-0 AutopilotData reaches the Orion.
        s = self.state(client, "main")["vehicle"]
        self.assertEqual(s["connected"], False)
        self.assertEqual(s["source"], "udp 127.0.0.1:%d" % vport)
        self.assertIsNone(s["position"])

        car = self.vehicle(vport)
        car.start()
        ev = events.wait_message(
            lambda m: gt.is_event("vehicle")(m) and m.get("connected") is True, 5)
        self.assertTrue(ev, "no vehicle connected event")

        # STATE vehicle, in degrees and metres, for both gimbals.
        for name in ("main", "nose"):
            v = self.wait_state(client, name, lambda s: s["vehicle"]["connected"] and
                                s["vehicle"]["position"] and s["vehicle"]["time"],
                                "vehicle connected")["vehicle"]
            self.assertAlmostEqual(v["attitude"]["roll"], 2.5, places=3)
            self.assertAlmostEqual(v["attitude"]["pitch"], -4.0, places=3)
            self.assertAlmostEqual(v["attitude"]["yaw"], 135.0, places=3)
            self.assertAlmostEqual(v["position"]["lat"], 45.7123456, places=7)
            self.assertAlmostEqual(v["position"]["lon"], -121.4987654, places=7)
            self.assertAlmostEqual(v["position"]["alt_msl"], 850.25, places=3)
            self.assertAlmostEqual(v["relative_alt"], 120.0, places=3)
            self.assertEqual([round(x, 2) for x in v["velocity_ned"]], [12.5, -3.0, 0.5])
            self.assertIs(v["armed"], True)
            self.assertIs(v["flying"], True)
            self.assertEqual(v["system_id"], 1)
            self.assertTrue(v["time"].startswith("2026-01-01T00:00"), v["time"])
            self.assertLess(v["age_s"], 1.0)

        # A few seconds of feed, then rates and contents.
        time.sleep(3.5)
        rx = orion.rx()
        ap = [e for e in rx if e.get("name") == "autopilot_data"]
        good = [e for e in ap if e["packet"]["comm_good"]]
        self.assertGreaterEqual(len(good), 2, ap[-5:])
        last = good[-1]["packet"]
        self.assertTrue(last["is_flying"])
        self.assertEqual(last["agl"], 120)
        self.assertTrue(0.6 <= rate_hz(good, 3.0) <= 1.5, rate_hz(good, 3.0))
        gps = [e for e in rx if e.get("name") == "gps_data"]
        self.assertTrue(3.0 <= rate_hz(gps, 2.0) <= 5.5, rate_hz(gps, 2.0))
        g = gps[-1]["packet"]
        self.assertAlmostEqual(g["lat"], 45.7123456, places=5)
        self.assertAlmostEqual(g["lon"], -121.4987654, places=5)
        self.assertEqual(g["source"], "mavlink_source")
        self.assertEqual([round(x, 2) for x in g["vel_ned"]], [12.5, -3.0, 0.5])

        in2 = [e for e in viewpro.rx() if e.get("kind") == "in2"]
        self.assertTrue(7.0 <= rate_hz(in2, 2.0) <= 13.0, rate_hz(in2, 2.0))
        f = in2[-1]["frame"]
        self.assertAlmostEqual(f["lat"], 45.7123456, places=6)
        self.assertAlmostEqual(f["lon"], -121.4987654, places=6)
        self.assertAlmostEqual(f["alt_msl"], 850.25, places=2)
        self.assertAlmostEqual(f["roll"], 2.5, places=2)
        self.assertAlmostEqual(f["pitch"], -4.0, places=2)
        self.assertAlmostEqual(f["yaw"], 135.0, places=2)
        self.assertEqual([round(x, 2) for x in f["vel_ned"]], [12.5, -3.0, 0.5])
        self.assertTrue(f["time"].startswith("2026-01-01T00:00"), f["time"])

        # Laser interlocks of the simulated Orion follow the fed state.
        def laser(predicate, what):
            return self.wait_state(client, "main", lambda s: s.get("lasers") and
                                   predicate(s["lasers"][0]), what, timeout=6)
        laser(lambda l: not l["altitude_lock"] and not l["ap_flying_lock"] and
              not l["ap_comm_lock"], "no interlock while flying at 120 m")
        car.set(armed=False, state=MAV_STATE_STANDBY)
        laser(lambda l: l["ap_flying_lock"], "ApFlyingLock once disarmed")
        car.set(armed=True, state=MAV_STATE_ACTIVE, rel_alt=5.0)
        laser(lambda l: l["altitude_lock"] and not l["ap_flying_lock"],
              "AltitudeLock at 5 m AGL")
        car.set(rel_alt=120.0)
        laser(lambda l: not l["altitude_lock"], "AltitudeLock released at 120 m")

        # Loss: CommGood 0 at once, the Viewpro feed stops, an event, STATE shows it.
        car.pause()
        ev = events.wait_message(
            lambda m: gt.is_event("vehicle")(m) and m.get("connected") is False, 5)
        self.assertTrue(ev, "no vehicle lost event")
        lost_at = time.monotonic()
        n_ap = len(ap)
        bad = gt.wait_for(lambda: [e for e in orion.rx() if e.get("name") == "autopilot_data"
                                   and not e["packet"]["comm_good"]], 3, interval=0.02)
        self.assertTrue(bad, "no CommGood 0 after the loss")
        self.assertLess(time.monotonic() - lost_at, 0.6, "CommGood 0 was not sent at once")
        self.assertGreater(len([e for e in orion.rx() if e.get("name") == "autopilot_data"]),
                           n_ap)
        self.assertIs(self.state(client, "nose")["vehicle"]["connected"], False)
        time.sleep(0.3)
        n_in2 = len([e for e in viewpro.rx() if e.get("kind") == "in2"])
        n_gps = len([e for e in orion.rx() if e.get("name") == "gps_data"])
        time.sleep(1.5)
        self.assertEqual(len([e for e in viewpro.rx() if e.get("kind") == "in2"]), n_in2,
                         "IN2 still sent while the feed is lost")
        self.assertEqual(len([e for e in orion.rx() if e.get("name") == "gps_data"]), n_gps,
                         "GPS_DATA still sent while the feed is lost")
        # AutopilotData keeps coming at 1 Hz, with CommGood 0.
        ap_lost = [e for e in orion.rx() if e.get("name") == "autopilot_data"][-1]
        self.assertFalse(ap_lost["packet"]["comm_good"])
        laser(lambda l: l["ap_comm_lock"], "ApCommLock while the feed is lost")

        # Recovery.
        car.start()
        ev = events.wait_message(
            lambda m: gt.is_event("vehicle")(m) and m.get("connected") is True, 5)
        self.assertTrue(ev, "no vehicle reconnected event")
        self.assertTrue(viewpro.wait_rx(lambda e: e.get("kind") == "in2", 3, start=n_in2),
                        "IN2 did not resume")
        self.assertTrue(orion.wait_rx(lambda e: e.get("name") == "autopilot_data" and
                                      e["packet"]["comm_good"], 3, start=len(orion.rx()) - 1),
                        "CommGood did not come back")
        laser(lambda l: not l["ap_comm_lock"], "ApCommLock released")

    def test_viewpro_in1_and_mavlink_forward(self):
        viewpro = self.start_sim("--protocol", "viewpro")
        raw = RawTcpGimbal()
        self.addCleanup(raw.close)
        vport = gt.free_port()
        in1 = gt.viewpro_tcp("nose", viewpro.port)
        in1["feed"] = "in1"
        fwd = gt.viewpro_tcp("tail", raw.port)
        fwd["feed"] = "mavlink"
        daemon = self.start_daemon({
            "gimbals": [in1, fwd],
            "vehicle": {"source": {"type": "udp", "bind": "127.0.0.1", "port": vport},
                        "system_id": 7, "timeout_s": 0.5}})
        client = self.client(daemon)
        self.wait_connected(client, "tail", telemetry=False)
        self.wait_connected(client, "nose", telemetry=False)

        other = Vehicle(vport, sysid=9)  # filtered out by system_id
        self.addCleanup(other.close)
        other.start()
        time.sleep(1.0)
        self.assertIs(self.state(client, "nose")["vehicle"]["connected"], False)
        self.assertEqual([e for e in viewpro.rx() if e.get("kind") in ("in1", "in2")], [])
        self.assertEqual(parse_v1(raw.received()), [])
        other.close()

        car = Vehicle(vport, sysid=7)
        self.addCleanup(car.close)
        car.start()
        self.wait_state(client, "tail", lambda s: s["vehicle"]["connected"], "connected")
        time.sleep(2.5)
        in1s = [e for e in viewpro.rx() if e.get("kind") == "in1"]
        self.assertEqual([e for e in viewpro.rx() if e.get("kind") == "in2"], [])
        self.assertTrue(7.0 <= rate_hz(in1s, 2.0) <= 13.0, rate_hz(in1s, 2.0))
        f = in1s[-1]["frame"]
        self.assertAlmostEqual(f["lat"], 45.7123456, places=6)
        self.assertAlmostEqual(f["yaw"], 135.0, places=2)
        self.assertNotIn("vel_ned", f)

        frames = parse_v1(raw.received())
        hb, att, pos, st = car.payloads()
        by_id = {}
        for msgid, sysid, payload in frames:
            self.assertEqual(sysid, 7)
            by_id.setdefault(msgid, []).append(payload)
        self.assertEqual(sorted(by_id), [SYSTEM_TIME, ATTITUDE, GLOBAL_POSITION_INT])
        self.assertEqual(by_id[ATTITUDE][-1], att)
        self.assertEqual(by_id[GLOBAL_POSITION_INT][-1], pos)
        # ~10 Hz each: 2.5 s of feed gives about 25 of each.
        self.assertTrue(15 <= len(by_id[ATTITUDE]) <= 35, len(by_id[ATTITUDE]))
        self.assertEqual(self.state(client, "tail")["vehicle"]["feed"]["kind"], "mavlink")

        car.pause()
        time.sleep(0.9)  # timeout 0.5 s, plus margin
        n = len(parse_v1(raw.received()))
        time.sleep(1.0)
        self.assertEqual(len(parse_v1(raw.received())), n, "MAVLink still forwarded when lost")

    def test_serial_vehicle_source(self):
        sim = self.start_sim()
        link = os.path.join(tempfile.mkdtemp(prefix="gimbald-mav-"), "ttyMAV")
        car = PtyVehicle(link)
        self.addCleanup(car.close)
        daemon = self.start_daemon({
            "gimbals": [gt.orion_tcp("main", sim.port)],
            "vehicle": {"source": {"type": "serial", "device": link, "baud": 57600},
                        "timeout_s": 0.5}})
        client = self.client(daemon)
        self.wait_connected(client, "main")
        car.start()
        s = self.wait_state(client, "main", lambda s: s["vehicle"]["connected"],
                            "vehicle connected over the serial source")["vehicle"]
        self.assertIn(link, s["source"])
        fed = sim.wait_rx(lambda e: e.get("name") == "autopilot_data" and
                          e["packet"]["comm_good"], timeout=5)
        self.assertTrue(fed, "no AutopilotData with CommGood from the serial feed")
        car.pause()
        self.wait_state(client, "main", lambda s: not s["vehicle"]["connected"],
                        "vehicle lost after the serial feed stopped")

    def test_without_vehicle_section_state_shows_no_feed(self):
        sim = self.start_sim()
        daemon = self.start_daemon({"gimbals": [gt.orion_tcp("main", sim.port)]})
        client = self.client(daemon)
        self.wait_connected(client, "main")
        # Nothing can tell gimbald about the aircraft: STATE `vehicle` is null.
        self.assertIsNone(self.state(client, "main")["vehicle"])
        time.sleep(1.5)
        self.assertEqual([e for e in sim.rx() if e.get("name") == "autopilot_data"], [],
                         "AutopilotData sent without a vehicle section")


if __name__ == "__main__":
    gt.main()
