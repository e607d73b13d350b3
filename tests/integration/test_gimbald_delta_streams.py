#!/usr/bin/env python3
"""Delta streams (contract section 14) on the UDP command socket and the WebSocket stream:
`subscribe` with `changes: true` sends a full STATE first and every `full_every_s`, and JSON
Merge Patches (RFC 7396) in between. A receiver that merges the pushes in order holds the
STATE: checked against a plain subscriber at the same rate (the daemon gives both the same
snapshot each tick: equal but for age_s) and against `state` replies taken right after a
push (when no gimbal byte arrived in between), while the gimbal (gimbal-sim) is driven
through modes, positions and new packet kinds. The MQTT side is test_gimbald_mqtt.sh."""

import json
import select
import socket
import time

import deltatest as dt
import gimbaltest as gt
import httptest as ht

RATE_HZ = 10
FULL_EVERY_S = 1.5
RUN_S = 6.0

# What the gimbal is told to do while the streams run: each changes something at some depth.
ACTIONS = [
    ("request", {"packet": "versions"}),
    ("position", {"pan": 20, "tilt": -30}),
    ("request", {"packet": "cameras"}),
    ("geopoint", {"lat": 45.71, "lon": -121.47, "alt": 100, "stare": True}),
    ("request", {"packet": "limits"}),
    ("rate", {"pan": 5, "tilt": 0}),
    ("request", {"packet": "network_diagnostics"}),
    ("position", {"pan": -40, "tilt": -10}),
    ("mode", {"mode": "disabled"}),
]


def link_key(state):
    """A push's snapshot, told apart by its link counters and age (equal only for the same
    snapshot)."""
    return json.dumps(state["link"], sort_keys=True)


def strict(value):
    """Comparable between two pushes of one snapshot: only age_s and nulls aside."""
    if isinstance(value, dict):
        return {k: strict(v) for k, v in value.items() if v is not None and k != "age_s"}
    if isinstance(value, list):
        return [strict(v) for v in value]
    return value


class Checker:
    """Merges the delta pushes of one stream and checks each merged STATE."""

    def __init__(self, test, control):
        self.test = test
        self.control = control
        self.receiver = dt.Receiver()
        self.plain = {}          # link_key -> plain STATE of that snapshot
        self.merged = []         # merged STATEs, in order
        self.full_times = []
        self.state_checks = 0
        self.patch_keys = set()  # top-level keys any patch carried

    def on_delta(self, msg, size, quiet):
        """`quiet`: nothing else is waiting on the stream, so a `state` request now sees the
        same gimbal data as this push unless gimbal bytes arrive meanwhile."""
        merged = self.receiver.push(msg, size)
        if msg["full"]:
            self.full_times.append(time.monotonic())
        else:
            self.patch_keys.update(msg["state"])
            self.test.assertNotIn("protocol", msg["state"], "an unchanged key in a patch")
        if merged is None:
            return
        self.merged.append(json.loads(json.dumps(merged)))
        if not quiet:
            return
        reply = self.control.request("state")
        self.test.assertOk(reply)
        now = reply["state"]
        if now["link"]["rx_bytes"] != merged["link"]["rx_bytes"] or \
                now["link"]["tx_bytes"] != merged["link"]["tx_bytes"]:
            return  # the gimbal said something since the push: not the same data
        self.state_checks += 1
        diff = dt.difference(dt.comparable(merged), dt.comparable(now))
        self.test.assertIsNone(diff, "merged pushes differ from `state`: %s" % diff)

    def on_plain(self, msg):
        self.test.assertNotIn("full", msg)
        self.plain[link_key(msg["state"])] = msg["state"]

    def verify(self):
        t = self.test
        t.assertGreater(self.receiver.patches, 20, "too few patches")
        t.assertGreaterEqual(len(self.full_times), 3)
        gaps = [b - a for a, b in zip(self.full_times, self.full_times[1:])]
        for gap in gaps:
            t.assertGreater(gap, FULL_EVERY_S - 0.25, gaps)
            t.assertLess(gap, FULL_EVERY_S + 1.0, gaps)
        twins = 0
        for merged in self.merged:
            plain = self.plain.get(link_key(merged))
            if plain is None:
                continue
            twins += 1
            diff = dt.difference(strict(merged), strict(plain))
            t.assertIsNone(diff, "merged pushes differ from the plain push: %s" % diff)
        t.assertGreaterEqual(twins, len(self.merged) // 2, "plain and delta pushes never met")
        t.assertGreaterEqual(self.state_checks, 3, "no quiet moment to compare with `state`")
        # Deep changes: telemetry moved, and keys the gimbal sent once stayed out of patches
        # after their first appearance (age_s alone is no change).
        t.assertIn("telemetry", self.patch_keys)
        t.assertIn("link", self.patch_keys)


class DeltaStreams(gt.GimbaldTestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.sim = cls.start_class_sim()
        cls.daemon = cls.start_class_daemon({"gimbals": [gt.orion_tcp("main", cls.sim.port)],
                                             "http": {"port": 0}})
        start = cls.daemon.wait_log(lambda e: e.get("event") == "start")
        cls.http_port = int(start["http"].rsplit(":", 1)[1])

    def setUp(self):
        super().setUp()
        self.control = self.client(self.daemon)
        self.wait_connected(self.control)
        self.assertOk(self.control.request("mode", mode="disabled"))

    def drive(self, step):
        """Runs one action of ACTIONS every RUN_S / len(ACTIONS) seconds while `step()`
        handles the streams."""
        start = time.monotonic()
        done = 0
        while time.monotonic() - start < RUN_S:
            if done < len(ACTIONS) and time.monotonic() - start >= done * RUN_S / len(ACTIONS):
                cmd, params = ACTIONS[done]
                self.assertOk(self.control.request(cmd, **params))
                done += 1
            step()

    def test_udp_delta_stream_merges_to_the_state(self):
        delta, plain = self.client(self.daemon), self.client(self.daemon)
        self.addCleanup(delta.request, "unsubscribe")
        self.addCleanup(plain.request, "unsubscribe")
        reply = delta.request("subscribe", rate_hz=RATE_HZ, ttl_s=30, events=False,
                              changes=True, full_every_s=FULL_EVERY_S)
        self.assertOk(reply)
        self.assertEqual((reply["changes"], reply["full_every_s"]), (True, FULL_EVERY_S))
        self.assertOk(plain.request("subscribe", rate_hz=RATE_HZ, ttl_s=30, events=False))
        checker = Checker(self, self.control)
        first = []

        def step():
            ready, _, _ = select.select([delta.sock, plain.sock], [], [], 0.2)
            if plain.sock in ready:
                data = plain.sock.recv(65536)
                checker.on_plain(json.loads(data))
            if delta.sock in ready:
                data = delta.sock.recv(65536)
                msg = json.loads(data)
                if "ok" in msg:
                    return
                if not first:
                    first.append(msg)
                    self.assertIs(msg["full"], True, "the first push after subscribe")
                quiet = not select.select([delta.sock], [], [], 0)[0]
                checker.on_delta(msg, len(data), quiet)

        self.drive(step)
        checker.verify()
        # A renewal is a subscribe: its first push is full again.
        fulls = checker.receiver.fulls
        self.assertOk(delta.request("subscribe", rate_hz=RATE_HZ, ttl_s=30, events=False,
                                    changes=True, full_every_s=3600))
        msg = delta.wait_message(gt.is_state, 2.0)
        self.assertIs(msg["full"], True)
        self.assertEqual(checker.receiver.fulls, fulls)

    def test_websocket_delta_stream_merges_to_the_state(self):
        delta = ht.WebSocket(self.http_port)
        plain = ht.WebSocket(self.http_port)
        self.addCleanup(delta.close)
        self.addCleanup(plain.close)
        delta.send_json({"cmd": "subscribe", "id": 1, "rate_hz": RATE_HZ, "events": False,
                         "changes": True, "full_every_s": FULL_EVERY_S})
        reply = delta.wait_json(lambda m: m.get("id") == 1)
        self.assertOk(reply)
        self.assertEqual((reply["changes"], reply["full_every_s"]), (True, FULL_EVERY_S))
        plain.send_json({"cmd": "subscribe", "id": 2, "rate_hz": RATE_HZ, "events": False})
        self.assertOk(plain.wait_json(lambda m: m.get("id") == 2))
        # Pushes of the connection's default stream (no `full` key) may precede the reply.
        checker = Checker(self, self.control)
        first = delta.wait_json(lambda m: m.get("type") == "state" and "full" in m)
        self.assertIs(first["full"], True, "the first push after subscribe")
        checker.on_delta(first, len(json.dumps(first)), quiet=False)

        def step():
            ready, _, _ = select.select([delta.sock, plain.sock], [], [], 0.2)
            if plain.sock in ready or plain.buffer:
                checker.on_plain(plain.recv_json())
            if delta.sock in ready or delta.buffer:
                msg = delta.recv_json()
                if msg.get("type") != "state":
                    return
                quiet = not delta.buffer and not select.select([delta.sock], [], [], 0)[0]
                checker.on_delta(msg, len(json.dumps(msg)), quiet)

        self.drive(step)
        checker.verify()

    def test_bad_delta_parameters(self):
        c = self.client(self.daemon)
        self.assertError(c.request("subscribe", changes="yes"), "bad_request")
        for bad in (0.5, 3601, "10"):
            reply = c.request("subscribe", changes=True, full_every_s=bad)
            self.assertIn(reply["error"]["code"], ("out_of_range", "bad_request"), reply)
            self.assertIn("full_every_s", reply["error"]["message"])
        # Without changes a subscription is as in v2: no `full` key, no changes in the reply.
        reply = c.request("subscribe", rate_hz=5, ttl_s=5)
        self.assertOk(reply)
        self.assertNotIn("changes", reply)
        self.assertNotIn("full", c.wait_message(gt.is_state, 2.0))
        self.assertOk(c.request("unsubscribe"))


if __name__ == "__main__":
    gt.main()
