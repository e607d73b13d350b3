"""Video inputs under trouble, through a real gimbald (contract section 17, issue 20):

- an RTSP source served in the test by GStreamer's RTSP server (rtsp_server.py, Debian's
  python3-gi): gimbald reads rtsp:// (H.264 over TCP, H.265 over UDP), its output has the
  video + klv (ffprobe), its recording the access units muxed into TS; the server going
  away is `video_down`, its return `video_up` again (reconnect with backoff);
- KLV in a synchronous metadata stream (ST 1402) is read like the asynchronous one;
- `"klv": "off"` relays the video alone, `"generate"` ignores the stream's KLV;
- an MPEG-TS over UDP with KLV sets whose checksum is wrong: counted in
  `klv_bad_checksums`, never shown or relayed;
- junk between packets, lost packets, a PID change and a restarted encoder: the video and
  its KLV keep flowing to the outputs;
- an output that cannot send (a broadcast address without SO_BROADCAST: EACCES on every
  send) is logged once and retried, and does not hold up the input or the other outputs;
  one without a route (in a network namespace) sends again once a route appears;
- a silent UDP input is `video_down`, and `video_up` when data comes back.

The TS is crafted here (videotest.TsWriter, libx264 units made by ffmpeg); what gimbald sends
is read back by the test's own TS reader and st0601.py.
"""

import glob
import os
import random
import shutil
import socket
import subprocess
import sys
import threading
import time
import unittest

import gimbaltest as gt
import skipping
import st0601
import videotest as vt
from pcapng_test_writer import INBOUND, OUTBOUND
from test_gimbal_replay_export import read_pcapng

HERE = os.path.dirname(os.path.abspath(__file__))
SYSTEM_PYTHON = "/usr/bin/python3"  # Debian's, with python3-gi
FPS = 30


def state_video(client, gimbal="cam"):
    reply = client.request("state", gimbal=gimbal, keys=["video"])
    return reply["state"]["video"] if reply and reply.get("ok") else None


def have_rtsp_server():
    if not os.path.exists(SYSTEM_PYTHON):
        return False
    r = subprocess.run([SYSTEM_PYTHON, "-c", "import gi; gi.require_version('Gst', '1.0'); "
                        "gi.require_version('GstRtspServer', '1.0')"], capture_output=True)
    return r.returncode == 0


class RtspServer:
    """rtsp_server.py on `port` (0: a free one), H.264 (or H.265) 320x240 at 15 fps,
    parameter sets only in the SDP."""

    def __init__(self, port=0, codec="h264"):
        self.proc = subprocess.Popen(
            [SYSTEM_PYTHON, os.path.join(HERE, "rtsp_server.py"), "--port", str(port),
             "--codec", codec],
            stdout=subprocess.PIPE, stderr=subprocess.PIPE, stdin=subprocess.DEVNULL,
            text=True)
        line = gt.read_line(self.proc.stdout, 15.0)
        if not line or not line.startswith("ready "):
            self.stop()
            raise RuntimeError("rtsp_server.py did not start: %r %s"
                               % (line, self.proc.stderr.read()))
        self.port = int(line.split()[1])

    def stop(self):
        gt.stop_process(self.proc)
        for pipe in (self.proc.stdout, self.proc.stderr):
            pipe.close()


@skipping.requires(have_rtsp_server(), "GStreamer's RTSP server (python3-gi, "
                   "gir1.2-gst-rtsp-server-1.0) is not installed")
class RtspSource(gt.GimbaldTestCase):
    """A Viewpro-like camera on RTSP (no KLV of its own): gimbald generates the KLV."""

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.server = RtspServer()
        cls.addClassCleanup(lambda: cls.server.stop())
        cls.out = gt.free_port()
        cls.input = "rtsp://127.0.0.1:%d/test?transport=tcp&timeout_s=1" % cls.server.port
        cls.daemon = cls.start_class_daemon({"gimbals": [{
            "name": "cam", "protocol": "viewpro", "link": {"type": "sim"},
            "video": {"input": cls.input, "outputs": ["udp://127.0.0.1:%d" % cls.out]}}]})

    def setUp(self):
        super().setUp()
        self.c = self.client(self.daemon)

    def wait_up(self, timeout=20.0):
        v = gt.wait_for(lambda: (lambda v: v if v and v["connected"] and v["codec"] and
                                 v["klv_source"] else None)(state_video(self.c)), timeout)
        self.assertTrue(v, "RTSP video never came up: %s" % state_video(self.c))
        return v

    def test_rtsp_input_relayed_as_ts_with_h264_and_klv(self):
        v = self.wait_up()
        self.assertEqual(v["input"], self.input)
        self.assertEqual(v["codec"], "h264")
        self.assertEqual((v["width"], v["height"]), (320, 240))
        self.assertEqual(v["klv_source"], "generated")
        t0 = time.monotonic()
        streams = vt.ffprobe_streams("udp://127.0.0.1:%d" % self.out)
        kinds = {(s.get("codec_type"), s.get("codec_name")) for s in streams}
        self.assertIn(("video", "h264"), kinds, streams)
        self.assertIn(("data", "klv"), kinds, streams)
        video = [s for s in streams if s.get("codec_type") == "video"][0]
        self.assertEqual((video["width"], video["height"]), (320, 240))
        print("ffprobe on the RTSP relay: %.1f s" % (time.monotonic() - t0))
        reply = self.c.request("klv", gimbal="cam")
        self.assertOk(reply)
        status, reason, _ = st0601.decode(bytes.fromhex(reply["klv_hex"]))
        self.assertEqual(status, "ok", reason)

    def test_rtsp_input_recorded_as_ts(self):
        # An RTSP input has no TS of its own: the recording gets its access units muxed.
        rec = os.path.join(self.workdir, "rec")
        os.mkdir(rec)
        daemon = self.start_daemon({
            "gimbals": [{"name": "cam", "protocol": "viewpro", "link": {"type": "sim"},
                         "video": {"input": self.input}}],
            "record": {"dir": rec}})
        c = self.client(daemon)
        self.assertTrue(gt.wait_for(lambda: (state_video(c) or {}).get("width"), 20.0),
                        state_video(c))
        self.assertTrue(gt.wait_for(lambda: state_video(c)["klv_sets"] >= 10, 10.0))
        self.assertEqual(daemon.stop(), 0)
        records = [r for p in glob.glob(os.path.join(rec, "*.pcapng")) for r in read_pcapng(p)]
        ts = [pdu for name, _, d, dissector, pdu in records
              if name == "video:cam" and d == INBOUND and dissector == "mp2t"]
        generated = [pdu for name, _, d, dissector, pdu in records
                     if name == "video:cam" and d == OUTBOUND and dissector == "data"]
        reader = vt.TsReader()
        for pdu in ts:
            self.assertEqual(len(pdu) % 188, 0)
            reader.push(pdu)
        reader.flush()
        self.assertEqual(reader.video_type, 0x1B)
        self.assertGreater(reader.video_units, 10)
        self.assertEqual(reader.klv, [])  # generated sets are recorded on their own
        self.assertGreaterEqual(len(generated), 10)
        self.assertEqual(st0601.decode(generated[0])[0], "ok")

    def test_h265_over_rtp_on_udp(self):
        server = RtspServer(codec="h265")
        self.addCleanup(server.stop)
        out = gt.free_port()
        daemon = self.start_daemon({"gimbals": [{
            "name": "cam", "protocol": "viewpro", "link": {"type": "sim"},
            "video": {"input": "rtsp://127.0.0.1:%d/test?transport=udp" % server.port,
                      "outputs": ["udp://127.0.0.1:%d" % out]}}]})
        c = self.client(daemon)
        v = gt.wait_for(lambda: (lambda v: v if v and v["width"] else None)(state_video(c)),
                        20.0)
        self.assertTrue(v, state_video(c))
        self.assertEqual((v["codec"], v["width"], v["height"]), ("h265", 320, 240))
        streams = vt.ffprobe_streams("udp://127.0.0.1:%d" % out)
        kinds = {(s.get("codec_type"), s.get("codec_name")) for s in streams}
        self.assertIn(("video", "hevc"), kinds, streams)
        self.assertIn(("data", "klv"), kinds, streams)

    def test_server_lost_is_video_down_then_reconnected(self):
        self.wait_up()
        ups = len(self.daemon.events("video_up"))
        port = self.server.port
        self.server.stop()
        down = self.daemon.wait_log(lambda e: e.get("event") == "video_down", 10.0)
        self.assertTrue(down, "no video_down after the RTSP server went away")
        self.assertEqual(down["input"], self.input)
        self.assertEqual(down["gimbal"], "cam")
        self.assertTrue(gt.wait_for(lambda: state_video(self.c)["connected"] is False, 5.0))
        type(self).server = RtspServer(port)  # the camera comes back on the same port
        self.assertTrue(gt.wait_for(lambda: len(self.daemon.events("video_up")) > ups, 20.0),
                        "no video_up after the RTSP server came back")
        self.wait_up()


class Feeder:
    """Feeds a crafted TS to gimbald frame by frame at FPS (class attributes: units, sock,
    dest, pts, frame)."""

    def feed(self, writer, frames, bad_every=0, junk=False, drop_every=0, lat=45.7):
        """Sends `frames` frames (PAT/PMT first and each second, a KLV set per frame; every
        `bad_every`-th set with a wrong checksum and latitude 10) at FPS; returns
        (good sets, bad sets) sent."""
        cls = type(self)
        rng = random.Random(cls.frame)
        good = bad = 0
        next_t = time.monotonic()
        for n in range(frames):
            ts = writer.psi() if n == 0 or cls.frame % FPS == 0 else b""
            ts += writer.video(cls.units[cls.frame % len(cls.units)], cls.pts)
            is_bad = bad_every and cls.frame % bad_every == 0
            k = vt.klv_set(int(time.time() * 1e6), 10.0 if is_bad else lat, -121.5,
                           bad_checksum=bool(is_bad))
            ts += writer.klv_pes(k, cls.pts)
            bad += 1 if is_bad else 0
            good += 0 if is_bad else 1
            packets = [ts[i:i + 188] for i in range(0, len(ts), 188)]
            if drop_every:
                packets = [p for n, p in enumerate(packets) if n % drop_every != drop_every - 1]
            for i in range(0, len(packets), 7):
                d = b"".join(packets[i:i + 7])
                if junk:
                    d = bytes(rng.randrange(256) for _ in range(rng.randrange(1, 40))) + d
                for dest in getattr(cls, "also", []) + [cls.dest]:
                    cls.sock.sendto(d, dest)
            cls.frame += 1
            cls.pts += vt.PTS_HZ // FPS
            next_t += 1.0 / FPS
            time.sleep(max(0.0, next_t - time.monotonic()))
        return good, bad


class TsFaults(Feeder, gt.GimbaldTestCase):
    """MPEG-TS over UDP with KLV, fed by the test frame by frame at 30 fps."""

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.units = vt.h264_access_units(cls.class_workdir, fps=FPS)
        cls.in_port = gt.free_port()
        cls.ts = vt.UdpCollector()
        cls.klv = vt.UdpCollector()
        cls.addClassCleanup(cls.ts.close)
        cls.addClassCleanup(cls.klv.close)
        cls.blocked_port = gt.free_port()
        cls.blocked = "udp://255.255.255.255:%d" % cls.blocked_port
        # Two more gimbals for the other KLV modes, fed the same stream when a test asks.
        cls.off_port, cls.own_port = gt.free_port(), gt.free_port()
        cls.off_ts = vt.UdpCollector()
        cls.own_ts = vt.UdpCollector()
        cls.addClassCleanup(cls.off_ts.close)
        cls.addClassCleanup(cls.own_ts.close)
        cls.daemon = cls.start_class_daemon({"gimbals": [{
            "name": "cam", "protocol": "viewpro", "link": {"type": "sim"},
            "video": {"input": "udp://127.0.0.1:%d?timeout_s=1" % cls.in_port,
                      "klv": "parse",
                      "outputs": [cls.blocked, "udp://127.0.0.1:%d" % cls.ts.port,
                                  "klv-udp://127.0.0.1:%d" % cls.klv.port]}}, {
            "name": "off", "protocol": "viewpro", "link": {"type": "sim"},
            "video": {"input": "udp://127.0.0.1:%d" % cls.off_port, "klv": "off",
                      "outputs": ["udp://127.0.0.1:%d" % cls.off_ts.port]}}, {
            "name": "own", "protocol": "viewpro", "link": {"type": "sim"},
            "video": {"input": "udp://127.0.0.1:%d" % cls.own_port, "klv": "generate",
                      "outputs": ["udp://127.0.0.1:%d" % cls.own_ts.port]}}]})
        cls.sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        cls.addClassCleanup(cls.sock.close)
        cls.dest = ("127.0.0.1", cls.in_port)
        cls.pts = 10 * vt.PTS_HZ
        cls.frame = 0

    def setUp(self):
        super().setUp()
        self.c = self.client(self.daemon)

    def relayed(self, since_ts, since_klv):
        """(video units, KLV PES) gimbald sent to the TS output, and the klv-udp sets, since
        the given collector counts."""
        time.sleep(0.3)  # the last datagrams in flight
        everything = self.ts.data()
        reader = vt.TsReader()
        for d in everything[:since_ts]:  # the PIDs from the PAT/PMT seen so far
            reader.push(d)
        reader.pending, reader.klv, reader.video_units = {}, [], 0
        for d in everything[since_ts:]:
            reader.push(d)
        reader.flush()
        return reader, self.klv.data(since_klv)

    def test_bad_checksums_are_counted_and_ignored(self):
        w = vt.TsWriter()
        self.feed(w, FPS)  # up and running
        before = state_video(self.c)
        self.assertTrue(before["connected"])
        ts0, klv0 = self.ts.count(), self.klv.count()
        good, bad = self.feed(w, 2 * FPS, bad_every=3)
        time.sleep(0.3)
        after = state_video(self.c)
        self.assertEqual(after["klv_bad_checksums"] - before["klv_bad_checksums"], bad)
        self.assertEqual(after["klv_sets"] - before["klv_sets"], good)
        self.assertEqual(after["klv_source"], "stream")
        self.assertAlmostEqual(after["klv"]["sensor_latitude"], 45.7, places=5)
        reader, sets = self.relayed(ts0, klv0)
        self.assertEqual(len(sets), good)  # only the good ones go on
        for s in sets:
            status, reason, items = st0601.decode(s)
            self.assertEqual(status, "ok", reason)
            self.assertAlmostEqual(items["sensor_latitude"], 45.7, places=5)
        relayed_klv = [s for _, payload in reader.klv for s in vt.split_sets(payload)]
        self.assertEqual(len(relayed_klv), good)
        self.assertTrue(self.daemon.wait_log(lambda e: e.get("event") == "klv_bad_checksum",
                                             5.0), "no klv_bad_checksum log")

    def test_klv_off_and_generate_ignore_the_streams_klv(self):
        type(self).also = [("127.0.0.1", self.off_port), ("127.0.0.1", self.own_port)]
        self.addCleanup(lambda: setattr(type(self), "also", []))
        self.feed(vt.TsWriter(), FPS)
        off0, own0 = self.off_ts.count(), self.own_ts.count()
        self.feed(vt.TsWriter(), 2 * FPS, lat=10.5)  # the stream's sets: latitude 10.5
        time.sleep(0.3)
        # "off": video only - no KLV stream in the output's PMT, nothing counted, no klv.
        off = state_video(self.c, "off")
        self.assertTrue(off["connected"])
        self.assertEqual((off["klv_source"], off["klv"], off["klv_sets"]), (None, None, 0))
        self.assertError(self.c.request("klv", gimbal="off"), "unavailable")
        reader = vt.TsReader()
        for d in self.off_ts.data(off0):
            reader.push(d)
        reader.flush()
        self.assertGreater(reader.video_units, FPS)
        self.assertIsNone(reader.klv_pid)
        self.assertEqual(reader.klv, [])
        # "generate": the sets come from STATE (the simulated Viewpro's position), the
        # stream's are not used.
        own = state_video(self.c, "own")
        self.assertEqual(own["klv_source"], "generated")
        self.assertGreater(own["klv_sets"], 0)
        self.assertNotAlmostEqual(own["klv"]["sensor_latitude"], 10.5, places=3)
        reader = vt.TsReader()
        for d in self.own_ts.data():
            reader.push(d)
        reader.flush()
        relayed = [st0601.decode(s)[2] for _, p in reader.klv for s in vt.split_sets(p)]
        self.assertTrue(relayed)
        self.assertFalse([k for k in relayed if abs(k["sensor_latitude"] - 10.5) < 1e-3])

    def test_synchronous_metadata_stream_is_read_and_relayed(self):
        self.feed(vt.TsWriter(), FPS // 2)
        before = state_video(self.c)
        ts0, klv0 = self.ts.count(), self.klv.count()
        good, _ = self.feed(vt.TsWriter(sync=True, version=2), 2 * FPS, lat=45.71)
        time.sleep(0.3)
        after = state_video(self.c)
        self.assertEqual(after["klv_sets"] - before["klv_sets"], good)
        self.assertEqual(after["klv_source"], "stream")
        self.assertAlmostEqual(after["klv"]["sensor_latitude"], 45.71, places=5)
        reader, sets = self.relayed(ts0, klv0)
        self.assertEqual(len(sets), good)
        # Out of gimbald, the same sets ride its asynchronous KLVA stream.
        relayed = [s for _, payload in reader.klv for s in vt.split_sets(payload)]
        self.assertEqual(relayed, sets)
        self.assertEqual(st0601.decode(relayed[-1])[0], "ok")

    def test_junk_lost_packets_pid_change_and_restart_keep_working(self):
        w = vt.TsWriter()
        self.feed(w, FPS)
        phases = [
            ("junk before every datagram", w, dict(junk=True)),
            ("every 10th TS packet lost", w, dict(drop_every=10)),
            ("new PIDs and PMT version", vt.TsWriter(video_pid=0x200, klv_pid=0x201,
                                                     pmt_pid=0x1100, version=1), {}),
            ("encoder restarted: PIDs, version 0, counters and PTS from the start",
             vt.TsWriter(), dict(restart=True)),
        ]
        for name, writer, faults in phases:
            with self.subTest(phase=name):
                if faults.pop("restart", False):
                    type(self).pts = vt.PTS_HZ  # back from far ahead: a new encoder's clock
                    type(self).frame = 0
                ts0, klv0 = self.ts.count(), self.klv.count()
                good, _ = self.feed(writer, 2 * FPS, **faults)
                reader, sets = self.relayed(ts0, klv0)
                v = state_video(self.c)
                self.assertTrue(v["connected"], v)
                self.assertEqual(v["codec"], "h264")
                self.assertEqual((v["width"], v["height"]), (320, 240))
                self.assertEqual(reader.video_type, 0x1B)
                # Damaged units are dropped, the rest go on (lost packets: about 1 in 10
                # units of ~3 packets, and those that lose their header).
                self.assertGreater(reader.video_units, FPS, name)
                self.assertGreater(len(sets), good // 2, name)
                print("%s: %d of %d units and %d of %d KLV sets relayed"
                      % (name, reader.video_units, 2 * FPS, len(sets), good))
        self.assertTrue(self.daemon.running())

    def test_output_that_cannot_send_is_logged_once_and_blocks_nothing(self):
        w = vt.TsWriter()
        ts0 = self.ts.count()
        self.feed(w, 3 * FPS)  # 3 s: the blocked output retries every second
        reader, _ = self.relayed(ts0, self.klv.count())
        errors = [e for e in self.daemon.events("video_output_error")
                  if e.get("output") == self.blocked]
        self.assertEqual(len(errors), 1, errors)  # once per outage, however often retried
        self.assertTrue(errors[0].get("error"), errors[0])
        self.assertEqual(errors[0]["gimbal"], "cam")
        # Nothing else is held up: the other outputs got (nearly) every frame.
        self.assertGreaterEqual(reader.video_units, 3 * FPS - 3)
        self.assertFalse([e for e in self.daemon.events("video_output_error")
                          if e.get("output") != self.blocked])

    def test_silence_is_video_down_and_data_again_video_up(self):
        w = vt.TsWriter()
        self.feed(w, FPS // 2)
        self.assertTrue(gt.wait_for(lambda: state_video(self.c)["connected"], 3.0))
        downs, ups = len(self.daemon.events("video_down")), len(self.daemon.events("video_up"))
        time.sleep(1.8)  # timeout_s=1
        v = state_video(self.c)
        self.assertIs(v["connected"], False)
        self.assertEqual(len(self.daemon.events("video_down")), downs + 1)
        self.feed(w, FPS // 2)
        self.assertTrue(gt.wait_for(lambda: state_video(self.c)["connected"], 3.0))
        self.assertEqual(len(self.daemon.events("video_up")), ups + 1)
        down = self.daemon.events("video_down")[-1]
        self.assertEqual(down["gimbal"], "cam")
        self.assertEqual(down["timeout_s"], 1)


IP_RECVTTL = 12  # linux/in.h; not in Python's socket module


class Multicast(Feeder, gt.GimbaldTestCase):
    """A multicast input (the group joined on 127.0.0.1) relayed to a multicast output with
    ?ttl=3: the datagrams arrive in the output group with IP TTL 3."""

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.units = vt.h264_access_units(cls.class_workdir, fps=FPS)
        port = gt.free_port()
        cls.in_group = "239.255.73.%d" % (port % 250 + 1)
        cls.out_group = "239.255.74.%d" % (port % 250 + 1)
        cls.out_port = gt.free_port()
        cls.rx = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        cls.addClassCleanup(cls.rx.close)
        cls.rx.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        cls.rx.bind((cls.out_group, cls.out_port))
        try:
            cls.rx.setsockopt(socket.IPPROTO_IP, socket.IP_ADD_MEMBERSHIP,
                              socket.inet_aton(cls.out_group) + socket.inet_aton("127.0.0.1"))
        except OSError as e:
            raise unittest.SkipTest("no multicast on the loopback interface here: %s" % e)
        cls.rx.setsockopt(socket.IPPROTO_IP, IP_RECVTTL, 1)
        cls.rx.settimeout(0.2)
        cls.sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        cls.addClassCleanup(cls.sock.close)
        cls.sock.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_IF,
                            socket.inet_aton("127.0.0.1"))
        cls.sock.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_TTL, 1)
        cls.dest = (cls.in_group, port)
        cls.pts = vt.PTS_HZ
        cls.frame = 0
        cls.input = "udp://%s:%d?iface=127.0.0.1" % cls.dest
        cls.daemon = cls.start_class_daemon({"gimbals": [{
            "name": "cam", "protocol": "viewpro", "link": {"type": "sim"},
            "video": {"input": cls.input, "klv": "parse", "outputs": [
                "udp://%s:%d?ttl=3&iface=127.0.0.1" % (cls.out_group, cls.out_port)]}}]})

    def test_multicast_in_and_out_with_ttl(self):
        c = self.client(self.daemon)
        w = vt.TsWriter()
        self.feed(w, FPS)  # gimbald has joined its group by now (it started before)
        v = state_video(c)
        self.assertTrue(v["connected"], v)
        self.assertEqual(v["input"], self.input)
        self.assertEqual(v["codec"], "h264")
        self.assertEqual(v["klv_source"], "stream")
        received, ttls = [], set()
        feeder = threading.Thread(target=self.feed, args=(w, FPS))
        feeder.start()
        deadline = time.monotonic() + 3.0
        while time.monotonic() < deadline and (feeder.is_alive() or len(received) < 5):
            try:
                data, ancillary, _, _ = self.rx.recvmsg(65536, socket.CMSG_SPACE(4))
            except socket.timeout:
                continue
            received.append(data)
            for level, kind, value in ancillary:
                if level == socket.IPPROTO_IP and kind == 2:  # IP_TTL
                    ttls.add(int.from_bytes(value[:4], "little"))
        feeder.join()
        reader = vt.TsReader()
        for d in received:
            reader.push(d)
        reader.flush()
        self.assertGreater(reader.video_units, FPS // 2)
        self.assertGreater(len(reader.klv), FPS // 2)
        self.assertEqual(ttls, {3})


class OutputRecovers(gt.GimbaldTestCase):
    """An output with no route (ENETUNREACH) is logged, and `video_output_ok` (with the
    datagrams dropped meanwhile) once a route appears - in a network namespace of its own
    (unshare --net, root), where the route can be added: no_route_child() below."""

    def test_no_route_then_route(self):
        if not shutil.which("unshare") or not shutil.which("ip") or \
                subprocess.run(["unshare", "--net", "true"], capture_output=True).returncode:
            self.skipTest("no network namespace here (needs root, unshare and ip)")
        r = subprocess.run(["unshare", "--net", sys.executable, os.path.abspath(__file__),
                            "--no-route-child", self.workdir],
                           capture_output=True, text=True, timeout=120)
        print(r.stdout.strip())
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr[-3000:])


def no_route_child(workdir):
    """Runs inside the new namespace: lo up, gimbald with an output to 10.77.0.1 (no route),
    a feed; then the route; returns an exit code."""
    subprocess.run(["ip", "link", "set", "lo", "up"], check=True)
    units = vt.h264_access_units(workdir, fps=FPS)
    in_port, rx = gt.free_port(), vt.UdpCollector()
    blocked = "udp://10.77.0.1:5000"
    daemon = gt.Daemon(workdir, {"gimbals": [{
        "name": "cam", "protocol": "viewpro", "link": {"type": "sim"},
        "video": {"input": "udp://127.0.0.1:%d" % in_port, "klv": "parse",
                  "outputs": [blocked, "udp://127.0.0.1:%d" % rx.port]}}]})
    sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    writer = vt.TsWriter()

    def feed(frames, first):
        for n in range(frames):
            i = first + n
            ts = (writer.psi() if i % FPS == 0 else b"") + \
                writer.video(units[i % len(units)], vt.PTS_HZ + i * (vt.PTS_HZ // FPS))
            for d in vt.datagrams(ts):
                sock.sendto(d, ("127.0.0.1", in_port))
            time.sleep(1.0 / FPS)

    try:
        feed(FPS, 0)
        error = daemon.wait_log(lambda e: e.get("event") == "video_output_error", 5.0)
        if not error or error.get("output") != blocked or \
                "unreachable" not in error.get("error", "").lower():
            print("no video_output_error for the unroutable output: %s" % error)
            return 1
        got_before = rx.count()
        if got_before < FPS // 2:
            print("the other output was held up: %d datagrams" % got_before)
            return 1
        subprocess.run(["ip", "route", "add", "10.77.0.0/24", "dev", "lo"], check=True)
        feed(2 * FPS, FPS)  # the pause after a failure is 1 s: then it sends again
        ok = daemon.wait_log(lambda e: e.get("event") == "video_output_ok", 5.0)
        if not ok or ok.get("output") != blocked or not ok.get("dropped"):
            print("no video_output_ok after the route appeared: %s" % ok)
            return 1
        errors = [e for e in daemon.events("video_output_error") if e.get("output") == blocked]
        print("video_output_error once (%s), video_output_ok after %d dropped datagrams"
              % (errors[0]["error"], ok["dropped"]))
        return 0 if len(errors) == 1 else 1
    finally:
        sock.close()
        rx.close()
        print("gimbald exit %s" % daemon.stop())


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "--no-route-child":
        sys.exit(no_route_child(sys.argv[2]))
    gt.main()
