#!/usr/bin/env python3
"""Subscriptions (contract 4.1): state datagrams at rate_hz, events, ttl_s and unsubscribe.

Rates are asserted loosely (the machine may be busy); what must hold exactly is the shape of
every datagram and that nothing arrives once a subscription has ended.
"""

import signal
import time

import gimbaltest as gt


class Subscriptions(gt.GimbaldTestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.sim = cls.start_class_sim()
        cls.daemon = cls.start_class_daemon({"gimbals": [gt.orion_tcp("main", cls.sim.port)]})

    def setUp(self):
        super().setUp()
        self.c = self.client(self.daemon)
        self.wait_connected(self.c)
        self.addCleanup(self.c.request, "unsubscribe")

    def settle_in_position_mode(self):
        self.assertOk(self.c.request("position", pan=0, tilt=-30))
        self.assertTrue(gt.wait_for(
            lambda: self.c.request("state")["state"]["telemetry"]["mode"] == "position", 3.0))

    def test_state_at_rate_hz(self):
        reply = self.c.request("subscribe", rate_hz=5, ttl_s=10)
        self.assertOk(reply)
        self.assertEqual((reply["rate_hz"], reply["ttl_s"], reply["events"]), (5, 10, True))
        self.assertNotIn("gimbal", reply)
        first = self.c.wait_message(gt.is_state, 1.0)  # the first goes out at once
        self.assertTrue(first)
        states = self.c.collect(1.0, gt.is_state)
        self.assertTrue(3 <= len(states) <= 8, len(states))
        for msg in [first] + states:
            self.assertEqual(set(msg), {"type", "gimbal", "state"})
            self.assertEqual(msg["gimbal"], "main")
            self.assertEqual(msg["state"]["protocol"], "orion")
            self.assertIs(msg["state"]["link"]["connected"], True)
            self.assertIsNotNone(msg["state"]["telemetry"])
        # Fresh snapshots, not copies of one.
        times = [m["state"]["telemetry"]["system_time_ms"] for m in states]
        self.assertEqual(times, sorted(times))
        self.assertGreater(times[-1], times[0])

    def test_subscribe_to_one_gimbal_by_name(self):
        reply = self.c.request("subscribe", gimbal="main", rate_hz=10, ttl_s=5)
        self.assertOk(reply)
        self.assertEqual(reply["gimbal"], "main")
        self.assertTrue(self.c.wait_message(gt.is_state, 1.0))

    def test_events_false_gets_no_events(self):
        self.settle_in_position_mode()
        quiet = self.client(self.daemon)
        self.addCleanup(quiet.request, "unsubscribe")
        self.assertOk(quiet.request("subscribe", rate_hz=1, ttl_s=10, events=False))
        self.assertOk(self.c.request("subscribe", rate_hz=1, ttl_s=10))
        # A mode change is an event for subscribers that want events.
        self.assertOk(self.c.request("mode", mode="disabled"))
        event = self.c.wait_message(gt.is_event("mode"), 3.0)
        self.assertTrue(event, "the events subscriber saw no mode event")
        got = quiet.collect(1.0)
        self.assertEqual([m for m in got if not gt.is_state(m)], [])
        self.assertTrue(any(gt.is_state(m) for m in got))

    def test_mode_event_after_geopoint(self):
        self.settle_in_position_mode()
        self.assertOk(self.c.request("subscribe", rate_hz=0.1, ttl_s=10))
        self.assertOk(self.c.request("geopoint", lat=45.7, lon=-121.5, alt=100))
        event = self.c.wait_message(gt.is_event("mode"), 3.0)
        self.assertEqual(event, {"type": "event", "gimbal": "main", "event": "mode",
                                 "from": "position", "to": "geopoint"})
        # The daemon logs the change too.
        self.assertTrue(self.daemon.wait_log(lambda e: e.get("event") == "mode_change" and
                                             e.get("to") == "geopoint"))

    def test_ttl_without_renewal_ends_the_subscription(self):
        self.assertOk(self.c.request("subscribe", rate_hz=10, ttl_s=1))
        subscribed = time.monotonic()
        arrivals = []
        deadline = subscribed + 2.5
        while time.monotonic() < deadline:
            msg = self.c.recv(max(0.0, deadline - time.monotonic()))
            if gt.is_state(msg):
                arrivals.append(time.monotonic() - subscribed)
        self.assertGreaterEqual(len(arrivals), 5, arrivals)
        self.assertLess(arrivals[-1], 1.4, "state datagrams went on after ttl_s")
        self.assertTrue(self.daemon.wait_log(lambda e: e.get("event") == "subscriber" and
                                             "expired" in e.get("msg", "")))

    def test_renewal_keeps_the_subscription(self):
        self.assertOk(self.c.request("subscribe", rate_hz=10, ttl_s=1))
        for _ in range(4):
            time.sleep(0.5)
            self.assertOk(self.c.request("subscribe", rate_hz=10, ttl_s=1))
        # Two seconds after the first subscribe, states still flow.
        self.assertTrue(self.c.collect(0.5, gt.is_state))

    def test_a_vanished_subscriber_does_not_disturb_others(self):
        gone = gt.Client(self.daemon.port)
        self.assertOk(gone.request("subscribe", rate_hz=50, ttl_s=3))
        gone.close()  # the daemon's datagrams now draw ICMP port unreachable
        for i in range(20):
            self.assertOk(self.c.request("ping", id=i), i)
            time.sleep(0.03)
        self.assertTrue(self.daemon.running())

    def test_unsubscribe_stops_everything(self):
        self.assertOk(self.c.request("subscribe", rate_hz=20, ttl_s=60))
        self.assertTrue(self.c.wait_message(gt.is_state, 1.0))
        reply = self.c.request("unsubscribe")
        self.assertOk(reply)
        self.assertIs(reply["subscribed"], False)
        self.c.collect(0.2)  # datagrams already in flight
        self.assertOk(self.c.request("mode", mode="disabled"))
        self.assertEqual(self.c.collect(1.0), [])
        # Unsubscribing twice is harmless.
        self.assertOk(self.c.request("unsubscribe"))


class Stare(gt.GimbaldTestCase):
    def start_pair(self, auto_ack):
        self.sim = self.start_sim()
        self.daemon = self.start_daemon({"gimbals": [gt.orion_tcp("main", self.sim.port)],
                                         "stare": {"auto_ack": auto_ack}})
        self.c = self.client(self.daemon)
        self.wait_connected(self.c)
        self.assertOk(self.c.request("subscribe", rate_hz=0.1, ttl_s=30))
        self.addCleanup(self.c.request, "unsubscribe")

    def stare_at_a_point(self):
        """geopoint with stare: the simulator starts a stare once on target."""
        self.assertOk(self.c.request("geopoint", lat=45.7, lon=-121.5, alt=100, stare=True))
        event = self.c.wait_message(gt.is_event("stare_start"), 8.0)
        self.assertTrue(event, "no stare_start event")
        self.assertEqual(event["gimbal"], "main")
        self.assertAlmostEqual(event["lat"], 45.7, delta=1e-4)
        self.assertAlmostEqual(event["lon"], -121.5, delta=1e-4)
        stare = self.c.request("state")["state"]["stare"]
        self.assertEqual(stare["system_time_ms"], event["system_time_ms"])
        self.assertTrue(self.daemon.wait_log(lambda e: e.get("event") == "stare_start"))
        return event

    def test_stare_start_event_and_stare_ack_of_the_latest(self):
        self.start_pair(auto_ack=False)
        event = self.stare_at_a_point()
        start = len(self.sim.rx())
        reply = self.c.request("stare_ack")  # system_time_ms defaults to the latest stare
        self.assertEqual(reply["sent"], [{"id": 218, "len": 4}])
        ack = self.sim.wait_rx(gt.by_name("stare_ack"), start=start)
        self.assertEqual(ack["packet"]["echo_system_time_ms"], event["system_time_ms"])
        self.assertEqual(len([e for e in self.sim.rx() if e["name"] == "stare_ack"]), 1)

    def test_auto_ack(self):
        self.start_pair(auto_ack=True)
        event = self.stare_at_a_point()
        ack = self.sim.wait_rx(gt.by_name("stare_ack"))
        self.assertTrue(ack, "the daemon did not acknowledge the stare by itself")
        self.assertEqual(ack["packet"]["echo_system_time_ms"], event["system_time_ms"])


class TwoGimbals(gt.GimbaldTestCase):
    def test_subscription_covers_all_gimbals_or_the_one_named(self):
        sim = self.start_sim()
        daemon = self.start_daemon({"gimbals": [
            gt.orion_tcp("main", sim.port), gt.orion_tcp("dead", gt.closed_tcp_port())]})
        everything = self.client(daemon)
        only_dead = self.client(daemon)
        self.wait_connected(everything, "main")
        self.assertOk(everything.request("subscribe", rate_hz=5, ttl_s=5))
        reply = only_dead.request("subscribe", gimbal="dead", rate_hz=5, ttl_s=5)
        self.assertEqual(reply["gimbal"], "dead")
        got = everything.collect(1.0, gt.is_state)
        self.assertEqual({m["gimbal"] for m in got}, {"main", "dead"})
        got = only_dead.collect(0.5, gt.is_state)
        self.assertTrue(got)
        self.assertEqual({m["gimbal"] for m in got}, {"dead"})
        self.assertIs(got[0]["state"]["link"]["connected"], False)
        for c in (everything, only_dead):
            self.assertOk(c.request("unsubscribe"))


class LinkEvents(gt.GimbaldTestCase):
    def test_link_event_when_the_gimbal_goes_away(self):
        sim = self.start_sim()
        daemon = self.start_daemon({"gimbals": [gt.orion_tcp("main", sim.port)]})
        c = self.client(daemon)
        self.wait_connected(c)
        self.assertOk(c.request("subscribe", rate_hz=1, ttl_s=30))
        sim.stop(signal.SIGKILL)
        event = c.wait_message(gt.is_event("link"), 5.0)
        self.assertEqual(event, {"type": "event", "gimbal": "main", "event": "link",
                                 "connected": False})
        # Telemetry stops: a `lost` event once stale_after_s (1 s) passes.
        lost = c.wait_message(gt.is_event("lost"), 3.0)
        self.assertTrue(lost, "no lost event")
        state = c.request("state")["state"]
        self.assertIs(state["link"]["connected"], False)
        self.assertIs(state["stale"], True)
        self.assertTrue(daemon.wait_log(lambda e: e.get("event") == "link_down"))
        c.request("unsubscribe")


if __name__ == "__main__":
    gt.main()
