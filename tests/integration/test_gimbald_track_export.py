"""The visual track in the flight recording and in gimbal-export (contract section 20,
"Recording and export"; docs/recording-format.md, docs/replay-export.md).

A real gimbald records while a real gimbal-track follows the simulator's `farm` landmark
(gimbal-sim --video, the simulated Orion's H.264): two tracks on the farm, the first ended
by track_stop (stopped), the second by a client's geopoint (overridden). The recording's
interface track:main is read by the independent pcapng reader of
test_gimbal_replay_export.py (the records: every event and STATE track after each box, as a
subscriber would have them) and by tshark, with and without dissectors/gimbald.lua. Then
gimbal-export writes GeoJSON (parsed with Python's json), KML (xml.etree) and track-csv, and
each must hold both tracks, their ids and end reasons, with positions near the farm.
"""

import csv
import glob
import io
import json
import math
import os
import shutil
import subprocess
import xml.etree.ElementTree as ET

import gimbaltest as gt
import skipping
from pcapng_test_writer import OUTBOUND, PcapngWriter
from test_gimbal_replay_export import read_pcapng
from test_gimbald_record import parse as parse_recording

GIMBAL_TRACK = os.environ.get("GIMBAL_TRACK")
GIMBAL_EXPORT = os.environ.get("GIMBAL_EXPORT")
SOURCE = os.environ.get("GIMBAL_SOURCE_DIR",
                        os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
KML = "{http://www.opengis.net/kml/2.2}"

# sim::landmarks(): docs/simulator.md "Video".
FARM = {"lat": 45.697301, "lon": -121.480740, "alt": 414.6}
NEAR_M = 60  # as test_gimbald_track.py: the located farm while the camera holds still


def metres_between(a, b):
    return math.dist(gt.lla_to_ecef(a["lat"], a["lon"], a["alt"]),
                     gt.lla_to_ecef(b["lat"], b["lon"], b["alt"]))


def near_farm(lon, lat, alt):
    return metres_between({"lat": lat, "lon": lon, "alt": alt}, FARM) < NEAR_M


class TrackRecordingExport(gt.GimbaldTestCase):

    def setUp(self):
        super().setUp()
        if not GIMBAL_EXPORT:
            skipping.need(self, "GIMBAL_EXPORT not given")

    def look_at_farm(self, c):
        """Points the camera at the farm; its image position once it is near the centre."""
        self.assertOk(c.request("geopoint", gimbal="main", **FARM))

        at = gt.settled_projection(c, "main", FARM)
        self.assertTrue(at, "the farm never came to the centre of the picture")
        return at

    def located(self, c, track_id, frames):
        def check():
            reply = c.request("state", gimbal="main", keys=["track"])
            t = reply and reply.get("ok") and reply["state"]["track"]
            return t if t and t["id"] == track_id and t["state"] == "tracking" and \
                t["ground"] and t["frames"] >= frames else None
        t = gt.wait_for(check, 20, 0.1)
        self.assertTrue(t, "track %d never located" % track_id)
        return t

    def record_two_tracks(self):
        """Records two tracks on the farm; returns (files, [(id, reason)])."""
        self.video_port = video_port = gt.free_port()
        sim = self.start_sim("--video", "udp://127.0.0.1:%d" % video_port, "--no-video-klv",
                             "--speed", "0", want=("tcp", "video"))
        self.sim_port = sim.port
        rec = os.path.join(self.workdir, "rec")
        os.mkdir(rec)
        daemon = self.start_daemon({
            "gimbals": [dict(gt.orion_tcp("main", sim.port),
                             video={"input": "udp://127.0.0.1:%d" % video_port,
                                    "tracking": {"tracker": "kcf"}})],
            "record": {"dir": rec}})
        c = self.client(daemon)
        self.assertTrue(daemon.wait_log(lambda e: e.get("event") == "track_process_ready",
                                        timeout=20), "gimbal-track never said hello")

        def video_up():
            reply = c.request("state", gimbal="main", keys=["video", "telemetry"])
            s = reply and reply.get("ok") and reply["state"]
            return s and s["video"] and s["video"]["connected"] and s["telemetry"]
        self.assertTrue(gt.wait_for(video_up, 25, 0.2), "no video or telemetry")

        ended = []
        # Track 1: followed, then stopped.
        at = self.look_at_farm(c)
        reply = c.request("track", gimbal="main", x=at["x"], y=at["y"])
        self.assertOk(reply)
        first = reply["track"]["id"]
        self.located(c, first, 30)
        self.assertEqual(c.request("track_stop", gimbal="main")["stopped"], first)
        ended.append((first, "stopped"))
        # Track 2: followed without steering, then a client's geopoint takes the gimbal.
        at = self.look_at_farm(c)
        reply = c.request("track", gimbal="main", x=at["x"], y=at["y"], steer=False)
        self.assertOk(reply)
        second = reply["track"]["id"]
        self.located(c, second, 20)
        self.assertOk(c.request("geopoint", gimbal="main", **FARM))
        ended.append((second, "overridden"))
        for track_id, reason in ended:
            self.assertTrue(daemon.wait_log(lambda e: e.get("event") == "track_end" and
                                            e.get("id") == track_id and
                                            e.get("reason") == reason, 10),
                            "no track_end %d %s" % (track_id, reason))
        self.assertEqual(daemon.stop(), 0)
        files = sorted(glob.glob(os.path.join(rec, "*.pcapng")))
        self.assertTrue(files)
        return files, ended

    def test_tracks_recorded_and_exported(self):
        if not GIMBAL_TRACK:
            skipping.need(self, "GIMBAL_TRACK not given")
        files, ended = self.record_two_tracks()
        ids = [track_id for track_id, _ in ended]
        records = self.check_recording(files, ended)
        self.check_tshark(files, len(records), ended)
        geojson = self.check_geojson(files, ended)
        self.check_kml(files, ids, geojson)
        self.check_track_csv(files, ended, records)

    def test_a_recording_without_tracking(self):
        """Without interface track:NAME, track-csv is exit 1 and says why; the other formats
        export the flight as before, with no object features."""
        path = os.path.join(self.workdir, "untracked.pcapng")
        writer = PcapngWriter(path, [("gimbal:main", "orion tcp 127.0.0.1:8747"),
                                     ("json", "gimbald JSON requests and replies")])
        writer.close()
        r = subprocess.run([GIMBAL_EXPORT, path, "--format", "track-csv"], capture_output=True,
                           text=True, timeout=30)
        self.assertEqual(r.returncode, 1, r.stderr)
        self.assertIn("no visual track of gimbal main (interface track:main", r.stderr)
        self.assertEqual(r.stdout, "")
        text, summary = self.export([path], "geojson")
        self.assertEqual(json.loads(text), {"type": "FeatureCollection", "features": []})
        self.assertNotIn("object", summary)
        text, _ = self.export([path], "kml")
        self.assertNotIn("object", text)
        ET.fromstring(text)

    def export(self, files, fmt):
        r = subprocess.run([GIMBAL_EXPORT, *files, "--format", fmt], capture_output=True,
                           text=True, timeout=60)
        self.assertEqual(r.returncode, 0, r.stderr)
        return r.stdout, r.stderr

    def check_recording(self, files, ended):
        """The records of track:main, read here: outbound gimbald-json, one JSON object
        each - the events as logged and STATE track after every box. Returns them."""
        # After the existing interfaces (gimbal, json, video), so their ids stay as they were.
        for f in files:
            self.assertEqual([(name, description) for name, description, *_ in
                              parse_recording(f)["interfaces"]],
                             [("gimbal:main", "orion tcp 127.0.0.1:%d" % self.sim_port),
                              ("json", "gimbald JSON requests and replies"),
                              ("video:main", "mp2t udp://127.0.0.1:%d" % self.video_port),
                              ("track:main", "gimbald-json visual track, kcf")])
        packets = [p for f in files for p in read_pcapng(f)]
        track = [p for p in packets if p[0] == "track:main"]
        self.assertTrue(all(d == OUTBOUND and dissector == "gimbald-json"
                            for _, _, d, dissector, _ in track))
        records = [(t, json.loads(pdu)) for _, t, _, _, pdu in track]
        self.assertEqual([t for t, _ in records], sorted(t for t, _ in records))
        events = [(m["event"], m["id"], m.get("reason")) for _, m in records
                  if m["type"] == "event"]
        expected = []
        for track_id, reason in ended:
            expected.append(("track_start", track_id, None))
            expected.append(("track_end", track_id, reason))
        # Losses on the way are allowed; starts and ends come in this order.
        self.assertEqual([e for e in events if e[0] in ("track_start", "track_end")], expected)
        boxes = [m for _, m in records if m["type"] == "state"]
        self.assertTrue(all(m["gimbal"] == "main" and set(m["state"]) == {"track"}
                            for m in boxes))
        for track_id, _ in ended:
            mine = [m["state"]["track"] for m in boxes if m["state"]["track"]["id"] == track_id]
            self.assertGreaterEqual(len(mine), 20, "too few STATE records of track %d" % track_id)
            for key in ("state", "box", "centre", "confidence", "ground", "velocity", "frames",
                        "started_utc", "age_s"):
                self.assertIn(key, mine[-1])
            self.assertEqual(mine[-1]["frames"], len(mine), "one record per box handled")
            g = mine[-1]["ground"]
            self.assertTrue(near_farm(g["lon"], g["lat"], g["alt"]), g)
        return records

    def check_tshark(self, files, count, ended):
        """tshark reads the interface without error, as outbound gimbald-json PDUs; with
        dissectors/gimbald.lua each is JSON and its Info names the event or the track."""
        tshark = shutil.which("tshark")
        if not tshark:
            skipping.need(self, "tshark not installed")
        lua = os.path.join(SOURCE, "dissectors", "gimbald.lua")
        for extra in ([], ["-X", "lua_script:" + lua]):
            rows = []
            for f in files:
                r = subprocess.run([tshark, *extra, "-r", f, "-Y",
                                    'frame.interface_name == "track:main"', "-T", "fields",
                                    "-e", "exported_pdu.prot_name",
                                    "-e", "frame.packet_flags_direction",
                                    "-e", "json.member_with_value", "-e", "_ws.col.Info"],
                                   capture_output=True, text=True, timeout=120)
                self.assertEqual(r.returncode, 0, r.stderr)
                rows += [line.split("\t") for line in r.stdout.splitlines()]
            self.assertEqual(len(rows), count)
            self.assertTrue(all(row[0] == "gimbald-json" and int(row[1], 0) == 2
                                for row in rows), rows[:3])
            if not extra:
                continue
            self.assertTrue(all("type:" in row[2] for row in rows), rows[:3])
            expected = []
            for track_id, reason in ended:
                expected += ["track_start id %d" % track_id,
                             "track_end id %d (%s)" % (track_id, reason)]
            self.assertEqual([row[3] for row in rows if row[3].startswith("track_") and
                              "lost" not in row[3] and "reacquired" not in row[3]], expected)
            self.assertTrue(any(row[3].startswith("track %d tracking, confidence " % ended[0][0])
                                for row in rows), rows[:3])

    def check_geojson(self, files, ended):
        text, summary = self.export(files, "geojson")
        doc = json.loads(text)
        self.assertEqual(doc["type"], "FeatureCollection")
        kinds = [f["properties"]["kind"] for f in doc["features"]]
        self.assertIn("aircraft_track", kinds)  # beside the aircraft's
        lines = [f for f in doc["features"] if f["properties"]["kind"] == "object_track"]
        self.assertEqual([(f["properties"]["id"], f["properties"]["end_reason"])
                          for f in lines], ended)
        for f in lines:
            p = f["properties"]
            self.assertEqual(p["gimbal"], "main")
            self.assertLess(p["start"], p["end"])
            self.assertEqual(f["geometry"]["type"], "LineString")
            coords = f["geometry"]["coordinates"]
            self.assertEqual(len(coords), p["points"])
            self.assertGreaterEqual(len(coords), 20)
            near = [c for c in coords if near_farm(*c)]
            # The filter settles while the camera holds still: most positions, and the last,
            # are on the farm.
            self.assertGreater(len(near), 0.8 * len(coords), coords[:5])
            self.assertTrue(near_farm(*coords[-1]), coords[-1])
        ends = [f for f in doc["features"] if f["properties"]["kind"] == "object_event" and
                f["properties"]["event"] == "track_end"]
        self.assertEqual([(f["properties"]["id"], f["properties"]["reason"]) for f in ends],
                         ended)
        self.assertIn("2 object tracks", summary)
        return doc

    def check_kml(self, files, ids, geojson):
        """The same tracks in KML: heights above mean sea level, with the geoid undulation
        the gimbal reported for the aircraft (the difference of the aircraft's heights in
        GeoJSON, above the ellipsoid, and in KML)."""
        text, _ = self.export(files, "kml")
        root = ET.fromstring(text)
        self.assertEqual(root.tag, KML + "kml")
        document = root.find(KML + "Document")
        aircraft = next(p for p in document.findall(KML + "Placemark")
                        if p.findtext(KML + "name") == "aircraft track")
        aircraft_msl = float(aircraft.find(KML + "LineString").findtext(KML + "coordinates")
                             .split()[-1].split(",")[2])
        geo = {f["properties"]["kind"] + str(f["properties"].get("id", "")):
               f["geometry"]["coordinates"] for f in geojson["features"]}
        undulation = geo["aircraft_track"][-1][2] - aircraft_msl
        folders = {f.findtext(KML + "name"): f for f in document.findall(KML + "Folder")}
        self.assertIn("object tracks", folders)
        tracks = folders["object tracks"].findall(KML + "Folder")
        self.assertEqual([f.findtext(KML + "name") for f in tracks],
                         ["object track %d" % i for i in ids])
        for folder, track_id in zip(tracks, ids):
            line = next(p for p in folder.findall(KML + "Placemark")
                        if p.findtext(KML + "name") == "object %d" % track_id)
            data = {d.get("name"): d.findtext(KML + "value")
                    for d in line.iter(KML + "Data")}
            self.assertEqual(data["id"], str(track_id))
            coords = [tuple(map(float, c.split(","))) for c in
                      line.find(KML + "LineString").findtext(KML + "coordinates").split()]
            self.assertGreaterEqual(len(coords), 20)
            ellipsoidal = geo["object_track%d" % track_id]
            self.assertEqual(len(coords), len(ellipsoidal))
            for (lon, lat, alt_msl), (glon, glat, galt) in zip(coords, ellipsoidal):
                self.assertEqual((lon, lat), (glon, glat))
                self.assertAlmostEqual(alt_msl, galt - undulation, delta=0.002)
            lon, lat, _ = coords[-1]
            self.assertLess(gt.ground_distance_m(lat, lon, FARM["lat"], FARM["lon"]), NEAR_M)

    def check_track_csv(self, files, ended, records):
        text, summary = self.export(files, "track-csv")
        rows = list(csv.DictReader(io.StringIO(text)))
        self.assertEqual(len(rows), len(records), "one row per track record")
        for row, (t, m) in zip(rows, records):
            self.assertEqual(row["gimbal"], "main")
            self.assertEqual(int(row["id"]), m["id"] if m["type"] == "event"
                             else m["state"]["track"]["id"])
            self.assertEqual(row["event"], m.get("event", ""))
        ends = [(int(r["id"]), r["reason"]) for r in rows if r["event"] == "track_end"]
        self.assertEqual(ends, ended)
        for track_id, _ in ended:
            located = [r for r in rows if r["id"] == str(track_id) and r["lat"]]
            self.assertGreaterEqual(len(located), 20)
            last = located[-1]
            self.assertTrue(near_farm(float(last["lon"]), float(last["lat"]),
                                      float(last["alt"])), last)
            self.assertIn(last["state"], ("tracking", "lost"))
            self.assertTrue(0 <= float(last["confidence"]) <= 1)
            self.assertTrue(-1 <= float(last["centre_x"]) <= 1)
        self.assertIn("visual track of gimbal main: 2 tracks", summary)


if __name__ == "__main__":
    gt.main()
