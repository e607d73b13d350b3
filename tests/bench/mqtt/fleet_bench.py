#!/usr/bin/python3
"""Fleet benchmark of the MQTT bridge (issue 10; not a ctest test): N gimbald processes with
G simulated gimbals each publish STATE at R Hz through one mosquitto to one subscriber.

Reported per run:
  - latency "telemetry -> subscriber": subscriber receive time minus the telemetry's own
    time stamp (`telemetry.utc`, the in-process simulated gimbal's clock, anchored to the
    system clock). It includes the wait for the next STATE tick (up to 1/R s).
  Both are corrected by the simulated clock's offset, measured per daemon over UDP.
  - latency "snapshot -> subscriber": the same minus `telemetry.age_s` (the telemetry's age
    when the STATE snapshot was taken): the bridge, the broker and the subscriber only.
  - each gimbald's CPU (utime+stime from /proc over the measuring window, % of one core).

Usage: /usr/bin/python3 tests/bench/mqtt/fleet_bench.py [--daemons 8] [--gimbals 4]
       [--rate 10] [--seconds 30] [--keys telemetry] (GIMBALD=path/to/gimbald)
"""

import argparse
import datetime
import json
import os
import shutil
import socket
import statistics
import subprocess
import sys
import tempfile
import threading
import time

import paho.mqtt.client as mqtt

HZ = os.sysconf("SC_CLK_TCK")


def free_port(kind):
    with socket.socket(socket.AF_INET, kind) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def cpu_ticks(pid):
    with open("/proc/%d/stat" % pid) as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return int(fields[11]) + int(fields[12])  # utime, stime


def parse_utc(text):
    return datetime.datetime.strptime(text, "%Y-%m-%dT%H:%M:%S.%fZ").replace(
        tzinfo=datetime.timezone.utc).timestamp()


def percentile(values, p):
    values = sorted(values)
    return values[min(len(values) - 1, int(round(p / 100.0 * (len(values) - 1))))]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--daemons", type=int, default=8)
    ap.add_argument("--gimbals", type=int, default=4)
    ap.add_argument("--rate", type=float, default=10)
    ap.add_argument("--seconds", type=float, default=30)
    ap.add_argument("--warmup", type=float, default=5)
    ap.add_argument("--keys", default=None, help="mqtt.state_keys, comma separated")
    ap.add_argument("--gimbald", default=os.environ.get("GIMBALD", "build/release/daemon/gimbald"))
    args = ap.parse_args()

    tmp = tempfile.mkdtemp(prefix="fleet-bench-")
    procs = []
    try:
        port = free_port(socket.SOCK_STREAM)
        conf = os.path.join(tmp, "mosquitto.conf")
        with open(conf, "w") as f:
            f.write("listener %d 127.0.0.1\nallow_anonymous true\npersistence false\nset_tcp_nodelay true\n" % port)
            if os.geteuid() == 0:
                f.write("user root\n")
        broker = subprocess.Popen([shutil.which("mosquitto") or "/usr/sbin/mosquitto", "-c",
                                   conf], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        procs.append(broker)
        time.sleep(0.5)

        samples = []  # (telemetry->sub, snapshot->sub) seconds
        offsets = {}
        udp_ports = []
        counting = threading.Event()
        lock = threading.Lock()

        def on_message(client, userdata, msg):
            now = time.time()
            if not counting.is_set():
                return
            state = json.loads(msg.payload)
            t = state.get("telemetry")
            if not t or not t.get("utc"):
                return
            _, station, gimbal, _ = msg.topic.split("/")
            offset = offsets.get((station, gimbal), 0.0)
            utc = parse_utc(t["utc"])
            with lock:
                samples.append((now - utc - offset, now - utc - t.get("age_s", 0.0) - offset))

        sub = mqtt.Client(client_id="fleet-bench-sub", protocol=mqtt.MQTTv5)
        sub.on_message = on_message
        sub.connect("127.0.0.1", port)
        sub.subscribe("gimbald/+/+/state", qos=0)
        sub.loop_start()

        daemons = []
        for d in range(args.daemons):
            section = {"url": "mqtt://127.0.0.1:%d" % port, "station": "st%d" % d,
                       "state_rate_hz": args.rate}
            if args.keys:
                section["state_keys"] = args.keys.split(",")
            udp_ports.append(free_port(socket.SOCK_DGRAM))
            config = {"gimbals": [{"name": "g%d" % g, "protocol": "orion",
                                   "link": {"type": "sim"}} for g in range(args.gimbals)],
                      "command": {"port": udp_ports[-1]},
                      "log": {"level": "warn"},
                      "mqtt": section}
            path = os.path.join(tmp, "gimbald-%d.json" % d)
            with open(path, "w") as f:
                json.dump(config, f)
            p = subprocess.Popen([args.gimbald, "-c", path], stdout=subprocess.DEVNULL,
                                 stderr=subprocess.DEVNULL)
            procs.append(p)
            daemons.append(p)

        time.sleep(args.warmup)
        # The simulated gimbal's clock (telemetry.utc) is not exactly the system clock: per
        # gimbal (each simulated gimbal has its own clock), measure `time - utc - age_s` of a
        # STATE fetched over the UDP socket and subtract it from that gimbal's samples.
        offsets = {}
        for d, port_udp in enumerate(udp_ports):
            u = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
            u.settimeout(1)
            for g in range(args.gimbals):
                values = []  # (round trip, offset)
                for i in range(21):
                    sent = time.time()
                    u.sendto(json.dumps({"cmd": "state", "id": i, "gimbal": "g%d" % g,
                                         "keys": ["telemetry"]}).encode(),
                             ("127.0.0.1", port_udp))
                    reply = json.loads(u.recv(65536))
                    received = time.time()
                    t = reply["state"]["telemetry"]
                    # The snapshot was taken between send and receive: as NTP does, trust
                    # the exchange with the shortest round trip and take its midpoint.
                    values.append((received - sent, (sent + received) / 2 - parse_utc(t["utc"])
                                   - t["age_s"]))
                    time.sleep(0.013)
                offsets[("st%d" % d, "g%d" % g)] = min(values)[1]
            u.close()
        start_ticks = [cpu_ticks(p.pid) for p in daemons]
        t0 = time.monotonic()
        counting.set()
        time.sleep(args.seconds)
        counting.clear()
        elapsed = time.monotonic() - t0
        end_ticks = [cpu_ticks(p.pid) for p in daemons]
        sub.loop_stop()

        with lock:
            data = list(samples)
        expected = args.daemons * args.gimbals * args.rate * elapsed
        e2e = [s[0] * 1000 for s in data]
        pipe = [s[1] * 1000 for s in data]
        cpu = [(e - s) / HZ / elapsed * 100 for s, e in zip(start_ticks, end_ticks)]
        print("fleet: %d gimbald x %d gimbals, STATE %g Hz%s, %.0f s" % (
            args.daemons, args.gimbals, args.rate,
            " (keys %s)" % args.keys if args.keys else " (full STATE)", elapsed))
        print("sim clock offsets (ms, subtracted, per gimbal): min %.1f, max %.1f" % (
            min(offsets.values()) * 1000, max(offsets.values()) * 1000))
        print("messages: %d received of %d expected (%.1f %%)" % (
            len(data), expected, 100.0 * len(data) / expected if expected else 0))
        print("| latency | p50 ms | p99 ms | max ms |")
        print("| --- | --- | --- | --- |")
        for name, v in (("telemetry -> subscriber (incl. STATE tick wait)", e2e),
                        ("snapshot -> subscriber (bridge + broker)", pipe)):
            print("| %s | %.1f | %.1f | %.1f |" % (name, statistics.median(v),
                                                   percentile(v, 99), max(v)))
        print("| gimbald | CPU % of one core |")
        print("| --- | --- |")
        for i, c in enumerate(cpu):
            print("| st%d | %.2f |" % (i, c))
        print("| mean / max | %.2f / %.2f |" % (statistics.mean(cpu), max(cpu)))
    finally:
        for p in reversed(procs):
            p.terminate()
        for p in procs:
            try:
                p.wait(5)
            except subprocess.TimeoutExpired:
                p.kill()
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
