#!/usr/bin/env python3
"""Links that come and go: a TCP gimbal that restarts on the same port, and an Orion on a
serial device (a gimbal-sim pseudo-terminal) that vanishes and comes back."""

import os
import signal
import time

import gimbaltest as gt

CONNECT_REQUESTS = {"clevis_version", "crown_version", "payload_version", "tracker_version",
                    "retract_version", "lensctl_version", "cameras", "limits"}


class TcpReconnect(gt.GimbaldTestCase):
    def test_reconnects_within_two_seconds_of_the_gimbal_returning(self):
        sim = self.start_sim()
        port = sim.port
        daemon = self.start_daemon({"gimbals": [
            gt.orion_tcp("main", port, reconnect_min_s=0.2, reconnect_max_s=1)]})
        c = self.client(daemon)
        before = self.wait_connected(c)["link"]["reconnects"]
        self.assertOk(c.request("subscribe", rate_hz=0.2, ttl_s=30))

        sim.stop(signal.SIGKILL)
        self.assertTrue(c.wait_message(gt.is_event("link"), 5.0))
        self.assertTrue(gt.wait_for(
            lambda: not c.request("state")["state"]["link"]["connected"], 5.0))
        self.assertOk(c.request("list"))
        # Several failed attempts: the back-off reaches reconnect_max_s.
        time.sleep(2.5)
        self.assertIs(c.request("list")["gimbals"][0]["link"]["connected"], False)

        sim = self.start_sim(port=port)
        returned = time.monotonic()
        up = gt.wait_for(lambda: c.request("state")["state"]["link"]["connected"], 4.0,
                         interval=0.05)
        took = time.monotonic() - returned
        self.assertTrue(up, "never reconnected")
        self.assertLess(took, 2.0, "reconnected %.2f s after the gimbal returned" % took)

        event = c.wait_message(lambda m: gt.is_event("link")(m) and m["connected"], 3.0)
        self.assertTrue(event, "no link connected:true event")
        state = self.wait_connected(c)
        self.assertGreater(state["link"]["reconnects"], before)
        self.assertTrue(daemon.wait_log(lambda e: e.get("event") == "link_up" and
                                        e["ts"] > daemon.events("link_down")[0]["ts"]))
        # The requests of a new connection went out again.
        self.assertTrue(sim.wait_rx(gt.by_name("limits")))
        self.assertEqual({e["name"] for e in sim.rx()[:8]}, CONNECT_REQUESTS)
        c.request("unsubscribe")


class LineFaults(gt.GimbaldTestCase):
    def test_bad_checksums_and_junk_are_counted_and_survived(self):
        sim = self.start_sim("--corrupt-fraction", "0.2", "--junk-every", "5")
        daemon = self.start_daemon({"gimbals": [gt.orion_tcp("main", sim.port)]})
        c = self.client(daemon)
        self.wait_connected(c)

        def counted():
            link = c.request("state")["state"]["link"]
            return link if link["bad_checksums"] > 0 and link["dropped_bytes"] > 0 else None
        link = gt.wait_for(counted, 5.0, interval=0.2)
        self.assertTrue(link, "no bad checksum or dropped byte counted")
        self.assertIs(link["connected"], True)
        self.assertEqual(link["reconnects"], 0)
        state = c.request("state")["state"]
        self.assertIs(state["stale"], False)
        entry = daemon.wait_log(lambda e: e.get("event") == "bad_checksum")
        self.assertTrue(entry)
        self.assertEqual(entry["level"], "warn")
        # Rate limited: far fewer lines than bad frames.
        self.assertLessEqual(len(daemon.events("bad_checksum")), 3)
        # Commands still get through whole.
        start = len(sim.rx())
        self.assertOk(c.request("geopoint", lat=45.7, lon=-121.5, alt=100))
        self.assertTrue(sim.wait_rx(gt.by_name("geopoint_cmd"), start=start))

    def test_a_silent_gimbal_goes_stale_and_comes_back(self):
        sim = self.start_sim("--stall-after", "1", "--stall-for", "2")
        daemon = self.start_daemon({"gimbals": [gt.orion_tcp("main", sim.port)],
                                    "telemetry": {"stale_after_s": 0.5}})
        c = self.client(daemon)
        self.wait_connected(c)
        self.assertOk(c.request("subscribe", rate_hz=0.1, ttl_s=30))
        self.addCleanup(c.request, "unsubscribe")
        lost = c.wait_message(gt.is_event("lost"), 4.0)
        self.assertTrue(lost, "no lost event while the gimbal was silent")
        state = c.request("state")["state"]
        self.assertIs(state["stale"], True)
        self.assertIs(state["link"]["connected"], True)  # silence shorter than the timeout
        self.assertTrue(daemon.wait_log(lambda e: e.get("event") == "telemetry_lost"))
        self.assertTrue(gt.wait_for(lambda: not c.request("state")["state"]["stale"], 4.0))
        self.assertEqual(c.request("state")["state"]["link"]["reconnects"], 0)


class Serial(gt.GimbaldTestCase):
    def test_orion_over_a_pty_that_vanishes_and_returns(self):
        device = os.path.join(self.workdir, "ttyGIMBAL")
        sim = self.start_sim(tcp=False, pty_link=device)
        self.assertTrue(sim.endpoints["pty"].startswith("/dev/pts/"))
        self.assertTrue(os.path.islink(device))
        daemon = self.start_daemon({"gimbals": [
            gt.orion_serial("main", device, reconnect_min_s=0.2, reconnect_max_s=1)]})
        c = self.client(daemon)
        state = self.wait_connected(c)
        self.assertEqual(state["link"]["type"], "serial")
        self.assertIn(device, state["link"]["endpoint"])
        self.assertIs(state["stale"], False)
        self.assertTrue(sim.wait_rx(gt.by_name("limits")))
        self.assertEqual({e["name"] for e in sim.rx()[:8]}, CONNECT_REQUESTS)
        self.assertTrue(all(e["src"] == "pty" for e in sim.rx()))

        # Commands go out on the serial line.
        start = len(sim.rx())
        self.assertOk(c.request("geopoint", lat=45.7, lon=-121.5, alt=100))
        self.assertTrue(sim.wait_rx(gt.by_name("geopoint_cmd"), start=start))

        # The simulator goes away (the symlink with it): link down, telemetry stale.
        self.assertEqual(sim.stop(), 0)
        self.assertFalse(os.path.lexists(device))
        self.assertTrue(gt.wait_for(
            lambda: not c.request("state")["state"]["link"]["connected"], 5.0))
        self.assertTrue(gt.wait_for(lambda: c.request("state")["state"]["stale"], 3.0))
        self.assertTrue(daemon.wait_log(lambda e: e.get("event") == "link_down"))

        # A new simulator at the same path: link back up, telemetry flowing again.
        sim = self.start_sim(tcp=False, pty_link=device)
        state = self.wait_connected(c)
        first = state["telemetry"]["system_time_ms"]
        self.assertTrue(gt.wait_for(
            lambda: c.request("state")["state"]["telemetry"]["system_time_ms"] > first, 3.0))
        self.assertIs(c.request("state")["state"]["stale"], False)
        self.assertTrue(sim.wait_rx(gt.by_name("limits")))
        self.assertOk(c.request("position", pan=10, tilt=-20))


if __name__ == "__main__":
    gt.main()
