#!/usr/bin/env python3
"""Terrain and image geometry end to end (contract sections 15 and 16): the real gimbald with
a `terrain` section naming a GeoTIFF that `gimbal-sim --write-dem` wrote through GDAL, two
real gimbal-sim Orions (one hovering, so its camera holds still; one flying its circle) and
an in-process Viewpro. The simulated Orion's own target meets the same terrain, so gimbald's
`ground` can be checked against it; the simulator's rx log shows what reached the gimbal.
"""

import json
import math
import random
import subprocess
import sys
import time

import gimbaltest as gt

# 1 % of the 1920-pixel image width (contract section 16 / issue 19).
SETTLE_PX = 19.2


def distance_m(a, b):
    """Straight-line distance between two {"lat","lon","alt"} points, metres."""
    pa = gt.lla_to_ecef(a["lat"], a["lon"], a["alt"])
    pb = gt.lla_to_ecef(b["lat"], b["lon"], b["alt"])
    return math.dist(pa, pb)


def write_dem(workdir):
    path = workdir + "/sim-dem.tif"
    result = gt.run([gt.GIMBAL_SIM, "--write-dem", path])
    if result.returncode != 0:
        raise RuntimeError("gimbal-sim --write-dem failed: %s" % result.stderr)
    return path


def terrain_section(dem):
    return {"files": [dem], "geoid": "none", "cache_mb": 16}


class Terrain(gt.GimbaldTestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.dem = write_dem(cls.class_workdir)
        cls.hover = cls.start_class_sim("--speed", "0")
        cls.demo = cls.start_class_sim()
        cls.daemon = cls.start_class_daemon({
            "gimbals": [gt.orion_tcp("hover", cls.hover.port), gt.orion_tcp("demo", cls.demo.port),
                        {"name": "nose", "protocol": "viewpro", "link": {"type": "sim"}}],
            "terrain": terrain_section(cls.dem)})

    def setUp(self):
        super().setUp()
        self.c = self.client(self.daemon)
        self.wait_connected(self.c, "hover")
        self.wait_connected(self.c, "demo")

    # --- helpers -----------------------------------------------------------------------

    def ask(self, cmd, gimbal="hover", **params):
        if gimbal:
            params["gimbal"] = gimbal
        return self.c.request(cmd, **params)

    def ok(self, cmd, gimbal="hover", **params):
        reply = self.ask(cmd, gimbal, **params)
        self.assertOk(reply)
        return reply

    def telemetry(self, gimbal="hover"):
        return self.ok("state", gimbal, keys=["telemetry"])["state"]["telemetry"]

    def aim(self, pan, tilt):
        """Points the hovering gimbal at pan/tilt and waits until its camera holds still."""
        self.ok("position", pan=pan, tilt=tilt)
        previous = {}

        def still():
            t = self.telemetry()
            pose = (t["pan"], t["tilt"], t["mode"])
            # OrionCmd carries milliradians: within 0.06 degrees of what was asked.
            settled = (t["mode"] == "position" and gt.angle_diff_deg(t["pan"], pan) < 0.06 and
                       abs(t["tilt"] - tilt) < 0.06 and previous.get("pose") == pose)
            previous["pose"] = pose
            return t if settled else None
        t = gt.wait_for(still, 8.0, interval=0.15)
        self.assertTrue(t, "the hovering gimbal never settled at pan %s tilt %s" % (pan, tilt))
        return t

    def sent(self, start):
        """Commands (not requests) that reached the hovering simulator since rx index start."""
        return [e for e in self.hover.rx()[start:] if e["len"] > 0]

    # --- STATE -------------------------------------------------------------------------

    def test_ground_meets_terrain_beside_the_gimbals_own_target(self):
        # The flying gimbal: each STATE's ground (gimbald on the GeoTIFF) and target (the
        # simulator on its analytic terrain) come from the same telemetry packet.
        worst = 0.0
        for _ in range(20):
            t = self.telemetry("demo")
            self.assertEqual(t["footprint_surface"], "terrain")
            self.assertEqual(t["ground"]["surface"], "terrain")
            self.assertEqual(len(t["footprint"]), 4)
            worst = max(worst, distance_m(t["ground"], t["target"]))
            gt.wait_for(lambda: False, 0.12)
        sys.stderr.write("ground vs the simulator's target, 20 packets in flight: worst %.3f m\n"
                         % worst)
        self.assertLess(worst, 3.0, "ground and target apart by %.2f m" % worst)
        # The hovering one, looking all round and steeper.
        for pan, tilt in ((0, -30), (90, -25), (180, -45), (-90, -60)):
            t = self.aim(pan, tilt)
            self.assertLess(distance_m(t["ground"], t["target"]), 3.0, (pan, tilt, t))
            # range_m is the slant range from the gimbal.
            gimbal = {"lat": t["lat"], "lon": t["lon"], "alt": t["alt"]}
            self.assertAlmostEqual(t["ground"]["range_m"], distance_m(gimbal, t["ground"]),
                                   delta=0.01)

    def test_corners_from_locate_are_the_footprint(self):
        t = self.aim(30, -35)
        self.assertEqual(t["footprint_surface"], "terrain")
        for (x, y), corner in zip(((-1, -1), (1, -1), (1, 1), (-1, 1)), t["footprint"]):
            reply = self.ok("locate", x=x, y=y)
            self.assertEqual(reply["surface"], "terrain")
            self.assertLess(gt.ground_distance_m(reply["lat"], reply["lon"], corner["lat"],
                                                 corner["lon"]), 0.5, (x, y, reply, corner))
        centre = self.ok("locate", x=0, y=0)
        self.assertLess(distance_m(centre, t["ground"]), 0.5)
        self.assertAlmostEqual(centre["range_m"], t["ground"]["range_m"], delta=0.5)
        # Pixels: the image's centre pixel and its corners are the same rays.
        by_pixel = self.ok("locate", px=t["pixel_width"] / 2, py=t["pixel_height"] / 2)
        self.assertLess(distance_m(by_pixel, centre), 0.01)
        by_pixel = self.ok("locate", px=0, py=t["pixel_height"])
        self.assertLess(gt.ground_distance_m(by_pixel["lat"], by_pixel["lon"],
                                             t["footprint"][3]["lat"], t["footprint"][3]["lon"]),
                        0.5)

    def test_locate_of_project_is_the_point(self):
        self.aim(-40, -32)
        rng = random.Random(19)
        worst, checked = 0.0, 0
        for _ in range(40):
            x, y = rng.uniform(-0.95, 0.95), rng.uniform(-0.95, 0.95)
            p = self.ok("locate", x=x, y=y)
            point = {"lat": p["lat"], "lon": p["lon"], "alt": p["alt"]}
            seen = self.ok("project", **point)
            self.assertTrue(seen["visible"], seen)
            self.assertAlmostEqual(seen["x"], x, delta=1e-3)
            self.assertAlmostEqual(seen["y"], y, delta=1e-3)
            back = self.ok("locate", x=seen["x"], y=seen["y"])
            worst = max(worst, distance_m(back, point))
            checked += 1
            # The same through pixels.
            back = self.ok("locate", px=seen["px"], py=seen["py"])
            worst = max(worst, distance_m(back, point))
        self.assertEqual(checked, 40)
        sys.stderr.write("locate(project(P)) vs P, 80 round trips: worst %.4f m\n" % worst)
        self.assertLess(worst, 0.5, "locate(project(P)) off by %.3f m" % worst)

    def test_project_says_what_the_image_does_not_show(self):
        t = self.aim(0, -30)
        # Behind the camera (the ground point mirrored through the gimbal): no image position.
        g = t["ground"]
        behind = self.ok("project", lat=2 * t["lat"] - g["lat"], lon=2 * t["lon"] - g["lon"],
                         alt=g["alt"])
        self.assertIsNone(behind["x"])
        self.assertIsNone(behind["y"])
        self.assertFalse(behind["visible"])
        # The gimbal itself, straight above the ground point: outside the image.
        far = self.ok("project", lat=t["ground"]["lat"], lon=t["ground"]["lon"],
                      alt=t["ground"]["alt"] + 3000)
        self.assertFalse(far["visible"])

    # --- commands ------------------------------------------------------------------------

    def test_elevation_inside_and_outside_the_terrain(self):
        t = self.telemetry("demo")
        g = t["ground"]
        reply = self.ok("elevation", gimbal=None, lat=g["lat"], lon=g["lon"])
        self.assertNotIn("gimbal", reply)
        self.assertAlmostEqual(reply["alt"], g["alt"], delta=0.5)
        self.assertIsNone(reply["alt_msl"])  # geoid none
        self.assertEqual(reply["source"], self.dem)
        self.assertError(self.ask("elevation", None, lat=47.5, lon=-121.5), "unavailable")
        self.assertError(self.ask("elevation", None, lat=45.7, lon=-119.0), "unavailable")

    def test_point_at_the_centre_leaves_the_gimbal_where_it_looks(self):
        t = self.aim(60, -40)
        start = len(self.hover.rx())
        reply = self.ok("point", x=0, y=0)
        self.assertEqual(reply["sent"], [{"id": 213, "len": 21}])
        self.assertLess(distance_m(reply, t["ground"]), 0.5)
        self.assertEqual(reply["surface"], "terrain")
        entry = self.hover.wait_rx(gt.by_name("geopoint_cmd"), start=start)
        self.assertIsNotNone(entry)
        self.assertLess(distance_m(entry["packet"], t["ground"]), 1.0,
                        (entry["packet"], t["ground"]))

    def test_point_off_centre_brings_the_point_to_the_image_centre(self):
        self.aim(-100, -35)
        start = len(self.hover.rx())
        clicked = self.ok("point", x=0.5, y=-0.3, stare=True)
        point = {"lat": clicked["lat"], "lon": clicked["lon"], "alt": clicked["alt"]}
        entry = self.hover.wait_rx(gt.by_name("geopoint_cmd"), start=start)
        self.assertIsNotNone(entry)
        self.assertLess(distance_m(entry["packet"], point), 1.0)
        self.assertEqual(entry["packet"]["options"], "stare", entry["packet"])

        def centred():
            if self.telemetry()["mode"] != "geopoint":
                return None
            seen = self.ok("project", **point)
            off = math.hypot(seen["px"] - 960, seen["py"] - 540)
            return seen if off < SETTLE_PX else None
        clicked_at = time.monotonic()
        seen = gt.wait_for(centred, 8.0, interval=0.2)
        self.assertTrue(seen, "the clicked point never came within %.1f px of the centre" %
                        SETTLE_PX)
        settled_after = time.monotonic() - clicked_at
        # ... and stays there.
        gt.wait_for(lambda: False, 1.5)
        seen = self.ok("project", **point)
        off = math.hypot(seen["px"] - 960, seen["py"] - 540)
        sys.stderr.write("point 0.5 -0.3: within %.1f px after %.1f s; %.2f px off 1.5 s later\n"
                         % (SETTLE_PX, settled_after, off))
        self.assertLess(off, SETTLE_PX)
        self.assertTrue(seen["visible"])
        centre = self.ok("locate", x=0, y=0)
        self.assertLess(distance_m(centre, point), 0.01 * 2 * centre["range_m"] *
                        math.tan(math.radians(self.telemetry()["hfov"] / 2)))

    def test_geopoint_and_path_without_altitude_take_the_terrain(self):
        lat, lon = 45.712, -121.47
        ground = self.ok("elevation", gimbal=None, lat=lat, lon=lon)["alt"]
        start = len(self.hover.rx())
        self.ok("geopoint", lat=lat, lon=lon)
        entry = self.hover.wait_rx(gt.by_name("geopoint_cmd"), start=start)
        self.assertAlmostEqual(entry["packet"]["alt"], ground, delta=0.01)
        # Height above the ground.
        start = len(self.hover.rx())
        self.ok("geopoint", lat=lat, lon=lon, alt=50, alt_ref="terrain")
        entry = self.hover.wait_rx(gt.by_name("geopoint_cmd"), start=start)
        self.assertAlmostEqual(entry["packet"]["alt"], ground + 50, delta=0.01)
        # Path points: some with, some without alt.
        points = [{"lat": 45.705, "lon": -121.49}, {"lat": 45.71, "lon": -121.48, "alt": 900.0}]
        heights = [self.ok("elevation", gimbal=None, lat=p["lat"], lon=p["lon"])["alt"]
                   for p in points]
        start = len(self.hover.rx())
        self.ok("path", points=points)
        entry = self.hover.wait_rx(gt.by_name("path"), start=start)
        for sent, point, want_alt in zip(entry["packet"]["points"], points, (heights[0], 900.0)):
            expected = gt.lla_to_ecef(point["lat"], point["lon"], want_alt)
            self.assertLess(math.dist(sent["pos_ecef"], expected), 1.0)
        start = len(self.hover.rx())
        self.ok("path", points=points, alt_ref="terrain")
        entry = self.hover.wait_rx(gt.by_name("path"), start=start)
        expected = gt.lla_to_ecef(45.71, -121.48, heights[1] + 900.0)
        self.assertLess(math.dist(entry["packet"]["points"][1]["pos_ecef"], expected), 1.0)
        # Outside the terrain: unavailable, nothing sent.
        start = len(self.hover.rx())
        reply = self.ask("geopoint", lat=47.5, lon=-121.5)
        self.assertError(reply, "unavailable")
        self.assertIn("'alt'", reply["error"]["message"])
        self.assertError(self.ask("path", points=[{"lat": 47.5, "lon": -121.5}]), "unavailable")
        gt.wait_for(lambda: False, 0.3)
        self.assertEqual(self.sent(start), [])

    def test_bad_input_gets_a_clear_error_and_changes_nothing(self):
        t = self.aim(20, -30)
        start = len(self.hover.rx())
        cases = [
            ("locate", {"x": 1.5, "y": 0}, "out_of_range", "x"),
            ("locate", {"x": 0, "y": -1.01}, "out_of_range", "y"),
            ("locate", {"x": 0.5}, "bad_request", "y"),
            ("locate", {}, "bad_request", "x"),
            ("locate", {"x": 0, "y": 0, "px": 5, "py": 5}, "bad_request", "px"),
            ("locate", {"px": 5}, "bad_request", "py"),
            ("locate", {"px": t["pixel_width"] + 1, "py": 0}, "out_of_range", "px"),
            ("locate", {"x": "0", "y": 0}, "bad_request", "x"),
            ("locate", {"x": 0, "y": 0, "zoom": 2}, "bad_request", "zoom"),
            ("point", {"x": 2, "y": 0}, "out_of_range", "x"),
            ("point", {"y": 0}, "bad_request", "x"),
            ("point", {"x": 0, "y": 0, "stare": "yes"}, "bad_request", "stare"),
            ("point", {"x": 0, "y": 0, "px": 1}, "bad_request", "px"),
            ("project", {"lat": 45.7, "lon": -121.5}, "bad_request", "alt"),
            ("project", {"lat": 95, "lon": -121.5, "alt": 0}, "out_of_range", "lat"),
            ("elevation", {"lat": 45.7}, "bad_request", "lon"),
            ("elevation", {"lat": 45.7, "lon": 190}, "out_of_range", "lon"),
            ("elevation", {"lat": 45.7, "lon": -121.5, "alt": 3}, "bad_request", "alt"),
            ("geopoint", {"lat": 45.7, "lon": -121.5, "alt_ref": "msl"}, "bad_request", "alt"),
            ("geopoint", {"lat": 45.7, "lon": -121.5, "alt_ref": "agl"}, "bad_request", "alt_ref"),
            ("geopoint", {"lat": 45.7, "lon": -121.5, "alt": "high", "alt_ref": "terrain"},
             "bad_request", "alt"),
            ("geopoint", {"lon": -121.5}, "bad_request", "lat"),
            ("path", {"points": [{"lat": 45.7}]}, "bad_request", "lon"),
        ]
        for cmd, params, code, key in cases:
            with self.subTest(cmd=cmd, params=params):
                reply = self.ask(cmd, None if cmd == "elevation" else "hover", **params)
                self.assertError(reply, code)
                self.assertIn("'%s'" % key, reply["error"]["message"])
        gt.wait_for(lambda: False, 0.3)
        self.assertEqual(self.sent(start), [], "a refused command reached the gimbal")
        after = self.telemetry()
        self.assertEqual((after["mode"], after["pan"], after["tilt"]),
                         (t["mode"], t["pan"], t["tilt"]))

    def test_a_gimbal_without_image_geometry_or_geopoint(self):
        # Viewpro output frames carry no field of view and Viewpro has no geopoint.
        for cmd, params in (("locate", {"x": 0, "y": 0}), ("point", {"x": 0, "y": 0}),
                            ("project", {"lat": 45.7, "lon": -121.5, "alt": 400})):
            with self.subTest(cmd=cmd):
                reply = self.ask(cmd, "nose", **params)
                self.assertError(reply, "unsupported")
        self.assertError(self.ask("geopoint", "nose", lat=45.7, lon=-121.5), "unsupported")

    def test_point_and_locate_are_audited_by_role(self):
        self.ok("locate", x=0, y=0)
        self.ok("point", x=0, y=0)
        audits = gt.wait_for(lambda: [e for e in self.daemon.events("audit")
                                      if e.get("cmd") in ("point", "locate")] or None, 3.0)
        self.assertTrue(audits)
        self.assertEqual({e["cmd"] for e in audits}, {"point"})


class WithoutTerrain(gt.GimbaldTestCase):
    """No terrain section: the flat world at the target's altitude, as before."""

    def test_flat_world(self):
        daemon = self.start_daemon({}, args=["--sim"])
        c = self.client(daemon)
        self.wait_connected(c)
        t = gt.wait_for(lambda: (lambda s: s if s["telemetry"]["target"] else None)(
            c.request("state")["state"]), 5.0)
        self.assertTrue(t)
        t = t["telemetry"]
        self.assertEqual(t["footprint_surface"], "ellipsoid")
        self.assertEqual(t["ground"]["surface"], "ellipsoid")
        # The simulator's target is its own (whole-metre losECEF); ground is gimbald's ray.
        self.assertLess(distance_m(t["ground"], t["target"]), 3.0)
        reply = c.request("locate", x=0.2, y=0.1)
        self.assertOk(reply)
        self.assertEqual(reply["surface"], "ellipsoid")
        reply = c.request("geopoint", lat=45.7, lon=-121.5)
        self.assertError(reply, "unavailable")
        self.assertIn("'alt'", reply["error"]["message"])
        self.assertError(c.request("elevation", lat=45.7, lon=-121.5), "unavailable")
        self.assertOk(c.request("geopoint", lat=45.7, lon=-121.5, alt=400))


class GeoidAndConfiguration(gt.GimbaldTestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.dem = write_dem(cls.class_workdir)

    def test_egm96_heights_become_ellipsoidal(self):
        daemon = self.start_daemon({"terrain": {"files": [self.dem]}}, args=["--sim"])
        c = self.client(daemon)
        reply = c.request("elevation", lat=45.7, lon=-121.5)
        self.assertOk(reply)
        # The file's heights are read as above EGM96; the geoid lies 19.9 m below the
        # ellipsoid here (EGM96 15' grid, as docs/terrain.md says).
        self.assertAlmostEqual(reply["alt"] - reply["alt_msl"], -19.9, delta=0.5)

    def test_a_missing_or_unreadable_dem_is_exit_1_naming_the_file(self):
        missing = self.workdir + "/no-such-dem.tif"
        junk = self.workdir + "/junk.tif"
        with open(junk, "w") as f:
            f.write("not a raster\n")
        for files in ([missing], [self.dem, junk], [self.workdir + "/*.hgt"]):
            with self.subTest(files=files):
                path = gt.unique_path(self.workdir, "terrain-", ".json")
                with open(path, "w") as f:
                    f.write('{"gimbals": [], "terrain": {"files": %s}}' % json.dumps(files))
                for args in (["--check-config"], []):
                    result = subprocess.run([gt.GIMBALD, "-c", path, *args], capture_output=True,
                                            text=True, timeout=20)
                    self.assertEqual(result.returncode, 1, result)
                    self.assertIn("terrain.files: " + files[-1].replace("*.hgt", ""),
                                  result.stderr)
        ok = subprocess.run([gt.GIMBALD, "--sim", "--check-config", "-c",
                             self._config({"terrain": terrain_section(self.dem)})],
                            capture_output=True, text=True, timeout=20)
        self.assertEqual(ok.returncode, 0, ok)
        self.assertIn("terrain: 1 file", ok.stdout)

    def _config(self, config):
        path = gt.unique_path(self.workdir, "config-", ".json")
        with open(path, "w") as f:
            json.dump(config, f)
        return path


if __name__ == "__main__":
    gt.main()
