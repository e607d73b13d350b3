"""Replies and pushes too large for one datagram (contract section 14, v4): "a reply or push
that cannot be sent is logged and counted; a reply too large for one datagram is too_large,
never silence".

The daemon's replies are made large the way the hostile review of issue 25 did it: one valid
MISB ST 0601 set of about 36 KB on the UDP video input, its items under tags ST 0601 does not
define (STATE and the `klv` reply show each of their bytes as two hex digits). Whatever bound
the video input puts on STATE `video.klv`, the `klv` reply carries the set itself as hex
(`klv_hex`, 72 KB): over the 65,507 bytes of one datagram. The STATE's own size is read over
HTTP (TCP, no datagram limit) to know which answer `state` must get.

A reply the socket refuses outright is provoked with a request from source port 0 (crafted
with a raw socket; needs root): Linux refuses to send to port 0 (EINVAL).
"""

import json
import os
import socket
import struct
import time

import gimbaltest as gt
import httptest as ht
import videotest as vt

DATAGRAM = 65507


def big_klv_set(items=6, item_bytes=6000):
    """A valid UAS Datalink LS: time stamp, latitude, longitude, version, `items` items of
    `item_bytes` under undefined tags 200.., checksum."""
    body = bytes([2, 8]) + int(time.time() * 1e6).to_bytes(8, "big")
    body += bytes([13, 4]) + vt.signed_map(45.7, 90, 4)
    body += bytes([14, 4]) + vt.signed_map(-121.5, 180, 4)
    body += bytes([65, 1, 19])
    for i in range(items):
        tag = 200 + i  # BER-OID: two bytes
        value = bytes((i * 7 + n) & 0xFF for n in range(item_bytes))
        body += bytes([0x80 | (tag >> 7), tag & 0x7F]) + vt.ber_length(len(value)) + value
    body += bytes([1, 2])
    packet = vt.UAS_LS_KEY + vt.ber_length(len(body) + 2) + body
    total = 0
    for i, b in enumerate(packet):
        total += b << (8 if i % 2 == 0 else 0)
    return packet + (total & 0xFFFF).to_bytes(2, "big")


def klv_only_ts(klv, pts):
    """PAT, PMT and one KLV PES (the PMT also names a video PID that never carries data)."""
    w = vt.TsWriter()
    return w.psi() + w.klv_pes(klv, pts)


def http_port(daemon):
    start = daemon.wait_log(lambda e: e.get("event") == "start")
    return int(start["http"].rsplit(":", 1)[1])


def udp_from_port_zero(dest_port, payload):
    """Sends `payload` to 127.0.0.1:dest_port from 127.0.0.1 port 0 (a raw socket builds the
    UDP header; checksum 0 means "none" on IPv4)."""
    raw = socket.socket(socket.AF_INET, socket.SOCK_RAW, socket.IPPROTO_UDP)
    try:
        header = struct.pack(">HHHH", 0, dest_port, 8 + len(payload), 0)
        raw.sendto(header + payload, ("127.0.0.1", 0))
    finally:
        raw.close()


class LargeReplies(gt.GimbaldTestCase):
    """A Viewpro sim gimbal whose video input got one 36 KB KLV set."""

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.in_port = gt.free_port()
        cls.daemon = cls.start_class_daemon({
            "gimbals": [{"name": "cam", "protocol": "viewpro", "link": {"type": "sim"},
                         "video": {"input": "udp://127.0.0.1:%d" % cls.in_port,
                                   "klv": "parse"}}],
            "http": {"port": 0}})
        cls.http = http_port(cls.daemon)
        cls.klv = big_klv_set()
        sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        try:
            ts = klv_only_ts(cls.klv, 10 * vt.PTS_HZ)
            for d in vt.datagrams(ts):
                sock.sendto(d, ("127.0.0.1", cls.in_port))
                time.sleep(0.001)
        finally:
            sock.close()

        def arrived():
            _, _, body = ht.request(cls.http, "GET", "/api/state")
            video = json.loads(body)["gimbals"]["cam"]["video"]
            return video if video and video["klv_sets"] >= 1 else None
        cls.video = gt.wait_for(arrived, 10.0, interval=0.1)

    def setUp(self):
        super().setUp()
        self.assertTrue(self.video, "the KLV set never reached STATE (HTTP /api/state)")
        self.c = self.client(self.daemon)

    def state_bytes(self):
        """The STATE's size as JSON text, read over HTTP (no datagram limit there)."""
        _, _, body = ht.request(self.http, "GET", "/api/state")
        state = json.loads(body)["gimbals"]["cam"]
        return len(json.dumps(state, separators=(",", ":")))

    def assertTooLarge(self, reply, request_id):
        self.assertError(reply, "too_large", request_id)
        message = reply["error"]["message"]
        self.assertIn("bytes, over the limit of one datagram (%d bytes)" % DATAGRAM, message)
        size = int(message.split("the reply is ", 1)[1].split(" ", 1)[0])
        self.assertGreater(size, DATAGRAM)
        return message

    def test_klv_reply_over_a_datagram_is_too_large(self):
        reply = self.c.request("klv", id="k1")
        self.assertIsNotNone(reply, "silence: no reply to `klv`")
        self.assertTooLarge(reply, "k1")
        entry = self.daemon.wait_log(lambda e: e.get("event") == "command" and
                                     e.get("id") == "k1")
        self.assertEqual((entry["cmd"], entry["ok"], entry["error"]), ("klv", False, "too_large"))
        # Over HTTP the same command has no datagram to fit: the whole set comes back.
        _, over_http = ht.post_command(self.http, {"cmd": "klv", "id": "k2"})
        self.assertEqual(over_http["klv_hex"].lower(), self.klv.hex())

    def test_state_gets_a_reply_and_too_large_names_keys(self):
        size = self.state_bytes()
        print("STATE over HTTP: %d bytes" % size)
        reply = self.c.request("state", id="s1")
        self.assertIsNotNone(reply, "silence: no reply to `state` (STATE is %d bytes)" % size)
        if size > DATAGRAM:
            message = self.assertTooLarge(reply, "s1")
            self.assertIn("'keys'", message)
        elif size < DATAGRAM - 1000:
            self.assertOk(reply)
        # Fewer keys always fit.
        small = self.c.request("state", id="s2", keys=["link"])
        self.assertOk(small)
        self.assertNotIn("video", small["state"])

    def test_subscription_is_never_silent(self):
        size = self.state_bytes()
        whole = self.client(self.daemon)
        lean = self.client(self.daemon)
        self.assertOk(whole.request("subscribe", rate_hz=5, ttl_s=10, events=False))
        self.assertOk(lean.request("subscribe", rate_hz=5, ttl_s=10, events=False,
                                   keys=["link"]))
        got = whole.collect(1.5)
        lean_got = lean.collect(0.2)
        self.assertGreaterEqual(len(got), 4, "silence: %d datagrams in 1.5 s at 5 Hz "
                                "(STATE is %d bytes)" % (len(got), size))
        self.assertTrue(lean_got and all(gt.is_state(m) for m in lean_got), lean_got)
        if size > DATAGRAM:
            for m in got:
                self.assertEqual((m.get("type"), m.get("event"), m.get("gimbal")),
                                 ("event", "too_large", "cam"), m)
                self.assertGreater(m["bytes"], DATAGRAM)
                self.assertEqual(m["limit"], DATAGRAM)
                self.assertIn("video", m["largest"])
                self.assertIn("keys", m["message"])
            counters = self.c.request("state", keys=["command"])["state"]["command"]
            self.assertGreaterEqual(counters["push_too_large"], len(got))
            self.assertTrue(self.daemon.wait_log(lambda e: e.get("event") == "push_too_large"))
        else:
            self.assertTrue(all(gt.is_state(m) for m in got), got)
        whole.request("unsubscribe")
        lean.request("unsubscribe")

    def test_a_reply_the_socket_refuses_is_logged_and_counted(self):
        if os.geteuid() != 0:
            self.skipTest("a raw socket (source port 0) needs root")
        before = self.c.request("state", keys=["command"])["state"]["command"]["send_failed"]
        udp_from_port_zero(self.daemon.port, b'{"cmd":"ping","id":"zero"}')
        entry = self.daemon.wait_log(lambda e: e.get("event") == "send_failed")
        self.assertTrue(entry, "no send_failed line")
        self.assertEqual((entry["what"], entry["src"]), ("reply", "127.0.0.1:0"))
        after = self.c.request("state", keys=["command"])["state"]["command"]["send_failed"]
        self.assertEqual(after - before, 1)


if __name__ == "__main__":
    gt.main()
