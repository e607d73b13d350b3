#!/usr/bin/env python3
"""The examples of README.md and docs/*.md, run as a reader would copy them, so they cannot
rot (issue 17). The convention is in docs/architecture.md ("Examples that are run"):

    <!-- example: sim -->            the next fenced block runs against `gimbald --sim`
    <!-- example: sim orion,viewpro -->        ... against `gimbald --sim orion,viewpro`
    <!-- example -->                 the next fenced block runs without a daemon
    <!-- example: config -->         the next ```json block is a configuration file that
                                     `gimbald --check-config` accepts
    <!-- example: mosquitto.conf --> the next block is a mosquitto.conf excerpt (checked for
                                     what mosquitto refuses: comments after a directive)

```sh blocks run in bash (`set -e`) from a scratch directory, ```python blocks in python3,
each within 30 s; a failing one fails the test. A line `# => TEXT` under a command says
that its output (stdout and stderr) contains TEXT, and lets the command exit non-zero.
The daemon runs on free ports: 8760 and 8761 in a block become those ports, 15010 (the
video output of config/sim.json) the daemon's video output port, and
`gimbalctl` (also as build/release/tools/gimbalctl) is the one under test, pointed at the
daemon's port. The Wireshark filters docs/wireshark.md names are compiled by tshark with
dissectors/gimbald.lua.
"""

import glob
import json
import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
import unittest

import gimbaltest as gt
import skipping

SOURCE = os.environ.get("GIMBAL_SOURCE_DIR",
                        os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
MARKER = re.compile(r"^\s*<!-- example(?::\s*(.*?))?\s*-->\s*$")
FENCE = re.compile(r"^(\s*)```(\w[\w.-]*)?\s*$")
EXPECT = re.compile(r"^\s*# => (.*)$")
BLOCK_TIMEOUT_S = 30


def documents():
    return [os.path.join(SOURCE, "README.md")] + sorted(
        glob.glob(os.path.join(SOURCE, "docs", "*.md")))


def marked_blocks():
    """[(path, line, kind, language, text)] of every block under an example marker."""
    out = []
    for path in documents():
        with open(path) as f:
            lines = f.read().splitlines()
        i = 0
        while i < len(lines):
            m = MARKER.match(lines[i])
            if not m:
                i += 1
                continue
            kind = (m.group(1) or "").strip()
            fence = FENCE.match(lines[i + 1]) if i + 1 < len(lines) else None
            if not fence:
                raise AssertionError("%s:%d: an example marker not followed by a fenced block"
                                     % (path, i + 1))
            indent, language = fence.group(1), fence.group(2) or ""
            body = []
            j = i + 2
            while j < len(lines) and lines[j].strip() != "```":
                body.append(lines[j][len(indent):] if lines[j].startswith(indent) else lines[j])
                j += 1
            out.append((path, i + 2, kind, language, "\n".join(body) + "\n"))
            i = j + 1
    return out


def with_expectations(script):
    """A shell block where `# => TEXT` lines check the output of the command above them."""
    lines = script.splitlines()
    out = []
    i = 0
    while i < len(lines):
        line = lines[i]
        expected = []
        while i + 1 < len(lines) and EXPECT.match(lines[i + 1]):
            expected.append(EXPECT.match(lines[i + 1]).group(1))
            i += 1
        if not expected:
            out.append(line)
        else:
            out.append("__out=$( { %s ; } 2>&1 ) || true" % line)
            out.append('printf "%s\\n" "$__out"')
            for text in expected:
                quoted = "'" + text.replace("'", "'\\''") + "'"
                out.append('grep -qF -- %s <<<"$__out" || { echo "expected in the output of '
                           'the command above: "%s >&2; exit 1; }' % (quoted, quoted))
        i += 1
    return "\n".join(out) + "\n"


class Workspace:
    """A scratch directory with the programs under test where the examples expect them."""

    def __init__(self, root):
        self.root = root
        self.bin = os.path.join(root, "bin")
        os.makedirs(self.bin)
        real = {"gimbald": gt.GIMBALD, "gimbal-sim": gt.GIMBAL_SIM,
                "gimbal-replay": os.environ.get("GIMBAL_REPLAY"),
                "gimbal-export": os.environ.get("GIMBAL_EXPORT")}
        for name, path in real.items():
            if path:
                os.symlink(os.path.abspath(path), os.path.join(self.bin, name))
        # gimbalctl talks to the daemon of the block unless the example names a port itself.
        shim = os.path.join(self.bin, "gimbalctl")
        with open(shim, "w") as f:
            f.write('#!/bin/bash\n'
                    'for a in "$@"; do [ "$a" = --port ] && exec %s "$@"; done\n'
                    'exec %s --port "${GIMBALD_EXAMPLE_PORT:-8760}" "$@"\n'
                    % (os.path.abspath(gt.GIMBALCTL), os.path.abspath(gt.GIMBALCTL)))
        os.chmod(shim, 0o755)
        for sub, name in (("tools", "gimbalctl"), ("daemon", "gimbald"),
                          ("tools", "gimbal-sim")):
            d = os.path.join(root, "build", "release", sub)
            os.makedirs(d, exist_ok=True)
            os.symlink(os.path.join(self.bin, name), os.path.join(d, name))
        os.symlink(os.path.join(SOURCE, "config"), os.path.join(root, "config"))
        os.symlink(os.path.join(SOURCE, "dissectors"), os.path.join(root, "dissectors"))

    def env(self, port):
        env = dict(os.environ)
        env["PATH"] = self.bin + os.pathsep + env.get("PATH", "")
        if port:
            env["GIMBALD_EXAMPLE_PORT"] = str(port)
        return env


class DocExamples(gt.GimbaldTestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.blocks = marked_blocks()
        cls.ws = Workspace(os.path.join(cls.class_workdir, "ws"))
        cls.daemons = {}

    @classmethod
    def daemon_for(cls, kind):
        """(command port, http port) of the daemon a marker asks for, started once."""
        if kind not in cls.daemons:
            args = kind.split()
            http = gt.free_port(socket.SOCK_STREAM)
            with open(os.path.join(SOURCE, "config", "sim.json")) as f:
                config = json.load(f)
            config["http"]["port"] = http
            if "terrain" in config:
                # config/sim.json reads the DEM scripts/run-sim.sh writes: write it here.
                dem = os.path.join(cls.class_workdir, "sim-dem.tif")
                if not os.path.exists(dem):
                    r = gt.run([gt.GIMBAL_SIM, "--write-dem", dem])
                    if r.returncode != 0:
                        raise RuntimeError("gimbal-sim --write-dem: %s" % r.stderr)
                config["terrain"]["files"] = [dem]
            video_out = cls.free_video_ports(config)
            daemon = cls.start_class_daemon(config, ["--" + args[0]] + args[1:])
            c = daemon.client()

            def ready():
                for g in c.request("list")["gimbals"]:
                    state = c.request("state", gimbal=g["name"], timeout=0.5)["state"]
                    if not state["link"]["connected"] or \
                            (state["protocol"] == "orion" and not state.get("telemetry")):
                        return False
                return True
            ok = gt.wait_for(ready, gt.START_TIMEOUT_S)
            c.close()
            if not ok:
                raise RuntimeError("the %s daemon has no telemetry" % kind)
            cls.daemons[kind] = (daemon.port, http, video_out)
        return cls.daemons[kind]

    @staticmethod
    def free_video_ports(config):
        """Moves config/sim.json's video input and outputs to free ports (each daemon its
        own), returning the port of the output that stood at 15010 (None without one)."""
        replaced = None
        for g in config.get("gimbals", []):
            video = g.get("video")
            if not video:
                continue
            host = video["input"].split("//", 1)[1].rsplit(":", 1)[0]
            video["input"] = "udp://%s:%d" % (host, gt.free_port())
            outputs = []
            for url in video.get("outputs", []):
                scheme, rest = url.split("://", 1)
                host, port = rest.rsplit(":", 1)
                new_port = gt.free_port()
                if port == "15010":
                    replaced = new_port
                outputs.append("%s://%s:%d" % (scheme, host, new_port))
            video["outputs"] = outputs
        return replaced

    def run_block(self, path, line, kind, language, text):
        where = "%s:%d" % (os.path.relpath(path, SOURCE), line)
        port = http = None
        if kind.startswith("sim"):
            port, http, video_out = self.daemon_for(kind)
            text = text.replace("8760", str(port)).replace("8761", str(http))
            if video_out:
                text = text.replace("15010", str(video_out))
        elif kind not in ("", "config", "mosquitto.conf"):
            self.fail("%s: unknown example kind %r" % (where, kind))
        if kind == "mosquitto.conf":
            for n, conf_line in enumerate(text.splitlines()):
                directive = conf_line.split("#", 1)[0]
                self.assertFalse(directive.strip() and "#" in conf_line,
                                 "%s: mosquitto allows comments only on lines of their own: %r"
                                 % (where, conf_line))
            return
        if kind == "config":
            self.assertEqual(language, "json", where)
            config = os.path.join(self.ws.root, "example.json")
            with open(config, "w") as f:
                f.write(text)
            r = gt.run([gt.GIMBALD, "--check-config", "-c", config])
            self.assertEqual(r.returncode, 0, "%s: --check-config refused the example:\n%s%s"
                             % (where, r.stdout, r.stderr))
            return
        if language == "sh":
            cmd = ["bash", "-e", "-c", with_expectations(text)]
        elif language == "python":
            cmd = [sys.executable, "-c", text]
        else:
            self.fail("%s: examples run as sh or python, not %r" % (where, language))
        try:
            r = subprocess.run(cmd, cwd=self.ws.root, env=self.ws.env(port), capture_output=True,
                               text=True, timeout=BLOCK_TIMEOUT_S, stdin=subprocess.DEVNULL)
        except subprocess.TimeoutExpired as e:
            self.fail("%s: the example ran over %d s:\n%s\n--- output\n%s"
                      % (where, BLOCK_TIMEOUT_S, text, e.stdout))
        self.assertEqual(r.returncode, 0, "%s: the example failed (exit %d):\n%s\n--- stdout\n%s"
                         "--- stderr\n%s" % (where, r.returncode, text, r.stdout, r.stderr))
        self.assertNotIn("Traceback", r.stderr, where)

    def test_marked_examples_run(self):
        # Markers must not vanish unnoticed: README and several docs carry them.
        files = {os.path.basename(b[0]) for b in self.blocks}
        self.assertGreaterEqual(len(self.blocks), 12, files)
        for name in ("README.md", "gimbalctl.md", "http.md", "json-api.md",
                     "configuration.md", "console.md", "fleet.md"):
            self.assertIn(name, files)
        for block in self.blocks:
            with self.subTest(example="%s:%d" % (os.path.basename(block[0]), block[1])):
                self.run_block(*block)

    def test_wireshark_field_names_exist(self):
        tshark = shutil.which("tshark")
        if not tshark:
            skipping.need(self, "tshark not installed")
        import pcapng_test_writer as pw
        empty = os.path.join(self.workdir, "empty.pcapng")
        pw.PcapngWriter(empty, [("gimbal:a", "orion a")]).close()
        with open(os.path.join(SOURCE, "docs", "wireshark.md")) as f:
            text = f.read()
        filters = set()
        for code in re.findall(r"`([^`\n]+)`", text):
            code = code.replace("-Y ", "")
            if re.match(r"^(orion|viewpro|gimbald_json|mavlink)\.[a-z0-9_.]+( |$)", code) \
                    and "<" not in code:
                filters.add(code)
        self.assertGreater(len(filters), 10)
        lua = os.path.join(SOURCE, "dissectors", "gimbald.lua")
        for expr in sorted(filters):
            with self.subTest(filter=expr):
                r = gt.run([tshark, "-X", "lua_script:" + lua, "-r", empty, "-Y", expr])
                self.assertEqual(r.returncode, 0, "%s: %s" % (expr, r.stderr.strip()))


if __name__ == "__main__":
    gt.main()
