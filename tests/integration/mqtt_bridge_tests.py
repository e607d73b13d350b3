#!/usr/bin/python3
"""The MQTT bridge (contract section 9) against a real mosquitto: retained status/state/link
topics, events, last will and clean-stop offline, commands with MQTT 5 response topic and
correlation data, commands off, broker loss, TLS and password login. Run by
test_gimbald_mqtt.sh under /usr/bin/python3 (paho-mqtt)."""

import json
import os
import signal
import socket
import threading
import time

import deltatest as dt
import gimbaltest as gt
import mqtttest as mt

P = "gimbald/st1"


class MqttCase(gt.GimbaldTestCase):
    def broker(self, **kwargs):
        b = mt.Broker(self.workdir, **kwargs)
        self.addCleanup(b.stop)
        return b

    def sub(self, broker, *topics, **kwargs):
        s = mt.Sub(broker, topics, **kwargs)
        self.addCleanup(s.close)
        return s

    def mqtt_daemon(self, broker, gimbals=None, **mqtt):
        section = {"url": broker.url(), "station": "st1"}
        section.update(mqtt)
        config = {"mqtt": section}
        args = ()
        if gimbals:
            config["gimbals"] = gimbals
        else:
            args = ("--sim",)
        return self.start_daemon(config, args)

    def wait_mqtt_up(self, daemon):
        self.assertTrue(daemon.wait_log(lambda e: e.get("event") == "mqtt_up", 5.0),
                        "no mqtt_up: " + daemon.log_text()[-2000:])


class Topics(MqttCase):
    def test_retained_topics_events_and_link_flap(self):
        broker = self.broker()
        sim = self.start_sim()
        port = sim.port
        daemon = self.mqtt_daemon(broker, [gt.orion_tcp("main", port, reconnect_min_s=0.2,
                                                        reconnect_max_s=0.5)],
                                  state_rate_hz=10, state_keys=["telemetry"])
        self.wait_mqtt_up(daemon)
        self.wait_connected(self.client(daemon))
        time.sleep(0.5)
        # A subscriber arriving late still gets status, state and link (retained).
        late = self.sub(broker, P + "/#")
        _, status = late.wait(P + "/status")
        self.assertEqual(status["online"], True)
        self.assertEqual(status["gimbals"], ["main"])
        self.assertIn("version", status)
        state_msg = late.wait(P + "/main/state", lambda s: s.get("telemetry"))
        self.assertTrue(state_msg, "no retained STATE with telemetry")
        state = state_msg[1]
        self.assertTrue(state_msg[0].retain)
        # state_keys: only telemetry beside the always-kept keys.
        self.assertEqual(set(state), {"protocol", "link", "stale", "telemetry"})
        link = late.wait(P + "/main/link")
        self.assertEqual(link[1], {"connected": True})
        self.assertTrue(link[0].retain)
        # STATE at about state_rate_hz.
        n = len(late.all(P + "/main/state"))
        time.sleep(1.0)
        rate = len(late.all(P + "/main/state")) - n
        self.assertTrue(5 <= rate <= 15, "STATE rate %d/s, want about 10" % rate)

        # The gimbal vanishes: link retained false, link event; it returns: true again.
        sim.kill()
        self.assertTrue(late.wait(P + "/main/link", lambda p: p == {"connected": False}, 5.0))
        event = late.wait(P + "/main/event", lambda e: e.get("event") == "link" and
                          e["connected"] is False, 5.0)
        self.assertTrue(event, "no link event")
        self.assertEqual(event[1]["type"], "event")
        self.assertEqual(event[1]["gimbal"], "main")
        self.assertEqual(event[0].qos, 1)
        self.start_sim(port=port)
        self.assertTrue(late.wait(P + "/main/link", lambda p: p == {"connected": True}, 5.0,
                                  start=2))
        later = self.sub(broker, P + "/main/link")
        self.assertEqual(later.wait(P + "/main/link")[1], {"connected": True})
        # STATE `mqtt`.
        reply = self.client(daemon).request("state", keys=["mqtt"])
        self.assertOk(reply)
        m = reply["state"]["mqtt"]
        self.assertEqual(m["connected"], True)
        self.assertGreater(m["published"], 10)
        self.assertEqual(set(m), {"connected", "published", "dropped", "reconnects"})

    def test_last_will_on_kill_and_offline_on_sigterm(self):
        broker = self.broker()
        daemon = self.mqtt_daemon(broker, keepalive_s=5)
        self.wait_mqtt_up(daemon)
        s = self.sub(broker, P + "/status")
        self.assertTrue(s.wait(P + "/status", lambda p: p["online"] is True))
        daemon.stop(signal.SIGKILL)
        # The broker publishes the will once it notices the socket closed.
        self.assertTrue(s.wait(P + "/status", lambda p: p == {"online": False}, 5.0),
                        "no last will")

        start = len(s.all())
        daemon = self.mqtt_daemon(broker)
        self.wait_mqtt_up(daemon)
        self.assertTrue(s.wait(P + "/status", lambda p: p["online"] is True, start=start))
        start = len(s.all())
        self.assertEqual(daemon.stop(signal.SIGTERM), 0)
        got = s.wait(P + "/status", lambda p: p == {"online": False}, 3.0, start=start)
        self.assertTrue(got, "no offline status on SIGTERM")
        late = self.sub(broker, P + "/status")
        self.assertEqual(late.wait(P + "/status")[1], {"online": False})


class Commands(MqttCase):
    def test_requests_with_response_topic_and_correlation(self):
        broker = self.broker()
        early = self.sub(broker)
        early.client.publish(P + "/cmd", json.dumps({"cmd": "ping", "id": 47}), qos=1,
                             retain=True).wait_for_publish(3)
        daemon = self.mqtt_daemon(broker, commands=True)
        self.wait_mqtt_up(daemon)
        c = self.sub(broker, "replies/op1", P + "/reply")
        c.request(P + "/cmd", {"cmd": "ping", "id": 41}, "replies/op1", b"\x00corr-1")
        got = c.wait("replies/op1", lambda r: r.get("id") == 41)
        self.assertTrue(got, "no reply on the response topic")
        self.assertEqual(got[1]["pong"], True)
        self.assertEqual(got[0].properties.CorrelationData, b"\x00corr-1")
        # A gimbal command runs through the same checks: an unknown parameter is refused.
        c.request(P + "/cmd", {"cmd": "position", "id": 42, "pan": 10, "tilt": -20},
                  "replies/op1", b"c2")
        got = c.wait("replies/op1", lambda r: r.get("id") == 42)
        self.assertTrue(got)
        self.assertTrue(got[1]["ok"], got[1])
        c.request(P + "/cmd", {"cmd": "position", "id": 43, "pan": 10, "bogus": 1},
                  "replies/op1", b"c3")
        got = c.wait("replies/op1", lambda r: r.get("id") == 43)
        self.assertEqual(got[1]["error"]["code"], "bad_request")
        # Without a response topic: P/reply.
        c.request(P + "/cmd", {"cmd": "version", "id": 44})
        got = c.wait(P + "/reply", lambda r: r.get("id") == 44)
        self.assertTrue(got, "no reply on P/reply")
        # Not JSON: bad_json, like the UDP socket.
        c.client.publish(P + "/cmd", b"{nope", qos=1)
        self.assertTrue(c.wait(P + "/reply", lambda r: r.get("error", {}).get("code") ==
                               "bad_json"))
        # A response topic among gimbald's own topics is not used: the reply goes to P/reply.
        c.request(P + "/cmd", {"cmd": "ping", "id": 46}, P + "/status", b"s")
        self.assertTrue(c.wait(P + "/reply", lambda r: r.get("id") == 46))
        # The retained request published before the start was never executed (it would
        # run again at every reconnection).
        self.assertTrue(daemon.wait_log(lambda e: e.get("event") == "mqtt_retained_cmd"))
        c.client.publish(P + "/cmd", b"", qos=1, retain=True)
        # The `command` log line names the MQTT source.
        entry = daemon.wait_log(lambda e: e.get("event") == "command" and e.get("id") == 41)
        self.assertTrue(entry)
        self.assertEqual(entry["src"], "mqtt:replies/op1")
        c.request(P + "/cmd", {"cmd": "ping", "id": 45}, "replies/op1", b"x", client_id="op-7")
        self.assertTrue(c.wait("replies/op1", lambda r: r.get("id") == 45))
        entry = daemon.wait_log(lambda e: e.get("event") == "command" and e.get("id") == 45)
        self.assertEqual(entry["src"], "mqtt:op-7")
        self.assertFalse([e for e in daemon.events("command") if e.get("id") == 47])

    def test_token_is_checked_like_udp(self):
        broker = self.broker()
        daemon = self.start_daemon({"command": {"token": "s3cret"},
                                    "mqtt": {"url": broker.url(), "station": "st1",
                                             "commands": True}}, ("--sim",))
        self.wait_mqtt_up(daemon)
        c = self.sub(broker, "r/1")
        c.request(P + "/cmd", {"cmd": "position", "id": 1, "pan": 1, "tilt": 1}, "r/1", b"a")
        self.assertEqual(c.wait("r/1", lambda r: r.get("id") == 1)[1]["error"]["code"],
                         "forbidden")
        c.request(P + "/cmd", {"cmd": "position", "id": 2, "pan": 1, "tilt": 1,
                               "token": "s3cret"}, "r/1", b"b")
        self.assertTrue(c.wait("r/1", lambda r: r.get("id") == 2)[1]["ok"])

    def test_commands_off_by_default(self):
        broker = self.broker()
        daemon = self.mqtt_daemon(broker)
        self.wait_mqtt_up(daemon)
        c = self.sub(broker, "r/#", P + "/reply")
        c.request(P + "/cmd", {"cmd": "ping", "id": 5}, "r/x", b"z")
        time.sleep(1.5)
        self.assertEqual(c.all("r/x"), [])
        self.assertEqual(c.all(P + "/reply"), [])
        self.assertFalse([e for e in daemon.events("command") if e.get("id") == 5])


class DeltaStream(MqttCase):
    """mqtt.state_changes (contract section 14): full STATEs (retained) every
    state_full_every_s, merge patches (not retained) in between; merged in order they give
    the STATE a `state` request returns."""

    def test_state_changes_merge_to_the_state(self):
        broker = self.broker()
        sim = self.start_sim()
        full_every_s = 1.5
        daemon = self.mqtt_daemon(broker, [gt.orion_tcp("main", sim.port)], state_rate_hz=10,
                                  state_changes=True, state_full_every_s=full_every_s)
        self.wait_mqtt_up(daemon)
        control = self.client(daemon)
        self.wait_connected(control)
        self.assertOk(control.request("mode", mode="disabled"))
        topic = P + "/main/state"
        live = self.sub(broker, topic)
        checker = dt.Checker(self, control, full_every_s)
        seen = 0
        start = time.monotonic()
        done = 0
        while time.monotonic() - start < 6.0:
            elapsed = time.monotonic() - start
            if done < len(dt.ACTIONS) and elapsed >= done * 6.0 / len(dt.ACTIONS):
                cmd, params = dt.ACTIONS[done]
                self.assertOk(control.request(cmd, **params))
                done += 1
            messages = live.all(topic)
            if len(messages) == seen:
                time.sleep(0.005)
                continue
            for i in range(seen, len(messages)):
                m = messages[i]
                msg = json.loads(m.payload)
                if m.retain:  # the retained full from before we subscribed: a snapshot
                    self.assertIs(msg["full"], True)
                    continue
                quiet = i == len(messages) - 1 and len(live.all(topic)) == len(messages)
                checker.on_delta(msg, len(m.payload), quiet)
            seen = len(messages)
        checker.verify()
        # gimbalctl --mqtt watch prints the merged STATE, whole, on every line.
        r = gt.run([gt.GIMBALCTL, "--mqtt", broker.url(), "--station", "st1", "watch",
                    "--no-events", "--count", "6"], timeout=10)
        self.assertEqual(r.returncode, 0, r.stderr)
        lines = [json.loads(line) for line in r.stdout.splitlines()]
        self.assertEqual(len(lines), 6)
        keys = set(lines[0]["state"])
        self.assertIn("telemetry", keys)
        for line in lines:
            self.assertEqual((line["type"], line["gimbal"]), ("state", "main"))
            self.assertEqual(set(line["state"]), keys)
        # A newcomer gets the retained message: always a full STATE, never a patch.
        late = self.sub(broker, topic)
        m, msg = late.wait(topic)
        self.assertTrue(m.retain)
        self.assertIs(msg["full"], True)
        self.assertEqual(msg["gimbal"], "main")
        self.assertEqual(msg["state"]["protocol"], "orion")


class Mqtt311Broker:
    """A minimal MQTT 3.1.1-only broker: refuses protocol level 5 with a 3.1.1 CONNACK
    (return code 1), accepts level 4 and records the topics of the PUBLISH packets."""

    def __init__(self):
        self.server = socket.socket()
        self.server.bind(("127.0.0.1", 0))
        self.server.listen(4)
        self.port = self.server.getsockname()[1]
        self.levels = []
        self.topics = []
        self.stop = False
        threading.Thread(target=self.serve, daemon=True).start()

    def url(self):
        return "mqtt://127.0.0.1:%d" % self.port

    @staticmethod
    def read_packet(conn):
        header = conn.recv(1)
        if not header:
            return None, b""
        length, shift = 0, 0
        while True:
            b = conn.recv(1)[0]
            length |= (b & 0x7F) << shift
            shift += 7
            if not b & 0x80:
                break
        body = b""
        while len(body) < length:
            chunk = conn.recv(length - len(body))
            if not chunk:
                return None, b""
            body += chunk
        return header[0], body

    def serve(self):
        self.server.settimeout(0.2)
        while not self.stop:
            try:
                conn, _ = self.server.accept()
            except OSError:
                continue
            with conn:
                conn.settimeout(5)
                try:
                    kind, body = self.read_packet(conn)
                    if kind is None or kind >> 4 != 1:
                        continue
                    level = body[6]  # after the 2-byte length and "MQTT"
                    self.levels.append(level)
                    if level != 4:
                        conn.sendall(bytes([0x20, 2, 0, 1]))
                        continue
                    conn.sendall(bytes([0x20, 2, 0, 0]))
                    while not self.stop:
                        kind, body = self.read_packet(conn)
                        if kind is None:
                            break
                        if kind >> 4 == 3:
                            n = (body[0] << 8) | body[1]
                            self.topics.append(body[2:2 + n].decode())
                            if (kind >> 1) & 3:  # QoS 1: PUBACK with the packet id
                                conn.sendall(bytes([0x40, 2]) + body[2 + n:4 + n])
                        elif kind >> 4 == 12:  # PINGREQ
                            conn.sendall(bytes([0xD0, 0]))
                except (OSError, IndexError):
                    continue

    def close(self):
        self.stop = True
        self.server.close()


class Gimbalctl(MqttCase):
    def test_commands_and_watch_through_the_broker(self):
        broker = self.broker()
        daemon = self.mqtt_daemon(broker, commands=True, state_rate_hz=10)
        self.wait_mqtt_up(daemon)
        base = [gt.GIMBALCTL, "--mqtt", broker.url(), "--station", "st1"]
        r = gt.run(base + ["ping"])
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(json.loads(r.stdout)["pong"], True)
        r = gt.run(base + ["send", '{"cmd":"position","pan":1,"tilt":2}'])
        self.assertEqual(r.returncode, 0, r.stderr)
        r = gt.run(base + ["send", '{"cmd":"position","pan":1}'])
        self.assertEqual(r.returncode, 1, r.stdout)
        self.assertEqual(json.loads(r.stdout)["error"]["code"], "bad_request")
        r = gt.run([gt.GIMBALCTL, "--mqtt", broker.url(), "--station", "other", "--timeout",
                    "0.5", "ping"])
        self.assertEqual(r.returncode, 2)
        self.assertIn("no reply", r.stderr)
        # The command log line carries gimbalctl's client id (the rate-limit key).
        self.assertTrue(daemon.wait_log(lambda e: e.get("event") == "command" and
                                        e.get("src", "").startswith("mqtt:gimbalctl-")))
        r = gt.run(base[:-2] + ["--station", "+", "watch", "--keys", "telemetry",
                                "--count", "3"], timeout=10)
        self.assertEqual(r.returncode, 0, r.stderr)
        lines = [json.loads(line) for line in r.stdout.splitlines()]
        self.assertEqual(len(lines), 3)
        for line in lines:
            self.assertEqual(line["type"], "state")
            self.assertEqual(line["station"], "st1")
            self.assertEqual(line["gimbal"], "sim")
            self.assertEqual(set(line["state"]), {"protocol", "link", "stale", "telemetry"})
        r = gt.run([gt.GIMBALCTL, "--mqtt", "mqtt://127.0.0.1:%d" % gt.closed_tcp_port(),
                    "--station", "st1", "ping"])
        self.assertEqual(r.returncode, 2)
        r = gt.run([gt.GIMBALCTL, "--mqtt", broker.url(), "ping"])
        self.assertEqual(r.returncode, 64)


    def test_signed_requests_through_the_broker(self):
        broker = self.broker()
        key = os.path.join(self.workdir, "ops.key")
        gt.run([gt.GIMBALCTL, "keygen", key]).check_returncode()
        daemon = self.start_daemon({
            "command": {"auth": "signed",
                        "keys": [{"id": "ops", "secret_file": key,
                                  "roles": ["observe", "control"]}]},
            "mqtt": {"url": broker.url(), "station": "st1", "commands": True}}, ("--sim",))
        self.wait_mqtt_up(daemon)
        base = [gt.GIMBALCTL, "--mqtt", broker.url(), "--station", "st1"]
        r = gt.run(base + ["--key-file", key, "--key-id", "ops", "position", "5", "-5"])
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        self.assertTrue(json.loads(r.stdout)["ok"])
        r = gt.run(base + ["position", "5", "-5"])
        self.assertEqual(r.returncode, 1, r.stdout + r.stderr)
        self.assertEqual(json.loads(r.stdout)["error"]["code"], "forbidden")
        audit = daemon.wait_log(lambda e: e.get("event") == "audit" and e.get("key") == "ops")
        self.assertTrue(audit)
        self.assertTrue(audit["src"].startswith("mqtt:gimbalctl-"), audit)


class BrokerLoss(MqttCase):
    def test_broker_down_ten_seconds(self):
        broker = self.broker()
        sim = self.start_sim()
        daemon = self.mqtt_daemon(broker, [gt.orion_tcp("main", sim.port)], state_rate_hz=50,
                                  queue_max=100, commands=True)
        self.wait_mqtt_up(daemon)
        c = self.client(daemon)
        self.wait_connected(c)
        broker.stop()
        self.assertTrue(daemon.wait_log(lambda e: e.get("event") == "mqtt_down", 5.0))
        rss_before = mt.rss_kib(daemon.proc.pid)
        # Ten seconds without a broker: the UDP socket and the gimbal link carry on.
        end = time.monotonic() + 10
        worst = 0.0
        while time.monotonic() < end:
            t0 = time.monotonic()
            reply = c.request("state", keys=["mqtt"])
            worst = max(worst, time.monotonic() - t0)
            self.assertOk(reply)
            self.assertTrue(reply["state"]["link"]["connected"])
            self.assertFalse(reply["state"]["mqtt"]["connected"])
            self.assertOk(c.request("position", pan=1, tilt=2))
            time.sleep(0.2)
        self.assertLess(worst, 0.5, "a UDP request took %.3f s while the broker was away" % worst)
        rss_after = mt.rss_kib(daemon.proc.pid)
        if not mt.sanitized(daemon.proc.pid):  # ASan's quarantine keeps freed memory
            self.assertLess(rss_after - rss_before, 4096,
                            "memory grew %d KiB" % (rss_after - rss_before))
        m = c.request("state", keys=["mqtt"])["state"]["mqtt"]
        self.assertGreater(m["dropped"], 100, m)  # 50 Hz STATE replaced while waiting
        # An event while the broker is away waits in the (bounded) queue.
        sim.kill()
        self.assertTrue(gt.wait_for(
            lambda: not c.request("state")["state"]["link"]["connected"], 5.0))
        # The broker returns without its retained messages (no persistence): gimbald
        # republishes them, and sends the queued event.
        broker.start()
        early = self.sub(broker, P + "/main/event")
        self.assertTrue(gt.wait_for(
            lambda: c.request("state", keys=["mqtt"])["state"]["mqtt"]["connected"], 8.0),
            "never reconnected")
        late = self.sub(broker, P + "/#")
        self.assertTrue(late.wait(P + "/status", lambda p: p["online"] is True))
        self.assertTrue(late.wait(P + "/main/state", lambda s: s.get("telemetry")))
        self.assertEqual(late.wait(P + "/main/link")[1], {"connected": False})
        self.assertTrue(early.wait(P + "/main/event", lambda e: e.get("event") == "link" and
                                   e["connected"] is False, 5.0), "queued event lost")
        self.assertGreaterEqual(c.request("state", keys=["mqtt"])["state"]["mqtt"]["reconnects"], 1)
        self.assertGreaterEqual(len(daemon.events("mqtt_up")), 2)


class Protocol311(MqttCase):
    def test_falls_back_to_mqtt_3_1_1(self):
        broker = Mqtt311Broker()
        self.addCleanup(broker.close)
        daemon = self.start_daemon({"mqtt": {"url": broker.url(), "station": "st1"}},
                                   ("--sim",))
        up = daemon.wait_log(lambda e: e.get("event") == "mqtt_up", 5.0)
        self.assertTrue(up, daemon.log_text()[-2000:])
        self.assertEqual(up["protocol"], "mqtt 3.1.1")
        self.assertEqual(broker.levels[:2], [5, 4])
        self.assertTrue(gt.wait_for(lambda: P + "/status" in broker.topics and
                                    P + "/sim/state" in broker.topics, 3.0), broker.topics)


class Security(MqttCase):
    def test_tls_with_a_test_ca(self):
        ca, cert, key = mt.make_tls_files(self.workdir)
        broker = self.broker(tls=True, extra=["cafile " + ca, "certfile " + cert,
                                              "keyfile " + key])
        daemon = self.mqtt_daemon(broker, ca_file=ca)
        self.wait_mqtt_up(daemon)
        s = self.sub(broker, P + "/status", ca_file=ca)
        self.assertTrue(s.wait(P + "/status", lambda p: p["online"] is True))

    def test_tls_with_the_wrong_ca_never_connects(self):
        ca, cert, key = mt.make_tls_files(self.workdir)
        other = os.path.join(self.workdir, "other")
        os.mkdir(other)
        other_ca, _, _ = mt.make_tls_files(other)
        broker = self.broker(tls=True, extra=["cafile " + ca, "certfile " + cert,
                                              "keyfile " + key])
        daemon = self.mqtt_daemon(broker, ca_file=other_ca)
        self.assertTrue(daemon.wait_log(lambda e: e.get("event") == "mqtt_down", 5.0))
        self.assertFalse(daemon.events("mqtt_up"))
        self.assertOk(self.client(daemon).request("ping"))

    def test_tls_with_a_client_certificate(self):
        ca, cert, key = mt.make_tls_files(self.workdir)
        gt.run(["openssl", "req", "-newkey", "rsa:2048", "-nodes", "-subj", "/CN=st1",
                "-keyout", "client.key", "-out", "client.csr"], cwd=self.workdir
               ).check_returncode()
        gt.run(["openssl", "x509", "-req", "-in", "client.csr", "-CA", "ca.crt", "-CAkey",
                "ca.key", "-CAcreateserial", "-days", "2", "-out", "client.crt"],
               cwd=self.workdir).check_returncode()
        client_key = os.path.join(self.workdir, "client.key")
        os.chmod(client_key, 0o600)
        broker = self.broker(tls=True, extra=["cafile " + ca, "certfile " + cert,
                                              "keyfile " + key, "require_certificate true"])
        # Without the client certificate the broker refuses the handshake.
        plain = self.mqtt_daemon(broker, ca_file=ca)
        self.assertTrue(plain.wait_log(lambda e: e.get("event") == "mqtt_down", 5.0))
        self.assertFalse(plain.events("mqtt_up"))
        plain.stop()
        daemon = self.mqtt_daemon(broker, ca_file=ca,
                                  cert_file=os.path.join(self.workdir, "client.crt"),
                                  key_file=client_key)
        self.wait_mqtt_up(daemon)

    def password_broker(self):
        pw = os.path.join(self.workdir, "passwd")
        gt.run(["mosquitto_passwd", "-c", "-b", pw, "op", "right-pw"]).check_returncode()
        return self.broker(extra=["allow_anonymous false", "password_file " + pw])

    def secret(self, text, mode=0o600):
        path = gt.unique_path(self.workdir, "pw-", ".txt")
        with open(path, "w") as f:
            f.write(text + "\n")
        os.chmod(path, mode)
        return path

    def test_password_login_and_refused_login(self):
        broker = self.password_broker()
        daemon = self.mqtt_daemon(broker, username="op", password_file=self.secret("right-pw"))
        self.wait_mqtt_up(daemon)
        daemon.stop()
        bad = self.mqtt_daemon(broker, username="op", password_file=self.secret("wrong"))
        down = bad.wait_log(lambda e: e.get("event") == "mqtt_down", 5.0)
        self.assertTrue(down, "no mqtt_down for a refused login")
        self.assertIn("refused", down["msg"])
        self.assertFalse(bad.events("mqtt_up"))
        # The rest of the daemon is unaffected.
        c = self.client(bad)
        self.assertOk(c.request("ping"))
        self.wait_connected(c)

    def test_start_up_errors_exit_1(self):
        cases = [
            ({"url": "http://127.0.0.1:1883"}, "mqtt.url"),
            ({"url": "mqtt://127.0.0.1:99999"}, "mqtt.url"),
            ({"username": "op", "password_file": self.secret("x", 0o644)}, "0644"),
            ({"username": "op", "password_file": "/nonexistent/pw"}, "missing"),
            ({"url": "mqtts://127.0.0.1:1", "ca_file": "/nonexistent/ca.crt"}, "mqtt.ca_file"),
            ({"station": "Bad Name"}, "mqtt.station"),
            ({"state_rate_hz": 60}, "mqtt.state_rate_hz"),
            ({"state_keys": ["nope"]}, "mqtt.state_keys"),
            ({"qos": 1}, "mqtt.qos"),
        ]
        for section, needle in cases:
            path = gt.unique_path(self.workdir, "bad-", ".json")
            with open(path, "w") as f:
                json.dump({"mqtt": section}, f)
            for extra in (["--check-config"], []):
                r = gt.run([gt.GIMBALD, "--sim", "-c", path, *extra], timeout=10)
                self.assertEqual(r.returncode, 1, (section, extra, r.stdout, r.stderr))
                self.assertIn(needle, r.stdout + r.stderr, (section, extra))


if __name__ == "__main__":
    gt.main()
