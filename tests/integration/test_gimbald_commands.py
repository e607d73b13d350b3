#!/usr/bin/env python3
"""gimbald's commands end to end (contract sections 4 and 5): the real daemon talks TCP to a
real gimbal-sim, and the simulator's rx log shows exactly what reached the gimbal.

Every expected wire frame is computed here from the ICD (scaling, Fletcher checksum), not
taken from the product.
"""

import datetime
import math
import struct

import gimbaltest as gt

# OrionMode_t values (ICD) of the commands sent below.
MODE_RATE, MODE_POSITION = 16, 80
TERRAIN_ALT_M = 100.0  # flat ground for gimbal-sim (--terrain-alt), not its hilly terrain
CONNECT_REQUESTS = ["clevis_version", "crown_version", "payload_version", "tracker_version",
                    "retract_version", "lensctl_version", "cameras", "limits"]
VERSION_REQUESTS = CONNECT_REQUESTS[:6]
LINK_KEYS = {"type", "endpoint", "connected", "rx_bytes", "tx_bytes", "rx_packets",
             "tx_packets", "bad_checksums", "dropped_bytes", "reconnects", "last_rx_age_s"}
TELEMETRY_KEYS = {"system_time_ms", "gps_week", "gps_itow_ms", "utc", "lat", "lon", "alt",
                  "alt_msl", "geoid_undulation", "vel_ned", "quat", "roll", "pitch", "yaw",
                  "pan", "tilt", "hfov", "vfov", "mode", "los_ecef", "target", "range_source",
                  "path_progress", "path_from", "path_to", "stare_time_s", "pixel_width",
                  "pixel_height", "age_s"}
ORION_KEYS = {"telemetry", "ins", "gps", "lasers", "diagnostics", "performance", "software",
              "network_diagnostics", "vibration", "retract", "stare", "cameras", "limits",
              "network_settings", "network_video", "uart_config", "ins_options", "versions",
              "reset_source", "boards"}


class OrionOverTcp(gt.GimbaldTestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.sim = cls.start_class_sim("--terrain-alt", str(TERRAIN_ALT_M))
        cls.daemon = cls.start_class_daemon(
            {"gimbals": [gt.orion_tcp("main", cls.sim.port)]})

    def setUp(self):
        super().setUp()
        self.c = self.client(self.daemon)
        self.wait_connected(self.c)

    def send_and_find(self, cmd, packet_name, **params):
        """Runs a command; returns (reply, the rx log entry of the packet it sent)."""
        start = len(self.sim.rx())
        reply = self.c.request(cmd, **params)
        self.assertOk(reply)
        self.assertEqual(reply["gimbal"], "main")
        entry = self.sim.wait_rx(gt.by_name(packet_name), start=start)
        self.assertIsNotNone(entry, "%s never reached the simulator" % packet_name)
        return reply, entry

    def state(self):
        reply = self.c.request("state")
        self.assertOk(reply)
        return reply["state"]

    # --- commands for every gimbal -------------------------------------------------------

    def test_ping_returns_the_id_unchanged(self):
        for request_id in (7, "abc", 1.5, {"nested": [1, "x"]}, [3], True):
            reply = self.c.request("ping", id=request_id)
            self.assertEqual(reply, {"id": request_id, "ok": True, "cmd": "ping", "pong": True})
        # Without an id the reply has none.
        self.c.send({"cmd": "ping"})
        reply = self.c.recv()
        self.assertEqual(reply, {"ok": True, "cmd": "ping", "pong": True})

    def test_version(self):
        reply = self.c.request("version")
        self.assertOk(reply)
        self.assertRegex(reply["version"], r"^\d+\.\d+\.\d+$")
        self.assertEqual(sorted(reply["protocols"]), ["mavlink", "orion", "siyi", "viewpro"])
        self.assertNotIn("gimbal", reply)

    def test_list(self):
        reply = self.c.request("list")
        self.assertOk(reply)
        self.assertEqual(reply["gimbals"], [{"name": "main", "protocol": "orion",
                                             "link": {"type": "tcp", "connected": True}}])

    def test_state_envelope_and_link_counters(self):
        state = self.state()
        self.assertEqual(state["protocol"], "orion")
        self.assertIs(state["stale"], False)
        self.assertTrue(ORION_KEYS <= set(state), ORION_KEYS - set(state))
        link = state["link"]
        self.assertEqual(set(link), LINK_KEYS)
        self.assertEqual(link["type"], "tcp")
        self.assertEqual(link["endpoint"], "127.0.0.1:%d" % self.sim.port)
        self.assertIs(link["connected"], True)
        for key in LINK_KEYS - {"type", "endpoint", "connected", "last_rx_age_s"}:
            self.assertIsInstance(link[key], int, key)
        self.assertGreater(link["rx_bytes"], 0)
        self.assertGreater(link["rx_packets"], 0)
        # At least the eight requests sent on connect.
        self.assertGreaterEqual(link["tx_packets"], 8)
        self.assertGreaterEqual(link["tx_bytes"], 8 * 6)
        self.assertEqual(link["bad_checksums"], 0)
        self.assertLess(link["last_rx_age_s"], 1.0)
        # Counters grow.
        later = gt.wait_for(lambda: self.state()["link"]["rx_bytes"] > link["rx_bytes"], 3.0)
        self.assertTrue(later)

    def test_state_telemetry(self):
        # Look down at the terrain so the line of sight meets it (a target exists).
        self.c.request("position", pan=0, tilt=-45)

        def settled():
            t = self.state()["telemetry"]
            return t if (abs(t["tilt"] + 45) < 0.5 and t["range_source"] == "internal"
                         and t["target"]) else None
        t = gt.wait_for(settled, 8.0, interval=0.1)
        self.assertTrue(t, "the gimbal never settled at tilt -45 with a target")
        self.assertTrue(TELEMETRY_KEYS <= set(t), TELEMETRY_KEYS - set(t))
        self.assertEqual(t["mode"], "position")
        self.assertLess(t["age_s"], 1.0)

        # utc: ISO-8601 with milliseconds, the simulator's clock is the system clock.
        self.assertRegex(t["utc"], r"^\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d\.\d{3}Z$")
        utc = datetime.datetime.strptime(t["utc"], "%Y-%m-%dT%H:%M:%S.%fZ").replace(
            tzinfo=datetime.timezone.utc)
        now = datetime.datetime.now(datetime.timezone.utc)
        self.assertLess(abs((utc - now).total_seconds()), 30.0)

        # Position: on the simulator's circle (radius 1000 m around 45.7 N 121.5 W, 1500 m).
        self.assertAlmostEqual(
            gt.ground_distance_m(t["lat"], t["lon"], 45.7, -121.5), 1000.0, delta=20.0)
        self.assertAlmostEqual(t["alt"], 1500.0, delta=0.5)
        # Each printed with the digits its source holds (contract section 1): within 1 cm.
        self.assertAlmostEqual(t["alt_msl"], t["alt"] - t["geoid_undulation"], delta=0.01)
        self.assertAlmostEqual(t["geoid_undulation"], -21.0, delta=0.5)

        # Attitude from quat: a coordinated clockwise turn at 25 m/s on a 1000 m circle
        # banks right by atan(v^2 / (g r)); the nose points along the velocity.
        self.assertEqual(len(t["quat"]), 4)
        self.assertAlmostEqual(math.sqrt(sum(q * q for q in t["quat"])), 1.0, places=3)
        vn, ve, _ = t["vel_ned"]
        self.assertAlmostEqual(math.hypot(vn, ve), 25.0, delta=0.5)
        self.assertLess(gt.angle_diff_deg(t["yaw"], math.degrees(math.atan2(ve, vn))), 2.0)
        self.assertAlmostEqual(t["roll"], math.degrees(math.atan(25.0 ** 2 / (9.80665 * 1000))),
                               delta=0.5)
        self.assertAlmostEqual(t["pitch"], 0.0, delta=0.5)

        # Target: gimbal position + los_ecef, on the terrain.
        x, y, z = gt.lla_to_ecef(t["lat"], t["lon"], t["alt"])
        dx, dy, dz = t["los_ecef"]
        lat, lon, alt = gt.ecef_to_lla(x + dx, y + dy, z + dz)
        self.assertAlmostEqual(t["target"]["lat"], lat, delta=1e-6)
        self.assertAlmostEqual(t["target"]["lon"], lon, delta=1e-6)
        self.assertAlmostEqual(t["target"]["alt"], alt, delta=0.05)
        self.assertAlmostEqual(t["target"]["alt"], TERRAIN_ALT_M, delta=3.0)
        # Slant range from 1400 m above the terrain looking 45 degrees down (plus bank).
        self.assertAlmostEqual(math.sqrt(dx * dx + dy * dy + dz * dz), 1400 * math.sqrt(2),
                               delta=150.0)

    def test_no_target_when_looking_above_the_horizon(self):
        self.assertOk(self.c.request("position", pan=0, tilt=20))

        def sky():
            t = self.state()["telemetry"]
            return t if abs(t["tilt"] - 20) < 0.5 and t["range_source"] == "none" else None
        t = gt.wait_for(sky, 8.0, interval=0.1)
        self.assertTrue(t, "never looked at the sky")
        self.assertEqual(t["los_ecef"], [0.0, 0.0, 0.0])
        self.assertIsNone(t["target"])

    def test_state_versions_cameras_limits_from_the_connect_requests(self):
        state = self.state()
        self.assertEqual(set(state["versions"]),
                         {"clevis", "crown", "payload", "tracker", "retract", "lensctl"})
        self.assertEqual(state["versions"]["crown"]["version"], "1.4.7-sim")
        self.assertEqual(len(state["cameras"]["cameras"]), 2)
        self.assertIn("max_vel", state["limits"])

    def test_state_lasers_array(self):
        # OrionLaserStates arrives at 1 Hz: two lasers, pointer and lightware.
        lasers = gt.wait_for(lambda: self.state()["lasers"], 3.0)
        self.assertIsInstance(lasers, list)
        self.assertEqual([laser["type"] for laser in lasers], ["pointer", "lightware"])
        self.assertIn("age_s", lasers[0])

    # --- what the daemon sends on connect ------------------------------------------------

    def test_connect_requests_versions_cameras_and_limits(self):
        first = self.sim.rx()[:8]
        self.assertEqual(sorted(e["name"] for e in first), sorted(CONNECT_REQUESTS))
        self.assertTrue(all(e["len"] == 0 for e in first))
        self.assertTrue(all(bytes.fromhex(e["hex"]) == gt.frame(e["id"]) for e in first))

    # --- Orion commands ------------------------------------------------------------------

    def test_geopoint(self):
        lat, lon = 45.7, -121.5
        reply, entry = self.send_and_find("geopoint", "geopoint_cmd", lat=lat, lon=lon,
                                          alt=TERRAIN_ALT_M)
        self.assertEqual(reply["sent"], [{"id": 213, "len": 21}])
        self.assertEqual(entry["len"], 21)
        self.assertAlmostEqual(entry["packet"]["lat"], lat, places=6)
        self.assertAlmostEqual(entry["packet"]["lon"], lon, places=6)
        self.assertAlmostEqual(entry["packet"]["alt"], TERRAIN_ALT_M, places=3)
        data = struct.pack(">iiihhhHB", gt.scaled(lat, 1e7), gt.scaled(lon, 1e7),
                           gt.scaled(TERRAIN_ALT_M, 1e4), 0, 0, 0, 0, 0)
        self.assertEqual(entry["hex"], gt.frame(213, data).hex())

        def on_target():
            t = self.state()["telemetry"]
            if t["mode"] != "geopoint" or not t["target"]:
                return None
            d = gt.ground_distance_m(t["target"]["lat"], t["target"]["lon"], lat, lon)
            return t if d < 30.0 else None
        t = gt.wait_for(on_target, 8.0, interval=0.1)
        self.assertTrue(t, "telemetry never showed mode geopoint looking at the point")
        self.assertAlmostEqual(t["target"]["alt"], TERRAIN_ALT_M, delta=3.0)

    def test_geopoint_options_and_velocity(self):
        _, entry = self.send_and_find("geopoint", "geopoint_cmd", lat=45.71, lon=-121.49,
                                      alt=250.5, vel_ned=[1.25, -2.5, 0.01],
                                      joystick_range_m=1200, stare=True, closure=True)
        data = struct.pack(">iiihhhHB", gt.scaled(45.71, 1e7), gt.scaled(-121.49, 1e7),
                           gt.scaled(250.5, 1e4), 125, -250, 1, 1200, 3)
        self.assertEqual(entry["hex"], gt.frame(213, data).hex())

    def test_path(self):
        points = [{"lat": 45.7, "lon": -121.5, "alt": 100.0},
                  {"lat": 45.705, "lon": -121.49, "alt": 120.0},
                  {"lat": 45.71, "lon": -121.48, "alt": 140.0}]
        reply, entry = self.send_and_find("path", "path", points=points, along_step_deg=10,
                                          cross_steps=3, cross_ratio=1.5)
        self.assertEqual(reply["sent"], [{"id": 215, "len": 5 + 9 * 3}])
        packet = entry["packet"]
        self.assertEqual(packet["num_cross_track_steps"], 3)
        self.assertAlmostEqual(packet["along_track_step_angle"], 10.0, delta=0.1)
        self.assertAlmostEqual(packet["cross_track_step_ratio"], 1.5, places=2)
        self.assertIs(packet["point_down"], False)
        for sent, point in zip(packet["points"], points):
            expected = gt.lla_to_ecef(point["lat"], point["lon"], point["alt"])
            for got, want in zip(sent["pos_ecef"], expected):
                self.assertAlmostEqual(got, want, delta=1.0)
        self.assertTrue(gt.wait_for(lambda: self.state()["telemetry"]["mode"] == "path", 3.0))

        # Lengths: 1 and 15 points, and "down" with none.
        for n in (1, 15):
            reply, entry = self.send_and_find("path", "path", points=points[:1] * n)
            self.assertEqual(reply["sent"], [{"id": 215, "len": 5 + 9 * n}], reply)
            self.assertEqual(entry["len"], 5 + 9 * n)
        reply, entry = self.send_and_find("path", "path", down=True)
        self.assertEqual(reply["sent"], [{"id": 215, "len": 5}])
        self.assertIs(entry["packet"]["point_down"], True)

    def test_position(self):
        reply, entry = self.send_and_find("position", "cmd", pan=30, tilt=-45,
                                          impulse_time_s=1.5)
        self.assertEqual(reply["sent"], [{"id": 1, "len": 7}])
        data = struct.pack(">hhBBB", gt.scaled(math.radians(30), 1000),
                           gt.scaled(math.radians(-45), 1000), MODE_POSITION, 0, 15)
        self.assertEqual(entry["hex"], gt.frame(1, data).hex())
        self.assertEqual(entry["packet"]["mode"], "position")
        self.assertIs(entry["packet"]["stabilized"], False)
        self.assertTrue(gt.wait_for(
            lambda: abs(self.state()["telemetry"]["pan"] - 30) < 0.5, 5.0))

    def test_rate(self):
        reply, entry = self.send_and_find("rate", "cmd", pan=5, tilt=-1)
        self.assertEqual(reply["sent"], [{"id": 1, "len": 7}])
        data = struct.pack(">hhBBB", gt.scaled(math.radians(5), 1000),
                           gt.scaled(math.radians(-1), 1000), MODE_RATE, 1, 0)
        self.assertEqual(entry["hex"], gt.frame(1, data).hex())
        _, entry = self.send_and_find("rate", "cmd", pan=0, tilt=0, stabilized=False)
        self.assertIs(entry["packet"]["stabilized"], False)

    def test_mode(self):
        for name in ("disabled", "ffc_auto", "ffc_manual", "calibration", "scene", "track",
                     "geo_rate"):
            _, entry = self.send_and_find("mode", "cmd", mode=name)
            self.assertEqual(entry["packet"]["mode"], name)
            self.assertEqual(entry["packet"]["target"], [0.0, 0.0])
        self.assertTrue(gt.wait_for(lambda: self.state()["telemetry"]["mode"] == "geo_rate", 3))

    def test_stare_ack(self):
        reply, entry = self.send_and_find("stare_ack", "stare_ack", system_time_ms=123456)
        self.assertEqual(reply["sent"], [{"id": 218, "len": 4}])
        self.assertEqual(entry["hex"], gt.frame(218, struct.pack(">I", 123456)).hex())

    def test_retract(self):
        for action, value in (("retract", 2), ("deploy", 1), ("disable", 0)):
            reply, entry = self.send_and_find("retract", "retract_cmd", action=action)
            self.assertEqual(reply["sent"], [{"id": 160, "len": 2}])
            self.assertEqual(entry["packet"]["cmd"], action)
            self.assertEqual(bytes.fromhex(entry["hex"])[4], value)
        self.assertTrue(gt.wait_for(
            lambda: (self.state()["retract"] or {}).get("cmd") == "disable", 3.0))

    def test_camera_switch_and_zoom(self):
        reply, entry = self.send_and_find("camera_switch", "camera_switch", index=1)
        self.assertEqual(reply["sent"], [{"id": 96, "len": 1}])
        self.assertEqual(entry["packet"], {"index": 1})
        self.assertTrue(gt.wait_for(
            lambda: self.state()["telemetry"]["pixel_width"] == 640, 3.0))
        self.send_and_find("camera_switch", "camera_switch", index=0)
        self.assertTrue(gt.wait_for(
            lambda: self.state()["telemetry"]["pixel_width"] == 1920, 3.0))

        reply, entry = self.send_and_find("camera_zoom", "camera_state", zoom=4.5)
        self.assertEqual(reply["sent"], [{"id": 97, "len": 5}])
        self.assertEqual(entry["packet"], {"zoom": 4.5, "focus": -1.0, "index": 0})
        _, entry = self.send_and_find("camera_zoom", "camera_state", zoom=2, focus=0.5,
                                      index=1)
        self.assertEqual(entry["packet"]["index"], 1)
        self.assertAlmostEqual(entry["packet"]["focus"], 0.5, places=2)

    def test_range(self):
        reply, entry = self.send_and_find("range", "range_data", range_m=512.5, max_age_ms=800,
                                          source="laser")
        self.assertEqual(reply["sent"], [{"id": 214, "len": 7}])
        self.assertEqual(entry["packet"]["source"], "laser")
        self.assertEqual(entry["packet"]["max_age_ms"], 800)
        self.assertAlmostEqual(entry["packet"]["range_m"], 512.5, places=1)

    def test_request_versions(self):
        start = len(self.sim.rx())
        reply = self.c.request("request", packet="versions")
        self.assertOk(reply)
        self.assertEqual(reply["sent"], [{"id": i, "len": 0} for i in (37, 40, 41, 44, 248, 249)])
        self.assertTrue(self.sim.wait_rx(gt.by_name("lensctl_version"), start=start))
        got = [e for e in self.sim.rx()[start:] if e["len"] == 0]
        self.assertEqual([e["name"] for e in got], VERSION_REQUESTS)
        versions = self.state()["versions"]
        self.assertEqual(set(versions), {"clevis", "crown", "payload", "tracker", "retract",
                                         "lensctl"})
        # Answered just now: fresh.
        self.assertTrue(gt.wait_for(lambda: self.state()["versions"]["crown"]["age_s"] < 1.0, 2))

    def test_request_one_packet(self):
        reply, entry = self.send_and_find("request", "network_settings",
                                          packet="network_settings")
        self.assertEqual(reply["sent"], [{"id": entry["id"], "len": 0}])
        self.assertTrue(gt.wait_for(lambda: self.state()["network_settings"], 3.0))
        self.assertRegex(self.state()["network_settings"]["ip"],
                         r"^\d+\.\d+\.\d+\.\d+$")

    def test_command_event_logged_per_request(self):
        reply = self.c.request("ping", id="log-me")
        self.assertOk(reply)
        entry = self.daemon.wait_log(lambda e: e.get("event") == "command" and
                                     e.get("id") == "log-me")
        self.assertTrue(entry)
        port = self.c.sock.getsockname()[1]
        self.assertEqual(entry["src"], "127.0.0.1:%d" % port)
        self.assertEqual((entry["cmd"], entry["ok"], entry["error"], entry["gimbal"]),
                         ("ping", True, None, None))
        self.assertRegex(entry["ts"], r"^\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d\.\d{6}Z$")


if __name__ == "__main__":
    gt.main()
