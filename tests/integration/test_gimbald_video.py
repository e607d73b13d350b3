"""Video and KLV with the simulator's picture (contract section 17): gimbal-sim --video sends
the simulated Orion's H.264 + ST 0601 KLV in MPEG-TS to a real gimbald, which relays it.

Checked with tools nobody here wrote: ffprobe finds an h264 video stream and a klv data
stream on gimbald's output, GStreamer's tsdemux reads the KLV as meta/x-klv; KLV decoded by
gimbald's lib/klv (the `klv` command) and by the independent decoder st0601.py agrees with
STATE.
"""

import json
import math
import os
import socket
import sys
import threading
import time

import gimbaltest as gt
import skipping
import st0601
import videotest as vt
from test_gimbald_terrain import terrain_section, write_dem


def ecef_distance(lat1, lon1, alt1, lat2, lon2, alt2):
    a = gt.lla_to_ecef(lat1, lon1, alt1)
    b = gt.lla_to_ecef(lat2, lon2, alt2)
    return math.dist(a, b)


def angle_diff(a, b):
    return abs((a - b + 180.0) % 360.0 - 180.0)


def tag_order(data):
    """The tags of a set in wire order (st0601.py's BER readers)."""
    length, at = st0601.ber_length(data, 16)
    end = at + length
    tags = []
    while at < end:
        tag, at = st0601.ber_oid(data, at, end)
        size, at = st0601.ber_length(data[:end], at)
        tags.append(tag)
        at += size
    return tags


def mapping_step(name):
    """One wire step of an ST 0601 item with a linear map (st0601.py's table), else 0."""
    for fmt, mapping in [(f, m) for n, f, m in st0601.TABLE.values() if n == name]:
        if not mapping or not fmt.split()[0].lstrip("u").startswith("int"):
            return 0
        bits = int("".join(c for c in fmt.split()[0] if c.isdigit()))
        if mapping.startswith("+-"):
            return 2 * float(mapping[2:]) / (2 ** bits - 2)
        lo, hi = (float(x) for x in mapping.split(".."))
        return (hi - lo) / (2 ** bits - 1)
    return 0


def state(client, gimbal=None, keys=None):
    params = {}
    if gimbal:
        params["gimbal"] = gimbal
    if keys:
        params["keys"] = keys
    reply = client.request("state", **params)
    return reply["state"] if reply and reply.get("ok") else None


def wait_video(test, client, gimbal=None, source=None, timeout=25.0, telemetry=True):
    def ready():
        s = state(client, gimbal, ["video", "telemetry"])
        v = s and s.get("video")
        if v and v["connected"] and v["codec"] and v["klv"] and \
                (s.get("telemetry") or not telemetry) and \
                (source is None or v["klv_source"] == source):
            return s
        return None
    s = gt.wait_for(ready, timeout, interval=0.2)
    test.assertTrue(s, "video never came up: %s" % (state(client, gimbal, ["video"]),))
    return s


def check_tools(test):
    for tool in ("ffmpeg", "ffprobe", "gst-launch-1.0"):
        if not vt.have(tool):
            skipping.need(test, "%s is not installed" % tool)


class SimulatorVideo(gt.GimbaldTestCase):
    """gimbal-sim --video (stream KLV on) -> gimbald -> outputs."""

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.video_port = gt.free_port()
        cls.out_ffprobe = gt.free_port()
        cls.out_gst = gt.free_port()
        cls.collect_ts = vt.UdpCollector()
        cls.collect_klv = vt.UdpCollector()
        cls.addClassCleanup(cls.collect_ts.close)
        cls.addClassCleanup(cls.collect_klv.close)
        cls.sim = cls.start_class_sim("--video", "udp://127.0.0.1:%d" % cls.video_port,
                                      "--speed", "0", want=("tcp", "video"))
        cls.daemon = cls.start_class_daemon({"gimbals": [dict(
            gt.orion_tcp("main", cls.sim.port),
            video={"input": "udp://127.0.0.1:%d" % cls.video_port,
                   "outputs": ["udp://127.0.0.1:%d" % cls.out_ffprobe,
                               "udp://127.0.0.1:%d" % cls.out_gst,
                               "udp://127.0.0.1:%d" % cls.collect_ts.port,
                               "klv-udp://127.0.0.1:%d" % cls.collect_klv.port]})]})

    def setUp(self):
        super().setUp()
        self.c = self.client(self.daemon)
        self.s = wait_video(self, self.c, source="stream")

    def test_state_video_as_section_17(self):
        v = self.s["video"]
        self.assertEqual(set(v), {"input", "connected", "codec", "width", "height", "fps",
                                  "bitrate_bps", "klv_source", "klv", "klv_sets",
                                  "klv_bad_checksums", "klv_refused", "klv_vs_telemetry",
                                  "source", "foreign_datagrams", "dropped_datagrams",
                                  "dropped_units", "reconnects", "last_error"})
        self.assertEqual(v["input"], "udp://127.0.0.1:%d" % self.video_port)
        self.assertIs(v["connected"], True)
        self.assertEqual(v["codec"], "h264")
        self.assertEqual((v["width"], v["height"]), (640, 360))
        self.assertEqual(v["fps"], 15)
        self.assertGreater(v["bitrate_bps"], 10000)
        self.assertEqual(v["klv_source"], "stream")
        self.assertGreater(v["klv_sets"], 0)
        self.assertEqual(v["klv_bad_checksums"], 0)
        self.assertEqual(v["klv_refused"], 0)
        # The simulator is the one sender: pinned, nobody else, nothing dropped or failed.
        self.assertRegex(v["source"], r"^127\.0\.0\.1:\d+$")
        self.assertEqual((v["foreign_datagrams"], v["dropped_datagrams"], v["dropped_units"]),
                         (0, 0, 0))
        self.assertEqual((v["reconnects"], v["last_error"]), (0, None))
        self.assertLessEqual(len(json.dumps(v["klv"], separators=(",", ":"))), 8192)
        self.assertNotIn("truncated", v["klv"])
        self.assertIn("age_s", v["klv"])
        self.assertEqual(v["klv"]["uas_datalink_ls_version_number"], 19)
        # The simulator's KLV and gimbald's own telemetry describe the same camera: the
        # sensor within a few metres (the two are sampled up to a tick apart), the frame
        # centre compared (the simulated KLV's is on the rendered terrain).
        vs = gt.wait_for(lambda: state(self.c, keys=["video"])["video"]["klv_vs_telemetry"],
                         5.0)
        self.assertTrue(vs)
        self.assertLess(vs["sensor_m"], 5.0, vs)
        self.assertIsInstance(vs["frame_center_m"], (int, float))
        # The stream's sensor position agrees with gimbald's telemetry within metres.
        t = self.s["telemetry"]
        k = self.s["video"]["klv"]
        self.assertLess(ecef_distance(k["sensor_latitude"], k["sensor_longitude"],
                                      k["sensor_true_altitude"], t["lat"], t["lon"],
                                      t["alt_msl"]), 5.0)

    def test_ffprobe_finds_h264_and_klv_on_the_output(self):
        check_tools(self)
        streams = vt.ffprobe_streams("udp://127.0.0.1:%d" % self.out_ffprobe)
        kinds = {(s.get("codec_type"), s.get("codec_name")) for s in streams}
        self.assertIn(("video", "h264"), kinds, streams)
        self.assertIn(("data", "klv"), kinds, streams)
        video = [s for s in streams if s.get("codec_type") == "video"][0]
        self.assertEqual((video["width"], video["height"]), (640, 360))

    def test_gstreamer_tsdemux_reads_the_klv(self):
        check_tools(self)
        data = vt.gst_klv_buffers(self.out_gst)
        self.assertIsNotNone(data, "no meta/x-klv buffer from tsdemux")
        sets = vt.split_sets(data)
        self.assertTrue(sets, data[:64].hex())
        status, reason, items = st0601.decode(sets[0])
        self.assertEqual(status, "ok", reason)
        self.assertIn("sensor_latitude", items)

    def test_klv_udp_output_is_one_set_per_datagram(self):
        start = self.collect_klv.count()
        gt.wait_for(lambda: self.collect_klv.count() >= start + 10, 10.0)
        got = self.collect_klv.data(start)
        self.assertGreaterEqual(len(got), 10)
        for d in got:
            self.assertEqual(vt.split_sets(d), [d])
            status, reason, _ = st0601.decode(d)
            self.assertEqual(status, "ok", reason)

    def test_relayed_ts_keeps_video_and_klv_with_rising_pts(self):
        start = self.collect_ts.count()
        gt.wait_for(lambda: self.collect_ts.count() >= start + 300, 15.0)
        reader = vt.TsReader()
        for d in self.collect_ts.data(start):
            reader.push(d)
        reader.flush()
        self.assertEqual(reader.video_type, 0x1B)
        self.assertGreater(reader.video_units, 10)
        self.assertGreater(len(reader.klv), 10)
        pts = [p for p, _ in reader.klv]
        self.assertTrue(all(p is not None for p in pts))
        self.assertEqual(pts, sorted(pts), "KLV PTS went backwards")
        for _, payload in reader.klv[-5:]:
            for s in vt.split_sets(payload):
                self.assertEqual(st0601.decode(s)[0], "ok")

    def test_klv_command_gives_the_whole_set_both_decoders_agree(self):
        reply = self.c.request("klv")
        self.assertOk(reply)
        self.assertEqual(reply["klv_source"], "stream")
        raw = bytes.fromhex(reply["klv_hex"])
        self.assertEqual(raw[:16], vt.UAS_LS_KEY)
        status, reason, items = st0601.decode(raw)
        self.assertEqual(status, "ok", reason)
        self.assertEqual(len(vt.split_sets(raw)), 1)
        mine = reply["klv"]
        for name, value in items.items():
            if isinstance(value, float):
                # lib/klv prints the fewest digits that keep the wire integer: within a step.
                self.assertLessEqual(abs(mine[name] - value), mapping_step(name) + 1e-9, name)
            else:
                self.assertEqual(mine[name], value, name)
        self.assertError(self.c.request("klv", bogus=1), "bad_request")


class GeneratedKlv(gt.GimbaldTestCase):
    """The stream carries no KLV (gimbal-sim --no-video-klv): gimbald generates ST 0601 from
    STATE, for an Orion and for a Viewpro whose video comes from elsewhere. With a `terrain`
    section (the simulator's own DEM), so the Orion's frame centre and corners are where the
    line of sight meets the terrain (`telemetry.ground`, `footprint_surface` terrain)."""

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.video_port = gt.free_port()
        cls.nose_port = gt.free_port()
        cls.sim = cls.start_class_sim("--video", "udp://127.0.0.1:%d" % cls.video_port,
                                      "--no-video-klv", "--speed", "0", want=("tcp", "video"))
        dem = write_dem(cls.class_workdir)
        cls.daemon = cls.start_class_daemon({"gimbals": [
            dict(gt.orion_tcp("main", cls.sim.port),
                 video={"input": "udp://127.0.0.1:%d" % cls.video_port, "klv_rate_hz": 10,
                        "mission_id": "M1"}),
            {"name": "nose", "protocol": "viewpro", "link": {"type": "sim"},
             "video": {"input": "udp://127.0.0.1:%d" % cls.nose_port}}],
            "terrain": terrain_section(dem)})
        # The Viewpro's picture: a crafted TS without KLV, 15 frames a second.
        cls.stop_feed = threading.Event()
        units = vt.h264_access_units(cls.class_workdir)
        cls.feeder = threading.Thread(target=feed_forever,
                                      args=(units, cls.nose_port, cls.stop_feed), daemon=True)
        cls.feeder.start()
        cls.addClassCleanup(cls.stop_feed.set)

    def setUp(self):
        super().setUp()
        self.c = self.client(self.daemon)

    def test_orion_generated_klv_agrees_with_state(self):
        wait_video(self, self.c, "main", source="generated")
        # Any laser range of another test has expired: the range is calculated.
        self.assertTrue(gt.wait_for(lambda: not self.c.request("klv", gimbal="main")["klv"][
            "generic_flag_data"]["slant_range"], 10.0))
        # The KLV of the moment: the klv command, then STATE (the aircraft hovers and the
        # gimbal holds still, so STATE does not move in between).
        reply = self.c.request("klv", gimbal="main")
        self.assertOk(reply)
        s = state(self.c, "main")
        t = s["telemetry"]
        raw = bytes.fromhex(reply["klv_hex"])
        status, reason, py = st0601.decode(raw)
        self.assertEqual(status, "ok", reason)
        mine = reply["klv"]
        for decoded in (py, mine):  # both decoders, the same checks
            self.assertEqual(decoded["mission_id"], "M1")
            self.assertLess(ecef_distance(decoded["sensor_latitude"],
                                          decoded["sensor_longitude"],
                                          decoded["sensor_true_altitude"],
                                          t["lat"], t["lon"], t["alt_msl"]), 0.5)
            # Angles within one step of their mapping (plus STATE's 1e-4 degree printing).
            self.assertLessEqual(angle_diff(decoded["platform_heading_angle"], t["yaw"]),
                                 360 / 65535 + 1e-4)
            self.assertLessEqual(abs(decoded["platform_pitch_angle"] - t["pitch"]),
                                 40 / 65534 + 1e-4)
            self.assertLessEqual(abs(decoded["platform_roll_angle"] - t["roll"]),
                                 100 / 65534 + 1e-4)
            self.assertLessEqual(angle_diff(decoded["sensor_relative_azimuth_angle"], t["pan"]),
                                 360 / 4294967295 + 1e-4)
            self.assertLessEqual(abs(decoded["sensor_relative_elevation_angle"] - t["tilt"]),
                                 360 / 4294967294 + 1e-4)
            self.assertLessEqual(abs(decoded["sensor_horizontal_field_of_view"] - t["hfov"]),
                                 180 / 65535 + 1e-4)
            self.assertLessEqual(abs(decoded["sensor_vertical_field_of_view"] - t["vfov"]),
                                 180 / 65535 + 1e-4)
            # Frame centre: on `telemetry.ground`, the terrain's hit (not the gimbal's own
            # target); elevations above mean sea level.
            self.assertEqual(t["ground"]["surface"], "terrain")
            self.assertEqual(t["footprint_surface"], "terrain")
            ground = t["ground"]
            n = t["alt"] - t["alt_msl"]
            self.assertLess(ecef_distance(decoded["frame_center_latitude"],
                                          decoded["frame_center_longitude"],
                                          decoded["frame_center_elevation"],
                                          ground["lat"], ground["lon"], ground["alt"] - n), 1.0)
            self.assertLess(ecef_distance(decoded["target_location_latitude"],
                                          decoded["target_location_longitude"],
                                          decoded["target_location_elevation"],
                                          t["target"]["lat"], t["target"]["lon"],
                                          t["target"]["alt"] - n), 1.0)
            distance = ecef_distance(t["lat"], t["lon"], t["alt_msl"], ground["lat"],
                                     ground["lon"], ground["alt"] - n)
            self.assertLess(abs(decoded["slant_range"] - distance), 1.0)
            self.assertIs(decoded["generic_flag_data"]["slant_range"], False)
        # Contract section 17's tags, 2 first and the checksum last.
        tags = tag_order(raw)
        self.assertEqual(tags[0], 2)
        self.assertEqual(tags[-1], 1)
        self.assertEqual(tags[-2], 65)
        corners = set(range(26, 34)) if 26 in tags else set(range(82, 90))
        for tag in {3, 5, 6, 7, 13, 14, 15, 16, 17, 18, 19, 20, 21, 23, 24, 25, 40, 41, 42,
                    47} | corners:
            self.assertIn(tag, tags)
        self.assertEqual(tags, [x for x in [2, 3, 5, 6, 7, 13, 14, 15, 16, 17, 18, 19, 20,
                                            21, 23, 24, 25, *sorted(corners), 40, 41, 42, 47,
                                            65, 1] if x in tags])
        # Corners: the footprint STATE shows.
        fp = t["footprint"]
        if 26 in tags:
            lat1 = mine["frame_center_latitude"] + mine["offset_corner_latitude_point_1"]
            lon1 = mine["frame_center_longitude"] + mine["offset_corner_longitude_point_1"]
        else:
            lat1, lon1 = mine["corner_latitude_point_1_full"], mine["corner_longitude_point_1_full"]
        self.assertLess(abs(lat1 - fp[0]["lat"]), 2e-6)
        self.assertLess(abs(lon1 - fp[0]["lon"]), 2e-6)
        # STATE shows the same latest set.
        self.assertEqual(s["video"]["klv_source"], "generated")
        self.assertGreater(s["video"]["klv_sets"], 0)
        self.assertIsNone(s["video"]["klv_vs_telemetry"])

    def test_generation_runs_at_klv_rate_hz(self):
        wait_video(self, self.c, "main", source="generated")
        first = state(self.c, "main", ["video"])["video"]["klv_sets"]
        time.sleep(3.0)
        n = state(self.c, "main", ["video"])["video"]["klv_sets"] - first
        self.assertGreaterEqual(n, 20)   # 10 Hz for 3 s, on a busy machine
        self.assertLessEqual(n, 33)

    def test_laser_range_is_the_slant_range(self):
        wait_video(self, self.c, "main", source="generated")
        self.assertOk(self.c.request("range", gimbal="main", range_m=1234.5, max_age_ms=3000,
                                     source="laser"))

        def measured():
            k = self.c.request("klv", gimbal="main")["klv"]
            return k if k["generic_flag_data"]["slant_range"] else None
        k = gt.wait_for(measured, 5.0)
        self.assertTrue(k, "the laser range never reached the KLV")
        self.assertAlmostEqual(k["slant_range"], 1234.5, delta=1.0)
        self.assertIs(k["generic_flag_data"]["laser_range"], True)

    def test_viewpro_generated_klv_from_its_output(self):
        wait_video(self, self.c, "nose", source="generated", telemetry=False)
        reply = self.c.request("klv", gimbal="nose")
        self.assertOk(reply)
        s = state(self.c, "nose")
        out = s["output"]
        status, reason, py = st0601.decode(bytes.fromhex(reply["klv_hex"]))
        self.assertEqual(status, "ok", reason)
        for decoded in (py, reply["klv"]):
            self.assertLess(ecef_distance(decoded["sensor_latitude"], decoded["sensor_longitude"],
                                          decoded["sensor_true_altitude"], out["uav"]["lat"],
                                          out["uav"]["lon"], out["uav"]["alt_msl"]), 0.5)
            self.assertLessEqual(angle_diff(decoded["platform_heading_angle"],
                                            out["uav"]["yaw"]), 360 / 65535 + 1e-3)
            if out.get("target"):
                self.assertLess(ecef_distance(decoded["frame_center_latitude"],
                                              decoded["frame_center_longitude"], 0,
                                              out["target"]["lat"], out["target"]["lon"], 0),
                                1.0)
            # No field of view on the Viewpro's wire: tags 16 and 17 are left out.
            self.assertNotIn("sensor_horizontal_field_of_view", decoded)
        self.assertEqual(s["video"]["codec"], "h264")
        self.assertEqual((s["video"]["width"], s["video"]["height"]), (320, 240))


def feed_forever(units, port, stop, fps=15):
    """Sends `units` as TS over UDP, looping with rising timestamps, until `stop` is set."""
    sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    w = vt.TsWriter(klv=False)
    pts = vt.PTS_HZ
    i = 0
    next_t = time.monotonic()
    while not stop.is_set():
        ts = (w.psi() if i % fps == 0 else b"") + w.video(units[i % len(units)], pts)
        for d in vt.datagrams(ts):
            sock.sendto(d, ("127.0.0.1", port))
        i += 1
        pts += vt.PTS_HZ // fps
        next_t += 1.0 / fps
        time.sleep(max(0.0, next_t - time.monotonic()))
    sock.close()


if __name__ == "__main__":
    gt.main()
