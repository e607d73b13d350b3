#!/usr/bin/env python3
"""A recording of gimbald + gimbal-sim, read by tshark with dissectors/gimbald.lua
(contract section 12): no malformed packets or bad checksums, and the fields of the latest
packet of every kind gimbald keeps in STATE (telemetry, gps, ins, performance, ...) match what
STATE shows, by name (lat, lon, alt, pan, tilt, mode, ...), each to one step of its wire field
(the step comes from the dissector's generated schema); the geopoint command gimbald sent
shows the values asked for, and the JSON requests and replies are decoded too.

Skipped (77) when tshark is missing or this gimbald has no `record` configuration yet.
"""
import json
import os
import re
import shutil
import signal
import subprocess
import time

import gimbaltest as gt
import skipping

SOURCE = os.environ.get("GIMBAL_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
LUA = os.path.join(SOURCE, "dissectors", "gimbald.lua")
# STATE key -> Orion packet (contract section 5).
STATE_PACKETS = {"telemetry": "geolocate_telemetry", "gps": "gps_data", "ins": "ins_quality",
                 "performance": "performance", "diagnostics": "diagnostics",
                 "network_diagnostics": "network_diagnostics", "retract": "retract_status",
                 "limits": "limits", "stare": "stare_start"}


def field_steps():
    """{(packet, key): one wire step in JSON units} from the dissector's generated schema."""
    steps = {}
    packet = None
    with open(LUA) as f:
        for line in f:
            m = re.match(r'  \[\d+\] = \{ name = "(\w+)"', line)
            if m:
                packet = m.group(1)
                continue
            m = re.match(r'    \{ kind = "(?:field|bits)", key = "(\w+)"(.*)', line)
            if packet and m:
                factor = re.search(r"factor = ([-0-9.e+]+)", m.group(2))
                step = 1.0 / float(factor.group(1)) if factor else 1.0
                if "radians = true" in m.group(2):
                    step *= 180.0 / 3.141592653589793
                steps[(packet, m.group(1))] = step
    return steps


def pairs(items):
    out = {}
    for k, v in items:
        out.setdefault(k, []).append(v)
    return out


def flatten(node, out):
    for key, values in node.items():
        for v in values:
            if isinstance(v, dict):
                flatten(v, out)
            else:
                out.setdefault(key, []).append(v)


class DissectorReadsRecording(gt.GimbaldTestCase):
    def test_recording_matches_state(self):
        tshark = shutil.which("tshark")
        if not tshark:
            skipping.need(self, "tshark not installed")
        rec_dir = os.path.join(self.workdir, "rec")
        os.makedirs(rec_dir)
        sim = self.start_sim()
        config = {"gimbals": [gt.orion_tcp("main", sim.port)],
                  "record": {"dir": rec_dir, "max_file_mb": 100, "max_total_mb": 1000}}
        daemon = self.start_daemon(config)
        c = self.client(daemon)
        self.wait_connected(c)
        self.assertTrue(c.request("geopoint", lat=47.4, lon=8.55, alt=480.0)["ok"])
        time.sleep(3.0)  # every periodic packet kind at least once
        sim.stop()       # no more telemetry: STATE now holds the last packets recorded
        time.sleep(0.5)
        state = c.request("state")["state"]
        self.assertIn("record", state)
        daemon.stop(signal.SIGTERM)

        files = sorted(os.path.join(rec_dir, f) for f in os.listdir(rec_dir)
                       if f.endswith(".pcapng"))
        self.assertTrue(files, "no recording written")
        sent, json_records = compare_recording(self, tshark, state, files)
        # The command went out as a geopoint_cmd with the values asked for, and the JSON
        # requests and replies are there too.
        self.assertIn("geopoint_cmd", sent)
        for key, want in (("lat", 47.4), ("lon", 8.55), ("alt", 480.0)):
            got = float(sent["geopoint_cmd"]["orion.geopoint_cmd." + key][0])
            self.assertAlmostEqual(got, want, delta=1e-3, msg=key)
        self.assertGreaterEqual(json_records, 2)


    def test_viewpro_recording_matches_state(self):
        tshark = shutil.which("tshark")
        if not tshark:
            skipping.need(self, "tshark not installed")
        rec_dir = os.path.join(self.workdir, "rec-viewpro")
        os.makedirs(rec_dir)
        sim = self.start_sim("--protocol", "viewpro")
        config = {"gimbals": [gt.viewpro_tcp("nose", sim.port)],
                  "record": {"dir": rec_dir, "max_file_mb": 100, "max_total_mb": 1000}}
        daemon = self.start_daemon(config)
        c = self.client(daemon)
        self.wait_connected(c, telemetry=False)
        self.assertTrue(gt.wait_for(lambda: c.request("state")["state"].get("output"), 5.0))
        time.sleep(1.0)
        sim.stop()
        time.sleep(0.5)
        output = c.request("state")["state"]["output"]
        daemon.stop(signal.SIGTERM)

        latest = None
        for path in sorted(os.path.join(rec_dir, f) for f in os.listdir(rec_dir)):
            proc = subprocess.run([tshark, "-X", "lua_script:" + LUA, "-r", path, "-T", "json"],
                                  capture_output=True, text=True, timeout=120)
            self.assertEqual(proc.returncode, 0, proc.stderr)
            self.assertNotIn("Lua", proc.stderr)  # a Lua error, or another copy of the dissector
            for pkt in json.loads(proc.stdout or "[]", object_pairs_hook=pairs):
                layers = pkt["_source"][0]["layers"][0]
                self.assertNotIn("_ws.malformed", layers)
                if "viewpro" not in layers:
                    continue
                fields = {}
                flatten(layers["viewpro"][0], fields)
                self.assertEqual(fields.get("viewpro.checksum.status", ["good"]), ["good"])
                if fields.get("viewpro.frame", [""])[0].startswith("out"):
                    latest = fields
        self.assertIsNotNone(latest, "no OUT frame in the recording")
        want = {}

        def walk(prefix, value):
            if isinstance(value, dict):
                for k, v in value.items():
                    walk(prefix + "." + k, v)
            else:
                want[prefix] = value
        walk("viewpro", output)
        compared = 0
        for field, value in want.items():
            if field.endswith(".age_s"):
                continue  # gimbald's own bookkeeping
            self.assertIn(field, latest)
            compared += 1
            got = latest[field][0]
            if isinstance(value, (int, float)) and not isinstance(value, bool):
                self.assertAlmostEqual(float(got), value, delta=1e-4 + 1e-7 * abs(value),
                                       msg=field)
            else:
                self.assertEqual(got, str(value), field)
        print("compared %d Viewpro fields (%s)" % (compared, output.get("format")))
        self.assertGreaterEqual(compared, 10)


def compare_recording(self, tshark, state, files):
    """tshark reads `files`; the latest inbound packet of each STATE kind matches `state`."""
    latest, sent = {}, {}
    malformed = json_records = 0
    for path in files:
        proc = subprocess.run([tshark, "-X", "lua_script:" + LUA, "-r", path, "-T", "json"],
                              capture_output=True, text=True, timeout=120)
        self.assertEqual(proc.returncode, 0, proc.stderr)
        self.assertNotIn("Lua", proc.stderr)  # a Lua error, or another copy of the dissector
        for pkt in json.loads(proc.stdout or "[]", object_pairs_hook=pairs):
            layers = pkt["_source"][0]["layers"][0]
            if "_ws.malformed" in layers:
                malformed += 1
            if "json" in layers:
                json_records += 1
            if "orion" not in layers or not isinstance(layers["orion"][0], dict):
                continue
            fields = {}
            flatten(layers["orion"][0], fields)
            self.assertNotIn("bad", fields.get("orion.checksum.status", []))
            name = fields.get("orion.packet", [""])[0]
            if layers["frame"][0].get("frame.p2p_dir", ["1"])[0] != "1":
                sent[name] = fields  # what gimbald sent, not what the gimbal said
            elif "orion.request" not in fields:
                latest[name] = fields
    self.assertEqual(malformed, 0)

    steps = field_steps()
    compared = 0
    for state_key, packet in STATE_PACKETS.items():
        shown = state.get(state_key)
        if shown is None:
            continue
        self.assertIn(packet, latest, "STATE has %s but the recording no %s" %
                      (state_key, packet))
        fields = latest[packet]
        for key, value in shown.items():
            field = "orion.%s.%s" % (packet, key)
            if field not in fields:
                continue  # derived (utc, roll, target, age_s) or not on the wire
            values = value if isinstance(value, list) else [value]
            got = fields[field]
            self.assertEqual(len(got), len(values), field)
            step = steps.get((packet, key), 1.0)
            for want, g in zip(values, got):
                compared += 1
                with self.subTest(field=field):
                    if isinstance(want, bool):
                        self.assertEqual(g in ("1", "True", "true"), want)
                    elif isinstance(want, (int, float)):
                        self.assertLessEqual(abs(float(g) - want), step, field)
                    else:
                        self.assertEqual(str(want), g, field)
    print("compared %d field values of %d packet kinds" % (compared, len(latest)))
    self.assertGreaterEqual(compared, 36)
    for key in ("lat", "lon", "alt", "pan", "tilt", "mode"):
        self.assertIn("orion.geolocate_telemetry." + key, latest["geolocate_telemetry"])
    return sent, json_records


def check_record_supported():
    """Exit 77 when this gimbald does not know the `record` key (recorder not built in)."""
    if not gt.GIMBALD:
        return
    import tempfile
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "c.json")
        with open(path, "w") as f:
            json.dump({"gimbals": [], "record": {"dir": tmp}}, f)
        result = subprocess.run([gt.GIMBALD, "--check-config", "-c", path],
                                capture_output=True, text=True, timeout=20)
        if result.returncode != 0 and "record" in (result.stdout + result.stderr):
            print("skipped: gimbald has no `record` configuration")
            raise SystemExit(gt.SKIP)


if __name__ == "__main__":
    check_record_supported()
    gt.main()
