"""Helpers of the MQTT integration tests: a real Debian `mosquitto` broker on a free loopback
port with its own configuration in the test's directory, and an independent MQTT 5 client
(paho-mqtt, which is only importable by Debian's /usr/bin/python3)."""

import json
import os
import shutil
import socket
import subprocess
import threading
import time

import paho.mqtt.client as mqtt
from paho.mqtt.packettypes import PacketTypes
from paho.mqtt.properties import Properties

import gimbaltest as gt

MOSQUITTO = shutil.which("mosquitto") or "/usr/sbin/mosquitto"


def available():
    return os.path.exists(MOSQUITTO)


class Broker:
    """mosquitto on 127.0.0.1:port; `extra` lines go into its configuration file."""

    def __init__(self, workdir, extra=(), port=None, tls=None):
        self.workdir = workdir
        self.port = port or gt.free_port(socket.SOCK_STREAM)
        self.extra = list(extra)
        self.tls = tls
        self.proc = None
        self.start()

    def start(self):
        conf = gt.unique_path(self.workdir, "mosquitto-", ".conf")
        lines = ["listener %d 127.0.0.1" % self.port, "persistence false"]
        if not any(line.startswith("allow_anonymous") for line in self.extra):
            lines.append("allow_anonymous true")
        if os.geteuid() == 0:
            # As root mosquitto drops to user "mosquitto", who cannot read the test's files.
            lines.append("user root")
        lines += self.extra
        with open(conf, "w") as f:
            f.write("\n".join(lines) + "\n")
        self.log_path = conf.replace(".conf", ".log")
        self._log = open(self.log_path, "wb")
        self.proc = subprocess.Popen([MOSQUITTO, "-c", conf], stdout=self._log,
                                     stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL)

        def listening():
            try:
                with socket.create_connection(("127.0.0.1", self.port), timeout=0.2):
                    return True
            except OSError:
                return self.proc.poll() is not None and "exited"
        if gt.wait_for(listening, gt.START_TIMEOUT_S) is not True:
            raise RuntimeError("mosquitto did not start: %s" % self.log())

    def log(self):
        with open(self.log_path, "rb") as f:
            return f.read().decode(errors="replace")

    def stop(self):
        if self.proc and self.proc.poll() is None:
            gt.stop_process(self.proc)
        if not self._log.closed:
            self._log.close()

    def url(self):
        return "%s://127.0.0.1:%d" % ("mqtts" if self.tls else "mqtt", self.port)


class Sub:
    """A paho MQTT 5 client that records every message it receives."""

    def __init__(self, broker, topics=(), client_id=None, username=None, password=None,
                 ca_file=None):
        self.messages = []
        self.lock = threading.Lock()
        self.client = mqtt.Client(client_id=client_id or "it-%d" % id(self),
                                  protocol=mqtt.MQTTv5)
        if username:
            self.client.username_pw_set(username, password)
        if ca_file:
            self.client.tls_set(ca_certs=ca_file)
        self.client.on_message = self._on_message
        connected = threading.Event()
        self.client.on_connect = lambda c, u, f, rc, p=None: connected.set()
        self.client.connect("127.0.0.1", broker.port)
        self.client.loop_start()
        if not connected.wait(gt.START_TIMEOUT_S):
            raise RuntimeError("test client could not connect to mosquitto")
        for topic in topics:
            self.subscribe(topic)

    def subscribe(self, topic):
        done = threading.Event()
        self.client.on_subscribe = lambda *a: done.set()
        self.client.subscribe(topic, qos=1)
        done.wait(gt.REPLY_TIMEOUT_S)

    def _on_message(self, client, userdata, msg):
        with self.lock:
            self.messages.append(msg)

    def all(self, topic=None):
        with self.lock:
            return [m for m in self.messages if topic is None or m.topic == topic]

    def json(self, topic):
        return [json.loads(m.payload) for m in self.all(topic)]

    def wait(self, topic, predicate=lambda payload: True, timeout=gt.REPLY_TIMEOUT_S, start=0):
        """The first message on `topic` (from index `start`) whose JSON payload satisfies
        predicate: (message, payload), or None."""
        def find():
            for m in self.all(topic)[start:]:
                payload = json.loads(m.payload)
                if predicate(payload):
                    return m, payload
            return None
        return gt.wait_for(find, timeout)

    def request(self, topic, request, response_topic=None, correlation=None, client_id=None):
        props = Properties(PacketTypes.PUBLISH)
        if response_topic:
            props.ResponseTopic = response_topic
        if correlation is not None:
            props.CorrelationData = correlation
        if client_id:
            props.UserProperty = ("client_id", client_id)
        self.client.publish(topic, json.dumps(request), qos=1, properties=props)

    def close(self):
        self.client.loop_stop()
        self.client.disconnect()


def rss_kib(pid):
    with open("/proc/%d/status" % pid) as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    return 0


def sanitized(pid):
    """True when the process runs with AddressSanitizer (its RSS says little then)."""
    with open("/proc/%d/maps" % pid) as f:
        return "libasan" in f.read()


def make_tls_files(workdir):
    """A CA and a server certificate for 127.0.0.1, made with the openssl command line.
    Returns (ca_cert, server_cert, server_key)."""
    def run(*args):
        gt.run(["openssl", *args], cwd=workdir).check_returncode()
    run("req", "-x509", "-newkey", "rsa:2048", "-nodes", "-days", "2", "-subj", "/CN=it-ca",
        "-keyout", "ca.key", "-out", "ca.crt")
    run("req", "-newkey", "rsa:2048", "-nodes", "-subj", "/CN=127.0.0.1",
        "-keyout", "server.key", "-out", "server.csr")
    with open(os.path.join(workdir, "san.ext"), "w") as f:
        f.write("subjectAltName=IP:127.0.0.1,DNS:localhost\n")
    run("x509", "-req", "-in", "server.csr", "-CA", "ca.crt", "-CAkey", "ca.key",
        "-CAcreateserial", "-days", "2", "-extfile", "san.ext", "-out", "server.crt")
    return tuple(os.path.join(workdir, n) for n in ("ca.crt", "server.crt", "server.key"))
