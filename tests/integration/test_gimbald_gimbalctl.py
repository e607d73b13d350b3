#!/usr/bin/env python3
"""gimbalctl against the real gimbald and a real gimbal-sim: the whole chain a shell script
uses, from the command line to the bytes that reach the gimbal."""

import json
import signal
import subprocess

import gimbaltest as gt


class GimbalctlAgainstGimbald(gt.GimbaldTestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.sim = cls.start_class_sim()
        cls.daemon = cls.start_class_daemon({"gimbals": [gt.orion_tcp("main", cls.sim.port)]})

    def setUp(self):
        super().setUp()
        self.wait_connected(self.client(self.daemon))

    def ctl(self, *args, timeout=15.0):
        return gt.run([gt.GIMBALCTL, "--port", str(self.daemon.port), *args], timeout=timeout)

    def test_geopoint_reaches_the_gimbal(self):
        start = len(self.sim.rx())
        result = self.ctl("geopoint", "45.7", "-121.5", "300", "--stare")
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
        reply = json.loads(result.stdout)
        self.assertEqual((reply["ok"], reply["cmd"], reply["gimbal"]), (True, "geopoint", "main"))
        self.assertEqual(reply["sent"], [{"id": 213, "len": 21}])
        entry = self.sim.wait_rx(gt.by_name("geopoint_cmd"), start=start)
        self.assertTrue(entry, "the geopoint never reached the simulator")
        self.assertAlmostEqual(entry["packet"]["lat"], 45.7, places=6)
        self.assertAlmostEqual(entry["packet"]["lon"], -121.5, places=6)
        self.assertAlmostEqual(entry["packet"]["alt"], 300.0, places=3)
        self.assertEqual(bytes.fromhex(entry["hex"])[4 + 20], 1)  # options: stare

    def test_error_reply_exits_1(self):
        result = self.ctl("position", "500", "0")
        self.assertEqual(result.returncode, 1, result.stdout + result.stderr)
        reply = json.loads(result.stdout)
        self.assertEqual(reply["error"]["code"], "out_of_range")
        self.assertIn("out_of_range", result.stderr)
        self.assertIn("pan", result.stderr)
        result = self.ctl("--gimbal", "nosuch", "state")
        self.assertEqual(result.returncode, 1)
        self.assertEqual(json.loads(result.stdout)["error"]["code"], "unknown_gimbal")

    def test_too_large_request_is_an_error_reply_not_a_timeout(self):
        request = json.dumps({"cmd": "ping", "pad": "x" * 9000})
        result = self.ctl("send", request)
        self.assertEqual(result.returncode, 1, result.stdout + result.stderr)
        self.assertEqual(json.loads(result.stdout)["error"]["code"], "too_large")

    def test_state_and_ping(self):
        result = self.ctl("ping")
        self.assertEqual(result.returncode, 0)
        self.assertIs(json.loads(result.stdout)["pong"], True)
        result = self.ctl("state")
        self.assertEqual(result.returncode, 0)
        self.assertIsNotNone(json.loads(result.stdout)["state"]["telemetry"])

    def test_watch_count_prints_that_many_lines(self):
        result = self.ctl("watch", "--count", "3", "--rate", "10")
        self.assertEqual(result.returncode, 0, result.stderr)
        lines = result.stdout.splitlines()
        self.assertEqual(len(lines), 3, lines)
        for line in lines:
            msg = json.loads(line)
            self.assertIn(msg["type"], ("state", "event"))
            self.assertEqual(msg["gimbal"], "main")
        # It unsubscribed on the way out.
        self.assertTrue(self.daemon.wait_log(
            lambda e: e.get("event") == "subscriber" and e.get("reason") == "unsubscribe"))

    def test_watch_changes_prints_the_merged_state(self):
        result = self.ctl("watch", "--changes", "--full-every", "3600", "--rate", "10",
                          "--count", "8", "--no-events")
        self.assertEqual(result.returncode, 0, result.stderr)
        lines = [json.loads(line) for line in result.stdout.splitlines()]
        self.assertEqual(len(lines), 8)
        self.assertEqual([m["full"] for m in lines], [True] + [False] * 7)
        first = lines[0]["state"]
        times = []
        for msg in lines:
            # Every line holds the whole STATE although the daemon sent only changes.
            self.assertEqual(set(msg["state"]), set(first))
            self.assertEqual(msg["state"]["protocol"], "orion")
            times.append(msg["state"]["telemetry"]["system_time_ms"])
        self.assertEqual(times, sorted(times))
        self.assertGreater(times[-1], times[0])
        # The subscribe asked for the delta stream.
        sub = self.daemon.wait_log(lambda e: e.get("event") == "command" and
                                   e.get("cmd") == "subscribe")
        self.assertTrue(sub)

    def test_watch_stops_on_sigterm(self):
        proc = subprocess.Popen([gt.GIMBALCTL, "--port", str(self.daemon.port), "watch",
                                 "--rate", "5", "--no-events"],
                                stdout=subprocess.PIPE, stderr=subprocess.DEVNULL)
        self.addCleanup(proc.stdout.close)
        self.addCleanup(gt.stop_process, proc, signal.SIGKILL)
        first = gt.read_line(proc.stdout, 5.0)
        self.assertTrue(first, "watch printed nothing")
        self.assertEqual(json.loads(first)["type"], "state")
        self.assertEqual(gt.stop_process(proc, signal.SIGTERM), 0)


class GimbalctlWithToken(gt.GimbaldTestCase):
    def test_token_option(self):
        daemon = self.start_daemon({"command": {"token": "tk"}}, args=["--sim"])
        base = [gt.GIMBALCTL, "--port", str(daemon.port)]
        self.assertEqual(gt.run(base + ["mode", "scene"]).returncode, 1)
        result = gt.run(base + ["--token", "tk", "mode", "scene"])
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)


if __name__ == "__main__":
    gt.main()
