#!/usr/bin/env python3
"""gimbalctl against a real UDP responder.

The responder is a small stand-in for gimbald's command socket (interface contract, section
4): it records every request datagram and answers as the contract says, or answers wrongly
or not at all when a test asks it to. Every test runs the real gimbalctl binary named by the
GIMBALCTL environment variable; without it the whole file is skipped (exit 77; with
CI=true it fails: skipping.py).
"""

import json
import os
import signal
import socket
import subprocess
import sys
import threading
import time
import unittest

import skipping

GIMBALCTL = os.environ.get("GIMBALCTL")

# Generous bounds: the machine running the tests may be busy. Nothing asserts a duration.
RUN_TIMEOUT_S = 20.0
WAIT_S = 10.0


def same_json(a, b):
    """Equality that also tells 1 from 1.0 and true from 1 (Python's == does not)."""
    if type(a) is not type(b):
        return False
    if isinstance(a, dict):
        return a.keys() == b.keys() and all(same_json(a[k], b[k]) for k in a)
    if isinstance(a, list):
        return len(a) == len(b) and all(same_json(x, y) for x, y in zip(a, b))
    return a == b


class Responder:
    """A UDP command socket run in a thread.

    mode: "ok" (reply ok:true), "error" (reply ok:false with self.error), "silent" (never
    reply), "wrong_id_first" (send junk, a reply without id and a reply with another id, each
    ok:false, before the right ok:true reply).
    stream: datagrams sent to a subscriber right after its first subscribe reply.
    """

    def __init__(self, family=socket.AF_INET, host="127.0.0.1"):
        self.sock = socket.socket(family, socket.SOCK_DGRAM)
        self.sock.bind((host, 0))
        self.sock.settimeout(0.05)
        self.port = self.sock.getsockname()[1]
        self.mode = "ok"
        self.error = {"code": "out_of_range", "message": "pan: must be in -180..180"}
        self.stream = []
        self.sent = []  # every datagram we sent, as objects
        self._requests = []
        self._cond = threading.Condition()
        self._subscribers = set()
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)
        self._thread.start()

    def close(self):
        self._stop.set()
        self._thread.join()
        self.sock.close()

    def requests(self):
        with self._cond:
            return list(self._requests)

    def wait_for(self, predicate, timeout=WAIT_S):
        """Waits until predicate(requests) is true; returns the requests."""
        deadline = time.monotonic() + timeout
        with self._cond:
            while not predicate(self._requests):
                left = deadline - time.monotonic()
                if left <= 0:
                    break
                self._cond.wait(left)
            return list(self._requests)

    def send_to(self, address, obj_or_bytes):
        data = obj_or_bytes if isinstance(obj_or_bytes, bytes) else json.dumps(obj_or_bytes).encode()
        # Recorded before it goes: gimbalctl may print the reply and exit, and the test read
        # `sent`, before this thread runs again.
        if not isinstance(obj_or_bytes, bytes):
            self.sent.append(obj_or_bytes)
        self.sock.sendto(data, address)

    def _run(self):
        while not self._stop.is_set():
            try:
                data, address = self.sock.recvfrom(65536)
            except socket.timeout:
                continue
            except OSError:
                return
            request = json.loads(data)
            with self._cond:
                self._requests.append(request)
                self._cond.notify_all()
            self._answer(request, address)

    def _reply(self, request, ok=True):
        reply = {"id": request.get("id"), "ok": ok, "cmd": request.get("cmd")}
        if ok:
            reply["gimbal"] = request.get("gimbal", "sim")
            reply["sent"] = [{"id": 213, "len": 21}]
        else:
            reply["error"] = self.error
        return reply

    def _answer(self, request, address):
        if self.mode == "silent":
            return
        if self.mode == "wrong_id_first":
            self.send_to(address, b"this is not json")
            self.send_to(address, {"ok": False, "cmd": request.get("cmd"), "error": self.error})
            stray = self._reply(request, ok=False)
            stray["id"] = "someone-else"
            self.send_to(address, stray)
        if self.mode == "error":
            self.send_to(address, self._reply(request, ok=False))
            return
        self.send_to(address, self._reply(request))
        if request.get("cmd") == "subscribe" and address not in self._subscribers:
            self._subscribers.add(address)
            for datagram in self.stream:
                self.send_to(address, datagram)


def run(*args, timeout=RUN_TIMEOUT_S):
    return subprocess.run([GIMBALCTL, *args], capture_output=True, text=True, timeout=timeout)


def state_datagram(n):
    return {"type": "state", "gimbal": "sim",
            "state": {"protocol": "orion", "stale": False, "seq": n, "pan": 1.5 * n}}


# (command line after the global options, the request's parameters after cmd and id).
# One row per sub-command and per interesting option; the expected objects are the
# contract's keys and types, written out by hand.
CASES = [
    (["ping"], {"cmd": "ping"}),
    (["version"], {"cmd": "version"}),
    (["list"], {"cmd": "list"}),
    (["state"], {"cmd": "state"}),
    (["geopoint", "45.7", "-121.5", "300"],
     {"cmd": "geopoint", "lat": 45.7, "lon": -121.5, "alt": 300}),
    (["geopoint", "45.7", "-121.5", "300", "--stare", "--closure", "--alt-ref", "msl",
      "--vel-ned", "1", "2", "0", "--joystick-range", "100"],
     {"cmd": "geopoint", "lat": 45.7, "lon": -121.5, "alt": 300, "alt_ref": "msl",
      "vel_ned": [1, 2, 0], "joystick_range_m": 100, "stare": True, "closure": True}),
    (["path", "45.7,-121.5,300", "45.71,-121.49,310.5", "--along-step", "10",
      "--cross-steps", "3", "--cross-ratio", "1.5"],
     {"cmd": "path", "points": [{"lat": 45.7, "lon": -121.5, "alt": 300},
                                {"lat": 45.71, "lon": -121.49, "alt": 310.5}],
      "along_step_deg": 10, "cross_steps": 3, "cross_ratio": 1.5}),
    (["path", "--down"], {"cmd": "path", "down": True}),
    # Altitudes left to the daemon's terrain (contract section 15).
    (["geopoint", "45.7", "-121.5"], {"cmd": "geopoint", "lat": 45.7, "lon": -121.5}),
    (["geopoint", "45.7", "-121.5", "20", "--alt-ref", "terrain"],
     {"cmd": "geopoint", "lat": 45.7, "lon": -121.5, "alt": 20, "alt_ref": "terrain"}),
    (["path", "45.7,-121.5", "45.71,-121.49,30", "--alt-ref", "terrain"],
     {"cmd": "path", "points": [{"lat": 45.7, "lon": -121.5},
                                {"lat": 45.71, "lon": -121.49, "alt": 30}],
      "alt_ref": "terrain"}),
    # The ground and the image (contract sections 15 and 16).
    (["elevation", "45.7", "-121.5"], {"cmd": "elevation", "lat": 45.7, "lon": -121.5}),
    (["locate", "0.5", "-0.3"], {"cmd": "locate", "x": 0.5, "y": -0.3}),
    (["locate", "1440", "270", "--pixels"], {"cmd": "locate", "px": 1440, "py": 270}),
    (["point", "-1", "1"], {"cmd": "point", "x": -1, "y": 1}),
    (["point", "0", "0", "--stare"], {"cmd": "point", "stare": True, "x": 0, "y": 0}),
    (["project", "45.7", "-121.5", "430.5"],
     {"cmd": "project", "lat": 45.7, "lon": -121.5, "alt": 430.5}),
    (["laser"], {"cmd": "laser", "enable": False, "arm": False, "fire": False}),
    (["laser", "--enable", "--arm", "--fire", "--index", "1", "--on-ms", "100",
      "--off-ms", "900", "--prf-code", "7", "--password", "X", "--safety-bypass"],
     {"cmd": "laser", "index": 1, "enable": True, "arm": True, "fire": True, "on_ms": 100,
      "off_ms": 900, "prf_code": 7, "password": "X", "safety_bypass": True}),
    (["laser", "--arm"], {"cmd": "laser", "enable": False, "arm": True, "fire": False}),
    (["position", "30", "-45.25"], {"cmd": "position", "pan": 30, "tilt": -45.25}),
    (["position", "30", "-45", "--stabilized", "--impulse-time", "0.5"],
     {"cmd": "position", "pan": 30, "tilt": -45, "stabilized": True, "impulse_time_s": 0.5}),
    (["rate", "5", "-1.5"], {"cmd": "rate", "pan": 5, "tilt": -1.5}),
    (["rate", "5", "0", "--no-stabilized", "--impulse-time", "2"],
     {"cmd": "rate", "pan": 5, "tilt": 0, "stabilized": False, "impulse_time_s": 2}),
    (["mode", "geo_rate"], {"cmd": "mode", "mode": "geo_rate"}),
    (["stare-ack"], {"cmd": "stare_ack"}),
    (["stare-ack", "--system-time", "123456"], {"cmd": "stare_ack", "system_time_ms": 123456}),
    (["retract", "deploy"], {"cmd": "retract", "action": "deploy"}),
    (["camera-switch", "1"], {"cmd": "camera_switch", "index": 1}),
    (["camera-zoom", "4.5"], {"cmd": "camera_zoom", "zoom": 4.5}),
    (["camera-zoom", "2", "--focus", "0.25", "--index", "1"],
     {"cmd": "camera_zoom", "zoom": 2, "focus": 0.25, "index": 1}),
    (["range", "1500.5"], {"cmd": "range", "range_m": 1500.5}),
    (["range", "1500", "--max-age-ms", "500", "--source", "laser"],
     {"cmd": "range", "range_m": 1500, "max_age_ms": 500, "source": "laser"}),
    (["request", "versions"], {"cmd": "request", "packet": "versions"}),
    (["viewpro-output", "--osd", "target", "--serial", "--no-network", "--format", "out3"],
     {"cmd": "viewpro_output", "osd": "target", "serial": True, "network": False,
      "format": "out3"}),
    (["viewpro-output", "--osd", "uav", "--no-serial", "--network", "--format", "out1"],
     {"cmd": "viewpro_output", "osd": "uav", "serial": False, "network": True,
      "format": "out1"}),
    (["viewpro-adjust", "--yaw", "-1.5"], {"cmd": "viewpro_adjust", "yaw_deg": -1.5}),
    (["viewpro-adjust", "--yaw", "3", "--pitch", "-0.01"],
     {"cmd": "viewpro_adjust", "yaw_deg": 3, "pitch_deg": -0.01}),
    (["vehicle", "--roll", "1.5", "--pitch", "-2", "--yaw", "359", "--lat", "45.7",
      "--lon", "-121.5", "--alt-msl", "310"],
     {"cmd": "vehicle", "roll": 1.5, "pitch": -2, "yaw": 359, "lat": 45.7, "lon": -121.5,
      "alt_msl": 310}),
    (["vehicle", "--roll", "0", "--pitch", "0", "--yaw", "90", "--lat", "1", "--lon", "2",
      "--alt-msl", "3", "--vel-ned", "1", "-2", "0.5", "--time", "2026-11-21T06:41:50.123Z"],
     {"cmd": "vehicle", "roll": 0, "pitch": 0, "yaw": 90, "lat": 1, "lon": 2, "alt_msl": 3,
      "vel_ned": [1, -2, 0.5], "time": "2026-11-21T06:41:50.123Z"}),
    (["send", '{"cmd":"subscribe","rate_hz":0.5,"events":false}'],
     {"cmd": "subscribe", "rate_hz": 0.5, "events": False}),
]


def with_id(expected, request_id):
    """The expected request: cmd first, then id, then the parameters (gimbalctl's order)."""
    obj = {"cmd": expected["cmd"], "id": request_id}
    obj.update({k: v for k, v in expected.items() if k != "cmd"})
    return obj


class GimbalctlTest(unittest.TestCase):
    def setUp(self):
        self.responder = Responder()
        self.addCleanup(self.responder.close)

    def ctl(self, *args, timeout="5"):
        return run("--port", str(self.responder.port), "--timeout", timeout, *args)

    def assertSameJson(self, actual, expected):
        self.assertTrue(same_json(actual, expected),
                        f"\n actual:   {json.dumps(actual)}\n expected: {json.dumps(expected)}")

    # --- every sub-command: the exact request, sent and printed ---

    def test_every_command_sends_the_contract_request(self):
        for n, (args, expected) in enumerate(CASES):
            with self.subTest(args=args):
                before = len(self.responder.requests())
                result = self.ctl("--id", str(n), *args)
                self.assertEqual(result.returncode, 0, result.stderr)
                requests = self.responder.requests()[before:]
                self.assertEqual(len(requests), 1)
                self.assertSameJson(requests[0], with_id(expected, n))

    def test_every_command_prints_the_same_request_without_sending(self):
        for n, (args, expected) in enumerate(CASES):
            with self.subTest(args=args):
                result = self.ctl("--print-request", "--id", str(n), *args)
                self.assertEqual(result.returncode, 0, result.stderr)
                self.assertEqual(result.stdout.count("\n"), 1, "one line")
                self.assertSameJson(json.loads(result.stdout), with_id(expected, n))
        time.sleep(0.2)
        self.assertEqual(self.responder.requests(), [], "--print-request sent something")

    def test_key_order_is_cmd_id_then_parameters(self):
        result = self.ctl("--print-request", "--id", "1", "--gimbal", "main", "--token", "t",
                          "position", "1", "2")
        self.assertEqual(list(json.loads(result.stdout)),
                         ["cmd", "id", "gimbal", "token", "pan", "tilt"])

    def test_gimbal_and_token_are_added_but_not_gimbal_to_daemon_commands(self):
        result = self.ctl("--id", "a", "--gimbal", "main", "--token", "s3cret", "state")
        self.assertEqual(result.returncode, 0, result.stderr)
        result = self.ctl("--id", "b", "--gimbal", "main", "--token", "s3cret", "ping")
        self.assertEqual(result.returncode, 0, result.stderr)
        requests = self.responder.requests()
        self.assertSameJson(requests[0],
                            {"cmd": "state", "id": "a", "gimbal": "main", "token": "s3cret"})
        self.assertSameJson(requests[1], {"cmd": "ping", "id": "b", "token": "s3cret"})

    def test_global_options_may_follow_the_command(self):
        result = run("ping", "--port", str(self.responder.port), "--id", "9")
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertSameJson(self.responder.requests()[0], {"cmd": "ping", "id": 9})

    def test_send_fills_only_missing_envelope_keys(self):
        result = self.ctl("--gimbal", "main", "--token", "t", "--id", "7", "send",
                          '{"cmd":"state","gimbal":"other","id":"mine"}')
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertSameJson(self.responder.requests()[0],
                            {"cmd": "state", "gimbal": "other", "id": "mine", "token": "t"})

    def test_send_without_id_gets_a_random_one(self):
        result = self.ctl("send", '{"cmd":"ping"}')
        self.assertEqual(result.returncode, 0, result.stderr)
        request = self.responder.requests()[0]
        self.assertIsInstance(request.get("id"), str)

    def test_id_is_random_when_not_given_and_the_reply_carries_it(self):
        first = self.ctl("ping")
        second = self.ctl("ping")
        self.assertEqual(first.returncode, 0, first.stderr)
        self.assertEqual(second.returncode, 0, second.stderr)
        ids = [r["id"] for r in self.responder.requests()]
        self.assertEqual(len(ids), 2)
        self.assertTrue(all(isinstance(i, str) and i for i in ids), ids)
        self.assertNotEqual(ids[0], ids[1])
        self.assertEqual(json.loads(first.stdout)["id"], ids[0])

    def test_id_text_is_sent_as_a_string(self):
        self.ctl("--id", "abc-1", "ping")
        self.assertSameJson(self.responder.requests()[0], {"cmd": "ping", "id": "abc-1"})

    # --- replies and exit status ---

    def test_ok_reply_exit_0_reply_on_stdout_as_one_line(self):
        result = self.ctl("--id", "5", "geopoint", "1", "2", "3")
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(result.stdout.count("\n"), 1)
        self.assertSameJson(json.loads(result.stdout), self.responder.sent[-1])
        self.assertEqual(result.stderr, "")

    def test_pretty_indents_the_reply(self):
        result = self.ctl("--pretty", "--id", "5", "ping")
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertGreater(result.stdout.count("\n"), 3)
        self.assertSameJson(json.loads(result.stdout), self.responder.sent[-1])

    def test_error_reply_exit_1_message_on_stderr_reply_on_stdout(self):
        self.responder.mode = "error"
        result = self.ctl("--id", "5", "position", "500", "0")
        self.assertEqual(result.returncode, 1)
        self.assertIn("gimbalctl: out_of_range: pan: must be in -180..180", result.stderr)
        self.assertSameJson(json.loads(result.stdout), self.responder.sent[-1])

    def test_silence_exit_2_after_timeout(self):
        self.responder.mode = "silent"
        result = self.ctl("ping", timeout="0.3")
        self.assertEqual(result.returncode, 2)
        self.assertEqual(result.stdout, "")
        self.assertIn("no reply", result.stderr)
        self.assertEqual(len(self.responder.requests()), 1)

    def test_nobody_listening_exit_2(self):
        probe = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        probe.bind(("127.0.0.1", 0))
        free_port = probe.getsockname()[1]
        probe.close()
        result = run("--port", str(free_port), "--timeout", "5", "ping")
        self.assertEqual(result.returncode, 2)
        self.assertIn("gimbalctl:", result.stderr)

    def test_replies_with_another_id_and_junk_are_ignored(self):
        self.responder.mode = "wrong_id_first"
        result = self.ctl("--id", "42", "state")
        self.assertEqual(result.returncode, 0, result.stderr)
        reply = json.loads(result.stdout)
        self.assertSameJson(reply, self.responder.sent[-1])
        self.assertEqual(reply["id"], 42)
        self.assertTrue(reply["ok"])

    def test_only_a_wrong_id_reply_means_no_reply(self):
        self.responder.mode = "wrong_id_first"
        self.responder.error = {"code": "internal", "message": "x"}
        # Make the right reply never come: answer only with the stray datagrams.
        original = self.responder._reply
        self.responder._reply = lambda request, ok=True: dict(original(request, ok), id="nope")
        result = self.ctl("--id", "42", "ping", timeout="0.5")
        self.assertEqual(result.returncode, 2, result.stdout)

    def test_host_name_and_ipv6(self):
        result = run("--host", "localhost", "--port", str(self.responder.port), "--timeout", "5",
                     "--id", "1", "ping")
        self.assertEqual(result.returncode, 0, result.stderr)
        try:
            v6 = Responder(socket.AF_INET6, "::1")
        except OSError:
            self.skipTest("no IPv6 loopback")
        self.addCleanup(v6.close)
        result = run("--host", "::1", "--port", str(v6.port), "--timeout", "5", "--id", "2",
                     "ping")
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertSameJson(v6.requests()[0], {"cmd": "ping", "id": 2})

    # --- usage ---

    def test_usage_errors_exit_64(self):
        bad = [
            [],
            ["no-such-command"],
            ["ping", "--no-such-option"],
            ["geopoint", "1"],
            ["geopoint", "north", "2", "3"],
            ["geopoint", "1", "2", "3", "--alt-ref", "agl"],
            ["geopoint", "1", "2", "3", "--vel-ned", "1", "2"],
            ["path"],
            ["path", "--down", "1,2,3"],
            ["path", "1"],
            ["path", "1,2,3,4"],
            ["locate", "0.5"],
            ["locate", "left", "0"],
            ["point", "0", "0", "--stare", "yes"],
            ["elevation", "45.7"],
            ["project", "45.7", "-121.5"],
            ["camera-switch", "1.5"],
            ["mode", "bogus"],
            ["retract", "sideways"],
            ["viewpro-output", "--osd", "target", "--serial", "--format", "out3"],
            ["viewpro-adjust"],
            ["vehicle", "--roll", "1"],
            ["send", "not json"],
            ["send", "[1,2]"],
            ["watch", "--count", "0"],
            ["--port", "0", "ping"],
            ["--timeout", "-1", "ping"],
        ]
        for args in bad:
            with self.subTest(args=args):
                result = self.ctl(*args)
                self.assertEqual(result.returncode, 64, result.stdout + result.stderr)
                self.assertNotEqual(result.stderr, "")
        time.sleep(0.2)
        self.assertEqual(self.responder.requests(), [])

    def test_usage_errors_are_one_prefixed_line_naming_the_problem(self):
        cases = [
            (["bogus"], "gimbalctl: unknown command 'bogus'"),
            (["bogus", "--port", "5"], "gimbalctl: unknown command 'bogus'"),
            ([], "gimbalctl: a COMMAND is required"),
            (["geopoint", "1"], "gimbalctl: LON is required (see gimbalctl geopoint --help)"),
            (["ping", "--no-such-option"], "--no-such-option"),
            (["watch", "--count", "0"], "gimbalctl: --count: '0' is not a whole number"),
            (["--timeout", "-1", "ping"], "gimbalctl: --timeout: '-1' is not a number above 0"),
        ]
        for args, expected in cases:
            with self.subTest(args=args):
                result = self.ctl(*args)
                self.assertEqual(result.returncode, 64, result.stderr)
                self.assertEqual(result.stdout, "")
                lines = result.stderr.splitlines()
                self.assertEqual(len(lines), 1, lines)
                self.assertTrue(lines[0].startswith("gimbalctl: "), lines)
                self.assertIn(expected, lines[0])

    def test_help_reads_like_a_man_page(self):
        result = run("--help")
        self.assertEqual(result.returncode, 0)
        text = result.stdout
        for section in ["NAME", "SYNOPSIS", "DESCRIPTION", "OPTIONS", "COMMANDS", "EXAMPLES",
                        "EXIT STATUS"]:
            self.assertIn("\n" + section + "\n", "\n" + text)
        for option, default in [("--host", "127.0.0.1"), ("--port", "8760"),
                                ("--timeout", "2"), ("--gimbal", ""), ("--token", ""),
                                ("--id", ""), ("--print-request", ""), ("--pretty", "")]:
            entry = text.split("\n       " + option, 1)[1].split("\n       -", 1)[0]
            entry = " ".join(entry.split())  # undo the word wrap
            self.assertIn("Default: " + default, entry, option)
        for command in ["ping", "version", "list", "state", "geopoint", "path", "laser",
                        "position", "rate", "mode", "stare-ack", "retract", "camera-switch",
                        "camera-zoom", "range", "request", "viewpro-output", "viewpro-adjust",
                        "vehicle", "watch", "send"]:
            self.assertIn("\n       " + command, text)
        self.assertIn("gimbalctl state | python3 -c", text)
        self.assertIn("socat", text)
        for status in ["0", "1", "2", "64"]:
            self.assertIn("\n       " + status + " ", text.split("EXIT STATUS")[1])
        self.assertTrue(all(len(line) <= 80 for line in text.splitlines()))

    def test_command_help_lists_arguments_and_keys(self):
        result = run("geopoint", "--help")
        self.assertEqual(result.returncode, 0)
        for word in ["LAT", "--alt-ref", '"joystick_range_m"', "Default: wgs84"]:
            self.assertIn(word, result.stdout)


class WatchTest(unittest.TestCase):
    def setUp(self):
        self.responder = Responder()
        self.addCleanup(self.responder.close)

    def start_watch(self, *args):
        process = subprocess.Popen(
            [GIMBALCTL, "--port", str(self.responder.port), "--timeout", "5", "--id", "w",
             "watch", *args],
            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        self.addCleanup(lambda: process.poll() is None and process.kill())
        return process

    def subscribes(self, requests):
        return [r for r in requests if r.get("cmd") == "subscribe"]

    def test_count_prints_exactly_the_subscription_datagrams(self):
        self.responder.stream = [
            state_datagram(1),
            {"type": "event", "gimbal": "sim", "event": "mode", "from": "rate", "to": "geopoint"},
            state_datagram(2),
            state_datagram(3),
        ]
        process = self.start_watch("--count", "3", "--rate", "20", "--ttl", "30")
        out, err = process.communicate(timeout=RUN_TIMEOUT_S)
        self.assertEqual(process.returncode, 0, err)
        lines = out.splitlines()
        self.assertEqual(len(lines), 3, out)
        for line, sent in zip(lines, self.responder.stream[:3]):
            self.assertSameJson(json.loads(line), sent)
        requests = self.responder.wait_for(lambda rs: any(r["cmd"] == "unsubscribe" for r in rs))
        self.assertSameJson(requests[0], {"cmd": "subscribe", "id": "w", "rate_hz": 20,
                                          "ttl_s": 30})
        self.assertSameJson(requests[-1], {"cmd": "unsubscribe", "id": "w"})

    def test_renews_before_ttl_and_unsubscribes_on_sigint(self):
        process = self.start_watch("--ttl", "1", "--no-events")
        requests = self.responder.wait_for(lambda rs: len(self.subscribes(rs)) >= 2)
        subscribes = self.subscribes(requests)
        self.assertGreaterEqual(len(subscribes), 2, "no renewal")
        for subscribe in subscribes:
            self.assertSameJson(subscribe, {"cmd": "subscribe", "id": "w", "ttl_s": 1,
                                            "events": False})
        process.send_signal(signal.SIGINT)
        out, err = process.communicate(timeout=RUN_TIMEOUT_S)
        self.assertEqual(process.returncode, 0, err)
        self.assertEqual(out, "", "subscribe replies must not be printed")
        requests = self.responder.wait_for(lambda rs: rs[-1]["cmd"] == "unsubscribe")
        self.assertSameJson(requests[-1], {"cmd": "unsubscribe", "id": "w"})

    def test_sigterm_unsubscribes_with_gimbal_and_token(self):
        process = subprocess.Popen(
            [GIMBALCTL, "--port", str(self.responder.port), "--id", "t", "--gimbal", "main",
             "--token", "s", "watch"],
            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        self.addCleanup(lambda: process.poll() is None and process.kill())
        self.responder.wait_for(lambda rs: len(rs) >= 1)
        time.sleep(0.2)  # let the reply arrive, so the SIGTERM finds watch subscribed
        process.send_signal(signal.SIGTERM)
        out, err = process.communicate(timeout=RUN_TIMEOUT_S)
        self.assertEqual(process.returncode, 0, err)
        requests = self.responder.wait_for(lambda rs: rs[-1]["cmd"] == "unsubscribe")
        self.assertSameJson(requests[0],
                            {"cmd": "subscribe", "id": "t", "gimbal": "main", "token": "s"})
        self.assertSameJson(requests[-1],
                            {"cmd": "unsubscribe", "id": "t", "gimbal": "main", "token": "s"})

    def test_refused_subscribe_exit_1(self):
        self.responder.mode = "error"
        self.responder.error = {"code": "busy", "message": "subscriber table full"}
        process = self.start_watch()
        out, err = process.communicate(timeout=RUN_TIMEOUT_S)
        self.assertEqual(process.returncode, 1)
        self.assertIn("gimbalctl: busy: subscriber table full", err)
        self.assertFalse(json.loads(out)["ok"])

    def test_no_reply_to_subscribe_exit_2(self):
        self.responder.mode = "silent"
        process = subprocess.Popen(
            [GIMBALCTL, "--port", str(self.responder.port), "--timeout", "0.3", "watch"],
            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        out, err = process.communicate(timeout=RUN_TIMEOUT_S)
        self.assertEqual(process.returncode, 2)
        self.assertEqual(out, "")

    def assertSameJson(self, actual, expected):
        self.assertTrue(same_json(actual, expected),
                        f"\n actual:   {json.dumps(actual)}\n expected: {json.dumps(expected)}")


if __name__ == "__main__":
    if not GIMBALCTL:
        skipping.need_for_file("GIMBALCTL is not set")
    unittest.main(verbosity=2)
