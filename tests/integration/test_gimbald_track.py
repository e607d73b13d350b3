"""Visual tracking end to end (contract section 20): a real gimbald starts a real gimbal-track
for a gimbal with `video.tracking`, fed the simulated Orion's H.264 by gimbal-sim --video.

The camera is pointed at the simulator's `farm` landmark (a 40 m disc of a colour found
nowhere else, with a dark ring); `project` says where it appears; `track` on that point
follows it: STATE `track` shows it tracking with a ground position near the landmark's true
one. `track_stop` ends it (track_end, stopped). A gimbal without video answers `track` with
`unavailable`. A gimbal-track killed with SIGKILL ends the running track (no_video) while
gimbald keeps answering, and is started again. A MAVLink ground station that acts as
QGroundControl does (SET_MESSAGE_INTERVAL for CAMERA_TRACKING_IMAGE_STATUS, then
CAMERA_TRACK_RECTANGLE) starts the track and sees its box and ground position in the
tracking status messages; STOP_TRACKING ends it. The stream carries no KLV (--no-video-klv)
and gimbald generates it: while a track runs, the generated sets carry it as a MISB ST 0903
VMTI set in tag 74 - read with st0903.py, written from the standard - and as tags 40-42.
"""

import math
import os
import signal
import struct
import time

import gimbaltest as gt
import mavlinktest as mt
import skipping
import st0601
import st0903

GIMBAL_TRACK = os.environ.get("GIMBAL_TRACK")

# sim::landmarks(): docs/simulator.md "Video".
FARM = {"lat": 45.697301, "lon": -121.480740, "alt": 414.6}


def metres_between(a, b):
    pa = gt.lla_to_ecef(a["lat"], a["lon"], a["alt"])
    pb = gt.lla_to_ecef(b["lat"], b["lon"], b["alt"])
    return math.dist(pa, pb)


def state(client, gimbal="main", keys=None):
    reply = client.request("state", gimbal=gimbal, keys=keys or ["track", "video", "telemetry"])
    return reply["state"] if reply and reply.get("ok") else None


class Tracking(gt.GimbaldTestCase):

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        if not GIMBAL_TRACK:
            skipping.need_for_file("GIMBAL_TRACK not set")
        cls.video_port = gt.free_port()
        cls.vehicle_port = gt.free_port()
        cls.sim = cls.start_class_sim("--video", "udp://127.0.0.1:%d" % cls.video_port,
                                      "--no-video-klv", "--speed", "0", want=("tcp", "video"))
        cls.daemon = cls.start_class_daemon({"gimbals": [
            dict(gt.orion_tcp("main", cls.sim.port),
                 video={"input": "udp://127.0.0.1:%d" % cls.video_port, "klv": "generate",
                        "klv_rate_hz": 10, "tracking": {"tracker": "kcf"}}),
            {"name": "nose", "protocol": "viewpro", "link": {"type": "sim"}}],
            "vehicle": {"source": {"type": "udp", "bind": "127.0.0.1",
                                   "port": cls.vehicle_port}},
            "mavlink": {"gimbal_manager": True, "system_id": 1}})

    def setUp(self):
        super().setUp()
        self.c = self.client(self.daemon)
        self.assertTrue(self.daemon.wait_log(lambda e: e.get("event") == "track_process_ready",
                                             timeout=20), "gimbal-track never said hello")
        s = gt.wait_for(lambda: (lambda s: s if s and s["video"] and s["video"]["connected"]
                                 and s["telemetry"] else None)(state(self.c)), 25, 0.2)
        self.assertTrue(s, "no video or telemetry: %s" % state(self.c))

    def look_at_farm(self):
        """Points the camera at the farm; returns its image position once it is near the
        centre."""
        self.assertOk(self.c.request("geopoint", gimbal="main", **FARM))

        at = gt.settled_projection(self.c, "main", FARM)
        self.assertTrue(at, "the farm never came to the centre of the picture")
        return at

    def wait_track(self, predicate, timeout=15):
        def check():
            s = state(self.c, keys=["track"])
            t = s and s["track"]
            return t if t and predicate(t) else None
        return gt.wait_for(check, timeout, 0.1)

    def track_ends(self, track_id, reason, timeout=10):
        return self.daemon.wait_log(lambda e: e.get("event") == "track_end" and
                                    e.get("id") == track_id and e.get("reason") == reason,
                                    timeout)

    def test_track_follows_the_farm_and_stops(self):
        at = self.look_at_farm()
        rx_start = len(self.sim.rx())
        reply = self.c.request("track", gimbal="main", x=at["x"], y=at["y"])
        self.assertOk(reply)
        t = reply["track"]
        self.assertEqual(t["state"], "tracking")
        for key in ("id", "box", "centre", "confidence", "ground", "velocity", "steer",
                    "frames", "lost_frames", "started_utc", "age_s"):
            self.assertIn(key, t)
        self.assertTrue(t["steer"])
        track_id = t["id"]

        located = self.wait_track(lambda t: t["state"] == "tracking" and t["ground"] and
                                  t["frames"] >= 10)
        self.assertTrue(located, "no located track: %s" % state(self.c, keys=["track"]))
        self.assertEqual(located["id"], track_id)
        self.assertGreater(located["confidence"], 0.4)
        self.assertLess(metres_between(located["ground"], FARM), 60, located)

        # Steering: once the filter knows the object's velocity (the hand-over, docs/tracking.md
        # "gimbald's side"), the Orion is sent geopoints on the object, about ten a second.
        steered = gt.wait_for(lambda: (lambda g: g if len(g) >= 5 else None)(
            [e for e in self.sim.rx()[rx_start:] if e.get("name") == "geopoint_cmd"]), 8, 0.1)
        self.assertTrue(steered, "too few steering geopoints")
        last = steered[-1]["packet"]
        self.assertLess(gt.ground_distance_m(last["lat"], last["lon"], FARM["lat"],
                                             FARM["lon"]), 60, last)

        stop = self.c.request("track_stop", gimbal="main")
        self.assertOk(stop)
        self.assertEqual(stop["stopped"], track_id)
        self.assertTrue(self.track_ends(track_id, "stopped"))
        self.assertIsNone(state(self.c, keys=["track"])["track"])
        again = self.c.request("track_stop", gimbal="main")
        self.assertOk(again)
        self.assertIsNone(again["stopped"])

    def generated_vmti(self):
        """(VMTI decoded by st0903.py, the ST 0601 set decoded by st0601.py, STATE track) of
        the latest generated set and the track of the moment; None without a tag 74."""
        reply = self.c.request("klv", gimbal="main")
        track = state(self.c, keys=["track"])["track"]
        if not (reply and reply.get("ok") and reply["klv_source"] == "generated"):
            return None
        packet = bytes.fromhex(reply["klv_hex"])
        value = st0903.tag74_of_st0601(packet)
        if value is None:
            return None
        status, reason, decoded = st0601.decode(packet)
        self.assertEqual(status, "ok", reason)
        return st0903.decode(value), decoded, track

    def test_generated_klv_carries_the_track_as_vmti(self):
        at = self.look_at_farm()
        reply = self.c.request("track", gimbal="main", x=at["x"], y=at["y"], steer=False)
        self.assertOk(reply)
        track_id = reply["track"]["id"]
        located = self.wait_track(lambda t: t["state"] == "tracking" and t["ground"] and
                                  t["frames"] >= 10)
        self.assertTrue(located, "no located track: %s" % state(self.c, keys=["track"]))
        video = state(self.c, keys=["video"])["video"]
        width, height = video["width"], video["height"]
        self.assertTrue(width and height, video)

        last = []

        def agreeing():
            got = self.generated_vmti()
            last[:] = [got]
            if not got or not got[2] or not got[2]["ground"]:
                return None
            vmti, klv, track = got
            if len(vmti["targets"]) != 1:
                return None
            target = vmti["targets"][0]
            # The pixel the centre falls in, rows and columns from 1 (ST 0903).
            column = (track["centre"]["x"] + 1) / 2 * width + 1
            row = (track["centre"]["y"] + 1) / 2 * height + 1
            centroid = target["centroid"]
            ground = track["ground"]
            location = target.get("location")
            near = (abs(centroid["column"] - column) <= 2 and abs(centroid["row"] - row) <= 2
                    and location is not None and
                    metres_between({"lat": location["lat"], "lon": location["lon"],
                                    "alt": location["hae"]}, ground) < 3 and
                    gt.ground_distance_m(klv["target_location_latitude"],
                                         klv["target_location_longitude"],
                                         ground["lat"], ground["lon"]) < 3)
            return got if near else None

        got = gt.wait_for(agreeing, 15, 0.2)
        self.assertTrue(got, "the generated VMTI never matched STATE track: %s" % last)
        vmti, klv, track = got
        self.assertEqual(vmti["version"], 5)
        self.assertEqual((vmti["frame_width"], vmti["frame_height"]), (width, height))
        self.assertEqual((vmti["total_targets"], vmti["reported_targets"]), (1, 1))
        target = vmti["targets"][0]
        self.assertEqual(target["id"], track_id)
        self.assertLessEqual(target["top_left"]["column"], target["centroid"]["column"])
        self.assertLessEqual(target["centroid"]["column"], target["bottom_right"]["column"])
        self.assertLessEqual(target["top_left"]["row"], target["centroid"]["row"])
        self.assertLessEqual(target["centroid"]["row"], target["bottom_right"]["row"])
        self.assertLessEqual(abs(target["confidence_level"] - 100 * track["confidence"]), 20)
        # gimbald's own decoding of its set agrees (STATE video.klv.vmti).
        ours = self.c.request("klv", gimbal="main")["klv"]["vmti"]
        self.assertEqual(ours["targets"][0]["id"], track_id)

        self.assertOk(self.c.request("track_stop", gimbal="main"))
        self.assertTrue(self.track_ends(track_id, "stopped"))
        self.assertTrue(gt.wait_for(lambda: self.generated_vmti() is None and
                                    self.c.request("klv", gimbal="main")["klv_source"] ==
                                    "generated", 5, 0.2), "tag 74 stayed after the track")

    def test_a_clients_steering_command_overrides_the_track(self):
        at = self.look_at_farm()
        reply = self.c.request("track", gimbal="main", x=at["x"], y=at["y"], steer=False)
        self.assertOk(reply)
        self.assertFalse(reply["track"]["steer"])
        self.assertOk(self.c.request("geopoint", gimbal="main", **FARM))
        self.assertTrue(self.track_ends(reply["track"]["id"], "overridden"))

    def test_mavlink_track_rectangle_as_qgroundcontrol_does(self):
        at = self.look_at_farm()
        gcs = mt.Peer(self.vehicle_port)
        self.addCleanup(gcs.close)
        camera = 100  # the Orion's camera component
        self.assertEqual(gcs.command(mt.MAV_CMD_REQUEST_MESSAGE, [259], target_component=camera),
                         0)
        info = gcs.wait(lambda m: m[3] == 259 and m[2] == camera)
        self.assertIsNotNone(info, "no CAMERA_INFORMATION")
        # flags: after time_boot_ms, firmware_version, focal_length and the sensor size.
        flags = struct.unpack_from("<I", info[4] + b"\0" * 240, 20)[0]
        for flag in (512, 1024, 2048):  # HAS_TRACKING_POINT, _RECTANGLE, _GEO_STATUS
            self.assertTrue(flags & flag, "flags %#x lack %d" % (flags, flag))
        # QGroundControl asks for the image status before it draws the box (10 Hz here).
        self.assertEqual(gcs.command(511, [275, 100000], target_component=camera), 0)
        x, y = (at["x"] + 1) / 2, (at["y"] + 1) / 2
        half = 0.04
        since = time.monotonic()
        self.assertEqual(gcs.command(2005, [x - half, y - half, x + half, y + half],
                                     target_component=camera), 0)
        located = self.wait_track(lambda t: t["state"] == "tracking" and t["ground"] and
                                  t["frames"] >= 10)
        self.assertTrue(located, "no located track: %s" % state(self.c, keys=["track"]))

        # CAMERA_TRACKING_IMAGE_STATUS: ACTIVE, mode RECTANGLE, the box about the farm.
        image = gcs.wait(lambda m: m[3] == 275 and m[2] == camera and
                         len(m[4]) >= 29 and m[4][28] == 1, 5, since)
        self.assertIsNotNone(image, "no ACTIVE CAMERA_TRACKING_IMAGE_STATUS")
        payload = image[4] + b"\0" * (32 - len(image[4]))
        px, py, _, tx, ty, bx, by, status, mode, data = struct.unpack_from("<7f3B", payload)
        self.assertEqual((status, mode, data), (1, 2, 4))
        self.assertAlmostEqual(px, x, delta=0.05)
        self.assertAlmostEqual(py, y, delta=0.05)
        self.assertTrue(tx < px < bx and ty < py < by, (tx, ty, px, py, bx, by))
        # CAMERA_TRACKING_GEO_STATUS: the object's ground position, near the farm.
        geo = gcs.wait(lambda m: m[3] == 276 and m[2] == camera and
                       struct.unpack_from("<i", m[4], 0)[0] != 0, 5, since)
        self.assertIsNotNone(geo, "no located CAMERA_TRACKING_GEO_STATUS")
        payload = geo[4] + b"\0" * (50 - len(geo[4]))
        lat, lon = struct.unpack_from("<ii", payload)
        status = payload[48]
        self.assertEqual(status, 1)
        self.assertLess(gt.ground_distance_m(lat / 1e7, lon / 1e7, FARM["lat"], FARM["lon"]), 60)

        # STOP_TRACKING: track_stop, then one IDLE status.
        since = time.monotonic()
        self.assertEqual(gcs.command(2010, [], target_component=camera), 0)
        self.assertTrue(self.track_ends(located["id"], "stopped"))
        idle = gcs.wait(lambda m: m[3] == 276 and m[2] == camera and
                        (m[4] + b"\0" * 50)[48] == 0, 3, since)
        self.assertIsNotNone(idle, "no IDLE CAMERA_TRACKING_GEO_STATUS after the stop")

    def test_bad_requests_change_nothing(self):
        self.assertError(self.c.request("track", gimbal="main"), "bad_request")
        self.assertError(self.c.request("track", gimbal="main", x=0, y=0, x0=0, y0=0, x1=1,
                                        y1=1), "bad_request")
        self.assertError(self.c.request("track", gimbal="main", x0=0.2, y0=0, x1=0.1, y1=0.5),
                         "bad_request")
        self.assertError(self.c.request("track", gimbal="main", x=2, y=0), "out_of_range")
        self.assertError(self.c.request("track", gimbal="main", x=0, y=0, colour="red"),
                         "bad_request")
        self.assertIsNone(state(self.c, keys=["track"])["track"])

    def test_track_without_video_is_unavailable(self):
        self.assertError(self.c.request("track", gimbal="nose", x=0, y=0), "unavailable")
        self.assertError(self.c.request("track", gimbal="nose", x=0, y=0, colour="red"),
                         "bad_request")
        self.assertIsNone(state(self.c, gimbal="nose", keys=["track"])["track"])

    def test_killed_gimbal_track_ends_the_track_and_restarts(self):
        at = self.look_at_farm()
        reply = self.c.request("track", gimbal="main", x=at["x"], y=at["y"])
        self.assertOk(reply)
        track_id = reply["track"]["id"]
        starts = self.daemon.events("track_process_start")
        pid = starts[-1]["pid"]
        os.kill(pid, signal.SIGKILL)
        self.assertTrue(self.track_ends(track_id, "no_video"), "the track did not end")
        self.assertOk(self.c.request("ping"))
        restarted = self.daemon.wait_log(lambda e: e.get("event") == "track_process_start" and
                                         e.get("pid") != pid, timeout=10)
        self.assertTrue(restarted, "gimbal-track was not started again")
        exits = self.daemon.events("track_process_exit")
        self.assertTrue(any(e.get("pid") == pid and e.get("signal") == signal.SIGKILL
                            for e in exits), exits)
        self.assertTrue(self.daemon.wait_log(
            lambda e: e.get("event") == "track_process_ready" and e.get("pid") != pid, 10))


if __name__ == "__main__":
    gt.main()
