"""Recorded video (contract section 17, issue 20): with `record`, each gimbal's video is its
own interface `video:<gimbal>` in the pcapng - the input's MPEG-TS inbound (dissector mp2t),
the KLV sets gimbald generated outbound (dissector data). gimbal-export --format klv-csv
writes both KLV tracks; gimbal-replay --video sends the recorded TS to a second gimbald,
which sees the flight's video and KLV again.

The simulated Orion (gimbal-sim --video, KLV in the stream) and a Viewpro fed a TS without
KLV (gimbald generates) are recorded for a few seconds. The recording is read by the
independent pcapng reader of test_gimbal_replay_export.py, the TS by videotest.TsReader and
the KLV by st0601.py; the tools' results are compared with what those find.
"""

import csv
import glob
import io
import os
import re
import shutil
import subprocess
import threading
import time

import gimbaltest as gt
import skipping
import st0601
import videotest as vt
from pcapng_test_writer import INBOUND, OUTBOUND
from test_gimbal_replay_export import read_pcapng
from test_gimbald_video import feed_forever

GIMBAL_REPLAY = os.environ.get("GIMBAL_REPLAY")
GIMBAL_EXPORT = os.environ.get("GIMBAL_EXPORT")
SOURCE = os.environ.get("GIMBAL_SOURCE_DIR",
                        os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))


def state_video(client, gimbal):
    reply = client.request("state", gimbal=gimbal, keys=["video"])
    return reply["state"]["video"] if reply and reply.get("ok") else None


class VideoRecording(gt.GimbaldTestCase):
    def setUp(self):
        super().setUp()
        if not GIMBAL_REPLAY or not GIMBAL_EXPORT:
            skipping.need(self, "GIMBAL_REPLAY / GIMBAL_EXPORT not given")

    def record(self):
        """Records the two gimbals' video; returns the recording's files."""
        video_port, nose_port = gt.free_port(), gt.free_port()
        # Junk on the gimbal link too: docs/recording.md's junk filter must find it there.
        sim = self.start_sim("--video", "udp://127.0.0.1:%d" % video_port, "--speed", "0",
                             "--junk-every", "20", want=("tcp", "video"))
        rec = os.path.join(self.workdir, "rec")
        os.mkdir(rec)
        daemon = self.start_daemon({
            "gimbals": [dict(gt.orion_tcp("main", sim.port),
                             video={"input": "udp://127.0.0.1:%d" % video_port}),
                        {"name": "nose", "protocol": "viewpro", "link": {"type": "sim"},
                         "video": {"input": "udp://127.0.0.1:%d" % nose_port,
                                   "klv_rate_hz": 5}}],
            "record": {"dir": rec}})
        stop = threading.Event()
        feeder = threading.Thread(target=feed_forever, daemon=True, args=(
            vt.h264_access_units(self.workdir), nose_port, stop))
        feeder.start()
        self.addCleanup(stop.set)
        c = self.client(daemon)

        def enough():
            main, nose = state_video(c, "main"), state_video(c, "nose")
            return main and nose and main["klv_source"] == "stream" and \
                main["klv_sets"] >= 30 and nose["klv_source"] == "generated" and \
                nose["klv_sets"] >= 10
        self.assertTrue(gt.wait_for(enough, 30.0),
                        "%s %s" % (state_video(c, "main"), state_video(c, "nose")))
        stop.set()
        feeder.join()
        self.assertEqual(daemon.stop(), 0)
        return sorted(glob.glob(os.path.join(rec, "*.pcapng")))

    def check_junk_filter(self, paths):
        """docs/recording.md's display filter for junk from a gimbal finds the junk of the
        gimbal link and nothing else - not the KLV gimbald generated (`data` as well, on a
        `video:` interface; issue 25)."""
        tshark = shutil.which("tshark")
        if not tshark:
            skipping.need(self, "tshark not installed")
        with open(os.path.join(SOURCE, "docs", "recording.md")) as f:
            found = re.search(r"`([^`]+)` \(junk from a\s+gimbal", f.read())
        self.assertTrue(found, "docs/recording.md names no filter for junk from a gimbal")
        interfaces = []
        for path in paths:
            r = subprocess.run([tshark, "-r", path, "-Y", found.group(1), "-T", "fields",
                                "-e", "frame.interface_name"],
                               capture_output=True, text=True, timeout=60)
            self.assertEqual(r.returncode, 0, r.stderr)
            interfaces += r.stdout.split()
        self.assertTrue(interfaces, "the junk filter %r found no junk" % found.group(1))
        self.assertEqual(set(interfaces), {"gimbal:main"}, found.group(1))

    def export_klv(self, paths, gimbal):
        r = subprocess.run([GIMBAL_EXPORT, *paths, "--format", "klv-csv", "--gimbal", gimbal],
                           capture_output=True, text=True, timeout=30)
        self.assertEqual(r.returncode, 0, r.stderr)
        return list(csv.DictReader(io.StringIO(r.stdout))), r.stderr

    def test_recorded_exported_and_replayed(self):
        t0 = time.monotonic()
        paths = self.record()
        print("recorded in %.1f s" % (time.monotonic() - t0))
        self.assertTrue(paths)
        records = [r for p in paths for r in read_pcapng(p)]
        main_ts = [pdu for name, _, d, dissector, pdu in records
                   if name == "video:main" and d == INBOUND and dissector == "mp2t"]
        nose_sets = [pdu for name, _, d, dissector, pdu in records
                     if name == "video:nose" and d == OUTBOUND and dissector == "data"]
        self.assertGreater(len(main_ts), 50)
        for pdu in main_ts:  # whole datagrams of whole TS packets
            self.assertEqual(len(pdu) % 188, 0)
            self.assertEqual(pdu[0], 0x47)
        reader = vt.TsReader()
        for pdu in main_ts:
            reader.push(pdu)
        reader.flush()
        self.assertEqual(reader.video_type, 0x1B)
        self.assertGreater(reader.video_units, 15)
        stream_sets = [s for _, payload in reader.klv for s in vt.split_sets(payload)]
        self.assertGreater(len(stream_sets), 15)
        self.assertGreaterEqual(len(nose_sets), 10)
        for s in nose_sets:  # one whole generated set per record
            self.assertEqual(vt.split_sets(s), [s])
            self.assertEqual(st0601.decode(s)[0], "ok")

        # klv-csv: the stream's sets of main, in order, then nose's generated ones.
        rows, summary = self.export_klv(paths, "main")
        stream_rows = [r for r in rows if r["source"] == "stream"]
        self.assertEqual(len(stream_rows), len(stream_sets), summary)
        for row, raw in zip(stream_rows, stream_sets):
            status, reason, items = st0601.decode(raw)
            self.assertEqual(status, "ok", reason)
            self.assertEqual(row["precision_time_stamp"], items["precision_time_stamp"])
            self.assertAlmostEqual(float(row["sensor_latitude"]), items["sensor_latitude"],
                                   places=6)
        self.assertIn("video of gimbal main", summary)
        rows, summary = self.export_klv(paths, "nose")
        self.assertEqual([r["source"] for r in rows], ["generated"] * len(nose_sets), summary)
        for row, raw in zip(rows, nose_sets):
            items = st0601.decode(raw)[2]
            self.assertAlmostEqual(float(row["sensor_longitude"]), items["sensor_longitude"],
                                   places=6)

        print("exported at %.1f s" % (time.monotonic() - t0))
        self.check_junk_filter(paths)
        # gimbal-replay --video into a second gimbald: the recorded KLV comes back unchanged.
        video_port = gt.free_port()
        replay = subprocess.Popen(
            [GIMBAL_REPLAY, *paths, "--gimbal", "main", "--tcp", "0", "--loop",
             "--progress-every", "0", "--video", "udp://127.0.0.1:%d" % video_port],
            stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        self.addCleanup(lambda: (gt.stop_process(replay), replay.stdout.close(),
                                 replay.stderr.close()))
        endpoints = {}
        while "tcp" not in endpoints:
            line = gt.read_line(replay.stdout, gt.START_TIMEOUT_S)
            self.assertTrue(line, "gimbal-replay printed no tcp line: %s" % endpoints)
            key, _, value = line.strip().partition(": ")
            endpoints[key] = value
        self.assertEqual(endpoints["video"], "udp://127.0.0.1:%d" % video_port)
        port = int(endpoints["tcp"].rsplit(":", 1)[1])
        daemon = self.start_daemon({"gimbals": [dict(
            gt.orion_tcp("main", port), video={"input": "udp://127.0.0.1:%d" % video_port})]})
        c = self.client(daemon)
        v = gt.wait_for(lambda: (lambda v: v if v and v["klv_source"] == "stream" and
                                 v["width"] else None)(state_video(c, "main")), 20.0)
        self.assertTrue(v, state_video(c, "main"))
        self.assertEqual((v["codec"], v["width"], v["height"]), ("h264", 640, 360))
        reply = c.request("klv", gimbal="main")
        self.assertOk(reply)
        self.assertIn(bytes.fromhex(reply["klv_hex"]), stream_sets)
        print("replayed at %.1f s" % (time.monotonic() - t0))


if __name__ == "__main__":
    gt.main()
