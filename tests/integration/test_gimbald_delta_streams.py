#!/usr/bin/env python3
"""Delta streams (contract section 14) on the UDP command socket and the WebSocket stream:
`subscribe` with `changes: true` sends a full STATE first and every `full_every_s`, and JSON
Merge Patches (RFC 7396) in between. A receiver that merges the pushes in order holds the
STATE: checked against a plain subscriber at the same rate (the daemon gives both the same
snapshot each tick: equal but for age_s) and against `state` replies taken right after a
push (when no gimbal byte arrived in between), while the gimbal (gimbal-sim) is driven
through modes, positions and new packet kinds. On UDP a tick's patch over one 1,472-byte
payload comes as several that fit, back to back, merged here as one push. The MQTT side is
test_gimbald_mqtt.sh."""

import json
import select
import time

import deltatest as dt
import gimbaltest as gt
import httptest as ht

RATE_HZ = 10
FULL_EVERY_S = 1.5
RUN_S = 6.0

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
        """Runs one action of dt.ACTIONS every RUN_S / len(dt.ACTIONS) seconds while `step()`
        handles the streams."""
        start = time.monotonic()
        done = 0
        while time.monotonic() - start < RUN_S:
            if done < len(dt.ACTIONS) and time.monotonic() - start >= done * RUN_S / len(dt.ACTIONS):
                cmd, params = dt.ACTIONS[done]
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
        checker = dt.Checker(self, self.control, FULL_EVERY_S)
        first = []

        ahead = []  # a datagram read while looking for more parts: the next push

        def read_delta(timeout):
            """The next datagram of the delta stream and its size, or None."""
            if ahead:
                return ahead.pop(0)
            if delta.backlog:  # pushes that came before the subscribe reply
                msg = delta.backlog.pop(0)
                return msg, len(json.dumps(msg, separators=(",", ":")))
            if not select.select([delta.sock], [], [], timeout)[0]:
                return None
            data = delta.sock.recv(65536)
            return json.loads(data), len(data)

        def step():
            wait = 0 if ahead or delta.backlog else 0.2
            ready, _, _ = select.select([delta.sock, plain.sock], [], [], wait)
            if plain.sock in ready:
                data = plain.sock.recv(65536)
                checker.on_plain(json.loads(data))
            got = read_delta(0)
            if got is None:
                return
            msg, size = got
            if "ok" in msg:
                return
            if not first:
                first.append(msg)
                self.assertIs(msg["full"], True, "the first push after subscribe")
            # A patch too large for one 1,472-byte payload comes as several, back to back
            # and with disjoint members (docs/json-api.md, "Delta streams"): together they are
            # the tick's push. The next tick's patch shares members with it (link, telemetry).
            while msg["full"] is False:
                more = read_delta(0.03)
                if more is None:
                    break
                part, part_size = more
                if part.get("full") is not False or set(part["state"]) & set(msg["state"]):
                    ahead.append(more)
                    break
                self.assertLessEqual(part_size, 1472)
                msg["state"].update(part["state"])
                size = max(size, part_size)
            quiet = not ahead and not select.select([delta.sock], [], [], 0)[0]
            checker.on_delta(msg, size, quiet)

        self.drive(step)
        checker.verify()
        # A renewal is a subscribe: its first push is full again.
        fulls = checker.receiver.fulls
        self.assertOk(delta.request("subscribe", rate_hz=RATE_HZ, ttl_s=30, events=False,
                                    changes=True, full_every_s=3600))
        # Pushes that arrived before the reply were sent before the renewal: not its first.
        delta.backlog.clear()
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
        checker = dt.Checker(self, self.control, FULL_EVERY_S)
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
