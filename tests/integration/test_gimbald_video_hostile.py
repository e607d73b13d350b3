"""Hostile video, KLV and RTSP inputs against a real gimbald (contract section 14 v4, issue 25).

A simulated Orion fires its laser under `laser.fire_timeout_s` 2 while the video input is
attacked over UDP; the cease-fire must reach the gimbal within 2.25 s (the simulator's own
clock, its rx log), pings from another socket must all be answered, gimbald's RSS must stay
bounded and STATE small:

- KLV sets of 8 MB with 2 M unknown tags, good and bad checksums, in an unbounded KLV PES
  (the review: cease-fire at 3.5-6.0 s, RSS 781 MB);
- synchronous KLV (ST 1402 metadata AU cells): a first fragment, then "middle" fragments
  without end (the review: 402 MiB sent, 461 MB kept);
- a valid 46.5 KB set (the review: STATE 165 KB, `state` never answered): STATE `video.klv`
  holds at most 8 KiB of JSON;
- a stranger sending KLV to the input once the camera is pinned: counted, never shown or
  relayed (`video.source`).

And an RTSP "camera" written here with plain sockets, speaking just enough RTSP for
libavformat, then misbehaving: a DESCRIBE answered with `Content-Length: 2000000000`, an
H.264 frame whose FU-A fragments never end (the review: 2-2.5 GB, SIGTERM 10.2 s), a camera
that asks for Basic credentials and redirects to another host (which must never see them),
and one that redirects to itself forever (the review: 10,237 connections in 40 s, nothing
logged).

Figures (cease-fire delay, ping p50/p99/max, RSS) are printed.
"""

import array
import base64
import json
import signal
import socket
import struct
import threading
import time

import gimbaltest as gt
import videotest as vt

FIRE = {"enable": True, "arm": True, "fire": True}
FIRE_TIMEOUT_S = 2.0
CEASE_MARGIN_S = 0.25
KLV_PID = 0x101


# --- measuring -------------------------------------------------------------------------------

def rss_mb(pid):
    with open("/proc/%d/status" % pid) as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024.0
    return 0.0


class RssSampler:
    """gimbald's resident memory every 20 ms, in a thread: start, peak, last."""

    def __init__(self, pid):
        self.pid = pid
        self.start = rss_mb(pid)
        self.peak = self.start
        self.last = self.start
        self.running = True
        self.thread = threading.Thread(target=self._run, daemon=True)
        self.thread.start()

    def _run(self):
        while self.running:
            try:
                self.last = rss_mb(self.pid)
            except OSError:
                return
            self.peak = max(self.peak, self.last)
            time.sleep(0.02)

    def stop(self):
        self.running = False
        self.thread.join(timeout=2)


class Pinger:
    """`ping` every 20 ms from a socket of its own; each reply's round trip."""

    def __init__(self, port):
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.sock.bind(("127.0.0.1", 0))
        self.sock.settimeout(0.01)
        self.dest = ("127.0.0.1", port)
        self.sent = {}
        self.rtts = []
        self.running = True
        self.thread = threading.Thread(target=self._run, daemon=True)
        self.thread.start()

    def _run(self):
        n = 0
        next_t = time.monotonic()
        while self.running:
            now = time.monotonic()
            if now >= next_t:
                n += 1
                self.sent[n] = now
                self.sock.sendto(json.dumps({"cmd": "ping", "id": n}).encode(), self.dest)
                next_t += 0.02
            try:
                data = self.sock.recv(65536)
            except socket.timeout:
                continue
            except OSError:
                return
            reply = json.loads(data)
            if reply.get("id") in self.sent:
                self.rtts.append(time.monotonic() - self.sent.pop(reply["id"]))

    def stop(self, grace=2.0):
        """Stops sending, waits `grace` for late replies; returns the unanswered count."""
        deadline = time.monotonic() + grace
        sent_before = dict(self.sent)
        self.running = False
        self.thread.join(timeout=2)
        self.sock.settimeout(0.05)
        while self.sent and time.monotonic() < deadline:
            try:
                reply = json.loads(self.sock.recv(65536))
            except (socket.timeout, OSError):
                continue
            if reply.get("id") in self.sent:
                self.rtts.append(time.monotonic() - self.sent.pop(reply["id"]))
        self.sock.close()
        # Pings sent in the last 20 ms before stopping may be answered after the grace.
        return len([n for n in self.sent if n in sent_before])

    def percentile(self, p):
        if not self.rtts:
            return float("inf")
        ordered = sorted(self.rtts)
        return ordered[min(len(ordered) - 1, int(p / 100.0 * len(ordered)))]


# --- crafting the stream ---------------------------------------------------------------------

def checksum16(data):
    """ST 0601's running 16-bit sum of big-endian words (an odd byte as if a zero followed)."""
    if len(data) % 2:
        data += b"\x00"
    words = array.array("H", data)
    if words.itemsize != 2:
        raise RuntimeError("array 'H' is not 16-bit here")
    words.byteswap()
    return sum(words) & 0xFFFF


def raw_set(items, bad_checksum=False):
    """A UAS Datalink set around `items` (bytes of tag-length-value items), checksum last."""
    body = items + b"\x01\x02"
    packet = vt.UAS_LS_KEY + vt.ber_length(len(body) + 2) + body
    total = checksum16(packet)
    if bad_checksum:
        total ^= 0x5A5A
    return packet + struct.pack(">H", total)


def huge_set(bad_checksum):
    """8 MB: a time stamp, then 2 M unknown items (tag 200, one byte each)."""
    items = bytes([2, 8]) + int(time.time() * 1e6).to_bytes(8, "big")
    items += b"\x81\x48\x01\x00" * 2_000_000
    return raw_set(items, bad_checksum)


def position_items(lat, lon):
    return (bytes([2, 8]) + int(time.time() * 1e6).to_bytes(8, "big") +
            bytes([13, 4]) + vt.signed_map(lat, 90, 4) + bytes([14, 4]) +
            vt.signed_map(lon, 180, 4))


def big_valid_set(lat, lon):
    """46.5 KB, valid: a position, then 911 unknown tags of 48 bytes (tags 200..1110)."""
    items = position_items(lat, lon)
    for tag in range(200, 1111):
        oid = bytes([0x80 | (tag >> 7), tag & 0x7F])
        items += oid + bytes([48]) + bytes([tag & 0xFF]) * 48
    return raw_set(items + bytes([65, 1, 19]))


class Packetizer:
    """Transport packets of a PES on one PID, continuity counted, fast enough for 8 MB."""

    def __init__(self):
        self.cc = {}

    def pes(self, pid, stream_id, payload, pts, bounded=True):
        header = vt._timestamp(0x2, pts)
        length = 3 + len(header) + len(payload)
        pes = (b"\x00\x00\x01" + bytes([stream_id]) +
               struct.pack(">H", length if bounded and length < 65536 else 0) +
               bytes([0x80, 0x80, len(header)]) + header + payload)
        return self.packets(pid, pes)

    def packets(self, pid, pes):
        out = []
        cc = self.cc.get(pid, 0)
        for i in range(0, len(pes), 184):
            chunk = pes[i:i + 184]
            b1 = (0x40 if i == 0 else 0) | (pid >> 8)
            if len(chunk) == 184:
                out.append(bytes((0x47, b1, pid & 0xFF, 0x10 | cc)) + chunk)
            else:
                fill = 184 - len(chunk)
                adaptation = b"\x00" if fill == 1 else bytes([fill - 1, 0]) + b"\xff" * (fill - 2)
                out.append(bytes((0x47, b1, pid & 0xFF, 0x30 | cc)) + adaptation + chunk)
            cc = (cc + 1) & 15
        self.cc[pid] = cc
        return out


def send_packets(sock, dest, packets, stop, burst=64):
    """7 packets a datagram, a short pause every `burst` datagrams so the kernel keeps them."""
    for n, i in enumerate(range(0, len(packets), 7)):
        if stop.is_set():
            return
        sock.sendto(b"".join(packets[i:i + 7]), dest)
        if n % burst == burst - 1:
            time.sleep(0.001)


def metadata_cell(fragment, data, sequence=0):
    """An ST 1402 metadata AU cell (13818-1 Table 2-99): fragment 3 whole, 2 first, 0 middle,
    1 last."""
    return bytes([0, sequence & 0xFF, (fragment << 6) | 0x1F]) + struct.pack(">H", len(data)) + data


# --- the UDP attacks -------------------------------------------------------------------------

class UdpAttacks(gt.GimbaldTestCase):
    """A simulated Orion over TCP with its laser allowed and a 2 s dead-man; the video input
    on UDP with KLV parsed and relayed to a klv-udp output."""

    def setUp(self):
        super().setUp()
        self.sim = self.start_sim()
        self.video_port = gt.free_port()
        self.klv_out = vt.UdpCollector()
        self.addCleanup(self.klv_out.close)
        gimbal = gt.orion_tcp("main", self.sim.port)
        gimbal["video"] = {"input": "udp://127.0.0.1:%d" % self.video_port, "klv": "parse",
                           "outputs": ["klv-udp://127.0.0.1:%d" % self.klv_out.port]}
        self.daemon = self.start_daemon({"gimbals": [gimbal],
                                         "laser": {"allow_fire": True,
                                                   "fire_timeout_s": FIRE_TIMEOUT_S}})
        self.c = self.client(self.daemon)
        self.wait_connected(self.c)
        self.camera = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.camera.bind(("127.0.0.1", 0))
        self.addCleanup(self.camera.close)
        self.dest = ("127.0.0.1", self.video_port)

    def video(self):
        reply = self.c.request("state", keys=["video"])
        self.assertOk(reply)
        return reply["state"]["video"]

    def under_attack(self, attack, name):
        """Runs attack(stop) in a thread, fires the laser 0.5 s in and waits for the
        dead-man's cease-fire, pinging all along; asserts the cease-fire's delay, the pings and
        RSS, and returns the figures."""
        link_before = self.c.request("state", keys=["link"])["state"]["link"]
        stop = threading.Event()
        rss = RssSampler(self.daemon.proc.pid)
        pinger = Pinger(self.daemon.port)
        thread = threading.Thread(target=attack, args=(stop,), daemon=True)
        thread.start()
        time.sleep(0.5)
        start = len(self.sim.rx())
        fire_reply = self.c.request("laser", index=0, timeout=10.0, **FIRE)
        cease = self.sim.wait_rx(lambda e: e["name"] == "laser_cmd" and not e["packet"]["fire"],
                                 timeout=15.0, start=start)
        time.sleep(0.5)
        stop.set()
        thread.join(timeout=30)
        lost = pinger.stop()
        time.sleep(1.0)  # what the attack left settles
        rss.stop()
        end_mb = rss_mb(self.daemon.proc.pid)
        fires = [e for e in self.sim.rx()[start:] if e["name"] == "laser_cmd" and
                 e["packet"]["fire"]]
        figures = {
            "cease_s": cease["t"] - fires[0]["t"] if cease and fires else None,
            "ping_p50_ms": 1000 * pinger.percentile(50),
            "ping_p99_ms": 1000 * pinger.percentile(99),
            "ping_max_ms": 1000 * max(pinger.rtts or [float("inf")]),
            "pings": len(pinger.rtts), "lost": lost,
            "rss_start_mb": rss.start, "rss_peak_mb": rss.peak, "rss_end_mb": end_mb}
        print("%s: %s" % (name, ", ".join(
            "%s %s" % (k, "%.3f" % v if isinstance(v, float) else v)
            for k, v in figures.items())))
        self.assertOk(fire_reply)
        self.assertTrue(fires, "the fire command never reached the gimbal")
        self.assertTrue(cease, "no cease-fire reached the gimbal")
        self.assertLessEqual(figures["cease_s"], FIRE_TIMEOUT_S + CEASE_MARGIN_S, figures)
        self.assertGreater(figures["pings"], 50, figures)
        self.assertEqual(lost, 0, figures)
        self.assertLess(figures["ping_max_ms"], 1000, figures)
        self.assertLess(rss.peak - rss.start, 64, figures)
        self.assertLess(end_mb - rss.start, 16, figures)
        # The Orion's TCP link held all along (the review saw it dropped).
        link = self.c.request("state", keys=["link"])["state"]["link"]
        self.assertIs(link["connected"], True)
        self.assertEqual(link["reconnects"], link_before["reconnects"])
        return figures

    def send_psi(self, writer):
        self.camera.sendto(writer.psi(), self.dest)

    def test_huge_klv_sets_do_not_delay_the_cease_fire(self):
        writer = vt.TsWriter()
        pk = Packetizer()
        sets = [huge_set(bad_checksum=False), huge_set(bad_checksum=True)]
        pts = 90000

        def attack(stop):
            nonlocal pts
            n = 0
            while not stop.is_set():
                self.send_psi(writer)
                packets = pk.pes(KLV_PID, 0xBD, sets[n % 2], pts, bounded=False)
                send_packets(self.camera, self.dest, packets, stop)
                n += 1
                pts += 3000

        self.under_attack(attack, "8 MB KLV sets")
        v = self.video()
        self.assertGreater(v["klv_refused"], 0, v)
        self.assertIsNone(v["klv"], v)  # nothing of them was decoded or shown
        self.assertEqual(self.klv_out.count(), 0)
        self.assert_logged_rolled_up("klv_refused")

    def assert_logged_rolled_up(self, event):
        lines = self.daemon.events(event)
        self.assertTrue(lines, "no %s log line" % event)
        self.assertLessEqual(len(lines), 5, lines)

    def test_sync_klv_middle_fragments_are_bounded(self):
        writer = vt.TsWriter(sync=True)
        pk = Packetizer()
        first = pk.pes(KLV_PID, 0xFC, metadata_cell(2, b"\xA1" * 60000), 90000)
        middle_cell = metadata_cell(0, b"\xA2" * 60000)

        def attack(stop):
            self.send_psi(writer)
            send_packets(self.camera, self.dest, first, stop)
            sent = 0
            while not stop.is_set() and sent < 256 << 20:
                if sent % (8 << 20) < 60000:
                    self.send_psi(writer)
                send_packets(self.camera, self.dest, pk.pes(KLV_PID, 0xFC, middle_cell, 90000),
                             stop)
                sent += len(middle_cell)
            print("middle fragments sent: %.0f MB" % (sent / 1e6))

        self.under_attack(attack, "sync KLV middle fragments")
        v = self.video()
        self.assertGreater(v["klv_refused"], 100, v)
        self.assertIsNone(v["klv"], v)
        self.assert_logged_rolled_up("klv_refused")

    def test_a_valid_46kb_set_keeps_state_small(self):
        writer = vt.TsWriter()
        pk = Packetizer()
        big = big_valid_set(45.7088577, -121.4977648)
        self.assertGreater(len(big), 46000)

        def attack(stop):
            pts = 90000
            while not stop.is_set():
                self.send_psi(writer)
                send_packets(self.camera, self.dest, pk.pes(KLV_PID, 0xBD, big, pts), stop)
                pts += 3000
                time.sleep(0.02)

        self.under_attack(attack, "46.5 KB valid sets")
        reply = self.c.request("state")
        self.assertOk(reply, "the full STATE was not answered")
        klv = reply["state"]["video"]["klv"]
        self.assertLessEqual(len(json.dumps(klv, separators=(",", ":"))), 8192)
        self.assertIs(klv["truncated"], True)
        self.assertNotIn("unknown", klv)
        self.assertAlmostEqual(klv["sensor_latitude"], 45.7088577, places=6)
        self.assertAlmostEqual(klv["sensor_longitude"], -121.4977648, places=6)
        self.assertIsInstance(klv["age_s"], (int, float))
        # The set itself is relayed whole.
        self.assertTrue(gt.wait_for(lambda: self.klv_out.count() > 0, 2.0))
        self.assertEqual(self.klv_out.data()[0], big)
        # The klv command shows the same cut JSON, and the whole set as hex.
        reply = self.c.request("klv")
        if reply is not None and reply.get("ok"):
            self.assertEqual(bytes.fromhex(reply["klv_hex"]), big)
            self.assertIs(reply["klv"]["truncated"], True)

    def test_a_foreign_sender_is_counted_not_used(self):
        writer = vt.TsWriter()
        stranger = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        stranger.bind(("127.0.0.1", 0))
        self.addCleanup(stranger.close)
        other_writer = vt.TsWriter()
        pts = 90000
        for n in range(30):  # the camera, first: pinned
            ts = (writer.psi() if n % 10 == 0 else b"") + writer.klv_pes(
                vt.klv_set(int(time.time() * 1e6), 45.7, -121.5), pts)
            self.camera.sendto(ts, self.dest)
            pts += 3000
            time.sleep(0.02)
        self.assertTrue(gt.wait_for(lambda: (self.video()["klv"] or {}).get("sensor_latitude"),
                                    2.0))
        time.sleep(0.3)  # the camera's sets still in flight
        relayed = self.klv_out.count()
        for n in range(30):  # now both: the stranger's sets say latitude 10
            self.camera.sendto(writer.klv_pes(vt.klv_set(int(time.time() * 1e6), 45.7, -121.5),
                                              pts), self.dest)
            ts = (other_writer.psi() if n % 10 == 0 else b"") + other_writer.klv_pes(
                vt.klv_set(int(time.time() * 1e6), 10.0, 10.0), pts)
            stranger.sendto(ts, self.dest)
            pts += 3000
            time.sleep(0.02)
            v = self.video()
            self.assertAlmostEqual(v["klv"]["sensor_latitude"], 45.7, places=5)
        time.sleep(0.3)
        v = self.video()
        self.assertEqual(v["source"], "127.0.0.1:%d" % self.camera.getsockname()[1])
        self.assertEqual(v["foreign_datagrams"], 30)
        sets = self.klv_out.data(relayed)
        self.assertEqual(len(sets), 30)
        for s in sets:
            self.assertEqual(s[:16], vt.UAS_LS_KEY)
            self.assertNotIn(vt.signed_map(10.0, 90, 4), s)
        log = self.daemon.wait_log(lambda e: e.get("event") == "video_foreign", 2.0)
        self.assertTrue(log, "no video_foreign log line")
        self.assertEqual(log["from"], "127.0.0.1:%d" % stranger.getsockname()[1])
        self.assertLessEqual(len(self.daemon.events("video_foreign")), 3)  # rolled up


# --- the hostile RTSP camera -----------------------------------------------------------------

SPS = bytes.fromhex("6742c016d900a02ff970110000030001000003001e0f162e48")
PPS = bytes.fromhex("68cb83cb20")


class RtspCamera:
    """An RTSP server on `host`, written with plain sockets: OPTIONS, DESCRIBE, SETUP, PLAY as
    libavformat sends them, then whatever `mode` says. Records every request (method, URL,
    headers) and counts connections."""

    def __init__(self, mode, host="127.0.0.1", redirect_to=None, user=None, password=None):
        self.mode, self.redirect_to = mode, redirect_to
        self.auth = None
        if user:
            self.auth = "Basic " + base64.b64encode(("%s:%s" % (user, password)).encode()).decode()
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
        self.sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        self.sock.bind((host, 0))
        self.sock.listen(64)
        self.sock.settimeout(0.2)
        self.host, self.port = host, self.sock.getsockname()[1]
        self.requests = []
        self.connections = 0
        self.bytes_sent = 0
        self.lock = threading.Lock()
        self.running = True
        self.thread = threading.Thread(target=self._accept, daemon=True)
        self.thread.start()

    def url(self, path="/stream", credentials=""):
        return "rtsp://%s%s:%d%s" % (credentials, self.host, self.port, path)

    def close(self):
        self.running = False
        self.thread.join(timeout=3)
        self.sock.close()

    def _accept(self):
        while self.running:
            try:
                conn, _ = self.sock.accept()
            except socket.timeout:
                continue
            except OSError:
                return
            with self.lock:
                self.connections += 1
            threading.Thread(target=self._serve, args=(conn,), daemon=True).start()

    def _serve(self, conn):
        conn.settimeout(0.5)
        pending = b""
        try:
            while self.running:
                while b"\r\n\r\n" not in pending:
                    try:
                        chunk = conn.recv(4096)
                    except socket.timeout:
                        if not self.running:
                            return
                        continue
                    if not chunk:
                        return
                    pending += chunk
                    while pending.startswith(b"$") and len(pending) >= 4:  # interleaved RTCP
                        size = struct.unpack(">H", pending[2:4])[0]
                        if len(pending) < 4 + size:
                            break
                        pending = pending[4 + size:]
                head, _, pending = pending.partition(b"\r\n\r\n")
                lines = head.decode(errors="replace").split("\r\n")
                method, url = (lines[0].split() + ["", ""])[:2]
                headers = {}
                for line in lines[1:]:
                    key, _, value = line.partition(":")
                    headers[key.strip().lower()] = value.strip()
                with self.lock:
                    self.requests.append((method, url, headers))
                if not self._answer(conn, method, headers):
                    return
        except OSError:
            return
        finally:
            conn.close()

    def _send(self, conn, status, cseq, extra="", body=b""):
        text = "RTSP/1.0 %s\r\nCSeq: %s\r\n%s" % (status, cseq, extra)
        if body:
            text += "Content-Length: %d\r\n" % len(body)
        conn.sendall(text.encode() + b"\r\n" + body)

    def _answer(self, conn, method, headers):
        """Answers one request; False ends the connection."""
        cseq = headers.get("cseq", "0")
        if self.auth and headers.get("authorization") != self.auth:
            self._send(conn, "401 Unauthorized", cseq, 'WWW-Authenticate: Basic realm="cam"\r\n')
            return True
        if self.mode == "loop":
            self._send(conn, "302 Moved", cseq, "Location: %s\r\n" % self.url(
                "/loop%d" % len(self.requests)))
            return True
        if method == "OPTIONS":
            self._send(conn, "200 OK", cseq, "Public: OPTIONS, DESCRIBE, SETUP, PLAY, TEARDOWN\r\n")
            return True
        if self.mode == "redirect" and method == "DESCRIBE":
            self._send(conn, "302 Moved", cseq, "Location: %s\r\n" % self.redirect_to)
            return True
        if self.mode == "refuse":
            self._send(conn, "404 Not Found", cseq)
            return True
        if method == "DESCRIBE" and self.mode == "huge_describe":
            conn.sendall(("RTSP/1.0 200 OK\r\nCSeq: %s\r\nContent-Type: application/sdp\r\n"
                          "Content-Length: 2000000000\r\n\r\nv=0\r\n" % cseq).encode())
            self._flood(conn, b"a=x-junk:" + b"z" * 65000 + b"\r\n")
            return False
        if method == "DESCRIBE":
            sdp = ("v=0\r\no=- 0 0 IN IP4 127.0.0.1\r\ns=hostile\r\nc=IN IP4 127.0.0.1\r\n"
                   "t=0 0\r\nm=video 0 RTP/AVP 96\r\na=rtpmap:96 H264/90000\r\n"
                   "a=fmtp:96 packetization-mode=1;sprop-parameter-sets=%s,%s\r\n"
                   "a=control:track1\r\n" % (base64.b64encode(SPS).decode(),
                                              base64.b64encode(PPS).decode())).encode()
            self._send(conn, "200 OK", cseq,
                       "Content-Type: application/sdp\r\nContent-Base: %s/\r\n" % self.url(), sdp)
            return True
        if method == "SETUP":
            self._send(conn, "200 OK", cseq, "Transport: RTP/AVP/TCP;unicast;interleaved=0-1\r\n"
                       "Session: 12345678;timeout=60\r\n")
            return True
        if method == "PLAY":
            self._send(conn, "200 OK", cseq, "Session: 12345678\r\n")
            if self.mode == "endless_frame":
                self._endless_frame(conn)
                return False
            return True
        self._send(conn, "200 OK", cseq, "Session: 12345678\r\n")
        return True

    def _flood(self, conn, chunk):
        while self.running:
            conn.sendall(chunk)
            self.bytes_sent += len(chunk)

    def _endless_frame(self, conn):
        """One IDR slice in FU-A fragments (RFC 6184 5.8): a start, then middles, never an end."""
        seq = 0
        fragment = b"\x55" * 32000

        def rtp(payload):
            nonlocal seq
            header = struct.pack(">BBHII", 0x80, 96, seq & 0xFFFF, 1000, 0x1234)
            seq += 1
            packet = header + payload
            return b"$\x00" + struct.pack(">H", len(packet)) + packet

        conn.sendall(rtp(bytes([0x7C, 0x85]) + fragment))  # FU-A, start, NAL type 5
        middle = rtp(bytes([0x7C, 0x05]) + fragment)
        while self.running:
            conn.sendall(middle[:6] + struct.pack(">H", seq & 0xFFFF) + middle[8:])
            seq += 1
            self.bytes_sent += len(middle)


class RtspAttacks(gt.GimbaldTestCase):
    """One gimbal (a simulated Viewpro: no link to wait for) whose video input is the hostile
    camera."""

    def start_with(self, camera, url):
        self.addCleanup(camera.close)
        self.daemon = self.start_daemon({"gimbals": [{
            "name": "cam", "protocol": "viewpro", "link": {"type": "sim"},
            "video": {"input": url + "?transport=tcp&timeout_s=1"}}]})
        self.c = self.client(self.daemon)
        return self.daemon

    def video(self):
        reply = self.c.request("state", keys=["video"])
        self.assertOk(reply)
        return reply["state"]["video"]

    def memory_and_sigterm(self, camera, name, seconds=6.0):
        """Lets the camera misbehave for `seconds`, then stops gimbald with SIGTERM: RSS stays
        bounded and gimbald exits 0 within 2 s."""
        daemon = self.start_with(camera, camera.url())
        rss = RssSampler(daemon.proc.pid)
        time.sleep(seconds)
        rss.stop()
        t0 = time.monotonic()
        daemon.proc.send_signal(signal.SIGTERM)
        try:
            code = daemon.proc.wait(timeout=15)
        except Exception:
            code = None
        stop_s = time.monotonic() - t0
        daemon.stop(signal.SIGKILL)
        print("%s: camera sent %.0f MB in %.0f s; RSS start %.1f MB, peak %.1f MB; SIGTERM to "
              "exit %.2f s (exit %s)" % (name, camera.bytes_sent / 1e6, seconds, rss.start,
                                         rss.peak, stop_s, code))
        self.assertGreater(camera.connections, 0)
        self.assertLess(rss.peak - rss.start, 64, "RSS grew from %.1f to %.1f MB" %
                        (rss.start, rss.peak))
        self.assertEqual(code, 0)
        self.assertLess(stop_s, 2.0)
        return daemon

    def test_describe_with_a_2gb_content_length(self):
        camera = RtspCamera("huge_describe")
        daemon = self.memory_and_sigterm(camera, "Content-Length 2000000000")
        errors = [e for e in daemon.logs() if e.get("event") == "video_input_error"]
        self.assertTrue(errors, "the failed connections were not logged")

    def test_a_frame_that_never_ends(self):
        camera = RtspCamera("endless_frame")
        self.memory_and_sigterm(camera, "endless FU-A frame")

    def test_credentials_never_follow_a_redirect_to_another_host(self):
        other = RtspCamera("refuse", host="127.0.0.2")
        self.addCleanup(other.close)
        camera = RtspCamera("redirect", redirect_to=other.url("/elsewhere"), user="admin",
                            password="s3cret")
        self.start_with(camera, camera.url(credentials="admin:s3cret@"))
        self.assertTrue(gt.wait_for(lambda: other.requests, 10.0),
                        "the redirect was not followed")
        time.sleep(1.0)
        seen = [r for r in camera.requests if r[2].get("authorization")]
        self.assertTrue(seen, "the camera itself never got the credentials")
        for method, url, headers in other.requests:
            self.assertNotIn("authorization", headers, (method, url, headers))
            self.assertNotIn("s3cret", url)
        log = self.daemon.wait_log(lambda e: e.get("event") == "rtsp_redirect", 3.0)
        self.assertTrue(log, "the redirect was not logged")
        self.assertEqual(log["to"], other.url("/elsewhere"))
        self.assertNotIn("s3cret", self.daemon.log_text())
        v = self.video()
        self.assertEqual(v["input"], camera.url(credentials="admin:***@") +
                         "?transport=tcp&timeout_s=1")

    def test_a_redirect_loop_is_cut_logged_and_backed_off(self):
        camera = RtspCamera("loop")
        self.start_with(camera, camera.url())
        time.sleep(8.0)
        connections = camera.connections
        v = self.video()
        print("redirect loop: %d connections in 8 s; STATE last_error %r, reconnects %s" %
              (connections, v.get("last_error"), v.get("reconnects")))
        self.assertLess(connections, 60)
        self.assertIn("redirect", v["last_error"])
        self.assertGreater(v["reconnects"], 0)
        self.assertFalse(v["connected"])
        errors = [e for e in self.daemon.logs() if e.get("event") == "video_input_error"]
        self.assertTrue(errors, "the failures were not logged")
        self.assertLessEqual(len(errors), 10)

    def test_a_camera_that_refuses_is_logged_and_shown(self):
        camera = RtspCamera("refuse")
        self.start_with(camera, camera.url())
        log = self.daemon.wait_log(lambda e: e.get("event") == "video_input_error", 10.0)
        self.assertTrue(log, "a camera that never sent a frame failed silently")
        self.assertIn("rtsp open", log["msg"])
        v = gt.wait_for(lambda: (lambda v: v if v["last_error"] else None)(self.video()), 5.0)
        self.assertTrue(v, self.video())
        self.assertIn("rtsp open", v["last_error"])


if __name__ == "__main__":
    gt.main()
