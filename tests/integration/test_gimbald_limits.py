#!/usr/bin/env python3
"""The request limits of contract section 14 on the UDP socket, HTTP POST /api/command and
the WebSocket stream: over 8192 bytes is too_large, answered unread ("id": null, nothing
echoed); JSON nested deeper than 32 levels is bad_json; neither crashes the daemon, grows its
memory by the request's size or writes the request into the log. (MQTT: test_gimbald_mqtt.sh,
mqtt_limits_tests.py.)"""

import json
import os
import socket
import time

import gimbaltest as gt
import httptest as ht

LIMIT = 8192
# The crash: an `id` of 70,000 nested arrays, about 140 KB.
NESTED_ID = '{"cmd":"ping","id":' + "[" * 70000 + "]" * 70000 + "}"


def nested(depth):
    """A ping whose id nests arrays so that the whole request is `depth` levels deep."""
    arrays = depth - 1  # the request object is the first level
    return '{"cmd":"ping","id":' + "[" * arrays + "]" * arrays + "}"


def padded(size, request_id=9):
    head = '{"cmd":"ping","id":%d,"pad":"' % request_id
    return head + "x" * (size - len(head) - 2) + '"}'


def rss_kib(pid):
    with open("/proc/%d/status" % pid) as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    return 0


def sanitized(pid):
    with open("/proc/%d/maps" % pid) as f:
        return "libasan" in f.read()


class Limits(gt.GimbaldTestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.daemon = cls.start_class_daemon(
            {"gimbals": [{"name": "s", "protocol": "orion", "link": {"type": "sim"}}],
             "http": {"port": 0}})
        start = cls.daemon.wait_log(lambda e: e.get("event") == "start")
        cls.http = int(start["http"].rsplit(":", 1)[1])

    def setUp(self):
        super().setUp()
        self.c = self.client(self.daemon)
        self.log_size = os.path.getsize(self.daemon.stdout_path)

    def tearDown(self):
        self.assertTrue(self.daemon.running(), "gimbald died: " + self.daemon.errors()[-2000:])
        self.assertOk(self.c.request("ping"))
        # Nothing of a refused request reaches the log: a few short lines per request.
        time.sleep(0.1)
        with open(self.daemon.stdout_path, "rb") as f:
            f.seek(self.log_size)
            grown = f.read()
        self.assertLess(len(grown), 64 * 1024, grown[:300])
        for line in grown.splitlines():
            self.assertLess(len(line), 2048, line[:300])

    def assertUnread(self, reply, code):
        """A refusal decided before the request was parsed: nothing echoed."""
        self.assertError(reply, code)
        self.assertIsNone(reply.get("id"), reply)
        self.assertIsNone(reply["cmd"], reply)
        self.assertLess(len(json.dumps(reply)), 300, reply)

    # --- UDP --------------------------------------------------------------------------------

    def test_udp_size_limit(self):
        reply_at = None
        self.c.send_raw(padded(LIMIT).encode())
        reply_at = self.c.recv()
        self.assertError(reply_at, "bad_request", 9)  # parsed: "pad" is unknown
        self.c.send_raw(padded(LIMIT + 1).encode())
        reply = self.c.recv()
        self.assertUnread(reply, "too_large")
        self.assertIn("id", reply)  # present, and null
        self.assertIn("8192", reply["error"]["message"])
        self.c.send_raw(b"[" * 65000)  # nearly the largest datagram there is
        self.assertUnread(self.c.recv(), "too_large")

    def test_udp_deeply_nested_id_is_too_large_not_a_crash(self):
        # A datagram holds at most 65507 bytes: 32,700 nested arrays.
        self.c.send_raw(('{"cmd":"ping","id":' + "[" * 32700 + "]" * 32700 + "}").encode())
        self.assertUnread(self.c.recv(), "too_large")
        entry = self.daemon.wait_log(lambda e: e.get("event") == "command" and
                                     e.get("error") == "too_large")
        self.assertIsNotNone(entry)
        self.assertIsNone(entry["id"])

    def test_udp_nesting_limit(self):
        self.assertOk(json.loads(self.exchange_udp(nested(32))))
        self.assertUnread(json.loads(self.exchange_udp(nested(33))), "bad_json")
        self.assertUnread(json.loads(self.exchange_udp(nested(4000))), "bad_json")
        # Brackets inside strings are text, not nesting.
        reply = json.loads(self.exchange_udp('{"cmd":"ping","id":"%s"}' % ("[{" * 200)))
        self.assertOk(reply)
        self.assertEqual(reply["id"], "[{" * 200)

    def exchange_udp(self, text):
        self.c.send_raw(text.encode())
        reply = self.c.recv()
        self.assertIsNotNone(reply, "no reply to %s..." % text[:40])
        return json.dumps(reply)

    # --- HTTP -------------------------------------------------------------------------------

    def post(self, body):
        status, headers, data = ht.request(self.http, "POST", "/api/command", body=body,
                                           headers={"Content-Type": "application/json"})
        return status, json.loads(data)

    def test_http_size_limit(self):
        status, reply = self.post(padded(LIMIT).encode())
        self.assertEqual(status, 200)
        self.assertError(reply, "bad_request", 9)
        status, reply = self.post(padded(LIMIT + 1).encode())
        self.assertEqual(status, 413)
        self.assertUnread(reply, "too_large")
        self.assertIn(str(LIMIT + 1), reply["error"]["message"])  # the declared length
        status, reply = self.post(NESTED_ID.encode())
        self.assertEqual(status, 413)
        self.assertUnread(reply, "too_large")

    def test_http_nesting_limit(self):
        status, reply = self.post(nested(32).encode())
        self.assertEqual(status, 200)
        self.assertOk(reply)
        status, reply = self.post(nested(33).encode())
        self.assertEqual(status, 200)
        self.assertUnread(reply, "bad_json")

    def test_http_20_mb_body_does_not_grow_memory(self):
        pid = self.daemon.proc.pid
        if sanitized(pid):
            self.skipTest("RSS says little under AddressSanitizer")
        before = rss_kib(pid)
        body = b"[" * (20 * 1024 * 1024)
        head = ("POST /api/command HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json"
                "\r\nContent-Length: %d\r\n\r\n" % len(body)).encode()
        raw = ht.raw_exchange(self.http, head + body, timeout=10)
        self.assertEqual(ht.status_of(raw), 413)
        self.assertIn(b'"too_large"', raw)
        self.assertLess(rss_kib(pid) - before, 16 * 1024)

    # --- WebSocket --------------------------------------------------------------------------

    def ws(self):
        w = ht.WebSocket(self.http)
        self.addCleanup(w.close)
        self.assertEqual(w.recv_json()["type"], "state")
        return w

    def ws_reply(self, w):
        return w.wait_json(lambda m: "ok" in m)

    def test_websocket_size_limit(self):
        w = self.ws()
        w.send_text(padded(LIMIT))
        self.assertError(self.ws_reply(w), "bad_request", 9)
        w.send_text(padded(LIMIT + 1))
        self.assertUnread(self.ws_reply(w), "too_large")
        self.assertEqual(w.wait_close(), 1009)

        w = self.ws()
        w.send_text(NESTED_ID)
        self.assertUnread(self.ws_reply(w), "too_large")
        self.assertEqual(w.wait_close(), 1009)

    def test_websocket_nesting_limit(self):
        w = self.ws()
        w.send_text(nested(33))
        self.assertUnread(self.ws_reply(w), "bad_json")
        # The stream goes on.
        w.send_json({"cmd": "ping", "id": 5})
        reply = self.ws_reply(w)
        self.assertOk(reply)
        self.assertEqual(reply["id"], 5)
        w.send_text(nested(32))
        self.assertOk(self.ws_reply(w))

    def test_websocket_20_mb_message_does_not_grow_memory(self):
        pid = self.daemon.proc.pid
        if sanitized(pid):
            self.skipTest("RSS says little under AddressSanitizer")
        before = rss_kib(pid)
        w = self.ws()
        payload = b"[" * (20 * 1024 * 1024)
        # Masked with the all-zero key (valid, RFC 6455 5.3): the payload goes as it is.
        head = bytes([0x81, 0x80 | 127]) + len(payload).to_bytes(8, "big") + b"\0\0\0\0"
        try:
            w.sock.sendall(head + payload)
        except OSError:
            pass  # the daemon may close before the last byte is sent
        self.assertUnread(self.ws_reply(w), "too_large")
        self.assertLess(rss_kib(pid) - before, 16 * 1024)


if __name__ == "__main__":
    gt.main()
