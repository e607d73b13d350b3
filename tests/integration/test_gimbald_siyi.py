#!/usr/bin/env python3
"""SIYI gimbal cameras end to end (docs/siyi.md): a real gimbald talks to `gimbal-sim
--protocol siyi` over UDP (the camera's transport) and over a pseudo-terminal (its TTL serial
port, 115200 8N1), with the aircraft's MAVLink on its vehicle port.

Checked: STATE `siyi` (hardware id and the model it names, firmware, attitude, zoom range)
and the shared `telemetry` (pan/tilt in gimbald's frame, the model's field of view, the
camera's position from the vehicle); `position` reaching the camera as 0x0E with SIYI's
left-positive yaw (the simulator's rx log); `camera_zoom` as 0x0F; the vehicle feed's 0x22
at 20 Hz; and a `geopoint` aimed by gimbald from the aircraft's position. The simulated
camera's video (gimbal-sim --video): the picture it renders from the position gimbald sends it
(0x3E), its KLV agreeing with gimbald's telemetry.
"""

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
AIRCRAFT = (45.7, -121.5, 500.0)  # level, heading north, MSL


class Aircraft:
    """HEARTBEAT (1 Hz), ATTITUDE and GLOBAL_POSITION_INT (20 Hz) to gimbald's vehicle port."""

    def __init__(self, port, position=AIRCRAFT):
        self.position = position
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.port = port
        self.seq = 0
        self.running = True
        self.start = time.monotonic()
        self.thread = threading.Thread(target=self.run, daemon=True)
        self.thread.start()

    def send(self, msgid, payload):
        self.sock.sendto(mt.frame(msgid, payload, 1, 1, self.seq), ("127.0.0.1", self.port))
        self.seq += 1

    def run(self):
        n = 0
        lat, lon, alt = self.position
        while self.running:
            ms = int((time.monotonic() - self.start) * 1000) & 0xFFFFFFFF
            if n % 20 == 0:
                self.send(HEARTBEAT, struct.pack("<IBBBBB", 0, 1, 3, 128, 4, 3))
            self.send(ATTITUDE, struct.pack("<Iffffff", ms, 0, 0, 0, 0, 0, 0))
            self.send(GLOBAL_POSITION_INT,
                      struct.pack("<IiiiihhhH", ms, int(round(lat * 1e7)), int(round(lon * 1e7)),
                                  int(round(alt * 1000)), int(alt * 1000), 0, 0, 0, 0))
            n += 1
            time.sleep(0.05)

    def close(self):
        self.running = False
        self.thread.join(2)
        self.sock.close()


class SiyiTest(gt.GimbaldTestCase):
    def state(self, client):
        reply = client.request("state", gimbal="cam")
        self.assertOk(reply)
        return reply["state"]

    def wait_state(self, client, predicate, what, timeout=gt.START_TIMEOUT_S):
        found = gt.wait_for(lambda: (lambda s: s if predicate(s) else None)(self.state(client)),
                            timeout, interval=0.1)
        self.assertTrue(found, "STATE never showed " + what)
        return found

    def start(self, link, sim, siyi=None, video=None, position=AIRCRAFT):
        vport = gt.free_port()
        gimbal = {"name": "cam", "protocol": "siyi", "link": link}
        gimbal["siyi"] = siyi or {"geoid_undulation_m": 0}
        if video:
            gimbal["video"] = video
        daemon = self.start_daemon({
            "gimbals": [gimbal],
            "vehicle": {"source": {"type": "udp", "bind": "127.0.0.1", "port": vport}},
        })
        client = self.client(daemon)
        aircraft = Aircraft(vport, position)
        self.addCleanup(aircraft.close)
        return daemon, client

    def check_camera(self, sim, client):
        s = self.wait_state(client, lambda s: s["siyi"]["model"] is not None and
                            s["telemetry"] and s["telemetry"]["lat"] is not None,
                            "the camera's model and a telemetry position")
        self.assertEqual(s["protocol"], "siyi")
        self.assertEqual(s["siyi"]["model"], "ZR10")
        self.assertTrue(s["siyi"]["hardware_id"].startswith("6B"))
        self.assertIsNotNone(s["siyi"]["firmware"])
        # Contract section 22's keys of STATE siyi, the attitude as the camera reports it.
        for key in ("model", "firmware", "hardware_id", "attitude", "attitude_rate", "zoom",
                    "zoom_max", "recording", "laser_range_m", "age_s"):
            self.assertIn(key, s["siyi"])
        self.assertEqual(set(s["siyi"]["firmware"]), {"camera", "gimbal", "zoom"})
        self.assertEqual(set(s["siyi"]["attitude"]), {"yaw", "pitch", "roll"})
        self.assertEqual(set(s["siyi"]["attitude_rate"]), {"yaw", "pitch", "roll"})
        self.assertAlmostEqual(s["siyi"]["attitude"]["yaw"], -s["telemetry"]["pan"], delta=0.5)
        self.assertIn(s["siyi"]["recording"], (True, False))
        self.assertFalse(s["stale"])
        self.assertEqual(s["vehicle"]["feed"]["kind"], "aircraft_attitude")
        t = s["telemetry"]
        self.assertAlmostEqual(t["lat"], AIRCRAFT[0], places=6)
        for key in ("pan", "tilt", "hfov", "vfov", "target", "footprint", "ground"):
            self.assertIn(key, t)

        # position: 0x0E with SIYI's yaw (left positive), and the camera gets there.
        start = len(sim.rx())
        self.assertOk(client.request("position", gimbal="cam", pan=30, tilt=-45))
        entry = sim.wait_rx(lambda e: e["kind"] == "set_gimbal_attitude", start=start)
        self.assertIsNotNone(entry, "no 0x0E")
        self.assertAlmostEqual(entry["message"]["yaw"], -30, places=3)
        self.assertAlmostEqual(entry["message"]["pitch"], -45, places=3)
        self.wait_state(client, lambda s: abs(s["telemetry"]["pan"] - 30) < 0.5 and
                        abs(s["telemetry"]["tilt"] + 45) < 0.5, "pan 30 tilt -45")

        # center: 0x08 one-key centring, and the camera comes back to 0 0.
        start = len(sim.rx())
        self.assertOk(client.request("center", gimbal="cam"))
        entry = sim.wait_rx(lambda e: e["kind"] == "center", start=start)
        self.assertIsNotNone(entry, "no 0x08")
        self.assertEqual(entry["message"]["position"], "one_key_center")
        self.wait_state(client, lambda s: abs(s["telemetry"]["pan"]) < 0.5 and
                        abs(s["telemetry"]["tilt"]) < 0.5, "centred")
        self.assertError(client.request("center", gimbal="cam", pan=0), "bad_request")

        # STATE restricted to the protocol's own key, which its registry entry declares.
        reply = client.request("state", gimbal="cam", keys=["siyi"])
        self.assertOk(reply)
        self.assertEqual(set(reply["state"]), {"protocol", "link", "stale", "siyi"})

        # camera_zoom: 0x0F; beyond the ZR10's 30x it is out_of_range.
        self.assertOk(client.request("camera_zoom", gimbal="cam", zoom=2.5))
        self.wait_state(client, lambda s: s["siyi"]["zoom"] == 2.5, "zoom 2.5")
        self.assertError(client.request("camera_zoom", gimbal="cam", zoom=31), "out_of_range")

        # The vehicle feed: 0x22 at about 20 Hz.
        time.sleep(1.0)
        feed = [e for e in sim.rx() if e["kind"] == "aircraft_attitude"]
        self.assertGreater(len(feed), 20)
        span = feed[-1]["t"] - feed[-21]["t"]
        self.assertTrue(0.5 <= span <= 2.0, "20 0x22 frames in %.3f s" % span)

        # geopoint: 778 m east of the aircraft, 500 m below: pan 90, tilt about -32.7.
        self.assertOk(client.request("geopoint", gimbal="cam", lat=AIRCRAFT[0], lon=-121.49,
                                     alt=0))
        want_tilt = -math.degrees(math.atan2(500.0, 778.0))
        self.wait_state(client, lambda s: abs(s["telemetry"]["pan"] - 90) < 1 and
                        abs(s["telemetry"]["tilt"] - want_tilt) < 1, "pan 90 on the geopoint")

    def test_udp(self):
        sim = self.start_sim("--protocol", "siyi", "--model", "zr10", "--udp", "0", tcp=False,
                             want=("udp",))
        port = int(sim.endpoints["udp"].rsplit(":", 1)[1])
        _, client = self.start({"type": "udp", "host": "127.0.0.1", "port": port,
                                "local_port": None}, sim)
        self.check_camera(sim, client)
        self.assertEqual(self.state(client)["link"]["type"], "udp")

    def test_udp_camera_comes_up_late(self):
        # No vehicle feed, and nothing listening when gimbald sends its first requests: the
        # session's poll asks again until the camera answers and streams.
        port = gt.free_port(socket.SOCK_DGRAM)
        daemon = self.start_daemon({"gimbals": [{
            "name": "cam", "protocol": "siyi", "siyi": {"geoid_undulation_m": 0},
            "link": {"type": "udp", "host": "127.0.0.1", "port": port, "local_port": None}}]})
        client = self.client(daemon)
        time.sleep(1.5)
        self.assertTrue(self.state(client)["stale"])
        self.start_sim("--protocol", "siyi", "--model", "zr10", "--udp", str(port), tcp=False,
                       want=("udp",))
        s = self.wait_state(client, lambda s: not s["stale"] and s["siyi"]["model"] is not None,
                            "the late camera's attitude stream and model")
        self.assertEqual(s["siyi"]["model"], "ZR10")

    def test_udp_video(self):
        # The simulated camera renders what it sees from where gimbald says the aircraft is
        # (1450 m MSL, above the simulator's terrain; not the simulator's default place); its
        # stream's KLV and gimbald's telemetry describe the same camera.
        video_port = gt.free_port(socket.SOCK_DGRAM)
        sim = self.start_sim("--protocol", "siyi", "--model", "zr10", "--udp", "0",
                             "--video", "udp://127.0.0.1:%d" % video_port, tcp=False,
                             want=("udp", "video"))
        port = int(sim.endpoints["udp"].rsplit(":", 1)[1])
        position = (45.705, -121.495, 1450.0)
        _, client = self.start({"type": "udp", "host": "127.0.0.1", "port": port,
                                "local_port": None}, sim,
                               video={"input": "udp://127.0.0.1:%d" % video_port},
                               position=position)
        s = self.wait_state(client, lambda s: s["video"]["connected"] and
                            s["video"]["klv_source"] == "stream", "the camera's video and KLV",
                            timeout=25.0)
        self.assertEqual(s["video"]["codec"], "h264")
        # Aim somewhere: the sim's yaw and pitch reach the picture as the KLV's angles.
        self.assertOk(client.request("position", gimbal="cam", pan=-60, tilt=-35))
        self.wait_state(client, lambda s: abs(s["telemetry"]["pan"] + 60) < 0.5 and
                        abs(s["telemetry"]["tilt"] + 35) < 0.5, "pan -60 tilt -35")

        def agreed():
            st = self.state(client)
            k = st["video"]["klv"]
            if abs(k.get("sensor_relative_azimuth_angle", 0) - 300) > 1:
                return None
            return st
        s = gt.wait_for(agreed, 10.0, interval=0.2)
        self.assertTrue(s, "the KLV never showed the camera at pan -60: %s" %
                        self.state(client)["video"]["klv"])
        k = s["video"]["klv"]
        t = s["telemetry"]
        self.assertAlmostEqual(k["sensor_latitude"], position[0], places=5)
        self.assertAlmostEqual(k["sensor_longitude"], position[1], places=5)
        self.assertAlmostEqual(k["sensor_true_altitude"], position[2], delta=1.0)
        self.assertAlmostEqual(k["sensor_relative_elevation_angle"], -35, delta=0.5)
        self.assertAlmostEqual(k["sensor_horizontal_field_of_view"], t["hfov"], delta=0.1)
        self.assertAlmostEqual(k["platform_heading_angle"] % 360, 0, delta=0.1)
        vs = gt.wait_for(lambda: self.state(client)["video"]["klv_vs_telemetry"], 5.0)
        self.assertTrue(vs)
        self.assertLess(vs["sensor_m"], 5.0, vs)
        # The stream's frame centre is on the rendered terrain, gimbald's on flat ground.
        self.assertIsInstance(vs["frame_center_m"], (int, float))

    def test_sim_link_video(self):
        # gimbald --sim siyi's in-process camera (a `sim` link) with a video section sends its
        # rendered picture to the video's input, as gimbal-sim --video does.
        video_port = gt.free_port(socket.SOCK_DGRAM)
        position = (45.705, -121.495, 1450.0)
        daemon, client = self.start({"type": "sim"}, None,
                                    video={"input": "udp://127.0.0.1:%d" % video_port},
                                    position=position)
        s = self.wait_state(client, lambda s: s["video"]["connected"] and
                            s["video"]["klv_source"] == "stream" and
                            abs(s["video"]["klv"]["sensor_latitude"] - position[0]) < 1e-5,
                            "the simulated camera's video from the aircraft's place",
                            timeout=25.0)
        self.assertEqual(s["video"]["codec"], "h264")
        self.assertEqual(s["siyi"]["model"], "ZT30")
        self.assertTrue(daemon.events("sim_video"), "no sim_video log line")
        self.assertFalse(daemon.events("sim_video_off"))

    def test_pty(self):
        device = os.path.join(self.workdir, "ttySIYI")
        sim = self.start_sim("--protocol", "siyi", "--model", "zr10", tcp=False, pty_link=device)
        _, client = self.start({"type": "serial", "device": device, "baud": 115200,
                                "reconnect_min_s": 0.2, "reconnect_max_s": 1}, sim)
        self.check_camera(sim, client)
        self.assertEqual(self.state(client)["link"]["type"], "serial")


if __name__ == "__main__":
    gt.main()
