"""gimbal-track, the visual tracking process (contract section 20), driven as gimbald drives
it: a Unix SOCK_SEQPACKET socket (a listening one with --socket, a socketpair with --fd), the
messages of docs/tracking.md "Wire protocol" encoded here from that description (not from the
C++ declarations), and real H.264 of a synthetic scene (a vehicle on a road, a bridge) made by
lib/sim_video's encoder (track_sample_stream), whose true positions are known.

Boxes come back for every frame and follow the vehicle; under the bridge the track is lost,
then re-acquired under the same id; stop ends it; garbage, oversized and truncated input is
refused with "error" and the process goes on; EOF and SIGTERM end it cleanly.
"""

import json
import math
import os
import select
import signal
import socket
import struct
import subprocess
import sys
import tempfile
import time
import unittest

GIMBAL_TRACK = os.environ.get("GIMBAL_TRACK")
SAMPLE_STREAM = os.environ.get("TRACK_SAMPLE_STREAM")
SKIP = 77
TIMEOUT_S = 10.0

# --- the wire protocol, as docs/tracking.md describes it ------------------------------------
VERSION = 1
HELLO, START, AU, STOP, BOX, ENDED, ERROR = 1, 2, 3, 4, 5, 6, 7
TRACKERS = ["csrt", "kcf"]
STATES = ["tracking", "lost"]
REASONS = ["stopped", "overridden", "timeout", "no_video"]


def start_message(track_id, box, tracker="kcf", width=640, lost_after_s=1.0, reacquire_s=10.0):
    return struct.pack("<BBI4fBHff", VERSION, START, track_id, *box, TRACKERS.index(tracker),
                       width, lost_after_s, reacquire_s)


def au_message(pts, key, data, codec=0, total=None, offset=0):
    total = len(data) if total is None else total
    return struct.pack("<BBqBBIII", VERSION, AU, pts, 1 if key else 0, codec, total, offset,
                       len(data)) + data


def stop_message(track_id):
    return struct.pack("<BBI", VERSION, STOP, track_id)


def decode(datagram):
    version, kind = datagram[0], datagram[1]
    assert version == VERSION, "protocol version %d" % version
    body = datagram[2:]
    if kind == HELLO:
        (ver,) = struct.unpack_from("<H", body)
        at, count = 3, body[2]
        trackers = []
        for _ in range(count):
            (n,) = struct.unpack_from("<H", body, at)
            trackers.append(body[at + 2:at + 2 + n].decode())
            at += 2 + n
        (max_au,) = struct.unpack_from("<I", body, at)
        assert at + 4 == len(body)
        return {"type": "hello", "version": ver, "trackers": trackers, "max_au_bytes": max_au}
    if kind == BOX:
        assert len(body) == 33, len(body)
        track_id, pts, x0, y0, x1, y1, conf, state = struct.unpack("<Iq5fB", body)
        return {"type": "box", "id": track_id, "pts_90k": pts, "box": (x0, y0, x1, y1),
                "confidence": conf, "state": STATES[state]}
    if kind == ENDED:
        track_id, reason = struct.unpack("<IB", body)
        return {"type": "ended", "id": track_id, "reason": REASONS[reason]}
    if kind == ERROR:
        (n,) = struct.unpack_from("<H", body)
        assert n + 2 == len(body)
        return {"type": "error", "message": body[2:].decode()}
    raise AssertionError("unexpected message type %d" % kind)


# --- the sample stream -----------------------------------------------------------------------

def sample(workdir, scenario, frames):
    out = os.path.join(workdir, scenario)
    os.makedirs(out, exist_ok=True)
    subprocess.run([SAMPLE_STREAM, "--scenario", scenario, "--frames", str(frames), "--out", out],
                   check=True, capture_output=True, timeout=120)
    units = []
    with open(os.path.join(out, "units.bin"), "rb") as f:
        data = f.read()
    at = 0
    while at < len(data):
        n, pts, key = struct.unpack_from("<IqB", data, at)
        at += 13
        units.append((pts, bool(key), data[at:at + n]))
        at += n
    with open(os.path.join(out, "truth.jsonl")) as f:
        truth = [json.loads(line) for line in f]
    return units, truth


def centre(box):
    return ((box[0] + box[2]) / 2, (box[1] + box[3]) / 2)


def error_px(box, truth_box, width=640, height=360):
    (x, y), (tx, ty) = centre(box), centre(truth_box)
    return math.hypot((x - tx) / 2 * width, (y - ty) / 2 * height)


# --- the process -----------------------------------------------------------------------------

class Track:
    """gimbal-track on one end of a SOCK_SEQPACKET connection, its log collected."""

    serial = 0

    def __init__(self, workdir, use_fd=False, log_level="info"):
        self.workdir = workdir
        self.stderr = tempfile.TemporaryFile("w+", dir=workdir)
        if use_fd:
            self.sock, theirs = socket.socketpair(socket.AF_UNIX, socket.SOCK_SEQPACKET)
            self.proc = subprocess.Popen(
                [GIMBAL_TRACK, "--fd", str(theirs.fileno()), "--log-level", log_level],
                pass_fds=[theirs.fileno()], stderr=self.stderr)
            theirs.close()
        else:
            Track.serial += 1
            path = os.path.join(workdir, "track%d.sock" % Track.serial)
            listener = socket.socket(socket.AF_UNIX, socket.SOCK_SEQPACKET)
            listener.bind(path)
            listener.listen(1)
            listener.settimeout(TIMEOUT_S)
            self.proc = subprocess.Popen(
                [GIMBAL_TRACK, "--socket", path, "--log-level", log_level], stderr=self.stderr)
            self.sock, _ = listener.accept()
            listener.close()
        # A datagram is bounded by the send buffer: ask for room for a whole 4 MiB unit
        # (pieces are tested apart).
        self.sock.setsockopt(socket.SOL_SOCKET, socket.SO_SNDBUF, 8 << 20)
        self.hello = self.receive()

    def send(self, datagram):
        self.sock.sendall(datagram)

    def receive(self, timeout=TIMEOUT_S):
        ready, _, _ = select.select([self.sock], [], [], timeout)
        if not ready:
            raise AssertionError("no message from gimbal-track within %.0f s" % timeout)
        data = self.sock.recv(1 << 16)
        if not data:
            raise EOFError("gimbal-track closed the socket")
        return decode(data)

    def receive_until(self, kind, timeout=TIMEOUT_S):
        """Messages up to and including the first of `kind`."""
        got = []
        deadline = time.monotonic() + timeout
        while True:
            m = self.receive(max(0.01, deadline - time.monotonic()))
            got.append(m)
            if m["type"] == kind:
                return got

    def quiet(self, seconds=0.3):
        """Whatever arrives within `seconds` (nothing expected)."""
        got = []
        while select.select([self.sock], [], [], seconds)[0]:
            data = self.sock.recv(1 << 16)
            if not data:
                break
            got.append(decode(data))
        return got

    def log(self):
        self.stderr.flush()
        self.stderr.seek(0)
        return [json.loads(line) for line in self.stderr.read().splitlines() if line.strip()]

    def close(self):
        if self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait(5)
        self.sock.close()
        self.stderr.close()


class TrackTestCase(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.workdir_handle = tempfile.TemporaryDirectory(prefix="gimbal-track-test-")
        cls.workdir = cls.workdir_handle.name
        cls.follow = sample(cls.workdir, "follow", 120)
        cls.bridge = sample(cls.workdir, "bridge", 135)

    @classmethod
    def tearDownClass(cls):
        cls.workdir_handle.cleanup()

    def setUp(self):
        self.run_dir = tempfile.mkdtemp(dir=self.workdir)
        self.track = None

    def tearDown(self):
        if self.track:
            self.track.close()

    def open(self, **kwargs):
        self.track = Track(self.run_dir, **kwargs)
        return self.track

    def lockstep(self, track, units, first=0, count=None):
        """Each unit sent, its box awaited: one box per frame, in order."""
        boxes = []
        for pts, key, data in units[first:None if count is None else first + count]:
            track.send(au_message(pts, key, data))
            m = track.receive()
            self.assertEqual(m["type"], "box", m)
            self.assertEqual(m["pts_90k"], pts)
            boxes.append(m)
        return boxes


class Tracking(TrackTestCase):
    def test_hello_first(self):
        t = self.open()
        self.assertEqual(t.hello, {"type": "hello", "version": 1, "trackers": ["csrt", "kcf"],
                                   "max_au_bytes": 4 << 20})

    def test_boxes_follow_the_vehicle_through_a_corner(self):
        units, truth = self.follow
        for tracker in ("kcf", "csrt"):
            with self.subTest(tracker=tracker):
                t = self.open()
                t.send(start_message(7, truth[0]["box"], tracker))
                boxes = self.lockstep(t, units)
                self.assertEqual(len(boxes), len(truth))
                errors = [error_px(b["box"], tr["box"]) for b, tr in zip(boxes, truth)]
                self.assertTrue(all(b["id"] == 7 and b["state"] == "tracking" for b in boxes))
                self.assertLess(max(errors), 6.0, errors)
                self.assertGreater(min(b["confidence"] for b in boxes), 0.4)
                t.send(stop_message(7))
                self.assertEqual(t.receive(), {"type": "ended", "id": 7, "reason": "stopped"})
                t.close()
                self.track = None

    def test_bridge_lost_then_reacquired_under_the_same_id(self):
        units, truth = self.bridge
        t = self.open()
        t.send(start_message(3, truth[0]["box"], "kcf"))
        boxes = self.lockstep(t, units)
        hidden_until = max(tr["t"] for tr in truth if tr["hidden"] >= 1.0)
        lost = [tr["t"] for b, tr in zip(boxes, truth) if b["state"] == "lost"]
        self.assertTrue(lost, "never lost under the bridge")
        back = [tr["t"] for b, tr in zip(boxes, truth)
                if b["state"] == "tracking" and tr["t"] > hidden_until]
        self.assertTrue(back, "not re-acquired")
        self.assertLessEqual(back[0] - hidden_until, 3.0)
        for b, tr in zip(boxes, truth):
            self.assertEqual(b["id"], 3)
            if tr["hidden"] >= 0.7:  # never a confident box on the bridge
                self.assertEqual(b["state"], "lost", tr)
                self.assertLess(b["confidence"], 0.4)
            if b["state"] == "tracking":
                self.assertLess(error_px(b["box"], tr["box"]), 6.0, tr)
        events = [line["event"] for line in t.log()]
        self.assertEqual(events.count("track_lost"), 1, events)
        self.assertEqual(events.count("track_reacquired"), 1, events)

    def test_timeout_on_the_frames_clock(self):
        units, truth = self.bridge
        t = self.open()
        t.send(start_message(4, truth[0]["box"], "kcf", reacquire_s=0.5))
        got = []
        for pts, key, data in units:
            t.send(au_message(pts, key, data))
            got += t.receive_until("box")
            if any(m["type"] == "ended" for m in t.quiet(0.05)):
                break
        lost_pts = min(m["pts_90k"] for m in got if m["type"] == "box" and m["state"] == "lost")
        last = max(m["pts_90k"] for m in got if m["type"] == "box")
        self.assertAlmostEqual((last - lost_pts) / 90000.0, 0.5, delta=0.07)
        # Nothing follows the end: units are no longer decoded.
        t.send(au_message(*units[-1][:2], units[-1][2]))
        self.assertEqual(t.quiet(), [])

    def test_fd_mode_and_pieces(self):
        # gimbald's way: a socketpair end passed as --fd; a key frame in 1000-byte pieces.
        units, truth = self.follow
        t = self.open(use_fd=True)
        self.assertEqual(t.hello["type"], "hello")
        t.send(start_message(1, truth[0]["box"]))
        pts, key, data = units[0]
        for offset in range(0, len(data), 1000):
            t.send(au_message(pts, key, data[offset:offset + 1000], total=len(data), offset=offset))
        box = t.receive()
        self.assertEqual((box["type"], box["pts_90k"], box["state"]), ("box", 0, "tracking"))
        self.assertLess(error_px(box["box"], truth[0]["box"]), 2.0)

    def test_no_decoding_without_a_track(self):
        units, truth = self.follow
        t = self.open(log_level="debug")
        for pts, key, data in units[:20]:
            t.send(au_message(pts, key, data))
        self.assertEqual(t.quiet(), [])
        t.send(stop_message(9))  # no such track: ignored
        self.assertEqual(t.quiet(), [])
        self.assertNotIn("decoder_open", [line["event"] for line in t.log()])
        # A track from the next key frame on; the units before it are skipped.
        t.send(start_message(2, truth[0]["box"]))
        for pts, key, data in units[1:15]:
            t.send(au_message(pts, key, data))
        self.assertEqual(t.quiet(), [])  # no key frame yet: nothing decoded
        t.send(au_message(*units[15][:2], units[15][2]))
        self.assertEqual(t.receive()["type"], "box")

    def test_a_box_on_empty_ground_is_lost(self):
        units, truth = self.follow
        t = self.open()
        t.send(start_message(5, (-0.1, -0.3, 0.0, -0.2), "kcf"))
        boxes = self.lockstep(t, units, count=20)
        self.assertTrue(all(b["state"] == "lost" and b["confidence"] < 0.4 for b in boxes))


class Hostile(TrackTestCase):
    def test_garbage_is_refused_and_the_process_goes_on(self):
        units, truth = self.follow
        t = self.open()
        bad = [b"", b"\x01", b"\x02\x05", b"\x01\x63", b"\x01\x05" + b"\x00" * 10,
               b"\x01\x03" + b"\xff" * 30, bytes(range(256)), b"\x01\x01\x01\x00"]
        for datagram in bad[1:]:
            t.send(datagram)
            m = t.receive()
            self.assertEqual(m["type"], "error", m)
            self.assertTrue(m["message"].startswith("refused a message: "), m)
        # A box from gimbald is not for gimbal-track either.
        t.send(struct.pack("<BBIq5fB", 1, BOX, 1, 0, 0, 0, 0.1, 0.1, 0.5, 0))
        self.assertEqual(t.receive()["message"], "refused a message: box is not for gimbal-track")
        # A datagram beyond 4 MiB + 64 bytes.
        t.send(au_message(0, True, b"\x00" * (4 << 20), total=4 << 20) + b"\x00" * 100)
        self.assertIn("larger than", t.receive()["message"])
        # Video that is no video, while tracking: decoder errors counted, no box, no crash.
        t.send(start_message(6, truth[0]["box"]))
        for i in range(30):
            t.send(au_message(i, True, b"\x00\x00\x00\x01\x65" + os.urandom(3000)))
        t.quiet(0.5)
        self.assertIsNone(t.proc.poll())
        # ... and real video afterwards is tracked.
        boxes = self.lockstep(t, units, count=5)
        self.assertEqual(boxes[0]["id"], 6)
        self.assertLess(error_px(boxes[-1]["box"], truth[4]["box"]), 6.0)

    def test_eof_ends_the_process(self):
        t = self.open()
        t.sock.shutdown(socket.SHUT_RDWR)
        self.assertEqual(t.proc.wait(TIMEOUT_S), 0)
        self.assertEqual(t.log()[-1]["event"], "stopping")

    def test_sigterm_ends_the_track_then_the_process(self):
        units, truth = self.follow
        t = self.open()
        t.send(start_message(8, truth[0]["box"]))
        self.lockstep(t, units, count=3)
        t.proc.send_signal(signal.SIGTERM)
        self.assertEqual(t.receive(), {"type": "ended", "id": 8, "reason": "stopped"})
        self.assertEqual(t.proc.wait(TIMEOUT_S), 0)
        events = [line["event"] for line in t.log()]
        self.assertEqual(events[-2:], ["stopping", "track_end"])
        for line in t.log():  # every line a record with the contract's keys
            self.assertLessEqual({"ts", "level", "event", "msg"}, set(line))

    def test_command_line(self):
        for args, code in ((["--help"], 0), (["--version"], 0), ([], 1), (["--fd", "x"], 1),
                           (["--fd", "0", "--socket", "/x"], 1), (["--fd", "0"], 1),
                           (["--socket", os.path.join(self.run_dir, "none")], 1)):
            with self.subTest(args=args):
                r = subprocess.run([GIMBAL_TRACK] + args, capture_output=True, text=True,
                                   timeout=TIMEOUT_S, stdin=subprocess.DEVNULL)
                self.assertEqual(r.returncode, code, r.stderr)
        r = subprocess.run([GIMBAL_TRACK, "--help"], capture_output=True, text=True)
        for section in ("NAME", "SYNOPSIS", "DESCRIPTION", "OPTIONS", "EXIT STATUS"):
            self.assertIn("\n" + section, "\n" + r.stdout)


if __name__ == "__main__":
    if not GIMBAL_TRACK or not SAMPLE_STREAM:
        print("skipped: GIMBAL_TRACK or TRACK_SAMPLE_STREAM not set")
        sys.exit(SKIP)
    unittest.main(verbosity=2)
