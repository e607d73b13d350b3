#!/usr/bin/env python3
"""Every error code of the gimbald contract (section 4), against the real daemon.

A refused command must send nothing: after the refusals a marker request is sent, and the
simulator's rx log must show the marker and nothing before it.

`internal` is not tested: it means a bug in the daemon (an exception in a handler), and no
well-formed or malformed request can trigger it from outside - which is the point.
"""


import gimbaltest as gt


class RefusalsTestCase(gt.GimbaldTestCase):
    """Helpers shared by the classes below."""

    def assert_refused(self, cmd, code, gimbal=None, **params):
        """Sends one request; asserts the error code, the id echoed and the cmd named."""
        request_id = "%s-%s-%d" % (cmd, code, len(params))
        if gimbal:
            params["gimbal"] = gimbal
        reply = self.c.request(cmd, id=request_id, **params)
        self.assertError(reply, code, request_id)
        self.assertEqual(reply["cmd"], cmd)
        self.assertEqual(set(reply), {"id", "ok", "cmd", "error"})
        return reply

    def assert_nothing_sent(self, sim, start, gimbal=None):
        """Nothing reached `sim` after rx index `start` except a marker request sent now."""
        params = {"gimbal": gimbal} if gimbal else {}
        self.assertOk(self.c.request("request", packet="uart_config", **params))
        marker = sim.wait_rx(gt.by_name("uart_config"), start=start)
        self.assertTrue(marker, "the marker request never arrived")
        arrived = sim.rx()[start:]
        self.assertEqual(arrived[0]["name"], "uart_config",
                         "a refused command reached the gimbal: %s" % arrived[:3])


class Errors(RefusalsTestCase):
    """One daemon with two gimbals: "main" (a simulator) and "dead" (a closed port)."""

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.sim = cls.start_class_sim()
        cls.daemon = cls.start_class_daemon({
            "gimbals": [gt.orion_tcp("main", cls.sim.port),
                        gt.orion_tcp("dead", gt.closed_tcp_port(), reconnect_min_s=0.5)],
            "command": {"max_subscribers": 1},
        })

    def setUp(self):
        super().setUp()
        self.c = self.client(self.daemon)
        self.wait_connected(self.c, "main")
        self.start = len(self.sim.rx())

    def test_bad_json(self):
        for datagram in (b"not json", b"[1, 2]", b'"cmd"', b"", b'{"cmd": "ping"',
                         b"\xff\xfe{}"):
            self.c.send_raw(datagram)
            reply = self.c.recv()
            self.assertError(reply, "bad_json")
            self.assertIsNone(reply["cmd"], datagram)
            self.assertNotIn("id", reply)

    def test_too_large(self):
        def padded(size):
            head = '{"cmd":"ping","id":9,"pad":"'
            return (head + "x" * (size - len(head) - 2) + '"}').encode()
        self.c.send_raw(padded(9000))
        reply = self.c.recv()
        # Refused unread (contract section 14): the id is not echoed, it is null.
        self.assertError(reply, "too_large", None)
        self.assertIn("id", reply)
        self.assertIsNone(reply["cmd"])
        self.assertIn("8192", reply["error"]["message"])
        self.c.send_raw(b"x" * 9000)  # not even JSON: too large all the same
        reply = self.c.recv()
        self.assertError(reply, "too_large")
        self.assertIsNone(reply["id"])
        # The limit is 8192 bytes: exactly that is parsed (and "pad" is then unknown).
        self.c.send_raw(padded(8192))
        reply = self.c.recv()
        self.assertError(reply, "bad_request", 9)
        self.assertIn("pad", reply["error"]["message"])
        self.c.send_raw(padded(8193))
        self.assertError(self.c.recv(), "too_large")

    def test_unknown_cmd(self):
        reply = self.c.request("fly_to_the_moon", id=11)
        self.assertError(reply, "unknown_cmd", 11)
        self.assertEqual(reply["cmd"], "fly_to_the_moon")
        self.c.send({"id": 12, "lat": 1})  # no cmd at all
        reply = self.c.reply_to(12)
        self.assertError(reply, "unknown_cmd", 12)
        self.assertIsNone(reply["cmd"])
        self.c.send({"id": 13, "cmd": 5})
        self.assertError(self.c.reply_to(13), "unknown_cmd", 13)

    def test_bad_request(self):
        # Unknown key, named in the message.
        reply = self.assert_refused("geopoint", "bad_request", "main", lat=45.7, lon=-121.5,
                                    alt=300, altitude_ref="msl")
        self.assertIn("altitude_ref", reply["error"]["message"])
        reply = self.assert_refused("ping", "bad_request", verbose=True)
        self.assertIn("verbose", reply["error"]["message"])
        # Wrong types.
        self.assert_refused("geopoint", "bad_request", "main", lat="45.7", lon=-121.5, alt=300)
        self.assert_refused("position", "bad_request", "main", pan=1, tilt=2, stabilized=1)
        self.assert_refused("geopoint", "bad_request", "main", lat=45.7, lon=-121.5, alt=300,
                            vel_ned=[1, 2])
        self.assert_refused("camera_switch", "bad_request", "main", index="one")
        self.assert_refused("subscribe", "bad_request", events="yes")
        self.c.send({"cmd": "ping", "id": 21, "gimbal": 5})
        self.assertError(self.c.reply_to(21), "bad_request", 21)
        # Missing parameters, named. (A geopoint without alt needs terrain, and none is
        # configured here: unavailable, naming alt.)
        reply = self.assert_refused("geopoint", "unavailable", "main", lat=45.7, lon=-121.5)
        self.assertIn("'alt'", reply["error"]["message"])
        self.assert_refused("retract", "bad_request", "main")
        self.assert_refused("laser", "bad_request", "main", enable=True, arm=True)
        self.assert_refused("path", "bad_request", "main")
        # Inconsistent: points with "down".
        self.assert_refused("path", "bad_request", "main", down=True,
                            points=[{"lat": 1, "lon": 2, "alt": 3}])
        self.assert_refused("mode", "bad_request", "main", mode="warp")
        self.assert_refused("request", "bad_request", "main", packet="reset")
        self.assert_nothing_sent(self.sim, self.start, "main")

    def test_out_of_range(self):
        cases = [
            ("geopoint", {"lat": 91, "lon": 0, "alt": 0}, "lat", ("-90", "90")),
            ("geopoint", {"lat": 0, "lon": -180.5, "alt": 0}, "lon", ("-180", "180")),
            ("geopoint", {"lat": 0, "lon": 0, "alt": 0, "joystick_range_m": 70000},
             "joystick_range_m", ("0", "65535")),
            ("position", {"pan": 181, "tilt": 0}, "pan", ("-180", "180")),
            ("position", {"pan": 0, "tilt": 0, "impulse_time_s": 30}, "impulse_time_s",
             ("0", "25.5")),
            ("laser", {"index": 2, "enable": False, "arm": False, "fire": False}, "index",
             ("0", "1")),
            ("path", {"points": [{"lat": 45, "lon": 0, "alt": 0}], "cross_steps": 16},
             "cross_steps", ("0", "15")),
            ("path", {"points": [{"lat": 45, "lon": 0, "alt": 0}], "cross_ratio": 3},
             "cross_ratio", ("0", "2.55")),
            ("subscribe", {"rate_hz": 100}, "rate_hz", ("0.1", "50")),
            ("subscribe", {"ttl_s": 0.5}, "ttl_s", ("1", "3600")),
        ]
        for cmd, params, key, bounds in cases:
            gimbal = None if cmd == "subscribe" else "main"
            reply = self.assert_refused(cmd, "out_of_range", gimbal, **params)
            message = reply["error"]["message"]
            self.assertIn(key, message)
            for bound in bounds:
                self.assertIn(bound, message, reply)
        self.assert_nothing_sent(self.sim, self.start, "main")

    def test_unknown_gimbal(self):
        reply = self.assert_refused("state", "unknown_gimbal", "nosuch")
        self.assertIn("nosuch", reply["error"]["message"])
        self.assert_refused("geopoint", "unknown_gimbal", "nosuch", lat=1, lon=2, alt=3)
        self.assert_refused("subscribe", "unknown_gimbal", "nosuch")
        # Two gimbals configured: "gimbal" may not be left out.
        self.assert_refused("state", "unknown_gimbal")
        self.assert_refused("geopoint", "unknown_gimbal", lat=45.7, lon=-121.5, alt=300)
        # ping/version/list take no gimbal, subscribe without one covers all.
        self.assertOk(self.c.request("list"))
        self.assert_nothing_sent(self.sim, self.start, "main")

    def test_unsupported(self):
        reply = self.assert_refused("viewpro_output", "unsupported", "main", osd="target",
                                    serial=True, network=False, format="out3")
        self.assertIn("orion", reply["error"]["message"])
        self.assert_refused("viewpro_adjust", "unsupported", "main", yaw_deg=1)
        self.assert_refused("vehicle", "unsupported", "main", roll=0, pitch=0, yaw=0, lat=1,
                            lon=2, alt_msl=3)
        self.assert_nothing_sent(self.sim, self.start, "main")

    def test_unavailable(self):
        # No telemetry ever from "dead": no geoid undulation for an MSL altitude.
        self.assert_refused("geopoint", "unavailable", "dead", lat=45.7, lon=-121.5, alt=300,
                            alt_ref="msl")
        # No StareStart yet from either gimbal: stare_ack needs the time to echo.
        self.assert_refused("stare_ack", "unavailable", "main")
        self.assert_nothing_sent(self.sim, self.start, "main")

    def test_geopoint_msl_uses_the_geoid_undulation(self):
        state = self.c.request("state", gimbal="main")["state"]
        undulation = state["telemetry"]["geoid_undulation"]
        start = len(self.sim.rx())
        self.assertOk(self.c.request("geopoint", gimbal="main", lat=45.7, lon=-121.5, alt=300,
                                     alt_ref="msl"))
        entry = self.sim.wait_rx(gt.by_name("geopoint_cmd"), start=start)
        self.assertAlmostEqual(entry["packet"]["alt"], 300 + undulation, delta=0.01)

    def test_link_down(self):
        state = self.c.request("state", gimbal="dead")["state"]
        self.assertIs(state["link"]["connected"], False)
        self.assertIsNone(state["telemetry"])
        self.assertIs(state["stale"], True)
        reply = self.assert_refused("geopoint", "link_down", "dead", lat=45.7, lon=-121.5,
                                    alt=300)
        self.assertIn("dead", reply["error"]["message"])
        self.assert_refused("request", "link_down", "dead", packet="versions")
        self.assertEqual(state["link"]["tx_packets"], 0)
        later = self.c.request("state", gimbal="dead")["state"]
        self.assertEqual(later["link"]["tx_packets"], 0)
        self.assertEqual(later["link"]["tx_bytes"], 0)
        # Validation still comes first.
        self.assert_refused("geopoint", "out_of_range", "dead", lat=95, lon=0, alt=0)
        self.assert_nothing_sent(self.sim, self.start, "main")

    def test_forbidden_laser_fire_and_bypass(self):
        reply = self.assert_refused("laser", "forbidden", "main", enable=True, arm=True,
                                    fire=True)
        self.assertIn("allow_fire", reply["error"]["message"])
        self.assert_refused("laser", "forbidden", "main", enable=True, arm=False, fire=False,
                            safety_bypass=True)
        self.assert_nothing_sent(self.sim, self.start, "main")

    def test_busy(self):
        first = self.client(self.daemon)
        second = self.client(self.daemon)
        self.assertOk(first.request("subscribe", rate_hz=0.1, ttl_s=10))
        try:
            reply = second.request("subscribe", id="s2")
            self.assertError(reply, "busy", "s2")
            self.assertIn("max_subscribers", reply["error"]["message"])
            # A renewal by the subscriber itself is not a new entry.
            self.assertOk(first.request("subscribe", rate_hz=0.1, ttl_s=10))
        finally:
            self.assertOk(first.request("unsubscribe"))
        self.assertOk(second.request("subscribe", rate_hz=0.1, ttl_s=1))
        self.assertOk(second.request("unsubscribe"))

    def test_errors_are_logged_with_their_code(self):
        self.assert_refused("geopoint", "unknown_gimbal", "nosuch", lat=1, lon=2, alt=3)
        entry = self.daemon.wait_log(lambda e: e.get("event") == "command" and
                                     e.get("id") == "geopoint-unknown_gimbal-3")
        self.assertTrue(entry)
        self.assertEqual((entry["ok"], entry["error"], entry["cmd"]),
                         (False, "unknown_gimbal", "geopoint"))


class Token(RefusalsTestCase):
    def setUp(self):
        super().setUp()
        self.sim = self.start_sim()
        self.daemon = self.start_daemon({"gimbals": [gt.orion_tcp("main", self.sim.port)],
                                         "command": {"token": "s3cret"}})
        self.c = self.client(self.daemon)
        self.wait_connected(self.c)

    def test_token(self):
        start = len(self.sim.rx())
        point = {"lat": 45.7, "lon": -121.5, "alt": 300}
        reply = self.assert_refused("geopoint", "forbidden", **point)
        self.assertIn("token", reply["error"]["message"])
        self.assert_refused("geopoint", "forbidden", token="wrong", **point)
        self.assert_refused("subscribe", "forbidden")
        self.assert_refused("request", "forbidden", packet="versions")
        # The open commands need none.
        for cmd in ("ping", "version", "list", "state"):
            self.assertOk(self.c.request(cmd), cmd)
        # Nothing reached the gimbal; then the right token works.
        self.assertOk(self.c.request("request", packet="uart_config", token="s3cret"))
        marker = self.sim.wait_rx(gt.by_name("uart_config"), start=start)
        self.assertTrue(marker)
        self.assertEqual(self.sim.rx()[start]["name"], "uart_config")
        reply = self.c.request("geopoint", token="s3cret", **point)
        self.assertEqual(reply["sent"], [{"id": 213, "len": 21}])
        # The token never appears in the log.
        self.assertNotIn("s3cret", self.daemon.log_text())


class Allow(gt.GimbaldTestCase):
    def test_other_sources_get_no_reply(self):
        daemon = self.start_daemon({"gimbals": [gt.orion_tcp("main", gt.closed_tcp_port())],
                                    "command": {"allow": ["10.0.0.0/8"]}})
        c = self.client(daemon)
        self.assertIsNone(c.request("ping", timeout=1.0))
        self.assertIsNone(c.request("state", timeout=0.5))
        entry = daemon.wait_log(lambda e: e.get("event") == "dropped_source")
        self.assertTrue(entry, "no dropped_source in the log")
        self.assertEqual(entry["src"], "127.0.0.1:%d" % c.sock.getsockname()[1])
        self.assertEqual(entry["level"], "warn")
        self.assertEqual(daemon.events("command"), [])

    def test_allowed_block_is_answered(self):
        daemon = self.start_daemon({"gimbals": [gt.orion_tcp("main", gt.closed_tcp_port())],
                                    "command": {"allow": ["10.0.0.0/8", "127.0.0.1"]}})
        self.assertOk(self.client(daemon).request("ping"))


if __name__ == "__main__":
    gt.main()
