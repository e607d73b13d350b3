"""gimbal-replay and gimbal-export on a real recording (contract section 12, issue 12).

A 30 s simulated flight: gimbald connected to gimbal-sim over TCP, recording on, with a
geopoint and then a path commanded during it. The recording is replayed at --speed 10 into
a second gimbald, and the telemetry both daemons show is compared at matching gimbal system
times (system_time_ms): lat, lon, alt, pan, tilt and mode must be equal. The same file is
exported as GeoJSON (checked against RFC 7946's structure), KML (parsed as XML, KML 2.2
names) and CSV (one row per telemetry packet, counted by an independent pcapng reader here
and by tshark with dissectors/gimbald.lua).

The flight is recorded by gimbald's own recorder (the "record" configuration). The shorter
checks (damaged files, pty, Viewpro, bad input) use recordings written here by
pcapng_test_writer.py from gimbal-sim's bytes."""

import csv
import io
import json
import os
import re
import shutil
import socket
import struct
import subprocess
import sys
import time
import xml.etree.ElementTree as ET

import gimbaltest as gt
from pcapng_test_writer import INBOUND, OUTBOUND, PcapngWriter, split_orion

GIMBAL_REPLAY = os.environ.get("GIMBAL_REPLAY")
GIMBAL_EXPORT = os.environ.get("GIMBAL_EXPORT")
FLIGHT_S = 30.0
SPEED = 10
COMPARED = ("lat", "lon", "alt", "pan", "tilt", "mode")
KML = "{http://www.opengis.net/kml/2.2}"


# --- an independent pcapng reader (not the C++ one under test) -----------------------------

def read_pcapng(path):
    """Yields (interface_name, time_us, direction, dissector, pdu) for every EPB."""
    with open(path, "rb") as f:
        data = f.read()
    at, endian, names = 0, "<", []
    while at + 12 <= len(data):
        if data[at:at + 4] == b"\x0a\x0d\x0d\x0a":
            endian = "<" if data[at + 8:at + 12] == b"\x4d\x3c\x2b\x1a" else ">"
            names = []
        block_type, total = struct.unpack_from(endian + "II", data, at)
        if total < 12 or at + total > len(data):
            break  # cut short: stop at the last complete block
        body = data[at + 8:at + total - 4]
        if block_type == 1:
            name, opt = "", 8
            while opt + 4 <= len(body):
                code, length = struct.unpack_from(endian + "HH", body, opt)
                if code == 0:
                    break
                if code == 2:
                    name = body[opt + 4:opt + 4 + length].decode()
                opt += 4 + length + (-length % 4)
            names.append(name)
        elif block_type == 6:
            itf, hi, lo, cap, _ = struct.unpack_from(endian + "IIIII", body, 0)
            packet = body[20:20 + cap]
            opt, flags = 20 + cap + (-cap % 4), 0
            while opt + 4 <= len(body):
                code, length = struct.unpack_from(endian + "HH", body, opt)
                if code == 0:
                    break
                if code == 2:
                    flags = struct.unpack_from(endian + "I", body, opt + 4)[0]
                opt += 4 + length + (-length % 4)
            dissector, tlv = "", 0
            while tlv + 4 <= len(packet):
                tag, length = struct.unpack_from(">HH", packet, tlv)
                tlv += 4
                if tag == 0:
                    break
                if tag == 12:
                    dissector = packet[tlv:tlv + length].decode()
                tlv += length + (-length % 4)
            yield names[itf], (hi << 32) | lo, flags & 3, dissector, packet[tlv:]
        at += total


def telemetry_system_times(paths, gimbal):
    """system_time_ms of every GeolocateTelemetry frame the gimbal sent, from the raw bytes
    of the recording's files in order."""
    stream = b"".join(pdu for path in paths for name, _, direction, _, pdu in read_pcapng(path)
                      if name == "gimbal:" + gimbal and direction == INBOUND)
    frames, _ = split_orion(stream)
    return [struct.unpack_from(">I", f, 4)[0] for kind, f in frames
            if kind == "orion" and f[2] == 212 and f[3] >= 4]


# --- the test ---------------------------------------------------------------------------------

def telemetry_by_system_time(messages):
    out = {}
    for m in messages:
        t = m.get("state", {}).get("telemetry")
        if t:
            out[t["system_time_ms"]] = {k: t[k] for k in COMPARED}
    return out


class ReplayExportTest(gt.GimbaldTestCase):
    def record_flight(self):
        """Flies 30 s with a geopoint and a path; returns (recording files, telemetry seen).
        Files rotate at 20 kB, so the flight spans several and the tools read them as one."""
        sim = self.start_sim()
        record_dir = os.path.join(self.workdir, "recordings")
        os.makedirs(record_dir)
        daemon = self.start_daemon({"gimbals": [gt.orion_tcp("main", sim.port)],
                                    "record": {"dir": record_dir, "max_file_mb": 0.02,
                                               "max_total_mb": 10}})
        client = self.client(daemon)
        state = self.wait_connected(client)
        self.assertOk(client.request("subscribe", rate_hz=50, keys=["telemetry"], ttl_s=120))
        lat, lon = state["telemetry"]["lat"], state["telemetry"]["lon"]
        start = time.monotonic()
        seen = client.collect(8)
        self.assertOk(client.request("geopoint", lat=lat + 0.004, lon=lon + 0.004, alt=100))
        seen += client.collect(10)
        points = [{"lat": lat + 0.002 * k, "lon": lon - 0.003, "alt": 120} for k in range(3)]
        self.assertOk(client.request("path", points=points))
        seen += client.collect(FLIGHT_S - (time.monotonic() - start))
        daemon.stop()
        files = sorted(os.path.join(record_dir, f) for f in os.listdir(record_dir)
                       if f.endswith(".pcapng"))
        self.assertGreaterEqual(len(files), 2, files)
        return files, telemetry_by_system_time(seen)

    def replay(self, paths):
        """Replays the recording at 10x into a second gimbald; returns the telemetry seen."""
        replay = subprocess.Popen([GIMBAL_REPLAY, *paths, "--tcp", "0", "--speed", str(SPEED),
                                   "--progress-every", "0"],
                                  stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        self.addCleanup(lambda: (gt.stop_process(replay), replay.stdout.close(),
                                 replay.stderr.close()))
        line = gt.read_line(replay.stdout, gt.START_TIMEOUT_S)
        self.assertTrue(line and line.startswith("tcp: "), line)
        port = int(line.strip().rsplit(":", 1)[1])
        daemon = self.start_daemon({"gimbals": [gt.orion_tcp("main", port)]})
        client = self.client(daemon)
        self.wait_connected(client, timeout=gt.START_TIMEOUT_S, telemetry=False)
        self.assertOk(client.request("subscribe", rate_hz=50, keys=["telemetry"], ttl_s=60))
        seen = []
        deadline = time.monotonic() + FLIGHT_S / SPEED + 10
        while replay.poll() is None and time.monotonic() < deadline:
            seen += client.collect(0.5)
        self.assertEqual(replay.wait(timeout=5), 0, replay.stderr.read().decode())
        out = replay.stdout.read().decode()
        self.assertIn("playing: gimbal main (orion)", out)
        # Recorded timing divided by --speed: ~30 s of recording in ~3 s.
        done = re.search(r"done: \d+ packets, \d+ bytes, ([\d.]+) s recorded in ([\d.]+) s", out)
        self.assertIsNotNone(done, out)
        recorded_s, played_s = float(done.group(1)), float(done.group(2))
        self.assertGreater(recorded_s, FLIGHT_S - 3)
        self.assertGreater(played_s, recorded_s / SPEED - 0.2)
        self.assertLess(played_s, recorded_s / SPEED + 1.5)
        seen += client.collect(0.3)
        daemon.stop()
        return telemetry_by_system_time(seen)

    def export(self, paths, fmt, *args):
        out = os.path.join(self.workdir, "export." + fmt)
        result = subprocess.run([GIMBAL_EXPORT, *paths, "--format", fmt, "-o", out, *args],
                                capture_output=True, text=True, timeout=30)
        self.assertEqual(result.returncode, 0, result.stderr)
        with open(out, encoding="utf-8") as f:
            return f.read()

    def test_record_replay_and_export(self):
        paths, flight = self.record_flight()
        self.assertGreater(len(flight), 100, "too little telemetry seen in flight")
        modes = {v["mode"] for v in flight.values()}
        self.assertTrue({"geopoint", "path"} <= modes, modes)

        replayed = self.replay(paths)
        system_times = telemetry_system_times(paths, "main")
        common = sorted(set(flight) & set(replayed))
        sys.stderr.write("flight: %d files, %d telemetry packets recorded, %d seen in flight, "
                         "%d seen in replay, %d compared\n" % (len(paths), len(system_times),
                                                              len(flight), len(replayed),
                                                              len(common)))
        # Everything the replay showed was recorded, and it showed a fair sample of it
        # (STATE at 50 Hz of telemetry arriving at 100 Hz).
        self.assertLessEqual(set(replayed), set(system_times))
        self.assertGreater(len(replayed), len(system_times) * 0.3)
        self.assertGreater(len(common), 50, "too few matching system times: %d of %d" %
                           (len(common), len(replayed)))
        for t in common:
            self.assertEqual(flight[t], replayed[t], "telemetry at system_time_ms %d" % t)
        self.assertTrue({"geopoint", "path"} <= {replayed[t]["mode"] for t in common})

        self.assertGreater(len(system_times), 250)
        self.check_tshark_count(paths, len(system_times))
        self.check_csv(self.export(paths, "csv"), system_times, flight)
        self.check_geojson(json.loads(self.export(paths, "geojson", "--footprint-every", "5")),
                           flight)
        self.check_kml(self.export(paths, "kml"))

    def check_tshark_count(self, paths, telemetry_packets):
        """tshark with the project's dissector counts the same GeolocateTelemetry packets as
        the test's own reader (skipped where tshark is not installed)."""
        tshark = shutil.which("tshark")
        lua = os.path.join(os.environ.get("GIMBAL_SOURCE_DIR", ""), "dissectors", "gimbald.lua")
        if not tshark or not os.path.exists(lua):
            sys.stderr.write("tshark or dissectors/gimbald.lua missing: tshark count not checked\n")
            return
        counted = 0
        for path in paths:
            result = subprocess.run([tshark, "-X", "lua_script:" + lua, "-r", path, "-Y",
                                     "orion.id == 212", "-T", "fields", "-e", "orion.id"],
                                    capture_output=True, text=True, timeout=60)
            self.assertEqual(result.returncode, 0, result.stderr)
            counted += len(result.stdout.split())
        self.assertEqual(counted, telemetry_packets)

    def check_csv(self, text, system_times, flight):
        rows = list(csv.reader(io.StringIO(text)))
        header, rows = rows[0], rows[1:]
        for column in ("time", "system_time_ms", "lat", "lon", "alt", "pan", "tilt",
                       "target_lat", "target_lon", "target_alt", "mode"):
            self.assertIn(column, header)
        self.assertEqual(len(rows), len(system_times), "one row per telemetry packet")
        col = {name: i for i, name in enumerate(header)}
        self.assertEqual([int(r[col["system_time_ms"]]) for r in rows], system_times)
        for r in rows:
            self.assertEqual(len(r), len(header))
            self.assertRegex(r[col["time"]], r"^\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d\.\d{3}Z$")
            t = int(r[col["system_time_ms"]])
            if t in flight:
                self.assertAlmostEqual(float(r[col["lat"]]), flight[t]["lat"], places=7)
                self.assertAlmostEqual(float(r[col["pan"]]), flight[t]["pan"], places=4)
                self.assertEqual(r[col["mode"]], flight[t]["mode"])

    def check_position(self, position, three_d):
        self.assertIsInstance(position, list)
        self.assertEqual(len(position), 3 if three_d else 2)
        self.assertTrue(all(isinstance(x, (int, float)) for x in position))
        lon, lat = position[0], position[1]
        self.assertTrue(-180 <= lon <= 180 and -90 <= lat <= 90, position)

    def check_geojson(self, doc, flight):
        """RFC 7946: FeatureCollection of Features; [lon, lat, alt]; closed CCW rings."""
        self.assertEqual(doc["type"], "FeatureCollection")
        self.assertIsInstance(doc["features"], list)
        some = next(iter(flight.values()))
        kinds = {}
        for feature in doc["features"]:
            self.assertEqual(feature["type"], "Feature")
            self.assertIsInstance(feature["properties"], dict)
            geometry = feature["geometry"]
            kinds.setdefault(feature["properties"]["kind"], []).append(geometry)
            if geometry["type"] == "LineString":
                coords = geometry["coordinates"]
                self.assertGreaterEqual(len(coords), 2)
                for c in coords:
                    self.check_position(c, True)
            else:
                self.assertEqual(geometry["type"], "Polygon")
                for ring in geometry["coordinates"]:
                    self.assertGreaterEqual(len(ring), 4)
                    self.assertEqual(ring[0], ring[-1], "ring not closed")
                    for c in ring:
                        self.check_position(c, True)
                    area = sum(a[0] * b[1] - b[0] * a[1] for a, b in zip(ring, ring[1:]))
                    self.assertGreater(area, 0, "exterior ring not counter-clockwise")
        self.assertEqual(len(kinds.get("aircraft_track", [])), 1)
        self.assertGreaterEqual(len(kinds.get("target_track", [])), 1)
        self.assertGreaterEqual(len(kinds.get("footprint", [])), 5)  # 30 s every 5 s
        track = kinds["aircraft_track"][0]["coordinates"]
        # Longitude first: the track lies where the flight's telemetry was.
        self.assertLess(abs(track[0][0] - some["lon"]) + abs(track[0][1] - some["lat"]), 0.1)

    def check_kml(self, text):
        root = ET.fromstring(text.encode())
        self.assertEqual(root.tag, KML + "kml")
        allowed = {"kml", "Document", "name", "Style", "LineStyle", "PolyStyle", "color", "width",
                   "Placemark", "Folder", "TimeSpan", "begin", "end", "TimeStamp", "when",
                   "styleUrl", "ExtendedData", "Data", "value", "LineString", "tessellate",
                   "altitudeMode", "coordinates", "Polygon", "outerBoundaryIs", "LinearRing"}
        for element in root.iter():
            self.assertTrue(element.tag.startswith(KML), element.tag)
            self.assertIn(element.tag[len(KML):], allowed)
        document = root.find(KML + "Document")
        self.assertIsNotNone(document)
        placemarks = list(document.iter(KML + "Placemark"))
        lines = [p.find(KML + "LineString") for p in placemarks if p.find(KML + "LineString")
                 is not None]
        polygons = [p.find(KML + "Polygon") for p in placemarks if p.find(KML + "Polygon")
                    is not None]
        self.assertGreaterEqual(len(lines), 2)
        self.assertGreaterEqual(len(polygons), 3)  # 30 s every 10 s
        for geometry in lines + polygons:
            self.assertEqual(geometry.find(KML + "altitudeMode").text, "absolute")
        for coords in root.iter(KML + "coordinates"):
            for tuple_text in coords.text.split():
                lon, lat, alt = (float(x) for x in tuple_text.split(","))
                self.assertTrue(-180 <= lon <= 180 and -90 <= lat <= 90)
        for polygon in polygons:
            ring = polygon.find(KML + "outerBoundaryIs/" + KML + "LinearRing/" + KML + "coordinates")
            tuples = ring.text.split()
            self.assertEqual(tuples[0], tuples[-1])



def capture(port, seconds, send=b""):
    """The bytes a gimbal-sim sends to a TCP client within `seconds` (after sending `send`),
    as (receive time in microseconds, chunk) pairs."""
    chunks = []
    with socket.create_connection(("127.0.0.1", port), timeout=gt.START_TIMEOUT_S) as s:
        if send:
            s.sendall(send)
        s.settimeout(0.2)
        deadline = time.monotonic() + seconds
        while time.monotonic() < deadline:
            try:
                data = s.recv(65536)
            except socket.timeout:
                continue
            if not data:
                break
            chunks.append((time.time_ns() // 1000, data))
    return chunks


class ToolsTest(gt.GimbaldTestCase):
    """Shorter checks on recordings written here: damaged files, pty, Viewpro, errors."""

    def orion_recording(self, seconds=2.0, cut=0, extra_gimbal=False):
        sim = self.start_sim()
        path = os.path.join(self.workdir, "orion.pcapng")
        interfaces = [("gimbal:main", "orion tcp 127.0.0.1:%d" % sim.port)]
        if extra_gimbal:
            interfaces.append(("gimbal:nose", "viewpro serial /dev/ttyUSB0"))
        writer = PcapngWriter(path, interfaces + [("json", "")])
        pending, frames = b"", []
        for t, data in capture(sim.port, seconds):
            pieces, pending = split_orion(pending + data)
            for dissector, pdu in pieces:
                writer.packet(0, t, dissector, pdu, INBOUND)
                if dissector == "orion":
                    frames.append(pdu)
        writer.packet(len(interfaces), time.time_ns() // 1000, "gimbald-json",
                      b'{"cmd":"ping"}', INBOUND)
        writer.close()
        if cut:
            with open(path, "r+b") as f:
                f.truncate(os.path.getsize(path) - cut)
        return path, frames

    def test_truncated_recording_over_a_pty(self):
        path, frames = self.orion_recording(cut=3)
        recorded = {struct.unpack_from(">I", f, 4)[0] for f in frames if f[2] == 212}
        link = os.path.join(self.workdir, "replay-pty")
        replay = subprocess.Popen([GIMBAL_REPLAY, path, "--no-tcp", "--pty", link, "--hold",
                                   "--speed", "2"], stdout=subprocess.PIPE,
                                  stderr=subprocess.PIPE)
        self.addCleanup(lambda: (gt.stop_process(replay), replay.stdout.close(),
                                 replay.stderr.close()))
        line = gt.read_line(replay.stdout, gt.START_TIMEOUT_S)
        self.assertTrue(line.startswith("pty: /dev/"), line)
        daemon = self.start_daemon({"gimbals": [gt.orion_serial("main", link)]})
        state = self.wait_connected(self.client(daemon))
        self.assertIn(state["telemetry"]["system_time_ms"], recorded)
        self.assertTrue(gt.wait_for(lambda: gt.read_line(replay.stdout, 0.5).startswith("done:"),
                                    10))
        self.assertEqual(gt.stop_process(replay), 0)
        self.assertIn("truncated", replay.stderr.read().decode())
        # The export reads the same file to its last complete block.
        result = gt.run([GIMBAL_EXPORT, path, "--format", "csv"])
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("truncated", result.stderr)
        self.assertEqual(len(result.stdout.splitlines()) - 1, len(recorded))

    def test_viewpro_export(self):
        sim = self.start_sim("--protocol", "viewpro")
        path = os.path.join(self.workdir, "viewpro.pcapng")
        writer = PcapngWriter(path, [("gimbal:nose", "viewpro tcp 127.0.0.1:%d" % sim.port)])
        writer.packet(0, time.time_ns() // 1000, "viewpro", gt.viewpro_mode(format="out2"),
                      OUTBOUND)
        stream = b""
        for t, data in capture(sim.port, 1.5, send=gt.viewpro_mode(format="out2")):
            writer.packet(0, t, "viewpro", data, INBOUND)  # chunks, not frames: still valid
            stream += data
        writer.close()
        frames = 0
        while len(stream) >= 76:
            self.assertEqual(stream[:2], b"\xfe\xfc")  # OUT2 only, back to back
            stream, frames = stream[76:], frames + 1
        self.assertGreater(frames, 5)
        result = gt.run([GIMBAL_EXPORT, path, "--format", "csv"])
        self.assertEqual(result.returncode, 0, result.stderr)
        rows = list(csv.DictReader(io.StringIO(result.stdout)))
        self.assertEqual(len(rows), frames)
        self.assertTrue(all(r["mode"] == "out2" and r["lat"] and r["alt_msl"] and r["pan"]
                            for r in rows), rows[0])
        doc = json.loads(gt.run([GIMBAL_EXPORT, path, "--format", "geojson"]).stdout)
        track = [f for f in doc["features"] if f["properties"]["kind"] == "aircraft_track"]
        self.assertEqual(len(track), 1)
        for position in track[0]["geometry"]["coordinates"]:
            self.assertEqual(len(position), 2)  # no ellipsoidal height in Viewpro frames
            self.assertAlmostEqual(position[1], float(rows[0]["lat"]), delta=0.1)

    def test_bad_input(self):
        garbage = os.path.join(self.workdir, "garbage.pcapng")
        with open(garbage, "wb") as f:
            f.write(b"not a capture" * 10)
        path, _ = self.orion_recording(seconds=0.5, extra_gimbal=True)
        for tool in (GIMBAL_REPLAY, GIMBAL_EXPORT):
            fmt = ["--format", "csv"] if tool == GIMBAL_EXPORT else ["--tcp", "0"]
            for args, message in (([os.path.join(self.workdir, "missing")], "cannot open"),
                                  ([garbage], "not a pcapng file"),
                                  ([path], "several gimbals (main, nose)"),
                                  ([path, "--gimbal", "tail"], "no gimbal \"tail\""),
                                  ([path, "--speed" if tool == GIMBAL_REPLAY else "--format",
                                    "fast"], "")):
                result = gt.run([tool] + fmt + args)
                self.assertEqual(result.returncode, 1, (tool, args, result.stderr))
                self.assertIn(message, result.stderr)
        # The JSON interface is no gimbal.
        result = gt.run([GIMBAL_EXPORT, path, "--format", "csv", "--gimbal", "json"])
        self.assertEqual(result.returncode, 1)

if __name__ == "__main__":
    if not GIMBAL_REPLAY or not GIMBAL_EXPORT:
        print("skipped: GIMBAL_REPLAY or GIMBAL_EXPORT not set")
        sys.exit(gt.SKIP)
    gt.main()
