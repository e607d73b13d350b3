#!/usr/bin/env python3
"""MAVLink gimbal devices end to end (contract section 19): a real gimbald is the gimbal
manager of `gimbal-sim --protocol mavlink` over a pseudo-terminal, with the aircraft's
MAVLink (built here with struct and X.25, independently of lib/mavlink) on its vehicle port.

Checked: STATE `device` from GIMBAL_DEVICE_INFORMATION / ATTITUDE_STATUS, the Orion-style
`telemetry`, a `position` command reaching the device as common.xml's quaternion (the
simulator's rx log), AUTOPILOT_STATE_FOR_GIMBAL_DEVICE at 10-50 Hz, staleness when the device
goes quiet, and the stare target: while the aircraft circles a geopoint, the line of sight
stays within 0.5 degrees of it at p95 after the first 2 s; a geopoint with `stare` gives one
`stare_start` event on a subscriber once the device is on the point, a stabilized position
keeps its yaw from north while the aircraft turns, and the geoid undulation is EGM96's
where none is configured; a path's step-stare gives a stare_start at each stare, and a
stare_ack echoing one ends it at once. And towards ground stations: a
ground station (tests/integration/mavlinktest.py) on gimbald's own MAVLink gimbal manager
steers the device with DO_GIMBAL_MANAGER_PITCHYAW and reads its attitude and limits. With a
signing key on both sides (gimbals[].mavlink.signing_key_file, gimbal-sim --signing-key)
they talk; with different keys neither hears the other; a bad key file is exit 1.
"""

import json
import math
import os
import socket
import struct
import threading
import time
import unittest

import gimbaltest as gt
import mavlinktest as mt

HEARTBEAT, ATTITUDE, GLOBAL_POSITION_INT = 0, 30, 33

# The stare geometry: a point on the ground (MSL 100 m, geoid 0), the aircraft 500 m above it
# on a 400 m circle at 30 m/s.
POINT = (45.7, -121.5, 100.0)
RADIUS, SPEED, HEIGHT = 400.0, 30.0, 500.0


def circle(t):
    """The aircraft at t seconds: lat, lon, alt (MSL), roll/pitch/yaw (rad), vn/ve (m/s),
    yaw rate (rad/s). Flat-earth offsets are fine over 400 m."""
    omega = SPEED / RADIUS
    a = omega * t
    north, east = RADIUS * math.cos(a), RADIUS * math.sin(a)
    lat = POINT[0] + math.degrees(north / 6378137.0)
    lon = POINT[1] + math.degrees(east / (6378137.0 * math.cos(math.radians(POINT[0]))))
    vn, ve = -SPEED * math.sin(a), SPEED * math.cos(a)
    return lat, lon, POINT[2] + HEIGHT, math.radians(12), 0.0, math.atan2(ve, vn), vn, ve, omega


class Aircraft:
    """Sends HEARTBEAT (1 Hz), ATTITUDE and GLOBAL_POSITION_INT (20 Hz) to gimbald's vehicle
    port from a thread, flying `circle` from its start."""

    def __init__(self, port):
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.port = port
        self.start = time.monotonic()
        self.seq = 0
        self.running = True
        self.thread = threading.Thread(target=self.run, daemon=True)
        self.thread.start()

    def send(self, msgid, payload):
        self.sock.sendto(mt.frame(msgid, payload, 1, 1, self.seq), ("127.0.0.1", self.port))
        self.seq += 1

    def run(self):
        n = 0
        while self.running:
            t = time.monotonic() - self.start
            lat, lon, alt, roll, pitch, yaw, vn, ve, yaw_rate = circle(t)
            ms = int(t * 1000) & 0xFFFFFFFF
            if n % 20 == 0:
                # custom_mode, type (fixed wing), autopilot (ArduPilot), base_mode (armed),
                # system_status (active), mavlink_version
                self.send(HEARTBEAT, struct.pack("<IBBBBB", 0, 1, 3, 128, 4, 3))
            self.send(ATTITUDE, struct.pack("<Iffffff", ms, roll, pitch, yaw, 0, 0, yaw_rate))
            hdg = int(round(math.degrees(yaw) % 360 * 100)) % 36000
            self.send(GLOBAL_POSITION_INT,
                      struct.pack("<IiiiihhhH", ms, int(round(lat * 1e7)), int(round(lon * 1e7)),
                                  int(round(alt * 1000)), int(HEIGHT * 1000), int(vn * 100),
                                  int(ve * 100), 0, hdg))
            n += 1
            time.sleep(0.05)

    def close(self):
        self.running = False
        self.thread.join(2)
        self.sock.close()


def los_error_deg(state):
    """The angle between the line of sight in STATE (device attitude, yaw from north or from
    the aircraft's heading) and the direction from the aircraft to POINT."""
    t, att = state["telemetry"], state["device"]["attitude"]
    yaw = att["yaw"] + (0.0 if att["frame"] == "earth" else t["yaw"])
    pitch = math.radians(att["pitch"])
    have = (math.cos(pitch) * math.cos(math.radians(yaw)),
            math.cos(pitch) * math.sin(math.radians(yaw)), -math.sin(pitch))
    north = math.radians(POINT[0] - t["lat"]) * 6378137.0
    east = math.radians(POINT[1] - t["lon"]) * 6378137.0 * math.cos(math.radians(POINT[0]))
    down = t["alt_msl"] - POINT[2]  # both above MSL (the geoid is EGM96 there)
    n = math.sqrt(north * north + east * east + down * down)
    want = (north / n, east / n, down / n)
    dot = sum(a * b for a, b in zip(have, want))
    return math.degrees(math.acos(max(-1.0, min(1.0, dot))))


def earth_yaw(state):
    """The device's line of sight from north (degrees), from STATE."""
    t, att = state["telemetry"], state["device"]["attitude"]
    return att["yaw"] + (0.0 if att["frame"] == "earth" else t["yaw"])


def wrap180(a):
    return (a + 180.0) % 360.0 - 180.0


class MavlinkDeviceTest(gt.GimbaldTestCase):
    def state(self, client, gimbal="cam"):
        reply = client.request("state", gimbal=gimbal)
        self.assertOk(reply)
        return reply["state"]

    def wait_state(self, client, predicate, what, timeout=gt.START_TIMEOUT_S):
        found = gt.wait_for(lambda: (lambda s: s if predicate(s) else None)(self.state(client)),
                            timeout, interval=0.1)
        self.assertTrue(found, "STATE never showed " + what)
        return found

    def wait_device(self, client, what="device information and telemetry"):
        """STATE once the device has sent its information and the aircraft its position."""
        return self.wait_state(client, lambda s: s["device"]["vendor"] == "gimbald" and
                               s["telemetry"] and s["telemetry"]["lat"] is not None, what)

    def start_pty(self, *sim_args, stale_after_s=None, manager=False):
        device = os.path.join(self.workdir, "ttyGIMBAL")
        sim = self.start_sim("--protocol", "mavlink", *sim_args, tcp=False, pty_link=device)
        vport = gt.free_port()
        config = {
            "gimbals": [{"name": "cam", "protocol": "mavlink",
                         "link": {"type": "serial", "device": device, "baud": 115200,
                                  "reconnect_min_s": 0.2, "reconnect_max_s": 1},
                         "mavlink": {"hfov_deg": 50, "vfov_deg": 30}}],
            "vehicle": {"source": {"type": "udp", "bind": "127.0.0.1", "port": vport}},
        }
        if stale_after_s is not None:
            config["telemetry"] = {"stale_after_s": stale_after_s}
        if manager:  # gimbald's MAVLink gimbal manager on the vehicle endpoint
            config["mavlink"] = {"gimbal_manager": True, "system_id": 1}
        daemon = self.start_daemon(config)
        return sim, daemon, vport

    def test_pty_device_state_position_feed_and_stare(self):
        sim, daemon, vport = self.start_pty("--attitude-rate", "25")
        client = self.client(daemon)
        aircraft = Aircraft(vport)
        self.addCleanup(aircraft.close)

        # STATE device: the simulator's information, its attitude; telemetry with positions.
        s = self.wait_device(client)
        self.assertEqual(s["protocol"], "mavlink")
        d = s["device"]
        self.assertEqual(d["model"], "simulated MAVLink gimbal")
        self.assertEqual(d["firmware"], "2.4.1")
        self.assertIn("supports_yaw_in_earth_frame", d["cap_flags"])
        self.assertAlmostEqual(d["limits"]["pitch_min"], -120, places=3)
        self.assertIn(d["attitude"]["frame"], ("vehicle", "earth"))
        self.assertEqual(len(d["angular_velocity"]), 3)
        self.assertNotIn("no_manager", d["failure_flags"])
        self.assertLess(d["age_s"], 0.5)
        self.assertFalse(s["stale"])
        t = s["telemetry"]
        for key in ("lat", "lon", "alt", "pan", "tilt", "hfov", "vfov", "target", "footprint",
                    "ground"):
            self.assertIn(key, t)
        self.assertEqual(t["hfov"], 50)
        self.assertEqual(s["vehicle"]["feed"]["kind"], "autopilot_state")

        # AUTOPILOT_STATE_FOR_GIMBAL_DEVICE reaches the device at 10-50 Hz.
        time.sleep(1.0)
        states = [e for e in sim.rx() if e["kind"] == "autopilot_state_for_gimbal_device"]
        self.assertGreater(len(states), 10)
        span = states[-1]["t"] - states[-11]["t"]
        self.assertTrue(10 / 50 <= span <= 10 / 10, "10 AUTOPILOT_STATEs in %.3f s" % span)
        # STATE counts them as the vehicle feed it sent (issue 25: it stayed 0).
        sent = self.state(client)["vehicle"]["feed"]["sent"]
        heard = len([e for e in sim.rx() if e["kind"] == "autopilot_state_for_gimbal_device"])
        self.assertGreaterEqual(sent, len(states))
        self.assertLessEqual(sent, heard + 5)  # a few may still be on their way

        # position: common.xml's quaternion, yaw in the vehicle frame, and the device gets there.
        start = len(sim.rx())
        self.assertOk(client.request("position", gimbal="cam", pan=30, tilt=-45))
        entry = sim.wait_rx(lambda e: e["kind"] == "gimbal_device_set_attitude", start=start)
        self.assertIsNotNone(entry, "no GIMBAL_DEVICE_SET_ATTITUDE")
        q = entry["message"]["q"]
        hp, ht = math.radians(30) / 2, math.radians(-45) / 2
        expected = (math.cos(hp) * math.cos(ht), -math.sin(hp) * math.sin(ht),
                    math.cos(hp) * math.sin(ht), math.sin(hp) * math.cos(ht))
        for got, want in zip(q, expected):
            self.assertAlmostEqual(got, want, places=5)
        self.assertEqual(entry["message"]["flags"] & (32 | 64), 32)
        self.wait_state(client, lambda s: abs(s["telemetry"]["pan"] - 30) < 0.5 and
                        abs(s["telemetry"]["tilt"] + 45) < 0.5, "pan 30 tilt -45")

        # The stare: geopoint held while the aircraft circles.
        self.assertOk(client.request("geopoint", gimbal="cam", lat=POINT[0], lon=POINT[1],
                                     alt=POINT[2], alt_ref="msl"))
        begin = time.monotonic()
        errors = []
        while time.monotonic() - begin < 12:
            s = self.state(client)
            if time.monotonic() - begin > 2:
                errors.append(los_error_deg(s))
            time.sleep(0.05)
        errors.sort()
        p95 = errors[int(len(errors) * 0.95)]
        print("stare over a pty: %d samples, p95 %.3f deg, max %.3f deg" %
              (len(errors), p95, errors[-1]))
        self.assertGreater(len(errors), 50)
        self.assertLess(p95, 0.5)

    def test_stare_start_and_stabilized_position_while_circling(self):
        sim, daemon, vport = self.start_pty("--attitude-rate", "25", "--slew-rate", "40")
        client = self.client(daemon)
        aircraft = Aircraft(vport)
        self.addCleanup(aircraft.close)
        s = self.wait_device(client)
        # No geoid_undulation_m configured: EGM96 at the aircraft (about -21 m there).
        t = s["telemetry"]
        self.assertAlmostEqual(t["geoid_undulation"], -21.0, delta=2.0)
        self.assertAlmostEqual(t["alt"], t["alt_msl"] + t["geoid_undulation"], delta=0.01)
        self.assertIsNone(s["stare"])

        # Look away first, so the stare has somewhere to come from.
        self.assertOk(client.request("position", gimbal="cam", pan=0, tilt=0))
        self.wait_state(client, lambda s: abs(s["telemetry"]["tilt"]) < 1, "tilt 0")

        # geopoint with stare: one stare_start on a subscriber once the device is on it.
        sub = self.client(daemon)
        self.assertOk(sub.request("subscribe", rate_hz=0.1, ttl_s=60))
        self.addCleanup(sub.request, "unsubscribe")
        self.assertOk(sub.request("geopoint", gimbal="cam", lat=POINT[0], lon=POINT[1],
                                  alt=POINT[2], alt_ref="msl", stare=True))
        event = sub.wait_message(gt.is_event("stare_start"), 10.0)
        self.assertTrue(event, "no stare_start event")
        self.assertEqual(event["gimbal"], "cam")
        self.assertAlmostEqual(event["lat"], POINT[0], delta=1e-6)
        self.assertAlmostEqual(event["lon"], POINT[1], delta=1e-6)
        undulation = self.state(client)["telemetry"]["geoid_undulation"]
        self.assertAlmostEqual(event["alt"], POINT[2] + undulation, delta=0.5)
        slant = math.hypot(RADIUS, HEIGHT)
        self.assertAlmostEqual(event["slant_range"], slant, delta=10)
        self.assertTrue(event["gimbal_data_valid"])
        self.assertEqual(self.state(client)["stare"]["system_time_ms"], event["system_time_ms"])
        self.assertTrue(daemon.wait_log(lambda e: e.get("event") == "stare_start"))
        # Once per command: none more while it stays on the point.
        more = sub.collect(2.0, gt.is_event("stare_start"))
        self.assertEqual(more, [])

        # A stabilized position keeps its yaw from north while the aircraft turns
        # (4.3 deg/s on its circle): YAW_IN_EARTH_FRAME | YAW_LOCK, the same set-point.
        start = len(sim.rx())
        self.assertOk(client.request("position", gimbal="cam", pan=90, tilt=-30,
                                     stabilized=True))
        heading = self.state(client)["telemetry"]["yaw"]
        # The geopoint's 20 Hz set-point may still be in flight when the command lands: the
        # command's own is the first with YAW_LOCK, and at most one tick goes before it.
        def set_points():
            return [(i, e) for i, e in enumerate(sim.rx()) if i >= start and
                    e["kind"] == "gimbal_device_set_attitude"]
        entry = sim.wait_rx(lambda e: e["kind"] == "gimbal_device_set_attitude" and
                            e["message"]["flags"] & 16, start=start)
        self.assertIsNotNone(entry, "no set-point with YAW_LOCK after a stabilized position")
        self.assertEqual(entry["message"]["flags"] & (16 | 32 | 64), 16 | 64)
        index = next(i for i, e in set_points() if e is entry or e == entry)
        before = [e for i, e in set_points() if i < index]
        self.assertLessEqual(len(before), 1, before)
        held = entry["message"]["yaw"]
        self.assertAlmostEqual(wrap180(held - heading - 90), 0, delta=2.0)
        time.sleep(1.5)  # the device slews there
        begin = time.monotonic()
        first = self.state(client)
        errors = []
        while time.monotonic() - begin < 6:
            s = self.state(client)
            errors.append(abs(wrap180(earth_yaw(s) - held)))
            time.sleep(0.1)
        turned = abs(wrap180(s["telemetry"]["yaw"] - first["telemetry"]["yaw"]))
        print("stabilized position: aircraft turned %.1f deg, yaw from north off by %.2f max"
              % (turned, max(errors)))
        self.assertGreater(turned, 20)
        self.assertLess(max(errors), 1.0)
        later = [e for i, e in set_points() if i >= index]
        self.assertGreater(len(later), 50)  # re-sent at 20 Hz
        self.assertTrue(all(abs(wrap180(e["message"]["yaw"] - held)) < 1e-3 for e in later))

    def test_path_step_stare_and_stare_ack(self):
        """A path with along-track steps gives a stare_start at each stare; a stare_ack that
        echoes its system_time_ms ends it at once (nothing goes to the device); without one
        the stare runs out its time."""
        sim, daemon, vport = self.start_pty("--attitude-rate", "25", "--slew-rate", "60")
        client = self.client(daemon)
        aircraft = Aircraft(vport)
        self.addCleanup(aircraft.close)
        self.wait_device(client)
        sub = self.client(daemon)
        self.assertOk(sub.request("subscribe", rate_hz=0.1, ttl_s=60))
        self.addCleanup(sub.request, "unsubscribe")
        # 600 m of ground through the circle's centre, north to south, in 5-degree steps.
        dlat = math.degrees(300.0 / 6378137.0)
        points = [{"lat": POINT[0] + dlat, "lon": POINT[1], "alt": 0},
                  {"lat": POINT[0] - dlat, "lon": POINT[1], "alt": 0}]
        self.assertOk(client.request("path", gimbal="cam", points=points, along_step_deg=5))
        first = sub.wait_message(gt.is_event("stare_start"), 10.0)
        self.assertTrue(first, "no stare_start from the path")
        self.assertTrue(first["along_track_stare"])
        start = len(sim.rx())
        reply = client.request("stare_ack", gimbal="cam", system_time_ms=first["system_time_ms"])
        self.assertOk(reply)
        self.assertEqual(reply["sent"], [])
        acked = sub.wait_message(gt.is_event("stare_start"), 10.0)
        self.assertTrue(acked, "no stare_start after the ack")
        print("stare ended by stare_ack after %.2f s" % acked["prev_stare_time_s"])
        self.assertFalse(acked["prev_stare_terminated_by_time"])
        self.assertLess(acked["prev_stare_time_s"], 0.5)
        # Nothing but set-points (and the feed) went to the device for the ack.
        kinds = {e["kind"] for e in sim.rx()[start:]}
        self.assertLessEqual(kinds, {"gimbal_device_set_attitude", "autopilot_state_for_gimbal_device",
                                     "heartbeat", "command_long"})
        # Unacknowledged, the stare runs out its time.
        timed = sub.wait_message(gt.is_event("stare_start"), 10.0)
        self.assertTrue(timed, "no third stare_start")
        self.assertTrue(timed["prev_stare_terminated_by_time"])
        self.assertGreater(timed["prev_stare_time_s"], 0.8)

    def test_udp_device_state_position_and_stare(self):
        sim = self.start_sim("--protocol", "mavlink", "--udp", "0", tcp=False, want=("udp",))
        sim_port = int(sim.endpoints["udp"].rsplit(":", 1)[1])
        vport = gt.free_port()
        daemon = self.start_daemon({
            "gimbals": [{"name": "cam", "protocol": "mavlink",
                         "link": {"type": "udp", "host": "127.0.0.1", "port": sim_port,
                                  "local_port": None}}],
            "vehicle": {"source": {"type": "udp", "bind": "127.0.0.1", "port": vport}},
        })
        client = self.client(daemon)
        aircraft = Aircraft(vport)
        self.addCleanup(aircraft.close)
        s = self.wait_device(client, "device information and telemetry over UDP")
        self.assertEqual(s["link"]["type"], "udp")
        self.assertEqual(s["link"]["endpoint"], "127.0.0.1:%d" % sim_port)
        self.assertFalse(s["stale"])

        start = len(sim.rx())
        self.assertOk(client.request("position", gimbal="cam", pan=-60, tilt=-20))
        entry = sim.wait_rx(lambda e: e["kind"] == "gimbal_device_set_attitude", start=start)
        self.assertIsNotNone(entry)
        self.assertEqual(entry["src"], "udp")
        self.assertAlmostEqual(entry["message"]["yaw"], -60, places=3)
        self.assertAlmostEqual(entry["message"]["pitch"], -20, places=3)
        self.wait_state(client, lambda s: abs(s["telemetry"]["pan"] + 60) < 0.5, "pan -60")

        self.assertOk(client.request("geopoint", gimbal="cam", lat=POINT[0], lon=POINT[1],
                                     alt=POINT[2], alt_ref="msl"))
        begin = time.monotonic()
        errors = []
        while time.monotonic() - begin < 8:
            s = self.state(client)
            if time.monotonic() - begin > 2:
                errors.append(los_error_deg(s))
            time.sleep(0.05)
        errors.sort()
        p95 = errors[int(len(errors) * 0.95)]
        print("stare over UDP: %d samples, p95 %.3f deg" % (len(errors), p95))
        self.assertLess(p95, 0.5)

    def test_ground_station_steers_the_device_through_the_gimbal_manager(self):
        sim, daemon, vport = self.start_pty("--attitude-rate", "25", manager=True)
        client = self.client(daemon)
        aircraft = Aircraft(vport)
        self.addCleanup(aircraft.close)
        gcs = mt.Peer(vport)
        self.addCleanup(gcs.close)
        self.wait_device(client)

        # DO_GIMBAL_MANAGER_PITCHYAW (yaw from the nose) -> position -> the device's set-point.
        start = len(sim.rx())
        self.assertEqual(gcs.command(mt.MAV_CMD_DO_GIMBAL_MANAGER_PITCHYAW,
                                     [-25, 40, mt.NAN, mt.NAN, 0, 0, 1]), 0)  # ACCEPTED
        entry = sim.wait_rx(lambda e: e["kind"] == "gimbal_device_set_attitude", start=start)
        self.assertIsNotNone(entry, "PITCHYAW never reached the device")
        self.assertAlmostEqual(entry["message"]["yaw"], 40, places=3)
        self.assertAlmostEqual(entry["message"]["pitch"], -25, places=3)
        self.wait_state(client, lambda s: abs(s["telemetry"]["pan"] - 40) < 0.5 and
                        abs(s["telemetry"]["tilt"] + 25) < 0.5, "pan 40 tilt -25")

        # GIMBAL_DEVICE_ATTITUDE_STATUS (285) from the manager: the device's attitude.
        def pitch_of(m):
            w, x, y, z = struct.unpack("<4f", (m[4] + bytes(40))[4:20])
            return math.degrees(math.asin(max(-1.0, min(1.0, 2 * (w * y - z * x)))))
        since = time.monotonic()
        status = gcs.wait(lambda m: m[3] == 285 and m[2] == 154 and
                          abs(pitch_of(m) + 25) < 1.0, 3.0, since)
        self.assertIsNotNone(status, "no GIMBAL_DEVICE_ATTITUDE_STATUS with the device's pitch")

        # GIMBAL_MANAGER_INFORMATION (280): the device's limits, point at a location.
        since = time.monotonic()
        self.assertEqual(gcs.command(mt.MAV_CMD_REQUEST_MESSAGE, [280, 0]), 0)
        info = gcs.wait(lambda m: m[3] == 280 and m[2] == 154, 3.0, since)
        self.assertIsNotNone(info, "no GIMBAL_MANAGER_INFORMATION")
        fields = struct.unpack("<II6fB", (info[4] + bytes(33))[:33])
        cap_flags, pitch_min = fields[1], fields[4]
        self.assertTrue(cap_flags & 131072, "CAN_POINT_LOCATION_GLOBAL missing")
        self.assertAlmostEqual(math.degrees(pitch_min), -120, places=2)
        # A gimbal device has no zoom: the manager says so.
        self.assertEqual(gcs.command(531, [2, 50, 0]), 3)  # SET_CAMERA_ZOOM: UNSUPPORTED

    def start_signed_udp(self, device_key, gimbald_key):
        sim = self.start_sim("--protocol", "mavlink", "--udp", "0", "--signing-key",
                             device_key.hex(), tcp=False, want=("udp",))
        sim_port = int(sim.endpoints["udp"].rsplit(":", 1)[1])
        key_file = os.path.join(self.workdir, "device.key")
        with open(key_file, "w") as f:
            f.write(gimbald_key.hex() + "\n")
        os.chmod(key_file, 0o600)
        daemon = self.start_daemon({
            "gimbals": [{"name": "cam", "protocol": "mavlink",
                         "link": {"type": "udp", "host": "127.0.0.1", "port": sim_port,
                                  "local_port": None},
                         "mavlink": {"signing_key_file": key_file}}],
        })
        return sim, daemon

    def test_signed_device_link(self):
        key = os.urandom(32)
        sim, daemon = self.start_signed_udp(key, key)
        client = self.client(daemon)
        s = self.wait_state(client, lambda s: s["device"]["vendor"] == "gimbald" and
                            s["device"]["attitude"] is not None, "a signed device's reports")
        self.assertFalse([e for e in daemon.logs() if e.get("event") == "decode_error"])
        start = len(sim.rx())
        self.assertOk(client.request("position", gimbal="cam", pan=25, tilt=-15))
        entry = sim.wait_rx(lambda e: e["kind"] == "gimbal_device_set_attitude", start=start)
        self.assertIsNotNone(entry)
        # Signed: incompat flag 0x01 (the frame's third byte) and 13 more bytes.
        self.assertEqual(int(entry["hex"][4:6], 16) & 1, 1)
        self.wait_state(client, lambda s: abs(s["telemetry"]["pan"] - 25) < 0.5, "pan 25")

    def test_device_with_another_key_is_not_heard(self):
        sim, daemon = self.start_signed_udp(os.urandom(32), os.urandom(32))
        client = self.client(daemon)
        # Its frames arrive and are refused (counted as decode errors).
        self.wait_state(client, lambda s: s["link"]["rx_bytes"] > 500, "the device's frames")
        self.assertTrue(daemon.wait_log(lambda e: e.get("event") == "decode_error"))
        s = self.state(client)
        self.assertEqual(s["link"]["rx_packets"], 0)
        self.assertIsNone(s["device"]["vendor"])
        self.assertIsNone(s["device"]["attitude"])
        self.assertTrue(s["stale"])
        # Nothing of the device's gets through later either.
        time.sleep(0.5)
        self.assertIsNone(self.state(client)["device"]["attitude"])

    def test_bad_signing_key_file_is_exit_1(self):
        key_file = os.path.join(self.workdir, "short.key")
        with open(key_file, "w") as f:
            f.write("abcd\n")
        os.chmod(key_file, 0o600)
        config = {"gimbals": [{"name": "cam", "protocol": "mavlink",
                               "link": {"type": "udp", "host": "127.0.0.1", "port": 14570,
                                        "local_port": None},
                               "mavlink": {"signing_key_file": key_file}}]}
        path = os.path.join(self.workdir, "signed.json")
        with open(path, "w") as f:
            json.dump(config, f)
        for extra in (["--check-config"], []):
            proc = gt.run([gt.GIMBALD, "-c", path, *extra])
            text = proc.stdout + proc.stderr
            self.assertEqual(proc.returncode, 1, text)
            self.assertIn("gimbals[0].mavlink.signing_key_file", text)
            self.assertIn("64 hex digits", text)

    def test_udp_link_takes_frames_only_from_its_host(self):
        # The device is at 127.0.0.2: datagrams from 127.0.0.1 (a stranger's) are dropped.
        stranger = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.addCleanup(stranger.close)
        device = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.addCleanup(device.close)
        try:
            device.bind(("127.0.0.2", 0))
        except OSError:
            self.skipTest("127.0.0.2 is not a local address here")
        local = gt.free_port()
        daemon = self.start_daemon({
            "gimbals": [{"name": "cam", "protocol": "mavlink",
                         "link": {"type": "udp", "host": "127.0.0.2",
                                  "port": device.getsockname()[1], "local_port": local}}]})
        client = self.client(daemon)
        device.settimeout(5)
        data, sender = device.recvfrom(2048)  # the REQUEST_MESSAGE gimbald sends at once
        self.assertEqual(sender[1], local)
        self.assertEqual(data[0], 0xFD)
        status = struct.pack("<I4ffffIHBB", 0, 1, 0, 0, 0, 0, 0, 0, 0, 32, 0, 0)
        frame = mt.frame(285, status, 1, 154)
        stranger.sendto(frame, ("127.0.0.1", local))
        time.sleep(0.5)
        self.assertIsNone(self.state(client)["device"]["attitude"])
        device.sendto(frame, ("127.0.0.1", local))
        self.wait_state(client, lambda s: s["device"]["attitude"] is not None,
                        "the attitude from the device's host")

    def test_pty_device_goes_stale_and_recovers(self):
        sim, daemon, vport = self.start_pty(stale_after_s=0.5)
        client = self.client(daemon)
        self.wait_state(client, lambda s: s["device"]["attitude"] is not None and not s["stale"],
                        "a fresh attitude")
        sim.kill()
        s = self.wait_state(client, lambda s: s["stale"], "stale after the device went quiet",
                            timeout=3)
        self.assertGreaterEqual(s["device"]["age_s"], 0.5)
        self.assertTrue(daemon.wait_log(lambda e: e.get("event") == "telemetry_lost"))


if __name__ == "__main__":
    gt.main()
