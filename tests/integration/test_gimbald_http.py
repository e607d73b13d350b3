#!/usr/bin/env python3
"""The HTTP side of gimbald (contract section 11) against the real daemon over loopback:
/metrics (checked by promtool), /healthz, /api/state, /api/command, /api/console, the
/api/stream WebSocket, static console files, the allow list and bad input. Clients are the
standard library's http.client and the small RFC 6455 client in httptest.py."""

import json
import os
import shutil
import socket
import subprocess
import time

import gimbaltest as gt
import skipping
import httptest as ht

from test_gimbald_auth import Signer, write_key  # noqa: E402 (signing helpers)


def http_port(daemon):
    """The HTTP port gimbald bound (the config asks for port 0: any free port)."""
    start = daemon.wait_log(lambda e: e.get("event") == "start")
    return int(start["http"].rsplit(":", 1)[1])


def with_http(config, **http):
    config = dict(config)
    config["http"] = dict({"port": 0}, **http)
    return config


def make_web_root(workdir):
    root = os.path.join(workdir, "web")
    os.makedirs(os.path.join(root, "js"))
    with open(os.path.join(root, "index.html"), "w") as f:
        f.write("<!doctype html><title>console under test</title>")
    with open(os.path.join(root, "js", "app.js"), "w") as f:
        f.write("console.log('app');\n")
    with open(os.path.join(root, "style.css"), "w") as f:
        f.write("body { margin: 0 }\n")
    with open(os.path.join(root, ".hidden"), "w") as f:
        f.write("secret")
    outside = os.path.join(workdir, "outside.txt")
    with open(outside, "w") as f:
        f.write("outside the web root")
    os.symlink(outside, os.path.join(root, "escape.txt"))
    return root


class HttpWithSimulator(gt.GimbaldTestCase):
    """One gimbal-sim Orion over TCP, gimbald with http enabled."""

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.web_root = make_web_root(cls.class_workdir)
        cls.sim = cls.start_class_sim()
        cls.daemon = cls.start_class_daemon(with_http(
            {"gimbals": [gt.orion_tcp("main", cls.sim.port)]}, web_root=cls.web_root,
            tiles_url="http://tiles.example/{z}/{x}/{y}.png"))
        cls.port = http_port(cls.daemon)

    def setUp(self):
        super().setUp()
        self.c = self.client(self.daemon)
        self.wait_connected(self.c)

    def metrics(self):
        status, headers, body = ht.request(self.port, "GET", "/metrics")
        self.assertEqual(status, 200)
        self.assertTrue(headers["content-type"].startswith("text/plain; version=0.0.4"))
        return body.decode(), ht.parse_metrics(body.decode())

    # --- /api/state, /api/console ----------------------------------------------------

    def test_state_matches_the_udp_state(self):
        status, body = ht.get_json(self.port, "/api/state")
        self.assertEqual(status, 200)
        self.assertEqual(list(body["gimbals"]), ["main"])
        http_state = body["gimbals"]["main"]
        udp_state = self.c.request("state")["state"]
        self.assertEqual(set(http_state), set(udp_state))
        self.assertEqual(http_state["protocol"], "orion")
        self.assertEqual(http_state["link"]["endpoint"], udp_state["link"]["endpoint"])
        self.assertTrue(http_state["link"]["connected"])
        # The simulator moves: the two snapshots are a few ms apart, not identical.
        for key in ("lat", "lon", "alt"):
            self.assertAlmostEqual(http_state["telemetry"][key], udp_state["telemetry"][key],
                                   delta=0.01)

    def test_console_info(self):
        status, body = ht.get_json(self.port, "/api/console")
        self.assertEqual(status, 200)
        version = self.c.request("version")["version"]
        self.assertEqual(body, {"version": version,
                                "gimbals": [{"name": "main", "protocol": "orion", "video": False,
                                             "tracking": False}],
                                "laser_allow_fire": False,
                                "terrain": False,
                                "tiles_url": "http://tiles.example/{z}/{x}/{y}.png"})

    # --- POST /api/command ---------------------------------------------------------

    def test_other_sites_pages_cannot_command_or_read(self):
        """A page from another site in the operator's browser (CSRF, cross-site WebSocket,
        DNS rebinding) is refused with 403 and nothing reaches the gimbal; the console's own
        origin and clients without an Origin header are served."""
        geopoint = json.dumps({"cmd": "geopoint", "lat": 45.0, "lon": -121.0,
                               "alt": 77.0}).encode()
        start = len(self.sim.rx())
        # A form or fetch() on another site: text/plain needs no CORS preflight.
        status, _, body = ht.request(self.port, "POST", "/api/command", body=geopoint,
                                     headers={"Content-Type": "text/plain",
                                              "Origin": "https://attacker.example"})
        self.assertEqual(status, 403)
        self.assertIn("attacker.example", json.loads(body)["error"])
        # Another local port is another origin too.
        status, _, _ = ht.request(self.port, "POST", "/api/command", body=geopoint,
                                  headers={"Origin": "http://127.0.0.1:1"})
        self.assertEqual(status, 403)
        # Cross-site WebSocket: the upgrade is refused before it happens.
        with self.assertRaises(ConnectionError) as refused:
            ht.WebSocket(self.port, origin="https://attacker.example")
        self.assertIn("403", str(refused.exception))
        # DNS rebinding: the page's own name in Host, even for reading.
        for path in ("/api/state", "/metrics", "/"):
            status, _, _ = ht.request(self.port, "GET", path,
                                      headers={"Host": "attacker.example:%d" % self.port})
            self.assertEqual(status, 403, path)
        time.sleep(0.5)
        self.assertIsNone(self.sim.wait_rx(gt.by_name("geopoint_cmd"), start=start,
                                           timeout=0.5),
                          "a cross-site request reached the gimbal")
        log = self.daemon.wait_log(lambda e: e.get("event") == "http_cross_site")
        self.assertEqual(log["level"], "warn")
        self.assertIn("attacker.example", log["reason"])  # the reason as text, not a body
        self.assertFalse(log["reason"].startswith("{"), log)
        _, metrics = self.metrics()
        self.assertGreaterEqual(ht.metric(metrics, "gimbald_http_cross_site_refused_total"), 6)
        # The console's own page (same origin) and plain clients still work.
        origin = "http://127.0.0.1:%d" % self.port
        status, _, body = ht.request(self.port, "POST", "/api/command", body=geopoint,
                                     headers={"Content-Type": "application/json",
                                              "Origin": origin})
        self.assertEqual(status, 200)
        self.assertTrue(json.loads(body)["ok"], body)
        self.assertIsNotNone(self.sim.wait_rx(gt.by_name("geopoint_cmd"), start=start))
        ws = ht.WebSocket(self.port, origin=origin)
        ws.close()
        status, _, _ = ht.request(self.port, "GET", "/api/state",
                                  headers={"Host": "localhost:%d" % self.port})
        self.assertEqual(status, 200)

    def test_command_reaches_the_simulator_and_the_metrics(self):
        _, before = self.metrics()
        count_before = ht.metric(before, "gimbald_command_duration_seconds_count") or 0
        ok_before = ht.metric(before, "gimbald_commands_total", cmd="geopoint",
                              result="ok") or 0
        start = len(self.sim.rx())
        status, reply = ht.post_command(self.port, {"cmd": "geopoint", "id": "h1",
                                                    "lat": 45.71, "lon": -121.49, "alt": 250.5})
        self.assertEqual(status, 200)
        self.assertEqual(reply["id"], "h1")
        self.assertTrue(reply["ok"], reply)
        self.assertEqual(reply["sent"], [{"id": 213, "len": 21}])
        entry = self.sim.wait_rx(gt.by_name("geopoint_cmd"), start=start)
        self.assertIsNotNone(entry, "the geopoint never reached the simulator")
        self.assertAlmostEqual(entry["packet"]["lat"], 45.71, places=6)
        self.assertAlmostEqual(entry["packet"]["lon"], -121.49, places=6)
        # A refused command is still HTTP 200, its reply says why.
        status, reply = ht.post_command(self.port, {"cmd": "geopoint", "id": "h2", "lat": 95,
                                                    "lon": 0, "alt": 0})
        self.assertEqual(status, 200)
        self.assertEqual(reply["error"]["code"], "out_of_range")
        log = self.daemon.wait_log(lambda e: e.get("event") == "command" and e.get("id") == "h1")
        self.assertTrue(log["src"].startswith("http:127.0.0.1:"), log)
        self.assertEqual(log["transport"], "http")

        _, after = self.metrics()
        self.assertEqual(ht.metric(after, "gimbald_commands_total", cmd="geopoint",
                                   result="ok"), ok_before + 1)
        self.assertGreaterEqual(ht.metric(after, "gimbald_commands_total", cmd="geopoint",
                                          result="out_of_range"), 1)
        self.assertGreaterEqual(ht.metric(after, "gimbald_command_duration_seconds_count"),
                                count_before + 2)
        inf = ht.metric(after, "gimbald_command_duration_seconds_bucket", le="+Inf")
        self.assertEqual(inf, ht.metric(after, "gimbald_command_duration_seconds_count"))

    def test_subscribe_over_post_is_unsupported(self):
        status, reply = ht.post_command(self.port, {"cmd": "subscribe", "id": 5})
        self.assertEqual(status, 200)
        self.assertEqual(reply["error"]["code"], "unsupported")

    def test_bad_json_post_is_a_bad_json_reply(self):
        status, _, body = ht.request(self.port, "POST", "/api/command", body=b"{not json")
        self.assertEqual(status, 200)
        self.assertEqual(json.loads(body)["error"]["code"], "bad_json")
        self.assertEqual(ht.post_command(self.port, {"cmd": "ping"})[1]["pong"], True)

    # --- /metrics, /healthz --------------------------------------------------------

    def test_metrics_values_and_promtool(self):
        text, m = self.metrics()
        self.assertEqual(ht.metric(m, "gimbald_link_up", gimbal="main"), 1)
        self.assertGreater(ht.metric(m, "gimbald_link_rx_bytes_total", gimbal="main"), 0)
        self.assertGreater(ht.metric(m, "gimbald_link_tx_bytes_total", gimbal="main"), 0)
        self.assertGreater(ht.metric(m, "gimbald_link_rx_packets_total", gimbal="main"), 0)
        self.assertEqual(ht.metric(m, "gimbald_link_bad_checksums_total", gimbal="main"), 0)
        self.assertIsNotNone(ht.metric(m, "gimbald_link_dropped_bytes_total", gimbal="main"))
        self.assertIsNotNone(ht.metric(m, "gimbald_link_reconnects_total", gimbal="main"))
        self.assertLess(ht.metric(m, "gimbald_telemetry_age_seconds", gimbal="main"), 1.0)
        self.assertEqual(ht.metric(m, "gimbald_laser_firing", gimbal="main", index="0"), 0)
        self.assertEqual(ht.metric(m, "gimbald_laser_firing", gimbal="main", index="1"), 0)
        self.assertEqual(ht.metric(m, "gimbald_vehicle_up"), 0)
        self.assertEqual(ht.metric(m, "gimbald_mqtt_up"), 0)
        self.assertIsNotNone(ht.metric(m, "gimbald_subscribers"))
        version = self.c.request("version")["version"]
        self.assertEqual(ht.metric(m, "gimbald_build_info", version=version), 1)
        # UDP subscribers count too.
        before = ht.metric(m, "gimbald_subscribers")
        sub = self.client(self.daemon)
        self.assertOk(sub.request("subscribe", rate_hz=1))
        _, m = self.metrics()
        self.assertEqual(ht.metric(m, "gimbald_subscribers"), before + 1)
        sub.request("unsubscribe")

        promtool = shutil.which("promtool")
        if not promtool:
            skipping.need(self, "promtool not installed (scripts/install-deps.sh: prometheus)")
        result = subprocess.run([promtool, "check", "metrics"], input=text,
                                capture_output=True, text=True, timeout=30)
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
        self.assertEqual((result.stdout + result.stderr).strip(), "",
                         "promtool lint: " + result.stdout + result.stderr)

    def test_healthz_ok(self):
        status, body = ht.get_json(self.port, "/healthz")
        self.assertEqual(status, 200, body)
        self.assertEqual(body["ok"], True)
        self.assertEqual(body["problems"], [])
        self.assertEqual(body["gimbals"]["main"], {"connected": True, "stale": False, "ok": True})

    # --- static files ----------------------------------------------------------------

    def test_static_files(self):
        cases = [("/", "text/html; charset=utf-8", b"console under test"),
                 ("/index.html", "text/html; charset=utf-8", b"console under test"),
                 ("/js/app.js", "text/javascript; charset=utf-8", b"console.log"),
                 ("/style.css?v=3", "text/css; charset=utf-8", b"margin")]
        for path, ctype, needle in cases:
            status, headers, body = ht.request(self.port, "GET", path)
            self.assertEqual(status, 200, path)
            self.assertEqual(headers["content-type"], ctype, path)
            self.assertIn(needle, body, path)
        status, headers, body = ht.request(self.port, "HEAD", "/js/app.js")
        self.assertEqual(status, 200)
        self.assertEqual(int(headers["content-length"]), len("console.log('app');\n"))
        self.assertEqual(body, b"")

    def test_no_traversal(self):
        for path in ("/../outside.txt", "/js/../../outside.txt", "/%2e%2e/outside.txt",
                     "/js/%2E%2E/%2e%2e/outside.txt", "/.hidden", "/escape.txt",
                     "/nothing-here.html", "/%00", "/%zz", "/js/..%5c..%5coutside.txt"):
            raw = ht.raw_exchange(self.port, ("GET %s HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close"
                                              "\r\n\r\n" % path).encode())
            self.assertIn(ht.status_of(raw), (400, 404), path)
            self.assertNotIn(b"outside the web root", raw, path)
            self.assertNotIn(b"secret", raw, path)
        self.assertEqual(ht.request(self.port, "GET", "/")[0], 200)

    # --- bad input, each followed by a good request ----------------------------------

    def assertServing(self):
        status, body = ht.get_json(self.port, "/api/console")
        self.assertEqual(status, 200)
        self.assertTrue(self.daemon.running())

    def test_unknown_path_and_wrong_method(self):
        self.assertEqual(ht.request(self.port, "GET", "/no/such/path")[0], 404)
        self.assertServing()
        status, headers, _ = ht.request(self.port, "DELETE", "/metrics")
        self.assertEqual(status, 405)
        self.assertIn("GET", headers["allow"])
        status, headers, _ = ht.request(self.port, "GET", "/api/command")
        self.assertEqual(status, 405)
        self.assertEqual(headers["allow"], "POST")
        self.assertEqual(ht.request(self.port, "POST", "/healthz", body=b"{}")[0], 405)
        self.assertServing()
        # /api/stream without the upgrade
        self.assertEqual(ht.request(self.port, "GET", "/api/stream")[0], 426)
        self.assertServing()

    def test_malformed_http(self):
        for raw in (b"THIS IS NOT HTTP\r\n\r\n", b"GET / HTTP/9.9\r\n\r\n",
                    b"GET / HTTP/1.1\r\nBad Header Line\r\n\r\n",
                    b"POST /api/command HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Length: abc\r\n\r\n",
                    b"\x16\x03\x01\x02\x00\x01\x00\x01\xfc\x03\x03" + os.urandom(64)):
            self.assertEqual(ht.status_of(ht.raw_exchange(self.port, raw)), 400, raw[:40])
            self.assertServing()

    def test_oversized_header_and_body(self):
        big_header = (b"GET /healthz HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Filler: " + b"a" * 9000 +
                      b"\r\n\r\n")
        self.assertEqual(ht.status_of(ht.raw_exchange(self.port, big_header)), 431)
        self.assertServing()
        body = json.dumps({"cmd": "ping", "pad": "x" * 9000}).encode()
        status, _, _ = ht.request(self.port, "POST", "/api/command", body=body)
        self.assertEqual(status, 413)
        self.assertServing()
        chunked = (b"POST /api/command HTTP/1.1\r\nHost: 127.0.0.1\r\nTransfer-Encoding: chunked\r\n\r\n" +
                   b"".join(b"1000\r\n" + b"x" * 4096 + b"\r\n" for _ in range(3)) + b"0\r\n\r\n")
        self.assertEqual(ht.status_of(ht.raw_exchange(self.port, chunked)), 413)
        self.assertServing()
        # At the limit it is a request like any other.
        request = {"cmd": "ping", "id": "x" * (8192 - 30)}
        text = json.dumps(request)
        self.assertLessEqual(len(text), 8192)
        status, reply = ht.post_command(self.port, request)
        self.assertEqual(status, 200)
        self.assertEqual(reply["pong"], True)

    def test_keep_alive(self):
        import http.client
        conn = http.client.HTTPConnection("127.0.0.1", self.port, timeout=5)
        try:
            for _ in range(3):
                conn.request("GET", "/healthz")
                res = conn.getresponse()
                res.read()
                self.assertEqual(res.status, 200)
            sock = conn.sock
            conn.request("POST", "/api/command", body=b'{"cmd":"ping"}')
            res = conn.getresponse()
            self.assertEqual(json.loads(res.read())["pong"], True)
            self.assertIs(conn.sock, sock, "the connection was not kept alive")
        finally:
            conn.close()

    def test_expect_100_continue(self):
        body = json.dumps({"cmd": "ping", "id": "e" * 2000}).encode()
        s = socket.create_connection(("127.0.0.1", self.port))
        self.addCleanup(s.close)
        s.settimeout(2)
        s.sendall(b"POST /api/command HTTP/1.1\r\nHost: 127.0.0.1\r\nExpect: 100-continue\r\n"
                  b"Content-Length: %d\r\n\r\n" % len(body))
        self.assertEqual(s.recv(25), b"HTTP/1.1 100 Continue\r\n\r\n")
        s.sendall(body)
        raw = b""
        while b'"pong"' not in raw:
            chunk = s.recv(65536)
            self.assertTrue(chunk, "closed before the reply")
            raw += chunk
        self.assertEqual(ht.status_of(raw), 200)
        self.assertIn(b'"pong":true', raw)

    # --- the WebSocket stream --------------------------------------------------------

    def ws(self, **kwargs):
        w = ht.WebSocket(self.port, **kwargs)
        self.addCleanup(w.close)
        return w

    def test_stream_state_at_2_hz_and_events(self):
        w = self.ws()
        first = w.recv_json()
        self.assertEqual(first["type"], "state")
        self.assertEqual(first["gimbal"], "main")
        self.assertEqual(first["state"]["protocol"], "orion")
        self.assertIn("telemetry", first["state"])
        start = time.monotonic()
        states = 0
        while time.monotonic() - start < 4.0:
            msg = w.recv_json(timeout=3)
            if msg.get("type") == "state":
                states += 1
        # 2 Hz for 4 s: 8, give or take one, and one more that a busy machine may have held
        # back in the socket before the clock started.
        self.assertGreaterEqual(states, 7)
        self.assertLessEqual(states, 10)
        # An event: the mode change a command causes reaches the stream.
        self.assertOk(self.c.request("mode", mode="track"))
        event = w.wait_json(lambda m: m.get("type") == "event" and m.get("event") == "mode",
                            timeout=5)
        self.assertIsNotNone(event, "no mode event on the stream")
        self.assertEqual(event["to"], "track")
        self.assertOk(self.c.request("mode", mode="geo_rate"))

    def test_stream_subscribe_and_commands(self):
        w = self.ws()
        w.send_json({"cmd": "subscribe", "id": 9, "rate_hz": 10, "keys": ["telemetry"]})
        reply = w.wait_json(lambda m: m.get("id") == 9)
        self.assertEqual(reply, {"id": 9, "ok": True, "cmd": "subscribe", "rate_hz": 10,
                                 "events": True, "keys": ["telemetry"]})
        msg = w.wait_json(lambda m: m.get("type") == "state" and "gps" not in m["state"])
        self.assertEqual(set(msg["state"]), {"protocol", "link", "stale", "telemetry"})
        t0 = time.monotonic()
        n = 0
        while time.monotonic() - t0 < 2.0:
            if w.recv_json().get("type") == "state":
                n += 1
        self.assertGreaterEqual(n, 17)  # 10 Hz, with slack for a busy machine
        self.assertLessEqual(n, 24)
        # The same validation as the UDP subscribe.
        w.send_json({"cmd": "subscribe", "id": 10, "rate_hz": 500})
        self.assertEqual(w.wait_json(lambda m: m.get("id") == 10)["error"]["code"],
                         "out_of_range")
        w.send_json({"cmd": "subscribe", "id": 11, "keys": ["nope"]})
        self.assertEqual(w.wait_json(lambda m: m.get("id") == 11)["error"]["code"],
                         "bad_request")
        w.send_json({"cmd": "subscribe", "id": 12, "colour": 1})
        self.assertEqual(w.wait_json(lambda m: m.get("id") == 12)["error"]["code"],
                         "bad_request")
        # Other requests go through the request path.
        w.send_json({"cmd": "ping", "id": 13})
        self.assertEqual(w.wait_json(lambda m: m.get("id") == 13),
                         {"id": 13, "ok": True, "cmd": "ping", "pong": True})
        w.send_json({"cmd": "unsubscribe", "id": 14})
        self.assertTrue(w.wait_json(lambda m: m.get("id") == 14)["ok"])
        time.sleep(0.3)
        w.sock.settimeout(0)
        # After unsubscribe: no more STATE.
        deadline = time.monotonic() + 1.0
        states = 0
        try:
            while time.monotonic() < deadline:
                msg = w.recv_json(timeout=max(0.01, deadline - time.monotonic()))
                if msg and msg.get("type") == "state":
                    states += 1
        except socket.timeout:
            pass
        self.assertEqual(states, 0)

    def test_stream_bad_input_close_codes(self):
        w = self.ws()
        w.send_frame(0x2, b"\x00\x01binary")
        self.assertEqual(w.wait_close(), 1003)
        self.assertEqual(self.ws().recv_json()["type"], "state")

        w = self.ws()
        w.send_text("this is not json")
        self.assertEqual(w.wait_close(), 1008)
        self.assertEqual(self.ws().recv_json()["type"], "state")

        w = self.ws()
        w.send_text(json.dumps({"cmd": "ping", "pad": "x" * 9000}))
        self.assertEqual(w.wait_close(), 1009)
        self.assertEqual(self.ws().recv_json()["type"], "state")

        w = self.ws()
        w.send_frame(0x1, b"unmasked", mask=False)  # clients must mask: protocol error
        self.assertEqual(w.wait_close(), 1002)
        self.assertEqual(self.ws().recv_json()["type"], "state")
        self.assertServing()

    def test_slow_websocket_client_is_dropped_others_unaffected(self):
        slow = self.ws(rcvbuf=4096)
        good = self.ws()
        for w in (slow, good):
            w.send_json({"cmd": "subscribe", "id": 1, "rate_hz": 50})
        self.assertTrue(good.wait_json(lambda m: m.get("id") == 1)["ok"])
        # `slow` reads nothing from now on.
        dropped = None
        deadline = time.monotonic() + 60
        received = 0
        while time.monotonic() < deadline and not dropped:
            msg = good.recv_json()
            self.assertIsNotNone(msg, "the good client was closed")
            received += 1
            dropped = [e for e in self.daemon.events("websocket_dropped")]
        self.assertTrue(dropped, "the slow client was never dropped")
        self.assertEqual(dropped[0]["level"], "warn")
        # The good client keeps receiving STATE at its rate.
        t0 = time.monotonic()
        n = 0
        while time.monotonic() - t0 < 1.0:
            if good.recv_json().get("type") == "state":
                n += 1
        self.assertGreaterEqual(n, 30)
        _, m = self.metrics()
        self.assertGreaterEqual(ht.metric(m, "gimbald_websocket_dropped_total"), 1)
        good.send_json({"cmd": "subscribe", "id": 2, "rate_hz": 2})
        self.assertTrue(good.wait_json(lambda m: m.get("id") == 2)["ok"])

    def test_websocket_clients_count_as_subscribers(self):
        _, m = self.metrics()
        before = ht.metric(m, "gimbald_subscribers")
        before_ws = ht.metric(m, "gimbald_websocket_clients")
        ws = [self.ws() for _ in range(3)]
        for w in ws:
            w.recv_json()
        _, m = self.metrics()
        self.assertEqual(ht.metric(m, "gimbald_subscribers"), before + 3)
        self.assertEqual(ht.metric(m, "gimbald_websocket_clients"), before_ws + 3)
        for w in ws:
            w.close()


class HttpHealthLinkDown(gt.GimbaldTestCase):
    def test_healthz_503_when_the_link_is_down(self):
        daemon = self.start_daemon(with_http(
            {"gimbals": [gt.orion_tcp("dead", gt.closed_tcp_port(), reconnect_max_s=0.5)]}))
        port = http_port(daemon)
        status, body = ht.get_json(port, "/healthz")
        self.assertEqual(status, 503)
        self.assertEqual(body["ok"], False)
        self.assertIn("dead: link down", body["problems"])
        self.assertEqual(body["gimbals"]["dead"]["connected"], False)
        m = ht.parse_metrics(ht.request(port, "GET", "/metrics")[2].decode())
        self.assertEqual(ht.metric(m, "gimbald_link_up", gimbal="dead"), 0)
        self.assertEqual(ht.metric(m, "gimbald_telemetry_age_seconds", gimbal="dead"),
                         float("inf"))


class HttpConfigured(gt.GimbaldTestCase):
    def test_allow_list_refuses_other_sources(self):
        daemon = self.start_daemon(with_http(
            {"gimbals": [{"name": "s", "protocol": "orion", "link": {"type": "sim"}}],
             "command": {"allow": ["127.0.0.2/32"]}}))
        port = http_port(daemon)
        raw = ht.raw_exchange(port, b"GET /healthz HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n",
                              source="127.0.0.1")
        self.assertEqual(raw, b"")  # closed without a response
        self.assertTrue(daemon.wait_log(lambda e: e.get("event") == "dropped_source"))
        raw = ht.raw_exchange(port, b"GET /api/console HTTP/1.1\r\nHost: 127.0.0.1\r\n"
                              b"Connection: close\r\n\r\n", source="127.0.0.2")
        self.assertEqual(ht.status_of(raw), 200)
        self.assertIn(b'"laser_allow_fire"', raw)

    def test_http_off_unless_configured(self):
        daemon = self.start_daemon(
            {"gimbals": [{"name": "s", "protocol": "orion", "link": {"type": "sim"}}]})
        start = daemon.wait_log(lambda e: e.get("event") == "start")
        self.assertNotIn("http", start)

    def test_console_off_serves_the_api_only(self):
        daemon = self.start_daemon(with_http(
            {"gimbals": [{"name": "s", "protocol": "orion", "link": {"type": "sim"}}]},
            console=False))
        port = http_port(daemon)
        self.assertEqual(ht.request(port, "GET", "/")[0], 404)
        self.assertEqual(ht.get_json(port, "/api/console")[0], 200)

    def test_default_web_root_is_the_checkout(self):
        daemon = self.start_daemon(with_http(
            {"gimbals": [{"name": "s", "protocol": "orion", "link": {"type": "sim"}}]}))
        port = http_port(daemon)
        status, headers, body = ht.request(port, "GET", "/")
        source = os.environ.get("GIMBAL_SOURCE_DIR")
        if not source:
            skipping.need(self, "GIMBAL_SOURCE_DIR not set")
        with open(os.path.join(source, "web", "index.html"), "rb") as f:
            self.assertEqual(body, f.read())
        self.assertEqual(headers["content-type"], "text/html; charset=utf-8")

    def test_max_connections(self):
        daemon = self.start_daemon(with_http(
            {"gimbals": [{"name": "s", "protocol": "orion", "link": {"type": "sim"}}]},
            max_connections=2))
        port = http_port(daemon)
        held = [socket.create_connection(("127.0.0.1", port)) for _ in range(2)]
        try:
            time.sleep(0.2)
            self.assertEqual(ht.raw_exchange(port, b"GET /healthz HTTP/1.1\r\n\r\n"), b"")
        finally:
            for s in held:
                s.close()
        time.sleep(0.2)
        self.assertEqual(ht.get_json(port, "/api/console")[0], 200)

    def test_idle_connection_is_closed(self):
        daemon = self.start_daemon(with_http(
            {"gimbals": [{"name": "s", "protocol": "orion", "link": {"type": "sim"}}]},
            idle_timeout_s=1))
        port = http_port(daemon)
        s = socket.create_connection(("127.0.0.1", port))
        s.settimeout(5)
        t0 = time.monotonic()
        s.sendall(b"GET /healthz HTTP/1.1\r\nHost: 127.0.0.1\r\n")  # never finished
        self.assertEqual(s.recv(100), b"")
        self.assertLess(time.monotonic() - t0, 4)
        s.close()
        self.assertEqual(ht.get_json(port, "/api/console")[0], 200)

    def test_http_port_in_use_is_exit_2(self):
        taken = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
        self.addCleanup(taken.close)
        taken.bind(("127.0.0.1", 0))
        taken.listen(1)
        daemon = self.start_daemon(
            {"gimbals": [{"name": "s", "protocol": "orion", "link": {"type": "sim"}}],
             "http": {"port": taken.getsockname()[1]}}, wait_started=False)
        self.assertEqual(daemon.proc.wait(timeout=gt.START_TIMEOUT_S), 2)
        self.assertEqual(daemon.stop(), 2)  # checked here: the cleanup expects no exit
        failure = daemon.wait_log(lambda e: e.get("event") == "runtime_failure")
        self.assertIn("in use", failure["msg"])

    def test_sigterm_with_open_connections_stops_at_once(self):
        daemon = self.start_daemon(with_http(
            {"gimbals": [{"name": "s", "protocol": "orion", "link": {"type": "sim"}}]}))
        port = http_port(daemon)
        streaming = ht.WebSocket(port)
        self.addCleanup(streaming.close)
        self.assertEqual(streaming.recv_json()["type"], "state")
        idle = socket.create_connection(("127.0.0.1", port))  # keep-alive, between requests
        idle.sendall(b"GET /api/console HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n")
        idle.settimeout(5)
        self.assertEqual(ht.status_of(idle.recv(65536)), 200)
        partial = socket.create_connection(("127.0.0.1", port))  # half a request
        partial.sendall(b"POST /api/command HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Length: 100\r\n\r\n{")
        for s in (idle, partial):
            self.addCleanup(s.close)
        time.sleep(0.2)
        t0 = time.monotonic()
        self.assertEqual(daemon.stop(), 0)
        self.assertLess(time.monotonic() - t0, 3.0)
        self.assertTrue(daemon.wait_log(lambda e: e.get("event") == "stop" and
                                        e.get("msg") == "gimbald stopped"))

    def test_signed_post(self):
        key_path = write_key(self.workdir, "ops")
        daemon = self.start_daemon(with_http(
            {"gimbals": [{"name": "s", "protocol": "orion", "link": {"type": "sim"}}],
             "command": {"auth": "signed",
                         "keys": [{"id": "ops", "secret_file": key_path,
                                   "roles": ["observe", "control"]}]}}))
        port = http_port(daemon)

        class HttpPost:
            """Signer's client interface over POST /api/command."""

            def __init__(self):
                self.reply = None

            def send(self, obj):
                self.reply = ht.post_command(port, obj)[1]

            def wait_message(self, match, timeout):
                return self.reply if match(self.reply) else None

        signer = Signer(HttpPost(), "ops", key_path)
        status, reply = ht.post_command(port, {"cmd": "state", "id": 1})
        self.assertEqual(status, 200)
        self.assertEqual(reply["error"]["code"], "forbidden")
        reply, was_signed = signer.send_payload(signer.payload("mode", mode="track"))
        self.assertTrue(was_signed)
        self.assertTrue(reply["ok"], reply)
        audit = daemon.wait_log(lambda e: e.get("event") == "audit" and e.get("cmd") == "mode")
        self.assertEqual(audit["key"], "ops")
        self.assertEqual(audit["transport"], "http")


if __name__ == "__main__":
    gt.main()
