#!/usr/bin/env python3
"""The MAVLink gimbal manager under the hardening of contract section 14 (issue 17): garbage
datagrams cannot hold the next command, `command.auth: "signed"` covers MAVLink, a signed frame
captured before a restart stays a replay after it, `mavlink.home_alt_msl`, and every refused
command logged as `mavlink_refused`. The MAVLink side is tests/integration/mavlinktest.py,
written from common.xml, not the product's codec.
"""

import json
import os
import signal
import struct
import subprocess
import time

import gimbaltest as gt
import mavlinktest as mt

PITCHYAW = mt.MAV_CMD_DO_GIMBAL_MANAGER_PITCHYAW
CONFIGURE = mt.MAV_CMD_DO_GIMBAL_MANAGER_CONFIGURE
ACCEPTED, TEMPORARILY_REJECTED, DENIED = 0, 1, 2


def manager_config(vehicle_port, **mavlink):
    return {"vehicle": {"source": {"type": "udp", "bind": "127.0.0.1", "port": vehicle_port}},
            "mavlink": dict({"gimbal_manager": True, "system_id": 1}, **mavlink)}


def write_key(workdir, name, data):
    path = os.path.join(workdir, name)
    with open(path, "wb") as f:
        f.write(data)
    os.chmod(path, 0o600)
    return path


class GarbageDatagrams(gt.GimbaldTestCase):
    def test_garbage_of_every_shape_never_holds_the_next_command(self):
        port = gt.free_port()
        daemon = self.start_daemon(manager_config(port), args=["--sim"])
        self.wait_connected(self.client(daemon))
        gcs = mt.Peer(port)
        self.addCleanup(gcs.close)

        good = lambda pan: mt.command_long(PITCHYAW, [-10, pan, mt.NAN, mt.NAN, 0, 0, 1])
        valid_other = mt.frame(0, struct.pack("<IBBBBB", 0, 6, 8, 0, 4, 3), 255, 190)
        bad_crc = bytearray(mt.frame(76, good(5.0), 255, 190, 9))
        bad_crc[-1] ^= 0xFF
        garbage = [
            ("truncated header", b"\xfd\x20\x00"),
            ("plausible header of an unknown id, length 255, signed flag",
             bytes([0xFD, 0xFF, 0x01, 0, 7, 1, 1, 0x39, 0x30, 0x00]) + b"\x55" * 20),
            ("plausible v1 header of an unknown id, length 255",
             bytes([0xFE, 0xFF, 7, 1, 1, 0xC8]) + b"\x11" * 10),
            ("COMMAND_LONG header whose length reaches past the datagram",
             bytes([0xFD, 0x21, 0, 0, 7, 0xFF, 0xBE, 0x4C, 0, 0]) + b"\x00" * 5),
            ("valid frame + junk", valid_other + bytes([0xFD, 0xF0, 0x00, 0, 0, 1, 1, 0x77, 0x77])),
            ("junk + valid frame", b"\x01\xfd\x05" + valid_other),
            ("bad CRC", bytes(bad_crc)),
            ("signed-flag garbage", bytes([0xFD, 0x40, 0x01, 0, 0, 1, 1, 0x77, 0x77, 7, 1])),
            ("310 bytes of noise", bytes((i * 37 + 11) & 255 for i in range(310))),
        ]
        for n, (what, junk) in enumerate(garbage):
            with self.subTest(what):
                since = time.monotonic()
                gcs.send_raw(junk)
                pan = 10.0 + n
                gcs.send(76, good(pan))  # immediately behind the garbage
                self.assertEqual(gcs.ack(PITCHYAW, timeout=1.5, since=since), ACCEPTED,
                                 "no COMMAND_ACK for the command after: %s" % what)
        # The bad CRC frame itself moved nothing: one command line per good frame only.
        def commands():
            return [e for e in daemon.logs() if e.get("event") == "command" and
                    e.get("transport") == "mavlink"]
        self.assertTrue(gt.wait_for(lambda: len(commands()) >= len(garbage), 2.0))
        time.sleep(0.3)
        self.assertEqual(len(commands()), len(garbage))


HEARTBEAT = struct.pack("<IBBBBB", 0, 6, 8, 0, 4, 3)  # a ground station's (MAV_TYPE_GCS)


class PeerSlots(gt.GimbaldTestCase):
    """Contract section 14 (v4): only a peer whose frame passed the endpoint's checks takes one
    of the 16 peer slots; 20 junk senders once evicted the ground station (issue 25)."""

    def start(self, **mavlink):
        self.port = gt.free_port()
        daemon = self.start_daemon(manager_config(self.port, **mavlink), args=["--sim"])
        self.wait_connected(self.client(daemon))
        return daemon

    def junk_senders(self, count, datagrams):
        """`count` senders, each on its own port, each sending every one of `datagrams`."""
        senders = []
        for _ in range(count):
            junk = mt.Peer(self.port, sysid=77)
            self.addCleanup(junk.close)
            for d in datagrams(junk):
                junk.send_raw(d)
            senders.append(junk)
        return senders

    def assert_still_served(self, daemon, gcs, senders):
        time.sleep(0.5)  # every junk datagram handled
        since = time.monotonic()
        self.assertTrue(gcs.wait(lambda m: m[3] == 285, 2.0, since),
                        "the ground station got no GIMBAL_DEVICE_ATTITUDE_STATUS after the junk")
        peers = self.client(daemon).request("state")["state"]["mavlink"]["peers"]
        self.assertEqual(peers, ["udp 127.0.0.1:%d" % gcs.sock.getsockname()[1]])
        for junk in senders:
            junk.pump(0.0)
            self.assertEqual(junk.received, [], "a junk sender was sent streams")

    def test_unsigned_and_forged_frames_take_no_slot_under_signing(self):
        key = os.urandom(32)
        daemon = self.start(signing_key_file=write_key(self.workdir, "m.key", key.hex().encode()))
        gcs = mt.Peer(self.port, key=key)
        self.addCleanup(gcs.close)
        captured = gcs.send(0, HEARTBEAT)
        self.assertTrue(gcs.wait(lambda m: m[3] == 285, 3.0), "the signed GCS got no streams")
        other_key = os.urandom(32)
        senders = self.junk_senders(20, lambda junk: [
            b"\xfd\x09\x00" + os.urandom(20),                     # garbage
            mt.frame(0, HEARTBEAT, 77, 190, 1),                     # valid but unsigned
            mt.frame(0, HEARTBEAT, 77, 190, 2, key=other_key),      # signed with another key
            captured,                                               # a replay from elsewhere
        ])
        self.assert_still_served(daemon, gcs, senders)

    def test_junk_takes_no_slot_and_a_real_peer_still_does(self):
        daemon = self.start()
        gcs = mt.Peer(self.port)
        self.addCleanup(gcs.close)
        gcs.send(0, HEARTBEAT)
        self.assertTrue(gcs.wait(lambda m: m[3] == 285, 3.0), "the GCS got no streams")
        bad_crc = bytearray(mt.frame(0, HEARTBEAT, 77, 190))
        bad_crc[-1] ^= 0xFF
        senders = self.junk_senders(20, lambda junk: [
            os.urandom(40), bytes(bad_crc), b"\xfd\xff\x00\x00\x00\x4d\xbe"])
        self.assert_still_served(daemon, gcs, senders)
        # Without signing any frame that parses is a peer: a second ground station joins.
        second = mt.Peer(self.port, sysid=254)
        self.addCleanup(second.close)
        second.send(0, HEARTBEAT)
        self.assertTrue(second.wait(lambda m: m[3] == 285, 3.0), "a real second GCS got nothing")


class OneCameraEach(gt.GimbaldTestCase):
    """Contract v4 (section 8): a manager whose gimbal has a camera component does not answer
    CAMERA_INFORMATION; MAVSDK's Camera plugin listed [154, 100] for one gimbal."""

    def test_only_the_camera_component_answers_camera_information(self):
        port = gt.free_port()
        daemon = self.start_daemon(manager_config(port), args=["--sim"])
        self.wait_connected(self.client(daemon))
        gcs = mt.Peer(port)
        self.addCleanup(gcs.close)
        gcs.send(0, HEARTBEAT)
        time.sleep(1.0)  # the simulated Orion's CAMERAS packet

        def camera_information(component):
            since = time.monotonic()
            result = gcs.command(mt.MAV_CMD_REQUEST_MESSAGE, [259, 0], target_component=component)
            gcs.pump(0.5)  # the messages follow the ACK
            infos = [m for m in gcs.received if m[0] >= since and m[3] == 259]
            return result, infos

        for component in (154, 0):  # the gimbal's manager, and every component
            with self.subTest(component=component):
                result, infos = camera_information(component)
                self.assertEqual(result, DENIED)
                self.assertEqual(infos, [], "a gimbal manager answered CAMERA_INFORMATION")
        refused = daemon.wait_log(lambda e: e.get("event") == "mavlink_refused" and
                                  e.get("command") == mt.MAV_CMD_REQUEST_MESSAGE)
        self.assertIn("camera component: 100 (sim)", refused["msg"])
        # The camera itself answers, once, from its own component.
        result, infos = camera_information(100)
        self.assertEqual(result, ACCEPTED)
        self.assertEqual([m[2] for m in infos], [100])
        # The manager's own information is still its own.
        self.assertEqual(gcs.command(mt.MAV_CMD_REQUEST_MESSAGE, [280, 0]), ACCEPTED)


class SignedAuthCoversMavlink(gt.GimbaldTestCase):
    def signed_config(self, port, **mavlink):
        key = write_key(self.workdir, "ops.key", os.urandom(32).hex().encode())
        config = manager_config(port, **mavlink)
        config["command"] = {"auth": "signed", "keys": [
            {"id": "ops", "secret_file": key, "roles": ["observe", "control"]}]}
        return config

    def run_gimbald(self, config, *args):
        path = os.path.join(self.workdir, "auth.json")
        with open(path, "w") as f:
            json.dump(config, f)
        return subprocess.run([gt.GIMBALD, "-c", path, "--sim", *args], capture_output=True,
                              text=True, timeout=20, stdin=subprocess.DEVNULL)

    def test_unsigned_mavlink_commands_are_refused_at_start(self):
        config = self.signed_config(gt.free_port())
        for args in (["--check-config"], []):
            proc = self.run_gimbald(config, *args)
            text = proc.stdout + proc.stderr
            self.assertEqual(proc.returncode, 1, text)
            self.assertIn("mavlink.signing_key_file", text)
            self.assertIn("command.auth", text)
            self.assertIn("mavlink.commands", text)

    def test_commands_false_only_reports(self):
        port = gt.free_port()
        config = self.signed_config(port, commands=False)
        self.assertEqual(self.run_gimbald(config, "--check-config").returncode, 0)
        daemon = self.start_daemon(config, args=["--sim"])
        gcs = mt.Peer(port)
        self.addCleanup(gcs.close)
        self.assertTrue(gt.wait_for(lambda: daemon.events("start"), 5.0))
        time.sleep(1.0)  # the simulated Orion's first telemetry
        self.assertEqual(gcs.command(PITCHYAW, [-10, 20, mt.NAN, mt.NAN, 0, 0, 1]), DENIED)
        self.assertEqual(gcs.command(CONFIGURE, [-2, -2, -1, -1, 0, 0, 0]), DENIED)
        # Section 14: every command is DENIED, REQUEST_MESSAGE too; the streams still report.
        self.assertEqual(gcs.command(mt.MAV_CMD_REQUEST_MESSAGE, [280, 0]), DENIED)
        since = time.monotonic()
        self.assertTrue(gcs.wait(lambda m: m[3] == 285, 2.0, since))  # ATTITUDE_STATUS
        refused = daemon.wait_log(lambda e: e.get("event") == "mavlink_refused")
        self.assertTrue(refused)
        self.assertEqual(refused["level"], "info")
        self.assertEqual(refused["result"], "MAV_RESULT_DENIED")
        self.assertIn("mavlink.commands", refused["msg"])
        self.assertFalse([e for e in daemon.logs() if e.get("event") == "command" and
                          e.get("transport") == "mavlink"], "a MAVLink command reached a gimbal")


class SigningStreamsSurviveRestarts(gt.GimbaldTestCase):
    def setUp(self):
        super().setUp()
        self.key = os.urandom(32)
        self.key_file = write_key(self.workdir, "mavlink.key", self.key.hex().encode())
        self.port = gt.free_port()

    def config(self, **mavlink):
        return manager_config(self.port, signing_key_file=self.key_file, **mavlink)

    def accepted_then_replayed(self, config, restart_signal, env=None):
        """Sends a signed CONFIGURE (accepted), restarts gimbald, replays the captured frame.
        Returns (result of the replay, daemon after the restart)."""
        old_env = os.environ.copy()
        if env:
            os.environ.update(env)
        try:
            daemon = self.start_daemon(config, args=["--sim"])
            gcs = mt.Peer(self.port, key=self.key)
            self.addCleanup(gcs.close)
            time.sleep(0.5)
            since = time.monotonic()
            captured = gcs.send(76, mt.command_long(CONFIGURE, [-2, -2, -1, -1, 0, 0, 0]))
            self.assertEqual(gcs.ack(CONFIGURE, since=since), ACCEPTED)
            if restart_signal == signal.SIGKILL:
                time.sleep(1.5)  # saved within a second of the change
            self.assertEqual(daemon.stop(restart_signal),
                             0 if restart_signal == signal.SIGTERM else -signal.SIGKILL)
            after = self.start_daemon(config, args=["--sim"])
            time.sleep(0.5)
        finally:
            os.environ.clear()
            os.environ.update(old_env)
        since = time.monotonic()
        gcs.send_raw(captured)
        replay = gcs.ack(CONFIGURE, timeout=1.5, since=since)
        # A fresh frame of the same stream is fine.
        fresh = gcs.command(CONFIGURE, [-3, -3, -1, -1, 0, 0, 0])
        self.assertEqual(fresh, ACCEPTED)
        return replay, after

    def test_replay_after_a_restart_is_ignored(self):
        state_file = os.path.join(self.workdir, "signing.json")
        replay, after = self.accepted_then_replayed(self.config(signing_state_file=state_file),
                                                    signal.SIGTERM)
        self.assertIsNone(replay, "the captured frame was accepted after the restart")
        state = self.client(after).request("state")["state"]["mavlink"]
        self.assertGreaterEqual(state["unsigned_ignored"], 1)
        with open(state_file) as f:
            saved = json.load(f)
        self.assertEqual([(s["sysid"], s["compid"], s["link_id"]) for s in saved["streams"]],
                         [(255, 190, 0)])
        self.assertEqual(os.stat(state_file).st_mode & 0o777, 0o600)

    def test_state_directory_and_kill(self):
        # systemd's StateDirectory=gimbald gimbald/recordings: the first one holds the file.
        first = os.path.join(self.workdir, "state")
        second = os.path.join(self.workdir, "state-recordings")
        os.mkdir(first)
        os.mkdir(second)
        replay, _ = self.accepted_then_replayed(self.config(), signal.SIGKILL,
                                                env={"STATE_DIRECTORY": first + ":" + second})
        self.assertIsNone(replay, "the captured frame was accepted after kill -9 and a restart")
        self.assertTrue(os.path.exists(os.path.join(first, "mavlink-signing.json")))

    def test_without_a_place_to_keep_them_it_says_so(self):
        saved = os.environ.pop("STATE_DIRECTORY", None)
        try:
            daemon = self.start_daemon(self.config(), args=["--sim"])
        finally:
            if saved is not None:
                os.environ["STATE_DIRECTORY"] = saved
        warning = daemon.wait_log(lambda e: e.get("event") == "mavlink_signing_state")
        self.assertTrue(warning)
        self.assertEqual(warning["level"], "warn")


class HomeAltitudeAndRefusals(gt.GimbaldTestCase):
    def roi(self, gcs, relative_alt):
        # COMMAND_INT DO_SET_ROI_LOCATION, frame GLOBAL_RELATIVE_ALT_INT (6), as MAVSDK sends.
        since = time.monotonic()
        gcs.send(75, mt.command_int(mt.MAV_CMD_DO_SET_ROI_LOCATION, [1, 0, 0, 0], 457189827,
                                    -1214993263, relative_alt, 6))
        return gcs.ack(mt.MAV_CMD_DO_SET_ROI_LOCATION, since=since)

    def start(self, **mavlink):
        port = gt.free_port()
        self.sim = self.start_sim("--geoid-undulation", "-20")
        config = manager_config(port, **mavlink)
        config["gimbals"] = [gt.orion_tcp("main", self.sim.port)]
        daemon = self.start_daemon(config)
        self.wait_connected(self.client(daemon))
        gcs = mt.Peer(port)
        self.addCleanup(gcs.close)
        return daemon, gcs

    def test_home_alt_msl_without_an_autopilot(self):
        daemon, gcs = self.start(home_alt_msl=400.0)
        self.assertEqual(self.roi(gcs, 20.0), ACCEPTED)
        # 400 m home + 20 m = 420 m MSL = 400 m above the ellipsoid (undulation -20 m).
        cmd = self.sim.wait_rx(gt.by_name("geopoint_cmd"))
        self.assertTrue(cmd, "no GeopointCmd reached the gimbal")
        self.assertAlmostEqual(cmd["packet"]["alt"], 400.0, places=1)
        self.assertAlmostEqual(cmd["packet"]["lat"], 45.7189827, places=5)

    def test_without_a_home_every_refusal_is_logged_with_its_reason(self):
        daemon, gcs = self.start()
        self.assertEqual(self.roi(gcs, 20.0), TEMPORARILY_REJECTED)
        line = daemon.wait_log(lambda e: e.get("event") == "mavlink_refused")
        self.assertTrue(line)
        self.assertEqual(line["level"], "info")
        self.assertEqual(line["result"], "MAV_RESULT_TEMPORARILY_REJECTED")
        self.assertEqual(line["command"], mt.MAV_CMD_DO_SET_ROI_LOCATION)
        self.assertIn("home altitude", line["msg"])
        self.assertEqual(line["src"], "mavlink:255/190")
        # DENIED (control) and a refusal from the gimbal's request path (out of range).
        other = mt.Peer(gcs.address[1], sysid=254)
        self.addCleanup(other.close)
        self.assertEqual(gcs.command(CONFIGURE, [-2, -2, -1, -1, 0, 0, 0]), ACCEPTED)
        self.assertEqual(other.command(PITCHYAW, [-10, 0, mt.NAN, mt.NAN, 0, 0, 1]), DENIED)
        self.assertEqual(gcs.command(PITCHYAW, [-10, 250, mt.NAN, mt.NAN, 0, 0, 1]), DENIED)
        self.assertTrue(gt.wait_for(lambda: len(daemon.events("mavlink_refused")) >= 3, 2.0))
        lines = daemon.events("mavlink_refused")
        self.assertIn("another system is in control", lines[1]["msg"])
        self.assertEqual(lines[1]["src"], "mavlink:254/190")
        self.assertIn("out_of_range", lines[2]["msg"])
        self.assertTrue(all(l["result"] == "MAV_RESULT_DENIED" for l in lines[1:]))


if __name__ == "__main__":
    gt.main()
