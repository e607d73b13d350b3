#!/usr/bin/env python3
"""GET /api/video/{gimbal} (contract section 18, format in docs/http.md) against gimbald with
an in-process simulated Orion sending its rendered H.264 to the gimbal's video input: the
first message is the decoder configuration read from the SPS (avc1.42C01E, 640 x 360), then
one binary message per access unit - 8-byte big-endian timestamp in microseconds, a flag
byte, the Annex B access unit - starting at a key frame that carries its SPS, timestamps
rising by the frame period; an unknown gimbal or one without video is 404, a plain GET 426,
another site's Origin 403; a viewer that stops reading is dropped (metrics, log) while
another viewer keeps receiving every frame; /api/console says which gimbals have video."""

import json
import socket
import struct
import time

import gimbaltest as gt
import httptest as ht

FPS = 15  # the simulated camera's default rate (docs/simulator.md)


def frame_of(payload):
    """(timestamp_us, key, Annex B bytes) of a binary video message."""
    ts, flags = struct.unpack(">QB", payload[:9])
    return ts, bool(flags & 1), payload[9:]


def nal_types(annexb):
    out, i = [], 0
    while True:
        i = annexb.find(b"\x00\x00\x01", i)
        if i < 0 or i + 3 >= len(annexb):
            return out
        out.append(annexb[i + 3] & 0x1F)
        i += 3


class VideoWebSocket(gt.GimbaldTestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        video_port = gt.free_port()
        config = {
            "gimbals": [
                {"name": "cam", "protocol": "orion", "link": {"type": "sim"},
                 "video": {"input": "udp://127.0.0.1:%d" % video_port}},
                {"name": "novideo", "protocol": "orion", "link": {"type": "sim"}},
            ],
            "http": {"port": 0},
        }
        cls.daemon = cls.start_class_daemon(config)
        start = cls.daemon.wait_log(lambda e: e.get("event") == "start")
        cls.port = int(start["http"].rsplit(":", 1)[1])

    def test_format_and_frames(self):
        ws = ht.WebSocket(self.port, "/api/video/cam", timeout=10)
        try:
            opcode, payload = ws.recv_frame(timeout=10)
            self.assertEqual(opcode, 0x1, "first message is text")
            config = json.loads(payload)
            self.assertEqual(config, {"type": "config", "gimbal": "cam", "codec": "avc1.42C01E",
                                      "width": 640, "height": 360})
            frames = []
            while len(frames) < 2 * FPS:
                opcode, payload = ws.recv_frame(timeout=5)
                self.assertEqual(opcode, 0x2, "access units are binary")
                frames.append(frame_of(payload))
            ts0, key0, au0 = frames[0]
            self.assertTrue(key0, "the first frame is a key frame")
            types = nal_types(au0)
            self.assertIn(7, types, "SPS in the first key frame")
            self.assertIn(8, types, "PPS in the first key frame")
            self.assertIn(5, types, "IDR slice")
            keys = [f for f in frames if f[1]]
            self.assertGreaterEqual(len(keys), 2, "an IDR every second")
            for ts, key, au in frames:
                self.assertEqual(key, 5 in nal_types(au), "flag bit 0 = IDR")
            steps = [b[0] - a[0] for a, b in zip(frames, frames[1:])]
            period = 1e6 / FPS
            self.assertTrue(all(abs(s - period) < 2 or s > 0 for s in steps), steps)
            self.assertLess(abs(sorted(steps)[len(steps) // 2] - period), 2,
                            "median step is the frame period: %s" % steps)
        finally:
            ws.close()

    def test_refusals(self):
        for path in ("/api/video/nosuch", "/api/video/novideo"):
            with self.assertRaises(ConnectionError) as cm:
                ht.WebSocket(self.port, path)
            self.assertIn("404", str(cm.exception))
        status, _, body = ht.request(self.port, "GET", "/api/video/cam")
        self.assertEqual(status, 426, body)
        status, _, _ = ht.request(self.port, "GET", "/api/video/novideo")
        self.assertEqual(status, 404)
        with self.assertRaises(ConnectionError) as cm:
            ht.WebSocket(self.port, "/api/video/cam", origin="http://evil.example")
        self.assertIn("403", str(cm.exception))
        _, info = ht.get_json(self.port, "/api/console")
        self.assertEqual({g["name"]: g["video"] for g in info["gimbals"]},
                         {"cam": True, "novideo": False})

    def test_stalled_viewer_dropped_others_unaffected(self):
        # A viewer with a tiny receive window that never reads, and one that reads all.
        stalled = ht.WebSocket(self.port, "/api/video/cam", rcvbuf=4096)
        reader = ht.WebSocket(self.port, "/api/video/cam", timeout=10)
        try:
            reader.recv_frame(timeout=10)  # config
            got, last_ts, gaps = 0, None, 0
            dropped = None
            deadline = time.monotonic() + 40
            while time.monotonic() < deadline:
                opcode, payload = reader.recv_frame(timeout=5)
                self.assertEqual(opcode, 0x2)
                ts, _, _ = frame_of(payload)
                if last_ts is not None and ts - last_ts > 1.5e6 / FPS:
                    gaps += 1
                last_ts = ts
                got += 1
                if got % FPS == 0:
                    m = ht.parse_metrics(ht.request(self.port, "GET", "/metrics")[2].decode())
                    if ht.metric(m, "gimbald_video_viewers_dropped_total") >= 1:
                        dropped = got
                        break
            self.assertIsNotNone(dropped, "the viewer that does not read was never dropped")
            self.assertEqual(gaps, 0, "the reading viewer missed frames")
            # Keeps going after the drop.
            for _ in range(FPS):
                opcode, _ = reader.recv_frame(timeout=5)
                self.assertEqual(opcode, 0x2)
            entry = self.daemon.wait_log(lambda e: e.get("event") == "video_viewer_dropped")
            self.assertTrue(entry, "video_viewer_dropped logged")
            m = ht.parse_metrics(ht.request(self.port, "GET", "/metrics")[2].decode())
            self.assertEqual(ht.metric(m, "gimbald_video_viewers"), 1)
            # The dropped viewer's socket is closed by gimbald.
            stalled.sock.settimeout(5)
            try:
                while stalled.sock.recv(1 << 20):
                    pass
                closed = True
            except socket.timeout:
                closed = False
            except (ConnectionResetError, OSError):
                closed = True
            self.assertTrue(closed, "gimbald closed the dropped viewer's connection")
        finally:
            reader.close()
            stalled.sock.close()


if __name__ == "__main__":
    gt.main()
