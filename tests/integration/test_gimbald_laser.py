#!/usr/bin/env python3
"""The laser safety rules of contract 4.2, enforced by the daemon whatever the client sends.

The simulator's rx log is the witness: it shows every laser command that reached the gimbal,
with the simulator's own clock (`t`), so the dead-man delay is measured where it matters.
"""

import signal
import time

import gimbaltest as gt

FIRE = {"enable": True, "arm": True, "fire": True}


def laser_commands(sim, start=0):
    return [e for e in sim.rx()[start:] if e["name"] == "laser_cmd"]


class LaserTestCase(gt.GimbaldTestCase):
    def start_pair(self, **laser):
        self.sim = self.start_sim()
        self.daemon = self.start_daemon({"gimbals": [gt.orion_tcp("main", self.sim.port)],
                                         "laser": laser})
        self.c = self.client(self.daemon)
        self.wait_connected(self.c)

    def assert_nothing_reached_the_gimbal(self, start):
        self.assertOk(self.c.request("request", packet="uart_config"))
        self.assertTrue(self.sim.wait_rx(gt.by_name("uart_config"), start=start))
        self.assertEqual(self.sim.rx()[start]["name"], "uart_config")


class FireDisabled(LaserTestCase):
    def test_fire_forbidden_and_nothing_sent(self):
        self.start_pair()  # allow_fire defaults to false
        start = len(self.sim.rx())
        reply = self.c.request("laser", id=1, **FIRE)
        self.assertError(reply, "forbidden", 1)
        self.assert_nothing_reached_the_gimbal(start)
        # Without fire the laser may still be enabled and armed.
        reply = self.c.request("laser", enable=True, arm=True, fire=False, on_ms=100)
        self.assertEqual(reply["sent"], [{"id": 3, "len": 14}])
        self.assertTrue(self.sim.wait_rx(gt.by_name("laser_cmd"), start=start))
        lasers = gt.wait_for(lambda: self.c.request("state")["state"]["lasers"], 3.0)
        self.assertTrue(lasers)


class FireEnabled(LaserTestCase):
    def setUp(self):
        super().setUp()
        self.start_pair(allow_fire=True, fire_timeout_s=1.0)

    def test_fire_needs_enable_and_arm(self):
        start = len(self.sim.rx())
        self.assertError(self.c.request("laser", id=2, enable=True, arm=False, fire=True),
                         "bad_request", 2)
        self.assertError(self.c.request("laser", id=3, enable=False, arm=True, fire=True),
                         "bad_request", 3)
        self.assert_nothing_reached_the_gimbal(start)

    def test_safety_bypass_forbidden_unless_allowed(self):
        start = len(self.sim.rx())
        reply = self.c.request("laser", id=4, safety_bypass=True, **FIRE)
        self.assertError(reply, "forbidden", 4)
        self.assertIn("allow_safety_bypass", reply["error"]["message"])
        self.assert_nothing_reached_the_gimbal(start)

    def test_dead_man_ceases_fire(self):
        self.assertOk(self.c.request("subscribe", rate_hz=0.1, ttl_s=30))
        self.addCleanup(self.c.request, "unsubscribe")
        start = len(self.sim.rx())
        reply = self.c.request("laser", index=0, on_ms=100, off_ms=900, password="abc", **FIRE)
        self.assertEqual(reply["sent"], [{"id": 3, "len": 14 + 3}])
        fired = time.monotonic()
        cease = self.sim.wait_rx(lambda e: e["name"] == "laser_cmd" and
                                 not e["packet"]["fire"], timeout=3.0, start=start)
        self.assertTrue(cease, "no cease-fire reached the gimbal")
        self.assertLess(time.monotonic() - fired, 1.0 + 1.0)
        sent = laser_commands(self.sim, start)
        self.assertEqual(len(sent), 2, sent)
        fire, cease = sent
        self.assertIs(fire["packet"]["fire"], True)
        # Within fire_timeout_s + 0.5 s of the fire, on the simulator's clock; not early.
        self.assertGreaterEqual(cease["t"] - fire["t"], 0.9)
        self.assertLessEqual(cease["t"] - fire["t"], 1.5)
        # The same command with fire off.
        expected = dict(fire["packet"], fire=False)
        self.assertEqual(cease["packet"], expected)
        self.assertEqual(cease["packet"]["password"], "abc")

        entry = self.daemon.wait_log(lambda e: e.get("event") == "laser_deadman")
        self.assertTrue(entry)
        self.assertEqual((entry["level"], entry["index"], entry["gimbal"]), ("warn", 0, "main"))
        event = self.c.wait_message(gt.is_event("laser_deadman"), 2.0)
        self.assertEqual(event, {"type": "event", "gimbal": "main", "event": "laser_deadman",
                                 "index": 0, "sent": True})
        # Nothing more: one cease-fire.
        time.sleep(1.2)
        self.assertEqual(len(laser_commands(self.sim, start)), 2)

    def test_laser_fire_logs_the_index_used(self):
        # Issue 25: a fire without `index` logged "index": null; laser 0 fired.
        start = len(self.sim.rx())
        self.assertOk(self.c.request("laser", **FIRE))
        sent = self.sim.wait_rx(gt.by_name("laser_cmd"), start=start)
        self.assertTrue(sent)
        line = self.daemon.wait_log(lambda e: e.get("event") == "laser_fire")
        self.assertTrue(line, "no laser_fire line")
        self.assertEqual(line["index"], sent["packet"]["index"])
        self.assertEqual(line["index"], 0)
        # The audit line keeps what the client sent.
        audit = self.daemon.wait_log(lambda e: e.get("event") == "audit" and e.get("fire"))
        self.assertIsNone(audit["index"])
        self.assertOk(self.c.request("laser", index=1, **FIRE))
        fired = gt.wait_for(lambda: len(self.daemon.events("laser_fire")) >= 2 and
                            self.daemon.events("laser_fire"), 2.0)
        self.assertEqual([e["index"] for e in fired], [0, 1])

    def test_a_follow_up_command_disarms_the_dead_man(self):
        start = len(self.sim.rx())
        self.assertOk(self.c.request("laser", index=1, **FIRE))
        time.sleep(0.5)
        # Still firing: a new fire command restarts the timer.
        self.assertOk(self.c.request("laser", index=1, **FIRE))
        time.sleep(0.7)
        self.assertEqual(len(laser_commands(self.sim, start)), 2,
                         "dead-man fired although a laser command came within the timeout")
        self.assertOk(self.c.request("laser", index=1, enable=True, arm=True, fire=False))
        time.sleep(1.3)
        self.assertEqual(len(laser_commands(self.sim, start)), 3)
        self.assertEqual(self.daemon.events("laser_deadman"), [])


class CeaseFire(LaserTestCase):
    def test_sigterm_sends_fire_off_before_closing(self):
        self.start_pair(allow_fire=True, fire_timeout_s=30)
        start = len(self.sim.rx())
        self.assertOk(self.c.request("laser", index=1, **FIRE))
        self.assertTrue(self.sim.wait_rx(gt.by_name("laser_cmd"), start=start))
        self.assertEqual(self.daemon.stop(signal.SIGTERM), 0)
        cease = self.sim.wait_rx(lambda e: e["name"] == "laser_cmd" and
                                 not e["packet"]["fire"], start=start)
        self.assertTrue(cease, "no cease-fire on shutdown")
        self.assertEqual(cease["packet"]["index"], 1)
        self.assertTrue(self.daemon.events("laser_cease"))
        self.assertEqual(self.daemon.events("stop")[-1]["msg"], "gimbald stopped")

    def test_reconnect_sends_fire_off(self):
        self.start_pair(allow_fire=True, fire_timeout_s=30)
        self.assertOk(self.c.request("laser", index=0, **FIRE))
        self.assertTrue(self.sim.wait_rx(gt.by_name("laser_cmd")))
        port = self.sim.port
        self.sim.stop(signal.SIGKILL)
        self.assertTrue(gt.wait_for(
            lambda: not self.c.request("state")["state"]["link"]["connected"], 5.0))
        sim = self.start_sim(port=port)
        cease = sim.wait_rx(gt.by_name("laser_cmd"), timeout=8.0)
        self.assertTrue(cease, "no cease-fire after the reconnect")
        self.assertIs(cease["packet"]["fire"], False)
        # Only once: the daemon now knows the laser is not firing.
        self.assertOk(self.c.request("request", packet="uart_config"))
        self.assertTrue(sim.wait_rx(gt.by_name("uart_config")))
        self.assertEqual(len(laser_commands(sim)), 1)


if __name__ == "__main__":
    gt.main()
