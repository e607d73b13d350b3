#!/usr/bin/env python3
"""HTTP hardening of contract section 14: no response can be framed by another site
(X-Frame-Options: DENY, Content-Security-Policy frame-ancestors 'none') whatever its path or
status, WebSocket handshakes and their refusals included; one client address holds at most
http.max_connections_per_client connections, so 64 slow header-trickling connections from
127.0.0.1 leave 127.0.0.2's /healthz alone; a started request has 10 s for its header."""

import os
import select
import socket
import time

import gimbaltest as gt
import httptest as ht

HEALTHZ = b"GET /healthz HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n"
SIM = {"gimbals": [{"name": "s", "protocol": "orion", "link": {"type": "sim"}}]}


def http_port(daemon):
    start = daemon.wait_log(lambda e: e.get("event") == "start")
    return int(start["http"].rsplit(":", 1)[1])


def head_of(raw):
    """(status, {lower-case name: value}) of a raw HTTP response."""
    head = raw.split(b"\r\n\r\n", 1)[0].decode(errors="replace")
    lines = head.split("\r\n")
    headers = {}
    for line in lines[1:]:
        name, _, value = line.partition(":")
        headers[name.strip().lower()] = value.strip()
    return ht.status_of(raw), headers


def connect_from(source, port, timeout=5.0):
    s = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    s.bind((source, 0))
    s.settimeout(timeout)
    s.connect(("127.0.0.1", port))
    return s


def closed_by_peer(sock, timeout):
    """True when the peer closes (or resets) `sock` within `timeout` seconds."""
    ready, _, _ = select.select([sock], [], [], timeout)
    if not ready:
        return False
    try:
        return sock.recv(4096) == b""
    except (ConnectionResetError, OSError):
        return True


class FramePolicy(gt.GimbaldTestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        config = dict(SIM, http={"port": 0})
        cls.daemon = cls.start_class_daemon(config)
        cls.port = http_port(cls.daemon)

    def assertNoFraming(self, status, headers, what):
        self.assertEqual(headers.get("x-frame-options"), "DENY", "%s (%s): %s" %
                         (what, status, headers))
        policy = headers.get("content-security-policy", "")
        self.assertIn("frame-ancestors 'none'", policy, "%s (%s)" % (what, status))

    def raw(self, data, what, expected_status):
        raw = ht.raw_exchange(self.port, data)
        status, headers = head_of(raw)
        expected = expected_status if isinstance(expected_status, tuple) else (expected_status,)
        self.assertIn(status, expected, "%s: %r" % (what, raw[:200]))
        self.assertNoFraming(status, headers, what)

    def test_every_path_and_status(self):
        host = "Host: 127.0.0.1\r\nConnection: close\r\n"
        cases = [
            ("console", b"GET / HTTP/1.1\r\n" + host.encode() + b"\r\n", 200),
            ("static file", b"GET /console.js HTTP/1.1\r\n" + host.encode() + b"\r\n", 200),
            ("HEAD", b"HEAD / HTTP/1.1\r\n" + host.encode() + b"\r\n", 200),
            ("metrics", b"GET /metrics HTTP/1.1\r\n" + host.encode() + b"\r\n", 200),
            # 503 while the simulated gimbal's telemetry is not (or no longer) fresh: on a
            # loaded machine it can be either; the headers are what this checks.
            ("healthz", b"GET /healthz HTTP/1.1\r\n" + host.encode() + b"\r\n", (200, 503)),
            ("state", b"GET /api/state HTTP/1.1\r\n" + host.encode() + b"\r\n", 200),
            ("console info", b"GET /api/console HTTP/1.1\r\n" + host.encode() + b"\r\n", 200),
            ("command", b"POST /api/command HTTP/1.1\r\n" + host.encode() +
             b"Content-Length: 14\r\n\r\n{\"cmd\":\"ping\"}", 200),
            ("not found", b"GET /nosuch HTTP/1.1\r\n" + host.encode() + b"\r\n", 404),
            ("method", b"GET /api/command HTTP/1.1\r\n" + host.encode() + b"\r\n", 405),
            ("stream without upgrade", b"GET /api/stream HTTP/1.1\r\n" + host.encode() +
             b"\r\n", 426),
            ("malformed", b"THIS IS NOT HTTP\r\n\r\n", 400),
            ("header too large", b"GET / HTTP/1.1\r\n" + host.encode() + b"X-F: " +
             b"a" * 9000 + b"\r\n\r\n", 431),
            ("body too large", b"POST /api/command HTTP/1.1\r\n" + host.encode() +
             b"Content-Length: 9000\r\n\r\n" + b"x" * 9000, 413),
            ("other body too large", b"POST /healthz HTTP/1.1\r\n" + host.encode() +
             b"Content-Length: 9000\r\n\r\n" + b"x" * 9000, 413),
            ("cross-site host", b"GET /api/state HTTP/1.1\r\nHost: evil.example\r\n\r\n", 403),
            ("cross-site origin", b"POST /api/command HTTP/1.1\r\n" + host.encode() +
             b"Origin: http://evil.example\r\nContent-Length: 14\r\n\r\n{\"cmd\":\"ping\"}",
             403),
        ]
        for what, data, status in cases:
            with self.subTest(what):
                self.raw(data, what, status)

    def test_websocket_handshakes(self):
        w = ht.WebSocket(self.port)
        self.addCleanup(w.close)
        lines = w.handshake.split("\r\n")
        headers = {k.strip().lower(): v.strip() for k, _, v in
                   (line.partition(":") for line in lines[1:])}
        self.assertNoFraming(101, headers, "WebSocket upgrade")
        # Beast refuses a broken upgrade itself (no Sec-WebSocket-Key): still decorated.
        self.raw(b"GET /api/stream HTTP/1.1\r\nHost: 127.0.0.1\r\nUpgrade: websocket\r\n"
                 b"Connection: Upgrade\r\nSec-WebSocket-Version: 13\r\n\r\n",
                 "broken upgrade", 400)
        self.raw(b"GET /api/stream HTTP/1.1\r\nHost: 127.0.0.1\r\nUpgrade: websocket\r\n"
                 b"Connection: Upgrade\r\nSec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\n"
                 b"Origin: http://evil.example\r\nSec-WebSocket-Version: 13\r\n\r\n",
                 "cross-site upgrade", 403)


class PerClientCap(gt.GimbaldTestCase):
    def test_one_host_trickling_headers_does_not_starve_another(self):
        daemon = self.start_daemon(dict(SIM, http={"port": 0}))
        port = http_port(daemon)
        held = []
        self.addCleanup(lambda: [s.close() for s in held])
        # 64 connections from 127.0.0.1, each sending its header a byte at a time.
        for _ in range(64):
            s = connect_from("127.0.0.1", port)
            s.sendall(b"G")
            held.append(s)
        time.sleep(0.3)
        # Past the 16 per client, the daemon closed them at once.
        closed = [s for s in held if closed_by_peer(s, 0.05)]
        self.assertEqual(len(closed), 64 - 16)
        # Another address is served as usual.
        t0 = time.monotonic()
        raw = ht.raw_exchange(port, HEALTHZ,
                              source="127.0.0.2")
        self.assertEqual(ht.status_of(raw), 200, raw[:200])
        self.assertLess(time.monotonic() - t0, 2.0)
        # And so is the first host, once it closes one of its connections.
        open_ones = [s for s in held if s not in closed]
        open_ones[0].close()
        time.sleep(0.2)
        raw = ht.raw_exchange(port, HEALTHZ,
                              source="127.0.0.1")
        self.assertEqual(ht.status_of(raw), 200)
        metrics = ht.parse_metrics(ht.request(port, "GET", "/metrics")[2].decode())
        self.assertGreaterEqual(ht.metric(metrics, "gimbald_http_connections_rejected_total"),
                                48)
        self.assertTrue(daemon.wait_log(lambda e: e.get("event") == "http_over_capacity" and
                                        "max_per_client" in e))

    def test_websocket_clients_count_against_the_cap(self):
        daemon = self.start_daemon(dict(SIM, http={"port": 0, "max_connections_per_client": 2}))
        port = http_port(daemon)
        streams = [ht.WebSocket(port) for _ in range(2)]
        for w in streams:
            self.addCleanup(w.close)
        time.sleep(0.2)
        self.assertEqual(ht.raw_exchange(port, b"GET /healthz HTTP/1.1\r\n\r\n"), b"")
        raw = ht.raw_exchange(port, HEALTHZ,
                              source="127.0.0.3")
        self.assertEqual(ht.status_of(raw), 200)
        streams[0].close()
        time.sleep(0.3)
        raw = ht.raw_exchange(port, HEALTHZ)
        self.assertEqual(ht.status_of(raw), 200)


class HeaderDeadline(gt.GimbaldTestCase):
    def test_a_started_header_has_10_s(self):
        # The idle timeout (30 s) applies only until a request's first byte.
        daemon = self.start_daemon(dict(SIM, http={"port": 0, "idle_timeout_s": 30}))
        port = http_port(daemon)
        s = connect_from("127.0.0.1", port, timeout=20)
        self.addCleanup(s.close)
        idle = connect_from("127.0.0.1", port, timeout=20)
        self.addCleanup(idle.close)
        t0 = time.monotonic()
        trickle = b"GET /healthz HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Slow: " + b"a" * 100
        closed_at = None
        for byte in trickle:
            try:
                s.sendall(bytes([byte]))
            except OSError:
                closed_at = time.monotonic()
                break
            if closed_by_peer(s, 0.4):
                closed_at = time.monotonic()
                break
        self.assertIsNotNone(closed_at, "the trickling connection was never closed")
        self.assertGreater(closed_at - t0, 9.0)
        self.assertLess(closed_at - t0, 13.0)
        # The connection that sent nothing yet is still open (idle timeout 30 s).
        self.assertFalse(closed_by_peer(idle, 0.1))
        idle.sendall(HEALTHZ)
        self.assertTrue(idle.recv(100).startswith(b"HTTP/1.1 200"))


if __name__ == "__main__":
    gt.main()
