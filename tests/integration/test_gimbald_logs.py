#!/usr/bin/env python3
"""Logs no request can forge, and logs the journal can filter (contract section 14).

- Repeated lines of one event and source are rolled up (section 14, v4): a flood of refused
  MAVLink commands writes about ten `mavlink_refused` lines a second and `suppressed` counts,
  while every `command` and `audit` line is written.
- `log.format: "text"` escapes control characters in every value and the message: the issue's
  request `{"cmd":"nosuch\\n2026-... WARN audit ... fire=true: ok"}` must not start a line.
- When standard output is the systemd journal (JOURNAL_STREAM names it), every record goes to
  journald natively: its level as the priority, its simple keys as fields. Tested against a
  real systemd-journald, run in a private mount namespace (tmpfs over /run and /var/log) so
  the machine's own journal is not touched: needs root and unshare(1); skipped otherwise.
  gimbald's standard output is a stream connection to that journald, set up as systemd does
  for a service (the stdout protocol's header, JOURNAL_STREAM = the socket's device:inode).
"""

import json
import os
import shutil
import signal
import socket
import subprocess
import time

import gimbaltest as gt
import mavlinktest as mt
import skipping

JOURNALD = "/lib/systemd/systemd-journald"
SIM = {"gimbals": [{"name": "s", "protocol": "orion", "link": {"type": "sim"}}]}
FIRE = {"enable": True, "arm": True, "fire": True}


class TextLogs(gt.GimbaldTestCase):
    def test_a_request_cannot_forge_a_line(self):
        daemon = self.start_daemon(dict(SIM, log={"format": "text"}), wait_started=False)
        c = self.client(daemon)
        self.assertTrue(gt.wait_for(lambda: c.request("ping", timeout=0.3), gt.START_TIMEOUT_S))
        forged = "2026-11-21 06:41:50.123 WARN  audit src=10.0.0.1:1 cmd=laser fire=true: ok"
        c.send({"cmd": "nosuch\n" + forged, "id": 1})
        reply = c.reply_to(1)
        self.assertEqual(reply["error"]["code"], "unknown_cmd")
        c.send({"cmd": "ping", "id": "a\r\x1b[2Kb\x7f\u0085c\nd"})
        self.assertOk(c.reply_to("a\r\x1b[2Kb\x7f\u0085c\nd"))

        def logged():
            with open(daemon.stdout_path, "rb") as f:
                text = f.read()
            return text if text.count(b" command ") >= 2 else None
        text = gt.wait_for(logged, gt.REPLY_TIMEOUT_S)
        self.assertTrue(text, "no command lines")
        lines = text.split(b"\n")
        self.assertEqual(lines[-1], b"")
        for line in lines[:-1]:
            # Every line is one of the daemon's: its own time stamp and level first.
            self.assertRegex(line.decode(), r"^\d{4}-\d\d-\d\d \d\d:\d\d:\d\d\.\d{3} "
                                            r"(TRACE|DEBUG|INFO |WARN |ERROR) \S")
            self.assertFalse(line.startswith(forged[:23].encode()), line)
            for byte in line:
                self.assertTrue(byte >= 0x20 and byte != 0x7F, line)
            self.assertNotIn(b"\xc2\x85", line)
        # The `command` line and the `audit` line (an unknown command is audited): each
        # holds the forged text, escaped, inside its own line.
        mentions = [line for line in lines if b"nosuch" in line]
        self.assertEqual(len(mentions), 2, lines)
        for line in mentions:
            self.assertIn(b"nosuch\\n2026-11-21 06:41:50.123 WARN  audit", line)


def iso_seconds(ts):
    """Seconds of the day of a log line's `ts` (ISO UTC with microseconds)."""
    clock = ts[11:-1]
    h, m, sec = clock.split(":")
    return int(h) * 3600 + int(m) * 60 + float(sec)


class RolledUp(gt.GimbaldTestCase):
    def test_a_flood_of_refused_mavlink_commands(self):
        port = gt.free_port()
        daemon = self.start_daemon(
            {"vehicle": {"source": {"type": "udp", "bind": "127.0.0.1", "port": port}},
             "mavlink": {"gimbal_manager": True, "system_id": 1}}, args=["--sim"])
        self.wait_connected(self.client(daemon))
        gcs = mt.Peer(port)
        self.addCleanup(gcs.close)
        # Pan 250 is out of range: DENIED by the request path, a `mavlink_refused` line, a
        # `command` line and an `audit` line each. Bursts of 50, each answered, for ~3 s.
        pitchyaw = mt.command_long(mt.MAV_CMD_DO_GIMBAL_MANAGER_PITCHYAW,
                                   [-10, 250, mt.NAN, mt.NAN, 0, 0, 1])
        def acks():
            return [r for r in gcs.received if r[3] == 77]
        begin = time.monotonic()
        sent = 0
        while time.monotonic() - begin < 3.0:
            for _ in range(50):
                gcs.send(76, pitchyaw)
            sent += 50
            deadline = time.monotonic() + 2.0
            while len(acks()) < sent and time.monotonic() < deadline:
                gcs.pump(0.05)
        gcs.pump(0.3)
        acks = acks()
        self.assertGreater(len(acks), 300, "the flood was too small to test anything")
        self.assertTrue(all(mt.ack_of(r[4])[1] != 0 for r in acks))
        self.assertEqual(daemon.stop(), 0)  # at the stop, every count still owed is written

        logs = daemon.logs()
        refused = [e for e in logs if e.get("event") == "mavlink_refused"]
        written = [e for e in refused if "suppressed" not in e]
        summaries = [e for e in refused if "suppressed" in e]
        duration = iso_seconds(refused[-1]["ts"]) - iso_seconds(refused[0]["ts"])
        print("%d refused commands in %.1f s: %d mavlink_refused lines written, %d summaries "
              "(%s suppressed)" % (len(acks), duration, len(written), len(summaries),
                                   [e["suppressed"] for e in summaries]))
        # At most ten a second (twenty in any one-second span across two windows)...
        times = [iso_seconds(e["ts"]) for e in written]
        for i, t in enumerate(times):
            self.assertLessEqual(len([u for u in times[i:] if u < t + 1.0]), 20)
        self.assertLessEqual(len(written), 10 * (duration + 2))
        # ...and the rest counted: nothing lost without a word.
        self.assertTrue(summaries, "no line says how many were rolled up")
        self.assertEqual(len(written) + sum(e["suppressed"] for e in summaries), len(acks))
        self.assertTrue(all(e["src"] == "mavlink:255/190" for e in summaries))
        # Every command and audit line is there.
        commands = [e for e in logs if e.get("event") == "command" and
                    e.get("transport") == "mavlink"]
        audits = [e for e in logs if e.get("event") == "audit" and
                  e.get("transport") == "mavlink"]
        self.assertEqual(len(commands), len(acks))
        self.assertEqual(len(audits), len(acks))


def run_in(namespace_pid, args, **kwargs):
    return subprocess.run(["nsenter", "-t", str(namespace_pid), "-m", *args],
                          capture_output=True, text=True, timeout=20, **kwargs)


class Journal(gt.GimbaldTestCase):
    def setUp(self):
        super().setUp()
        if os.geteuid() != 0 or not shutil.which("unshare") or not shutil.which("nsenter"):
            self.skipTest("a private journald needs root, unshare and nsenter")
        if not os.path.exists(JOURNALD) or not shutil.which("journalctl"):
            skipping.need(self, "systemd-journald or journalctl not installed")
        # A mount namespace of our own: its /run and /var/log are empty tmpfs.
        self.holder = subprocess.Popen(
            ["unshare", "-m", "--propagation", "private", "sh", "-c",
             "mount -t tmpfs tmpfs /run && mount -t tmpfs tmpfs /var/log && echo ready && "
             "exec sleep 600"], stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        self.addCleanup(self.holder.stderr.close)
        self.addCleanup(self.holder.stdout.close)
        self.addCleanup(gt.stop_process, self.holder, signal.SIGKILL)
        ready = gt.read_line(self.holder.stdout, gt.START_TIMEOUT_S)
        if ready.strip() != "ready":
            self.skipTest("cannot make a private mount namespace here: " +
                          self.holder.stderr.read1(2000).decode(errors="replace"))
        self.root = "/proc/%d/root" % self.holder.pid

    def in_namespace(self, path):
        return self.root + path

    def start_journald(self):
        journald = subprocess.Popen(["nsenter", "-t", str(self.holder.pid), "-m", JOURNALD],
                                    stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        self.addCleanup(gt.stop_process, journald)
        sockets = [self.in_namespace("/run/systemd/journal/" + n) for n in ("socket", "stdout")]
        if not gt.wait_for(lambda: all(os.path.exists(s) for s in sockets), 5.0):
            self.skipTest("systemd-journald did not start in the namespace")
        return journald

    def journal_stream(self):
        """A connection to journald's stdout socket with the stream header sent, as systemd
        makes one for a service's standard output."""
        s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        s.connect(self.in_namespace("/run/systemd/journal/stdout"))
        # identifier, unit id, priority, level prefix, to syslog, to kmsg, to console
        s.sendall(b"gimbald\n\n6\n0\n0\n0\n0\n")
        st = os.fstat(s.fileno())
        return s, "%d:%d" % (st.st_dev, st.st_ino)

    def start_gimbald(self, stdout, journal_stream, config):
        port = gt.free_port()
        config = dict(config, command={"port": port})
        path = os.path.join(self.workdir, "gimbald.json")
        with open(path, "w") as f:
            json.dump(config, f)
        env = dict(os.environ, JOURNAL_STREAM=journal_stream)
        proc = subprocess.Popen(["nsenter", "-t", str(self.holder.pid), "-m", gt.GIMBALD,
                                 "-c", path], stdout=stdout, stderr=subprocess.PIPE,
                                stdin=subprocess.DEVNULL, env=env)
        self.addCleanup(gt.stop_process, proc)
        c = self.client(port)
        self.assertTrue(gt.wait_for(lambda: c.request("ping", timeout=0.3), gt.START_TIMEOUT_S),
                        "gimbald did not answer")
        return proc, c

    def journal(self, *args):
        r = run_in(self.holder.pid, ["journalctl", "--no-pager", "-o", "json", *args])
        self.assertEqual(r.returncode, 0, r.stderr)
        return [json.loads(line) for line in r.stdout.splitlines() if line.strip()]

    def test_levels_are_priorities_and_keys_are_fields(self):
        self.start_journald()
        stream, journal_stream = self.journal_stream()
        self.addCleanup(stream.close)
        proc, c = self.start_gimbald(stream, journal_stream,
                                     dict(SIM, laser={"allow_fire": True, "fire_timeout_s": 30}))
        stream.close()  # gimbald holds its own copy
        self.assertOk(c.request("laser", index=0, on_ms=100, off_ms=900, **FIRE))
        self.assertOk(c.request("laser", index=0, enable=False, arm=False, fire=False))
        pid = "_PID=%d" % proc.pid

        def fired():
            return self.journal(pid, "EVENT=laser_fire")
        entries = gt.wait_for(fired, 5.0)
        self.assertEqual(len(entries), 1, entries)
        fire = entries[0]
        self.assertEqual(fire["PRIORITY"], "4")
        self.assertEqual(fire["_TRANSPORT"], "journal")  # sent natively, not as stdout text
        self.assertEqual(fire["GIMBAL"], "s")
        self.assertEqual(fire["INDEX"], "0")
        self.assertEqual(fire["SYSLOG_IDENTIFIER"], "gimbald")
        self.assertTrue(fire["SRC"].startswith("127.0.0.1:"))
        message = json.loads(fire["MESSAGE"])  # the JSON line itself
        self.assertEqual(message["event"], "laser_fire")
        self.assertEqual(message["level"], "warn")

        everything = self.journal(pid)
        self.assertGreater(len(everything), 5)
        levels = {"error": "3", "warn": "4", "info": "6", "debug": "7", "trace": "7"}
        for e in everything:
            self.assertEqual(e["_TRANSPORT"], "journal", e)
            line = json.loads(e["MESSAGE"])
            self.assertEqual(e["PRIORITY"], levels[line["level"]], e)
            self.assertEqual(e["EVENT"], line["event"])
        start = [e for e in everything if e["EVENT"] == "start"]
        self.assertEqual(len(start), 1)
        self.assertEqual(start[0]["PRIORITY"], "6")
        # -p warning: the fire (audit and laser_fire), no info lines.
        warnings = self.journal(pid, "-p", "warning")
        events = sorted(e["EVENT"] for e in warnings)
        self.assertEqual(events, ["audit", "laser_fire"], events)
        audit = [e for e in warnings if e["EVENT"] == "audit"][0]
        self.assertEqual((audit["CMD"], audit["FIRE"], audit["OK"]), ("laser", "true", "true"))
        self.assertEqual(gt.stop_process(proc), 0)

    def test_without_journald_the_lines_go_to_standard_output(self):
        # JOURNAL_STREAM names standard output, but no journald listens: nothing is lost.
        out_path = os.path.join(self.workdir, "stdout")
        with open(out_path, "wb") as out:
            st = os.fstat(out.fileno())
            proc, c = self.start_gimbald(out, "%d:%d" % (st.st_dev, st.st_ino), SIM)
            self.assertOk(c.request("ping", id=77))
            self.assertEqual(gt.stop_process(proc), 0)
        lines = gt.read_json_lines(out_path)
        self.assertTrue([e for e in lines if e.get("event") == "start"], lines)
        self.assertTrue([e for e in lines if e.get("event") == "command" and e.get("id") == 77])
        self.assertTrue([e for e in lines if e.get("event") == "stop"])


if __name__ == "__main__":
    gt.main()
