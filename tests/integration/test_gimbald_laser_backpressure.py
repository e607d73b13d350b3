#!/usr/bin/env python3
"""A laser cease-fire is never lost (contract section 14, issue 17 item 2).

The gimbal (gimbal-sim) stops reading, or reads no faster than a 115200-baud line, while a
client floods `path` at 200/s: the link's queue fills. The dead-man expires. The cease-fire
must go ahead of everything queued, nothing may claim `"sent": true` before the gimbal reads
again, the laser must count as firing until then (STATE and /metrics), and once the gimbal
reads, the cease-fire must reach it - ahead of the commands that were waiting. The
simulator's rx log is the witness of what reached the gimbal, in order.
"""

import threading
import time
import urllib.request

import gimbaltest as gt

FIRE = {"enable": True, "arm": True, "fire": True}
FLOOD_HZ = 200.0


def path_points(i):
    """15 points whose first latitude numbers the request (1e-5 degree steps)."""
    first = {"lat": 45.0 + i * 1e-5, "lon": -121.5, "alt": 100.0}
    return [first] + [{"lat": 45.1, "lon": -121.4 + k * 1e-3, "alt": 120.0} for k in range(14)]


def path_index(entry):
    """The number a `path` rx entry carries (from its first point's latitude)."""
    x, y, z = entry["packet"]["points"][0]["pos_ecef"]
    lat, _, _ = gt.ecef_to_lla(x, y, z)
    return round((lat - 45.0) / 1e-5)


class Flood(threading.Thread):
    """Sends `path` at FLOOD_HZ from its own socket and keeps every reply."""

    def __init__(self, port):
        super().__init__(daemon=True)
        self.client = gt.Client(port)
        self.stop_flag = threading.Event()
        self.sent = 0
        self.replies = {}  # index -> (monotonic time, ok, error code)

    def run(self):
        next_t = time.monotonic()
        while not self.stop_flag.is_set():
            now = time.monotonic()
            if now >= next_t:
                i = self.sent
                self.client.send({"cmd": "path", "id": i, "points": path_points(i)})
                self.sent += 1
                next_t += 1.0 / FLOOD_HZ
            msg = self.client._receive(max(0.0, min(next_t - time.monotonic(), 0.005)))
            if isinstance(msg, dict) and msg.get("cmd") == "path" and isinstance(msg.get("id"), int):
                error = msg.get("error", {}).get("code") if not msg.get("ok") else None
                self.replies[msg["id"]] = (time.monotonic(), bool(msg.get("ok")), error)

    def stop(self):
        self.stop_flag.set()
        self.join(5.0)
        self.client.close()

    def refused(self):
        return [i for i, (_, ok, _) in self.replies.items() if not ok]


def metric(http_port, name, labels):
    text = urllib.request.urlopen("http://127.0.0.1:%d/metrics" % http_port, timeout=3).read()
    for line in text.decode().splitlines():
        if line.startswith(name + "{") and all('%s="%s"' % kv in line for kv in labels.items()):
            return float(line.rsplit(" ", 1)[1])
    return None


class CeaseFireUnderBackpressure(gt.GimbaldTestCase):
    FIRE_TIMEOUT_S = 6.0

    def start(self, sim_args, link, pty=None):
        self.sim = self.start_sim(*sim_args, **({"tcp": False, "pty_link": pty} if pty else {}))
        self.http_port = gt.free_port(__import__("socket").SOCK_STREAM)
        config = {"gimbals": [link(self.sim)],
                  "laser": {"allow_fire": True, "fire_timeout_s": self.FIRE_TIMEOUT_S},
                  "http": {"port": self.http_port, "console": False}}
        self.daemon = self.start_daemon(config)
        self.c = self.client(self.daemon)
        self.wait_connected(self.c)

    def fire(self):
        reply = self.c.request("laser", index=0, **FIRE)
        self.assertOk(reply)
        fired = time.monotonic()
        self.assertTrue(self.sim.wait_rx(lambda e: e.get("name") == "laser_cmd" and
                                         e["packet"]["fire"]), "the fire never reached the gimbal")
        return fired

    def wait_not_reading(self):
        # Flooding only once the gimbal stopped reading keeps the kernel's buffers for the
        # connection small (TCP grows them while data flows), so the queue fills in seconds.
        self.assertTrue(gt.wait_for(lambda: "not reading" in self.sim.errors(), 5.0),
                        "gimbal-sim never stopped reading")

    def deadman_lines(self):
        return self.daemon.events("laser_deadman")

    def cease_entries(self):
        return [(n, e) for n, e in enumerate(self.sim.rx())
                if e.get("name") == "laser_cmd" and not e["packet"]["fire"]]

    def check_cease_went_first(self, flood, expired_at):
        """The cease-fire reached the gimbal ahead of most of what was queued when it was."""
        rx = self.sim.rx()
        ceases = self.cease_entries()
        self.assertEqual(len(ceases), 1, "one cease-fire, not %d" % len(ceases))
        at = ceases[0][0]
        queued_before = [i for i, (t, ok, _) in flood.replies.items() if ok and t < expired_at]
        arrived_before = {path_index(e) for e in rx[:at] if e.get("name") == "path"}
        overtaken = [i for i in queued_before if i not in arrived_before]
        # The queue held up to 256 packets; all but the half-written one and the kernel's
        # buffers were overtaken (or dropped to make room).
        self.assertGreater(len(overtaken), 50, "the cease-fire did not jump the queue")

    def test_tcp_gimbal_stops_reading(self):
        # The gimbal stops reading 2 s after the link came up, for 10 s.
        self.start(["--stall-reading-after", "2", "--stall-reading-for", "10"],
                   lambda sim: gt.orion_tcp("main", sim.port))
        fired = self.fire()
        self.wait_not_reading()
        flood = Flood(self.daemon.port)
        flood.start()
        self.addCleanup(flood.stop)
        # The queue fills: the flood starts to be refused.
        self.assertTrue(gt.wait_for(lambda: flood.refused(), self.FIRE_TIMEOUT_S + 2.0),
                        "the link's queue never filled")
        expired_at = fired + self.FIRE_TIMEOUT_S
        pending = self.daemon.wait_log(lambda e: e.get("event") == "laser_cease_pending",
                                       self.FIRE_TIMEOUT_S + 3.0)
        self.assertTrue(pending, "no laser_cease_pending while the gimbal did not read")
        self.assertIs(pending["sent"], False)
        self.assertGreater(pending["displaced"], 0, "nothing was dropped to make room")
        # Not written yet: nothing claims it was, the laser still counts as firing.
        self.assertFalse([e for e in self.deadman_lines() if e.get("sent")],
                         "sent: true before the gimbal read the cease-fire")
        self.assertEqual(self.cease_entries(), [])
        self.assertEqual(metric(self.http_port, "gimbald_laser_firing",
                                {"gimbal": "main", "index": "0"}), 1.0)
        lasers = self.c.request("state")["state"]["lasers"]
        self.assertTrue(lasers[0]["firing"], lasers)  # the daemon's record
        self.assertTrue(lasers[0]["active"], lasers)  # and the gimbal's: it never heard the cease
        # The gimbal reads again (12 s after the connect): the cease-fire arrives.
        cease = self.sim.wait_rx(lambda e: e.get("name") == "laser_cmd" and
                                 not e["packet"]["fire"], timeout=15.0)
        self.assertTrue(cease, "no cease-fire reached the gimbal once it read again")
        line = self.daemon.wait_log(lambda e: e.get("event") == "laser_deadman" and e.get("sent"))
        self.assertTrue(line, "laser_deadman sent: true never logged")
        self.assertEqual((line["level"], line["index"], line["gimbal"]), ("warn", 0, "main"))
        flood.stop()
        self.check_cease_went_first(flood, expired_at)
        self.assertTrue(gt.wait_for(lambda: metric(self.http_port, "gimbald_laser_firing",
                                                   {"gimbal": "main", "index": "0"}) == 0.0, 3.0))
        self.assertTrue(gt.wait_for(
            lambda: not self.c.request("state")["state"]["lasers"][0]["firing"], 3.0))
        self.assertTrue(gt.wait_for(
            lambda: not self.c.request("state")["state"]["lasers"][0]["active"], 3.0))
        self.assertEqual(len(self.deadman_lines()), 1)

    def pty_case(self, sim_args):
        pty = gt.unique_path(self.workdir, "orion-pty-", "")
        self.start(sim_args, lambda sim: gt.orion_serial("main", pty, 115200), pty=pty)
        fired = self.fire()
        if "--stall-reading-after" in sim_args:
            self.wait_not_reading()
        flood = Flood(self.daemon.port)
        flood.start()
        self.addCleanup(flood.stop)
        self.assertTrue(gt.wait_for(lambda: flood.refused(), self.FIRE_TIMEOUT_S + 2.0),
                        "the link's queue never filled")
        return fired, flood

    def test_pty_gimbal_stops_reading(self):
        fired, flood = self.pty_case(["--stall-reading-after", "2", "--stall-reading-for", "10"])
        pending = self.daemon.wait_log(lambda e: e.get("event") == "laser_cease_pending",
                                       self.FIRE_TIMEOUT_S + 3.0)
        self.assertTrue(pending, "no laser_cease_pending while the gimbal did not read")
        self.assertFalse([e for e in self.deadman_lines() if e.get("sent")])
        self.assertEqual(metric(self.http_port, "gimbald_laser_firing",
                                {"gimbal": "main", "index": "0"}), 1.0)
        cease = self.sim.wait_rx(lambda e: e.get("name") == "laser_cmd" and
                                 not e["packet"]["fire"], timeout=15.0)
        self.assertTrue(cease, "no cease-fire reached the gimbal once it read again")
        self.assertTrue(self.daemon.wait_log(lambda e: e.get("event") == "laser_deadman" and
                                             e.get("sent")))
        flood.stop()
        self.check_cease_went_first(flood, fired + self.FIRE_TIMEOUT_S)

    def test_115200_baud_line_falls_behind(self):
        # ~29 KB/s of path into an 11.5 KB/s line: the queue fills, the gimbal keeps reading.
        fired, flood = self.pty_case(["--read-baud", "115200"])
        cease = self.sim.wait_rx(lambda e: e.get("name") == "laser_cmd" and
                                 not e["packet"]["fire"], timeout=self.FIRE_TIMEOUT_S + 8.0)
        self.assertTrue(cease, "the cease-fire never reached a gimbal on a slow line")
        line = self.daemon.wait_log(lambda e: e.get("event") == "laser_deadman", 3.0)
        self.assertTrue(line and line["sent"], line)
        flood.stop()
        self.check_cease_went_first(flood, fired + self.FIRE_TIMEOUT_S)


if __name__ == "__main__":
    gt.main()
