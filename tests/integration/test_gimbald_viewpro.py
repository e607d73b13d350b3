#!/usr/bin/env python3
"""Viewpro gimbals end to end (contract sections 3, 4.3, 5 and 7): gimbald and a
`gimbal-sim --protocol viewpro` over a pseudo-terminal (and once over TCP).

Wire bytes are checked as the simulator received them (its rx log), against frames built
here from the ICD's tables; what the gimbal sends back is checked in STATE `output`.
"""

import datetime
import math
import os
import struct
import sys
import time
import unittest

import gimbaltest as gt

# Where the simulated vehicle sits until the first IN frame (gimbal-sim options).
HOME_LAT, HOME_LON, HOME_ALT_MSL = 47.3977419, 8.5455938, 300.0
GIMBAL_PITCH = -45.0  # the simulator's default encoder pitch; yaw 0 looks along the heading

# IN1 / IN2 (ICD 4.1.1, 4.1.2): header, id, year, month..second, roll/pitch/yaw (rad float),
# lat/lon (degE7), altitude (mm MSL)[, vx/vy/vz (cm/s)], checksum.
IN1 = struct.Struct("<BBHBBBBBfffiiiB")
IN2 = struct.Struct("<BBHBBBBBfffiiihhhB")

# The keys of STATE output each format carries (contract section 5, simulator's table).
OUTPUT_KEYS = {
    "out1": {"format", "gimbal", "lrf_m", "target", "age_s"},
    "out2": {"format", "time", "zoom", "gimbal", "lrf_m", "uav", "target", "age_s"},
    "out3": {"format", "time", "zoom", "gimbal", "lrf_m", "uav", "target", "age_s"},
    "out4": {"format", "time", "zoom", "gimbal", "lrf_m", "uav", "target", "age_s"},
}
GIMBAL_KEYS = {"out1": {"pitch", "yaw"}, "out2": {"roll", "pitch", "yaw"},
               "out3": {"roll", "pitch", "yaw"}, "out4": {"roll", "pitch", "yaw"}}
UAV_KEYS = {"out2": {"roll", "pitch", "yaw", "lat", "lon", "alt_msl"},
            "out3": {"roll", "pitch", "yaw", "lat", "lon", "alt_msl"},
            "out4": {"pitch", "yaw", "lat", "lon", "alt_msl"}}
TARGET_KEYS = {"out1": {"lat", "lon"}, "out2": {"lat", "lon"}, "out3": {"lat", "lon"},
               "out4": {"lat", "lon", "alt_msl"}}


def hexof(data):
    return bytes(data).hex()


def iso_utc(text):
    return datetime.datetime.strptime(text.rstrip("Z")[:19], "%Y-%m-%dT%H:%M:%S").replace(
        tzinfo=datetime.timezone.utc)


def bearing_deg(lat1, lon1, lat2, lon2):
    """Initial bearing from point 1 to point 2 (flat approximation, fine over a few km)."""
    north = math.radians(lat2 - lat1)
    east = math.radians(lon2 - lon1) * math.cos(math.radians((lat1 + lat2) / 2))
    return math.degrees(math.atan2(east, north)) % 360.0


class ViewproTestCase(gt.GimbaldTestCase):
    def start_viewpro_sim(self, *args, device=None, tcp=False):
        """A simulated Viewpro at HOME on a pty (symlinked at `device`) and/or TCP."""
        if device is None and not tcp:
            device = os.path.join(self.workdir, "ttyVIEWPRO")
        want = (("tcp",) if tcp else ()) + (("pty",) if device else ())
        return self.start_sim("--protocol", "viewpro", "--lat", str(HOME_LAT), "--lon",
                              str(HOME_LON), "--alt", str(HOME_ALT_MSL), *args, tcp=tcp,
                              pty_link=device, want=want)

    def start_viewpro_daemon(self, sim, output=None, stale_after_s=None, **link):
        device = os.path.join(self.workdir, "ttyVIEWPRO")
        gimbal = gt.viewpro_serial("nose", device, output=output,
                                   **dict({"reconnect_min_s": 0.2, "reconnect_max_s": 1},
                                          **link))
        config = {"gimbals": [gimbal]}
        if stale_after_s is not None:
            config["telemetry"] = {"stale_after_s": stale_after_s}
        return self.start_daemon(config)

    def state(self, client, gimbal=None):
        params = {"gimbal": gimbal} if gimbal else {}
        reply = client.request("state", **params)
        self.assertOk(reply)
        return reply["state"]

    def wait_output(self, client, predicate=lambda out: True, gimbal=None,
                    timeout=gt.START_TIMEOUT_S, what="output"):
        """The first STATE whose link is up and whose output is fresh and passes predicate."""
        params = {"gimbal": gimbal} if gimbal else {}

        def ready():
            reply = client.request("state", **params)
            if not reply or not reply.get("ok"):
                return None
            state = reply["state"]
            out = state.get("output")
            if state["link"]["connected"] and not state["stale"] and out and predicate(out):
                return state
            return None
        state = gt.wait_for(ready, timeout, interval=0.1)
        self.assertTrue(state, "no STATE with %s" % what)
        return state

    def assertRxHex(self, entries, expected):
        self.assertEqual([e["hex"] for e in entries], [hexof(f) for f in expected])

    def sent_since(self, sim, start, count, timeout=gt.REPLY_TIMEOUT_S):
        """The next `count` rx-log entries after index `start` (fewer on timeout)."""
        entries = gt.wait_for(lambda: sim.rx()[start:] if len(sim.rx()) >= start + count
                              else None, timeout)
        return entries or sim.rx()[start:]


class ModeOnConnect(ViewproTestCase):
    def test_configured_output_is_the_first_frame_on_the_pty(self):
        output = {"osd": "uav", "serial": True, "network": False, "format": "out1"}
        sim = self.start_viewpro_sim()
        daemon = self.start_viewpro_daemon(sim, output=output)
        c = self.client(daemon)
        state = self.wait_output(c, lambda out: out["format"] == "out1")
        self.assertEqual(state["protocol"], "viewpro")
        self.assertEqual(state["link"]["type"], "serial")
        self.assertIn("ttyVIEWPRO", state["link"]["endpoint"])

        first = sim.rx()[0]
        self.assertEqual(gt.viewpro_mode_byte("uav", True, False, "out1"), 0x10)
        self.assertEqual(first["hex"], "aa550f10ff")
        self.assertEqual((first["kind"], first["len"], first["src"]), ("mode", 5, "pty"))
        self.assertEqual(first["frame"], dict(output))
        # Nothing else is sent on connect: the protocol has no requests.
        time.sleep(0.5)
        self.assertEqual(len(sim.rx()), 1, sim.rx())

    def test_default_output_is_out3_on_serial_showing_the_target(self):
        sim = self.start_viewpro_sim()
        c = self.client(self.start_viewpro_daemon(sim))
        self.wait_output(c, lambda out: out["format"] == "out3")
        # ICD example 1.2 without the network bit: AA 55 0F 51 FF.
        self.assertEqual(sim.rx()[0]["hex"], hexof(gt.viewpro_mode()))
        self.assertEqual(sim.rx()[0]["hex"], "aa550f51ff")

    def test_over_tcp_the_mode_goes_out_on_every_reconnect(self):
        output = {"osd": "target", "serial": True, "network": True, "format": "out4"}
        sim = self.start_viewpro_sim("--drop-after", "1.5", tcp=True)
        daemon = self.start_daemon({"gimbals": [gt.viewpro_tcp(
            "nose", sim.port, output=output, reconnect_min_s=0.2, reconnect_max_s=0.5)]})
        c = self.client(daemon)
        state = self.wait_output(c, lambda out: out["format"] == "out4")
        self.assertEqual(state["link"]["type"], "tcp")
        self.assertEqual(state["link"]["endpoint"], "127.0.0.1:%d" % sim.port)

        modes = gt.wait_for(lambda: [e for e in sim.rx() if e["kind"] == "mode"]
                            if len([e for e in sim.rx() if e["kind"] == "mode"]) >= 3 else None,
                            8.0, interval=0.2)
        self.assertTrue(modes, "the mode command was not re-sent on reconnects: %s" % sim.rx())
        self.assertEqual({e["hex"] for e in modes}, {"aa550f79ff"})  # ICD example 1.2 + OUT4
        self.assertEqual({e["src"] for e in modes}, {"tcp"})
        self.assertEqual(sim.rx(), modes)  # nothing but the mode commands
        self.assertGreaterEqual(self.state(c)["link"]["reconnects"], 2)
        self.wait_output(c, lambda out: out["format"] == "out4")


class Commands(ViewproTestCase):
    def setUp(self):
        super().setUp()
        self.sim = self.start_viewpro_sim()
        self.daemon = self.start_viewpro_daemon(self.sim)
        self.c = self.client(self.daemon)
        self.wait_output(self.c)
        self.assertTrue(self.sim.wait_rx(gt.by_kind("mode")))

    def test_viewpro_output_is_the_five_byte_mode_command(self):
        cases = [  # (osd, serial, network, format) -> the ICD's examples where there is one
            (("target", True, True, "out3"), "aa550f59ff"),   # 1.2
            (("uav", True, False, "out2"), "aa550f30ff"),     # 1.3
            (("target", True, False, "out1"), "aa550f11ff"),  # 1.4
            (("target", False, True, "out4"), "aa550f69ff"),  # 1.5, encoded from the bit table
            (("target", False, False, "out1"), "aa550f01ff"),  # 1.6
            (("uav", False, False, "out2"), "aa550f20ff"),
        ]
        for (osd, serial, network, fmt), wire in cases:
            with self.subTest(wire=wire):
                self.assertEqual(hexof(gt.viewpro_mode(osd, serial, network, fmt)), wire)
                start = len(self.sim.rx())
                reply = self.c.request("viewpro_output", osd=osd, serial=serial,
                                       network=network, format=fmt)
                self.assertOk(reply)
                self.assertEqual(reply["gimbal"], "nose")
                self.assertEqual(reply["sent"], [{"frame": "mode", "len": 5}])
                entries = self.sent_since(self.sim, start, 1)
                self.assertRxHex(entries, [bytes.fromhex(wire)])
                self.assertEqual(entries[0]["frame"], {"osd": osd, "serial": serial,
                                                       "network": network, "format": fmt})

    def test_viewpro_output_parameters_are_checked(self):
        start = len(self.sim.rx())
        full = {"osd": "target", "serial": True, "network": False, "format": "out3"}
        self.assertError(self.c.request("viewpro_output", **dict(full, format="out5")),
                         "bad_request")
        self.assertError(self.c.request("viewpro_output", **dict(full, osd="ground")),
                         "bad_request")
        self.assertError(self.c.request("viewpro_output", **dict(full, serial="yes")),
                         "bad_request")
        missing = dict(full)
        del missing["format"]
        self.assertError(self.c.request("viewpro_output", **missing), "bad_request")
        self.assertError(self.c.request("viewpro_output", **dict(full, baud=9600)),
                         "bad_request")
        time.sleep(0.3)
        self.assertEqual(self.sim.rx()[start:], [])

    def test_viewpro_adjust_sends_yaw_then_pitch_in_steps_of_one_degree(self):
        start = len(self.sim.rx())
        reply = self.c.request("viewpro_adjust", pitch_deg=-1.3, yaw_deg=2.5)
        self.assertOk(reply)
        expected = [gt.viewpro_command(0x06, 100), gt.viewpro_command(0x06, 100),
                    gt.viewpro_command(0x06, 50), gt.viewpro_command(0x36, -100),
                    gt.viewpro_command(0x36, -30)]
        self.assertEqual(hexof(expected[3]), "aa55369cff")  # the ICD's -1 degree example
        self.assertEqual(reply["sent"], [{"frame": "yaw_shift", "len": 5}] * 3 +
                         [{"frame": "pitch_shift", "len": 5}] * 2)
        entries = self.sent_since(self.sim, start, 5)
        self.assertRxHex(entries, expected)
        self.assertEqual([e["kind"] for e in entries], ["yaw_shift"] * 3 + ["pitch_shift"] * 2)
        self.assertEqual([e["frame"]["hundredths_deg"] for e in entries],
                         [100, 100, 50, -100, -30])

    def test_viewpro_adjust_negative_yaw_and_pitch_alone(self):
        start = len(self.sim.rx())
        reply = self.c.request("viewpro_adjust", yaw_deg=-0.07)
        self.assertOk(reply)
        self.assertEqual(reply["sent"], [{"frame": "yaw_shift", "len": 5}])
        reply = self.c.request("viewpro_adjust", pitch_deg=5.5)  # the ICD's example
        self.assertOk(reply)
        self.assertEqual(len(reply["sent"]), 6)
        entries = self.sent_since(self.sim, start, 7)
        self.assertRxHex(entries, [bytes.fromhex("aa5506f9ff")] +
                         [bytes.fromhex("aa553664ff")] * 5 + [bytes.fromhex("aa553632ff")])

    def test_viewpro_adjust_limits(self):
        start = len(self.sim.rx())
        self.assertError(self.c.request("viewpro_adjust", yaw_deg=20.5), "out_of_range")
        self.assertError(self.c.request("viewpro_adjust", pitch_deg=-20.01), "out_of_range")
        self.assertError(self.c.request("viewpro_adjust"), "bad_request")
        self.assertError(self.c.request("viewpro_adjust", roll_deg=1), "bad_request")
        # The limits themselves are allowed: 20 degrees is 20 full steps.
        reply = self.c.request("viewpro_adjust", yaw_deg=-20)
        self.assertOk(reply)
        self.assertEqual(len(reply["sent"]), 20)
        entries = self.sent_since(self.sim, start, 20)
        self.assertRxHex(entries, [gt.viewpro_command(0x06, -100)] * 20)

    def test_yaw_adjust_turns_the_computed_target(self):
        # The simulator applies the shift to its calculation only: the target's bearing from
        # the vehicle (heading north, gimbal yaw 0) becomes the shift.
        state = self.wait_output(self.c)
        out = state["output"]
        self.assertLess(gt.angle_diff_deg(bearing_deg(HOME_LAT, HOME_LON, out["target"]["lat"],
                                                      out["target"]["lon"]), 0.0), 1.0)
        self.assertOk(self.c.request("viewpro_adjust", yaw_deg=15))

        def turned(out):
            b = bearing_deg(HOME_LAT, HOME_LON, out["target"]["lat"], out["target"]["lon"])
            return gt.angle_diff_deg(b, 15.0) < 1.0
        state = self.wait_output(self.c, turned, timeout=3.0, what="the target turned 15 deg")
        self.assertAlmostEqual(state["output"]["gimbal"]["yaw"], 0.0, delta=0.1)

    def check_vehicle_frame(self, entry, in_struct, expected, vel_cms=None):
        """Decodes the received frame here (ICD tables) and compares with what was asked."""
        raw = bytes.fromhex(entry["hex"])
        self.assertEqual(len(raw), in_struct.size)
        fields = in_struct.unpack(raw)
        self.assertEqual(fields[-1], gt.sum8(raw[:-1]))
        t = iso_utc(expected["time"])
        self.assertEqual(fields[2:8], (t.year, t.month, t.day, t.hour, t.minute, t.second))
        for got, want in zip(fields[8:11], ("roll", "pitch", "yaw")):
            self.assertLess(gt.angle_diff_deg(math.degrees(got), expected[want]), 1e-4, want)
        self.assertEqual(fields[11], gt.scaled(expected["lat"], 1e7))
        self.assertEqual(fields[12], gt.scaled(expected["lon"], 1e7))
        self.assertEqual(fields[13], gt.scaled(expected["alt_msl"], 1e3))
        if vel_cms is not None:
            self.assertEqual(list(fields[14:17]), vel_cms)
        # The simulator's own decoding agrees.
        frame = entry["frame"]
        self.assertEqual(iso_utc(frame["time"]), t)
        for key in ("roll", "pitch", "yaw"):
            self.assertLess(gt.angle_diff_deg(frame[key], expected[key]), 1e-4, key)
        for key in ("lat", "lon"):
            self.assertAlmostEqual(frame[key], expected[key], places=7)
        self.assertAlmostEqual(frame["alt_msl"], expected["alt_msl"], places=3)

    def test_vehicle_without_velocity_is_in1(self):
        vehicle = {"time": "2026-11-21T06:41:50Z", "roll": 1.5, "pitch": -2.25, "yaw": 90.0,
                   "lat": 47.3977419, "lon": 8.5455938, "alt_msl": 600.125}
        start = len(self.sim.rx())
        reply = self.c.request("vehicle", **vehicle)
        self.assertOk(reply)
        self.assertEqual(reply["sent"], [{"frame": "in1", "len": 34}])
        entries = self.sent_since(self.sim, start, 1)
        self.assertEqual(len(entries), 1)
        self.assertEqual((entries[0]["kind"], entries[0]["len"]), ("in1", 34))
        self.assertTrue(entries[0]["hex"].startswith("f9fb"))
        self.check_vehicle_frame(entries[0], IN1, vehicle)
        self.assertNotIn("vel_ned", entries[0]["frame"])

    def test_vehicle_with_velocity_is_in2(self):
        vehicle = {"time": "2025-02-28T23:59:59Z", "roll": -10.0, "pitch": 3.0, "yaw": 359.5,
                   "lat": -33.8688197, "lon": -151.2092955, "alt_msl": -12.5,
                   "vel_ned": [1.5, -20.0, 0.25]}
        start = len(self.sim.rx())
        reply = self.c.request("vehicle", **vehicle)
        self.assertOk(reply)
        self.assertEqual(reply["sent"], [{"frame": "in2", "len": 40}])
        entries = self.sent_since(self.sim, start, 1)
        self.assertEqual((entries[0]["kind"], entries[0]["len"]), ("in2", 40))
        self.assertTrue(entries[0]["hex"].startswith("f9fc"))
        self.check_vehicle_frame(entries[0], IN2, vehicle, vel_cms=[150, -2000, 25])
        self.assertEqual(entries[0]["frame"]["vel_ned"], [1.5, -20.0, 0.25])

    def test_vehicle_time_defaults_to_now(self):
        start = len(self.sim.rx())
        before = datetime.datetime.now(datetime.timezone.utc).replace(microsecond=0)
        self.assertOk(self.c.request("vehicle", roll=0, pitch=0, yaw=0, lat=HOME_LAT,
                                     lon=HOME_LON, alt_msl=300))
        after = datetime.datetime.now(datetime.timezone.utc)
        entries = self.sent_since(self.sim, start, 1)
        sent = iso_utc(entries[0]["frame"]["time"])
        self.assertTrue(before - datetime.timedelta(seconds=1) <= sent <= after,
                        (before, sent, after))

    def test_vehicle_parameters_are_checked(self):
        start = len(self.sim.rx())
        ok = {"roll": 0, "pitch": 0, "yaw": 0, "lat": 10, "lon": 20, "alt_msl": 100}
        self.assertError(self.c.request("vehicle", **dict(ok, lat=91)), "out_of_range")
        self.assertError(self.c.request("vehicle", **dict(ok, vel_ned=[1, 2])), "bad_request")
        self.assertError(self.c.request("vehicle", **dict(ok, time="yesterday")), "bad_request")
        missing = dict(ok)
        del missing["lon"]
        self.assertError(self.c.request("vehicle", **missing), "bad_request")
        time.sleep(0.3)
        self.assertEqual(self.sim.rx()[start:], [])


class Output(ViewproTestCase):
    def check_geometry(self, fmt, out):
        """The simulated vehicle is level at HOME, heading north, the gimbal 45 deg down:
        the target lies alt_msl ahead, at a slant range of alt_msl x sqrt(2)."""
        self.assertAlmostEqual(out["gimbal"]["pitch"], GIMBAL_PITCH, delta=0.05)
        self.assertAlmostEqual(out["gimbal"]["yaw"], 0.0, delta=0.05)
        self.assertAlmostEqual(out["lrf_m"], HOME_ALT_MSL * math.sqrt(2), delta=5.0)
        ahead = gt.ground_distance_m(HOME_LAT, HOME_LON, out["target"]["lat"],
                                     out["target"]["lon"])
        self.assertAlmostEqual(ahead, HOME_ALT_MSL, delta=5.0)
        self.assertLess(out["target"]["lon"] - HOME_LON, 1e-5)  # due north
        self.assertGreater(out["target"]["lat"], HOME_LAT)
        if "uav" in out:
            self.assertAlmostEqual(out["uav"]["lat"], HOME_LAT, places=6)
            self.assertAlmostEqual(out["uav"]["lon"], HOME_LON, places=6)
            self.assertAlmostEqual(out["uav"]["alt_msl"], HOME_ALT_MSL, delta=0.01)
            self.assertAlmostEqual(out["uav"]["pitch"], 0.0, delta=0.01)
        if "time" in out:
            age = datetime.datetime.now(datetime.timezone.utc) - iso_utc(out["time"])
            self.assertLess(abs(age.total_seconds()), 5.0, out["time"])
            self.assertEqual(out["zoom"], 0)
        if fmt == "out4":
            self.assertAlmostEqual(out["target"]["alt_msl"], 0.0, delta=0.5)

    def test_each_format_reaches_state(self):
        sim = self.start_viewpro_sim()
        c = self.client(self.start_viewpro_daemon(sim))
        self.wait_output(c)
        for fmt in ("out1", "out2", "out4", "out3"):
            with self.subTest(format=fmt):
                self.assertOk(c.request("viewpro_output", osd="target", serial=True,
                                        network=False, format=fmt))
                state = self.wait_output(c, lambda out: out["format"] == fmt, timeout=3.0,
                                         what=fmt)
                out = state["output"]
                self.assertEqual(set(out), OUTPUT_KEYS[fmt], out)
                self.assertEqual(set(out["gimbal"]), GIMBAL_KEYS[fmt])
                self.assertEqual(set(out["target"]), TARGET_KEYS[fmt])
                if fmt in UAV_KEYS:
                    self.assertEqual(set(out["uav"]), UAV_KEYS[fmt])
                self.assertGreaterEqual(out["age_s"], 0.0)
                self.assertLess(out["age_s"], 1.0)
                self.assertIs(state["stale"], False)
                self.check_geometry(fmt, out)
        self.assertEqual(self.state(c)["link"]["bad_checksums"], 0)

    def test_a_feed_of_vehicle_positions_moves_the_target(self):
        sim = self.start_viewpro_sim()
        c = self.client(self.start_viewpro_daemon(sim))
        self.wait_output(c)
        alt, lat0, lon0 = 200.0, 47.40, 8.55
        samples = []
        lon = lon0
        for step in range(30):  # 3 s at 10 Hz, flying east at about 75 m/s
            lon = lon0 + step * 1e-4
            reply = c.request("vehicle", roll=0, pitch=0, yaw=90, lat=lat0, lon=lon,
                              alt_msl=alt, vel_ned=[0, 75, 0])
            self.assertOk(reply)
            if step % 5 == 4:
                samples.append(self.state(c)["output"])
            time.sleep(0.1)
        last = self.wait_output(
            c, lambda out: abs(out["uav"]["lon"] - lon) < 1e-6, timeout=2.0,
            what="the latest vehicle position")["output"]
        samples.append(last)
        self.assertEqual(len([e for e in sim.rx() if e["kind"] == "in2"]), 30)

        target_lons = [s["target"]["lon"] for s in samples]
        self.assertEqual(target_lons, sorted(target_lons))
        self.assertGreater(target_lons[-1] - target_lons[0], 20e-4)
        for out in samples:
            uav, target = out["uav"], out["target"]
            self.assertAlmostEqual(uav["lat"], lat0, places=6)
            self.assertAlmostEqual(uav["alt_msl"], alt, delta=0.01)
            self.assertAlmostEqual(uav["yaw"], 90.0, delta=0.01)
            # Gimbal 45 degrees down along the heading: the target is `alt` metres east.
            ahead = gt.ground_distance_m(uav["lat"], uav["lon"], target["lat"], target["lon"])
            self.assertAlmostEqual(ahead, alt, delta=4.0)
            self.assertLess(gt.angle_diff_deg(
                bearing_deg(uav["lat"], uav["lon"], target["lat"], target["lon"]), 90.0), 1.0)
            self.assertAlmostEqual(out["lrf_m"], alt * math.sqrt(2), delta=5.0)

    def test_garbage_on_the_line_is_counted_and_output_still_updates(self):
        sim = self.start_viewpro_sim("--corrupt-fraction", "0.2", "--junk-every", "3",
                                     "--gimbal-yaw-rate", "10")
        daemon = self.start_viewpro_daemon(sim)
        c = self.client(daemon)
        self.wait_output(c)

        def counted():
            link = self.state(c)["link"]
            return link if link["bad_checksums"] >= 2 and link["dropped_bytes"] >= 2 else None
        first = gt.wait_for(counted, 6.0, interval=0.2)
        self.assertTrue(first, "no bad checksum or dropped byte counted")
        yaw0 = self.state(c)["output"]["gimbal"]["yaw"]
        time.sleep(1.0)
        state = self.wait_output(c)
        link = state["link"]
        self.assertGreater(link["bad_checksums"], first["bad_checksums"])
        self.assertGreater(link["dropped_bytes"], first["dropped_bytes"])
        self.assertGreater(link["rx_packets"], first["rx_packets"])
        self.assertIs(link["connected"], True)
        self.assertEqual(link["reconnects"], 0)
        self.assertGreater(gt.angle_diff_deg(state["output"]["gimbal"]["yaw"], yaw0), 3.0)
        self.assertLess(state["output"]["age_s"], 0.5)


class LinkLoss(ViewproTestCase):
    def test_pty_vanishes_and_returns(self):
        output = {"osd": "uav", "serial": True, "network": False, "format": "out2"}
        device = os.path.join(self.workdir, "ttyVIEWPRO")
        sim = self.start_viewpro_sim(device=device)
        daemon = self.start_viewpro_daemon(sim, output=output)
        c = self.client(daemon)
        self.wait_output(c, lambda out: out["format"] == "out2")
        self.assertOk(c.request("subscribe", rate_hz=0.2, ttl_s=60))
        self.addCleanup(c.request, "unsubscribe")

        self.assertEqual(sim.stop(), 0)
        self.assertFalse(os.path.lexists(device))
        down = c.wait_message(gt.is_event("link"), 5.0)
        self.assertEqual(down, {"type": "event", "gimbal": "nose", "event": "link",
                                "connected": False})
        state = self.state(c)
        self.assertIs(state["link"]["connected"], False)
        self.assertTrue(gt.wait_for(lambda: self.state(c)["stale"], 3.0))
        self.assertError(c.request("viewpro_adjust", yaw_deg=1), "link_down")
        time.sleep(1.5)  # a few failed reopen attempts

        sim = self.start_viewpro_sim(device=device)
        up = c.wait_message(gt.is_event("link"), 5.0)
        self.assertEqual(up, {"type": "event", "gimbal": "nose", "event": "link",
                              "connected": True})
        first = sim.wait_rx(lambda e: True)
        self.assertTrue(first, "nothing received after the reconnect")
        self.assertEqual(first["hex"], hexof(gt.viewpro_mode("uav", True, False, "out2")))
        state = self.wait_output(c, lambda out: out["format"] == "out2", timeout=5.0)
        self.assertGreaterEqual(state["link"]["reconnects"], 1)
        age = state["output"]["age_s"]
        self.assertLess(age, 1.0)
        start = len(sim.rx())
        self.assertOk(c.request("viewpro_adjust", yaw_deg=1))
        self.assertTrue(sim.wait_rx(gt.by_kind("yaw_shift"), start=start))

    def test_a_stalled_gimbal_goes_stale_with_a_lost_event_and_comes_back(self):
        sim = self.start_viewpro_sim("--stall-after", "2", "--stall-for", "2.5")
        daemon = self.start_viewpro_daemon(sim, stale_after_s=0.5)
        c = self.client(daemon)
        self.wait_output(c)
        self.assertOk(c.request("subscribe", rate_hz=0.1, ttl_s=60))
        self.addCleanup(c.request, "unsubscribe")
        lost = c.wait_message(gt.is_event("lost"), 5.0)
        self.assertTrue(lost, "no lost event while the gimbal was silent")
        self.assertEqual(lost["gimbal"], "nose")
        state = self.state(c)
        self.assertIs(state["stale"], True)
        self.assertIs(state["link"]["connected"], True)
        self.assertGreater(state["output"]["age_s"], 0.5)
        self.wait_output(c, timeout=5.0, what="output after the stall")
        self.assertEqual(self.state(c)["link"]["reconnects"], 0)

    def test_output_switched_off_goes_stale_and_back_on(self):
        sim = self.start_viewpro_sim()
        daemon = self.start_viewpro_daemon(sim, stale_after_s=0.5)
        c = self.client(daemon)
        self.wait_output(c)
        self.assertOk(c.request("subscribe", rate_hz=0.1, ttl_s=60))
        self.addCleanup(c.request, "unsubscribe")
        self.assertOk(c.request("viewpro_output", osd="target", serial=False, network=False,
                                format="out3"))
        switched_off = time.monotonic()
        lost = c.wait_message(gt.is_event("lost"), 3.0)
        self.assertTrue(lost, "no lost event after the output was switched off")
        self.assertGreaterEqual(time.monotonic() - switched_off, 0.4)
        state = self.state(c)
        self.assertIs(state["stale"], True)
        self.assertIs(state["link"]["connected"], True)
        rx = state["link"]["rx_packets"]
        time.sleep(0.5)
        self.assertEqual(self.state(c)["link"]["rx_packets"], rx)  # nothing comes any more
        # Only one lost event per silence.
        self.assertEqual(c.collect(1.0, gt.is_event("lost")), [])
        self.assertOk(c.request("viewpro_output", osd="target", serial=True, network=False,
                                format="out1"))
        self.wait_output(c, lambda out: out["format"] == "out1", timeout=3.0)


class EmbeddedSims(ViewproTestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.daemon = cls.start_class_daemon({}, args=["--sim", "orion,viewpro"])

    def setUp(self):
        super().setUp()
        self.c = self.client(self.daemon)

    def test_list_and_state(self):
        reply = self.c.request("list")
        self.assertOk(reply)
        self.assertEqual(reply["gimbals"], [
            {"name": "sim-orion", "protocol": "orion", "link": {"type": "sim", "connected": True}},
            {"name": "sim-viewpro", "protocol": "viewpro",
             "link": {"type": "sim", "connected": True}}])
        state = self.wait_output(self.c, gimbal="sim-viewpro")
        self.assertEqual(state["protocol"], "viewpro")
        self.assertEqual(state["link"]["type"], "sim")
        self.assertEqual(set(state["output"]), OUTPUT_KEYS["out3"])
        self.assertNotIn("telemetry", state)
        orion = self.wait_connected(self.c, gimbal="sim-orion")
        self.assertEqual(orion["protocol"], "orion")
        self.assertNotIn("output", orion)

    def test_vehicle_on_the_embedded_viewpro_moves_its_uav(self):
        self.wait_output(self.c, gimbal="sim-viewpro")
        reply = self.c.request("vehicle", gimbal="sim-viewpro", roll=0, pitch=0, yaw=45,
                               lat=-20.5, lon=150.25, alt_msl=500)
        self.assertOk(reply)
        self.assertEqual(reply["sent"], [{"frame": "in1", "len": 34}])
        state = self.wait_output(
            self.c, lambda out: abs(out["uav"]["lat"] + 20.5) < 1e-6, gimbal="sim-viewpro",
            timeout=3.0, what="the new vehicle position")
        self.assertAlmostEqual(state["output"]["uav"]["lon"], 150.25, places=6)

    def test_orion_commands_on_the_viewpro_are_unsupported(self):
        requests = [
            ("geopoint", {"lat": 45.7, "lon": -121.5, "alt": 100}),
            ("path", {"points": [{"lat": 45.7, "lon": -121.5, "alt": 100}]}),
            ("laser", {"enable": True, "arm": False, "fire": False}),
            ("position", {"pan": 10, "tilt": -20}),
            ("rate", {"pan": 1, "tilt": 0}),
            ("mode", {"mode": "disabled"}),
            ("stare_ack", {"system_time_ms": 1}),
            ("retract", {"action": "deploy"}),
            ("camera_switch", {"index": 1}),
            ("camera_zoom", {"zoom": 2}),
            ("range", {"range_m": 100, "max_age_ms": 1000, "source": "laser"}),
            ("request", {"packet": "crown_version"}),
        ]
        for cmd, params in requests:
            with self.subTest(cmd=cmd):
                reply = self.c.request(cmd, gimbal="sim-viewpro", id="u-" + cmd, **params)
                self.assertError(reply, "unsupported", "u-" + cmd)
                self.assertEqual(reply["cmd"], cmd)

    def test_viewpro_commands_on_the_orion_are_unsupported(self):
        requests = [
            ("viewpro_output", {"osd": "target", "serial": True, "network": False,
                                "format": "out3"}),
            ("viewpro_adjust", {"yaw_deg": 1}),
            ("vehicle", {"roll": 0, "pitch": 0, "yaw": 0, "lat": 1, "lon": 2, "alt_msl": 3}),
        ]
        for cmd, params in requests:
            with self.subTest(cmd=cmd):
                reply = self.c.request(cmd, gimbal="sim-orion", id="u-" + cmd, **params)
                self.assertError(reply, "unsupported", "u-" + cmd)
                self.assertEqual(reply["cmd"], cmd)

    def test_gimbal_is_required_with_two_gimbals(self):
        self.assertError(self.c.request("viewpro_adjust", yaw_deg=1), "unknown_gimbal")


class OrionAndViewproSideBySide(ViewproTestCase):
    def test_a_config_with_both_routes_each_command_to_its_own_wire(self):
        device = os.path.join(self.workdir, "ttyVIEWPRO")
        viewpro = self.start_viewpro_sim(device=device)
        orion = self.start_sim()
        daemon = self.start_daemon({"gimbals": [
            gt.orion_tcp("main", orion.port),
            gt.viewpro_serial("nose", device, reconnect_min_s=0.2, reconnect_max_s=1)]})
        c = self.client(daemon)
        self.wait_connected(c, gimbal="main")
        self.wait_output(c, gimbal="nose")
        v_start, o_start = len(viewpro.rx()), len(orion.rx())

        self.assertError(c.request("viewpro_adjust", gimbal="main", yaw_deg=1), "unsupported")
        self.assertError(c.request("geopoint", gimbal="nose", lat=45.7, lon=-121.5, alt=100),
                         "unsupported")
        self.assertOk(c.request("viewpro_adjust", gimbal="nose", yaw_deg=1))
        self.assertOk(c.request("geopoint", gimbal="main", lat=45.7, lon=-121.5, alt=100))
        self.assertTrue(viewpro.wait_rx(gt.by_kind("yaw_shift"), start=v_start))
        self.assertTrue(orion.wait_rx(gt.by_name("geopoint_cmd"), start=o_start))
        time.sleep(0.3)
        self.assertEqual([e["kind"] for e in viewpro.rx()[v_start:]], ["yaw_shift"])
        self.assertEqual([e["name"] for e in orion.rx()[o_start:]], ["geopoint_cmd"])


def main():
    missing = [name for name, path in (("GIMBALD", gt.GIMBALD), ("GIMBAL_SIM", gt.GIMBAL_SIM))
               if not path]
    if missing:
        print("skipped: %s not set" % ", ".join(missing))
        sys.exit(gt.SKIP)
    unittest.main(verbosity=2)


if __name__ == "__main__":
    main()
