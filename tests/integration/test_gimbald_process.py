#!/usr/bin/env python3
"""gimbald as a process (contract sections 2, 3 and 6): --sim, exit codes, signals, logs."""

import json
import os
import signal
import socket
import subprocess

import gimbaltest as gt

SOURCE = os.environ.get("GIMBAL_SOURCE_DIR",
                        os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
TS = r"^\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d\.\d{6}Z$"


class EmbeddedSim(gt.GimbaldTestCase):
    def test_sim_answers_ping_and_state(self):
        daemon = self.start_daemon({}, args=["--sim"])
        c = self.client(daemon)
        self.assertOk(c.request("ping"))
        reply = c.request("list")
        self.assertEqual(reply["gimbals"], [{"name": "sim", "protocol": "orion",
                                             "link": {"type": "sim", "connected": True}}])
        state = self.wait_connected(c)
        reply = c.request("state")
        self.assertEqual(reply["gimbal"], "sim")
        self.assertEqual(state["link"]["type"], "sim")
        self.assertIs(reply["state"]["stale"], False)
        # The in-process model obeys commands like the real one.
        self.assertOk(c.request("geopoint", lat=45.7, lon=-121.5, alt=100))
        self.assertTrue(gt.wait_for(
            lambda: c.request("state")["state"]["telemetry"]["mode"] == "geopoint", 3.0))

    def test_sim_replaces_the_gimbals_of_the_file(self):
        daemon = self.start_daemon(
            {"gimbals": [gt.orion_tcp("main", gt.closed_tcp_port())]}, args=["--sim"])
        names = [g["name"] for g in self.client(daemon).request("list")["gimbals"]]
        self.assertEqual(names, ["sim"])


class ExitCodes(gt.GimbaldTestCase):
    def write(self, name, config):
        path = os.path.join(self.workdir, name)
        with open(path, "w") as f:
            f.write(config if isinstance(config, str) else json.dumps(config))
        return path

    def test_port_in_use_by_another_program_exits_2(self):
        holder = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.addCleanup(holder.close)
        holder.bind(("127.0.0.1", 0))
        port = holder.getsockname()[1]
        path = self.write("busy.json", {"gimbals": [gt.orion_tcp("main", 1)],
                                        "command": {"port": port}})
        result = gt.run([gt.GIMBALD, "-c", path])
        self.assertEqual(result.returncode, 2, result.stdout + result.stderr)
        logs = [json.loads(line) for line in result.stdout.splitlines()]
        self.assertEqual(logs[-1]["event"], "runtime_failure")
        self.assertEqual(logs[-1]["level"], "error")

    def test_port_in_use_by_another_gimbald_exits_2(self):
        first = self.start_daemon({}, args=["--sim"])
        path = self.write("second.json", {"command": {"port": first.port}})
        result = gt.run([gt.GIMBALD, "--sim", "-c", path])
        self.assertEqual(result.returncode, 2, result.stdout[-2000:] + result.stderr)
        self.assertOk(self.client(first).request("ping"))

    def test_invalid_config_exits_1_and_names_every_problem(self):
        path = self.write("bad.json", {
            "gimbals": [{"name": "Main!", "protocol": "orion",
                         "link": {"type": "tcp", "host": "h", "port": 0}}],
            "laser": {"alow_fire": True}})
        for args in ([gt.GIMBALD, "-c", path], [gt.GIMBALD, "--check-config", "-c", path]):
            result = gt.run(args)
            self.assertEqual(result.returncode, 1, args)
            text = result.stdout + result.stderr
            for where in ("gimbals[0].name", "gimbals[0].link.port", "laser.alow_fire"):
                self.assertIn(where, text)
            self.assertIn("allow_fire", text)  # the suggestion
        # It never started: nothing listens.
        self.assertNotIn('"event":"start"', result.stdout)

    def test_check_config_of_a_valid_file_exits_0_and_opens_nothing(self):
        # A serial device that does not exist: --check-config does not open it.
        path = self.write("good.json", {"gimbals": [gt.orion_serial("main", "/dev/ttyNOPE9")]})
        result = gt.run([gt.GIMBALD, "--check-config", "-c", path])
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
        self.assertIn("main", result.stdout)

    def test_syntax_error_exits_1_with_line_and_column(self):
        path = self.write("syntax.json", '{\n  "gimbals": [\n    }\n')
        result = gt.run([gt.GIMBALD, "-c", path])
        self.assertEqual(result.returncode, 1)
        self.assertRegex(result.stderr, r"line 3, column \d+")

    def test_missing_file_exits_1(self):
        result = gt.run([gt.GIMBALD, "-c", os.path.join(self.workdir, "nope.json")])
        self.assertEqual(result.returncode, 1)
        self.assertIn("nope.json", result.stderr)

    def test_version_option(self):
        result = gt.run([gt.GIMBALD, "--version"])
        self.assertEqual(result.returncode, 0)
        version = self.start_daemon({}, args=["--sim"])
        reply = self.client(version).request("version")
        self.assertIn(reply["version"], result.stdout)


class ConfigurationFiles(gt.GimbaldTestCase):
    """Contract section 14 (v4): configuration files are regular files of at most 1 MiB with
    no NUL; every key file is checked by --check-config; any configuration problem found at
    start exits 1 (the unit restarts on anything else: issue 25 saw a restart every 2 s)."""

    def run_both(self, path, *extra):
        """--check-config and a start, each with a deadline (a FIFO used to hang forever)."""
        results = []
        for args in ([gt.GIMBALD, "--check-config", "-c", path, *extra],
                     [gt.GIMBALD, "-c", path, *extra]):
            try:
                results.append(gt.run(args, timeout=10.0, stdin=subprocess.DEVNULL))
            except subprocess.TimeoutExpired:
                self.fail("%s did not return within 10 s" % " ".join(args))
        return results

    def assert_refused(self, path, *needles, extra=()):
        for result in self.run_both(path, *extra):
            text = result.stdout + result.stderr
            self.assertEqual(result.returncode, 1, text[-2000:])
            for needle in needles:
                self.assertIn(needle, text)
            self.assertNotIn('"event":"start"', result.stdout)

    def test_only_regular_files_of_at_most_1_mib_without_a_nul(self):
        self.assert_refused("/dev/zero", "/dev/zero", "not a regular file (a character device)")
        fifo = os.path.join(self.workdir, "config.fifo")
        os.mkfifo(fifo)
        self.assert_refused(fifo, "not a regular file (a FIFO)")
        self.assert_refused(self.workdir, "not a regular file (a directory)")
        nul = os.path.join(self.workdir, "nul.json")
        with open(nul, "wb") as f:
            f.write(b'{"gimbals": []}\n\0{"laser": {"allow_fire": true}}')
        self.assert_refused(nul, "line 2, column 1: a NUL byte")
        big = os.path.join(self.workdir, "big.json")
        with open(big, "w") as f:  # a valid configuration, padded past 1 MiB
            f.write('{"gimbals": []}' + " " * (1024 * 1024))
        self.assert_refused(big, "larger than 1 MiB")
        unclosed = os.path.join(self.workdir, "unclosed.json")
        with open(unclosed, "w") as f:
            f.write('{"gimbals": ' + "[" * 1000000)
        self.assert_refused(unclosed, "nested deeper than 32 levels")
        # At exactly the limit it is read.
        edge = os.path.join(self.workdir, "edge.json")
        with open(edge, "w") as f:
            f.write('{"gimbals": []}' + " " * (1024 * 1024 - 15))
        self.assertEqual(os.path.getsize(edge), 1024 * 1024)
        result = gt.run([gt.GIMBALD, "--check-config", "-c", edge])
        self.assertEqual(result.returncode, 0, result.stderr)

    def test_the_examples_pass_as_installed(self):
        # Issue 25: the installed sim.json named build/release/sim-dem.tif (relative to the
        # working directory) and gimbald.json /var/lib/gimbald/dem/*.tif. What `cmake
        # --install` and the package install (packaging/examples.cmake) passes from anywhere.
        build = os.path.dirname(os.path.dirname(os.path.abspath(gt.GIMBALD)))
        examples = sorted(os.listdir(os.path.join(build, "examples")))
        self.assertEqual([e for e in examples if e.endswith(".json")], ["gimbald.json", "sim.json"])
        for name in ("gimbald.json", "sim.json"):
            with self.subTest(name):
                path = os.path.join(build, "examples", name)
                result = gt.run([gt.GIMBALD, "--check-config", "-c", path], cwd=self.workdir)
                self.assertEqual(result.returncode, 0, result.stderr)
                with open(path) as f:
                    installed = json.load(f)
                with open(os.path.join(SOURCE, "config", name)) as f:
                    source = json.load(f)
                source.pop("terrain")
                self.assertEqual(installed, source, "only the terrain section is left out")

    def manager(self, key_path, **more):
        config = {"vehicle": {"source": {"type": "udp", "bind": "127.0.0.1",
                                         "port": gt.free_port()}},
                  "mavlink": {"gimbal_manager": True, "system_id": 1,
                              "signing_key_file": key_path}}
        config.update(more)
        path = os.path.join(self.workdir, "manager.json")
        with open(path, "w") as f:
            json.dump(config, f)
        return path

    def write_key(self, name, data, mode):
        path = os.path.join(self.workdir, name)
        with open(path, "wb") as f:
            f.write(data)
        os.chmod(path, mode)
        return path

    def test_the_gimbal_managers_signing_key_is_checked(self):
        good = self.write_key("good.key", os.urandom(32).hex().encode(), 0o600)
        result = gt.run([gt.GIMBALD, "--sim", "--check-config", "-c", self.manager(good)])
        self.assertEqual(result.returncode, 0, result.stderr)
        cases = [
            ("malformed", self.write_key("short.key", b"abcd\n", 0o600),
             "must hold 32 bytes, or 64 hex digits"),
            ("readable by others", self.write_key("open.key", os.urandom(32), 0o644),
             "readable by group or others (mode 0644)"),
            ("missing", os.path.join(self.workdir, "none.key"), "missing"),
        ]
        fifo = os.path.join(self.workdir, "key.fifo")
        os.mkfifo(fifo, 0o600)
        cases.append(("a FIFO", fifo, "not a regular file (a FIFO)"))
        for what, key, reason in cases:
            with self.subTest(what):
                self.assert_refused(self.manager(key), "mavlink.signing_key_file", reason,
                                    extra=("--sim",))

    def test_a_key_that_goes_bad_after_the_check_is_exit_1_at_start(self):
        # The daemon reads the key again when it starts: the same problem is exit 1, not 2.
        key = self.write_key("late.key", os.urandom(32).hex().encode(), 0o600)
        path = self.manager(key)
        self.assertEqual(gt.run([gt.GIMBALD, "--sim", "--check-config", "-c", path]).returncode, 0)
        os.chmod(key, 0o644)
        result = gt.run([gt.GIMBALD, "--sim", "-c", path], stdin=subprocess.DEVNULL)
        self.assertEqual(result.returncode, 1, result.stdout[-2000:] + result.stderr)
        self.assertIn("mavlink.signing_key_file", result.stderr)


class SignalsAndLogs(gt.GimbaldTestCase):
    def test_sigterm_and_sigint_exit_0_with_start_and_stop(self):
        for sig, name in ((signal.SIGTERM, "SIGTERM"), (signal.SIGINT, "SIGINT")):
            daemon = self.start_daemon({}, args=["--sim"])
            self.assertOk(self.client(daemon).request("ping"))
            self.assertEqual(daemon.stop(sig), 0, name)
            events = [e["event"] for e in daemon.logs()]
            self.assertEqual(events[:2], ["config", "start"])
            self.assertEqual(events[-2:], ["stop", "stop"])
            # Both lines name the signal (issue 25: the second one did not).
            self.assertEqual([e["signal"] for e in daemon.logs()[-2:]], [name, name])

    def test_log_lines_are_json_with_the_required_keys(self):
        sim = self.start_sim()
        daemon = self.start_daemon({"gimbals": [gt.orion_tcp("main", sim.port)]})
        c = self.client(daemon)
        self.wait_connected(c)
        self.assertOk(c.request("state", id=41))
        self.assertError(c.request("position", id="p", pan=999, tilt=0), "out_of_range")
        c.send_raw(b"junk")
        self.assertError(c.recv(), "bad_json")
        self.assertEqual(daemon.stop(), 0)

        with open(daemon.stdout_path) as f:
            lines = f.read().splitlines()
        self.assertTrue(lines)
        for line in lines:
            entry = json.loads(line)  # every line is one JSON object
            for key in ("ts", "level", "event", "msg"):
                self.assertIn(key, entry, line)
            self.assertRegex(entry["ts"], TS)
            self.assertIn(entry["level"], ("trace", "debug", "info", "warn", "error"))
            self.assertRegex(entry["event"], r"^[a-z][a-z0-9_]*$")
        events = {json.loads(line)["event"] for line in lines}
        self.assertTrue({"config", "start", "link_up", "command", "stop"} <= events, events)

        src = "127.0.0.1:%d" % c.sock.getsockname()[1]
        commands = daemon.events("command")
        fields = {"src", "id", "cmd", "gimbal", "ok", "error"}
        for entry in commands:
            self.assertTrue(fields <= set(entry), entry)
        by_id = {json.dumps(e["id"]): e for e in commands}
        state = by_id["41"]
        self.assertEqual((state["src"], state["cmd"], state["gimbal"], state["ok"],
                          state["error"]), (src, "state", "main", True, None))
        position = by_id['"p"']
        self.assertEqual((position["cmd"], position["ok"], position["error"]),
                         ("position", False, "out_of_range"))
        junk = by_id["null"]
        self.assertEqual((junk["cmd"], junk["error"]), (None, "bad_json"))

    def test_sighup_reopens_the_log_file(self):
        log_file = os.path.join(self.workdir, "gimbald.log")
        daemon = self.start_daemon({"log": {"file": log_file}}, args=["--sim"])
        c = self.client(daemon)
        self.assertOk(c.request("ping", id="before"))
        self.assertTrue(gt.wait_for(
            lambda: any(e.get("id") == "before" for e in gt.read_json_lines(log_file)), 3.0))
        rotated = log_file + ".1"
        os.rename(log_file, rotated)
        os.kill(daemon.proc.pid, signal.SIGHUP)
        self.assertTrue(gt.wait_for(lambda: os.path.exists(log_file), 3.0),
                        "SIGHUP did not reopen the log file")
        self.assertOk(c.request("ping", id="after"))
        self.assertTrue(gt.wait_for(
            lambda: any(e.get("id") == "after" for e in gt.read_json_lines(log_file)), 3.0))
        self.assertFalse(any(e.get("id") == "after" for e in gt.read_json_lines(rotated)))
        self.assertTrue(any(e.get("id") == "before" for e in gt.read_json_lines(rotated)))
        # Still running, and standard output got every line too.
        self.assertTrue(daemon.running())
        self.assertTrue(any(e.get("id") == "after" for e in daemon.logs()))
        self.assertEqual(daemon.stop(), 0)

    def test_sighup_without_a_log_file_is_harmless(self):
        daemon = self.start_daemon({}, args=["--sim"])
        os.kill(daemon.proc.pid, signal.SIGHUP)
        self.assertTrue(daemon.wait_log(lambda e: e.get("event") == "reopen"))
        self.assertOk(self.client(daemon).request("ping"))
        self.assertEqual(daemon.stop(), 0)

    def test_log_level_option_overrides_the_file(self):
        daemon = self.start_daemon({"log": {"level": "info"}},
                                   args=["--sim", "--log-level", "warn"], wait_started=False)
        c = self.client(daemon)
        self.assertTrue(gt.wait_for(lambda: c.request("ping", timeout=0.3), 5.0))
        self.assertEqual(daemon.stop(), 0)
        self.assertEqual(daemon.events("command"), [])

    def test_text_format(self):
        daemon = self.start_daemon({}, args=["--sim", "--log-format", "text"],
                                   wait_started=False)
        c = self.client(daemon)
        self.assertTrue(gt.wait_for(lambda: c.request("ping", timeout=0.3), 5.0))
        self.assertEqual(daemon.stop(), 0)
        text = daemon.log_text()
        self.assertIn("start", text)
        self.assertFalse(text.lstrip().startswith("{"))


if __name__ == "__main__":
    gt.main()
