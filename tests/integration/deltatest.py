"""Helpers of the delta-stream tests (contract section 14): a JSON Merge Patch (RFC 7396)
receiver written from the RFC, independent of gimbald's C++, and the comparison of a merged
STATE with a `state` reply."""

import copy
import json
import time

# Top-level keys that count the test's own traffic (requests, MQTT messages): a `state`
# request moves them, so they are compared only between pushes, not with a `state` reply.
SELF_COUNTING = ("command", "mqtt")


def merge_patch(target, patch):
    """RFC 7396 section 2, MergePatch(Target, Patch)."""
    if not isinstance(patch, dict):
        return copy.deepcopy(patch)
    if not isinstance(target, dict):
        target = {}
    for name, value in patch.items():
        if value is None:
            target.pop(name, None)
        else:
            target[name] = merge_patch(target.get(name), value)
    return target


def comparable(value, top=True):
    """`value` without age_s members (and link.last_rx_age_s, an age too) at any depth, and
    without null object members (a receiver treats a missing member as null)."""
    if isinstance(value, dict):
        out = {}
        for k, v in value.items():
            if v is None or k == "age_s" or (top and k in SELF_COUNTING):
                continue
            if k == "link" and top and isinstance(v, dict):
                v = {lk: lv for lk, lv in v.items() if lk != "last_rx_age_s"}
            out[k] = comparable(v, False)
        return out
    if isinstance(value, list):
        return [comparable(v, False) for v in value]
    return value


def difference(a, b, path=""):
    """The first path where two comparable values differ, or None."""
    if isinstance(a, dict) and isinstance(b, dict):
        for k in sorted(set(a) | set(b)):
            if k not in a or k not in b:
                return "%s/%s (only in %s)" % (path, k, "first" if k in a else "second")
            d = difference(a[k], b[k], path + "/" + k)
            if d:
                return d
        return None
    if a != b:
        return "%s: %s != %s" % (path, json.dumps(a)[:200], json.dumps(b)[:200])
    return None


class Receiver:
    """Merges the state messages of one delta stream, per gimbal, as a client would."""

    def __init__(self):
        self.states = {}   # gimbal -> merged STATE
        self.fulls = 0
        self.patches = 0
        self.patch_sizes = []

    def push(self, msg, size=None):
        """Applies one {"type":"state","gimbal","full","state"} message; returns the merged
        STATE of that gimbal, or None while no full STATE has arrived yet."""
        assert set(msg) == {"type", "gimbal", "full", "state"}, sorted(msg)
        gimbal = msg["gimbal"]
        if msg["full"] is True:
            self.fulls += 1
            self.states[gimbal] = copy.deepcopy(msg["state"])
        else:
            assert msg["full"] is False, msg["full"]
            self.patches += 1
            if size is not None:
                self.patch_sizes.append(size)
            if gimbal not in self.states:
                return None
            self.states[gimbal] = merge_patch(self.states[gimbal], msg["state"])
        return self.states[gimbal]


# What the gimbal is told to do while the streams run: each changes something at some depth.
ACTIONS = [
    ("request", {"packet": "versions"}),
    ("position", {"pan": 20, "tilt": -30}),
    ("request", {"packet": "cameras"}),
    ("geopoint", {"lat": 45.71, "lon": -121.47, "alt": 100, "stare": True}),
    ("request", {"packet": "limits"}),
    ("rate", {"pan": 5, "tilt": 0}),
    ("request", {"packet": "network_diagnostics"}),
    ("position", {"pan": -40, "tilt": -10}),
    ("mode", {"mode": "disabled"}),
]


def link_key(state):
    """A push's snapshot, told apart by its link counters and age (equal only for the same
    snapshot)."""
    return json.dumps(state["link"], sort_keys=True)


def strict(value, top=True):
    """Comparable between two pushes of one snapshot: only age_s, nulls and the daemon's own
    request counters aside (the test's `state` requests may land between the two pushes, which
    the gimbal's link counters cannot tell apart)."""
    if isinstance(value, dict):
        return {k: strict(v, False) for k, v in value.items()
                if v is not None and k != "age_s" and not (top and k in SELF_COUNTING)}
    if isinstance(value, list):
        return [strict(v, False) for v in value]
    return value


class Checker:
    """Merges the delta pushes of one stream and checks each merged STATE."""

    def __init__(self, test, control, full_every_s):
        self.test = test
        self.full_every_s = full_every_s
        self.control = control
        self.receiver = Receiver()
        self.plain = {}          # link_key -> plain STATE of that snapshot
        self.merged = []         # merged STATEs, in order
        self.full_times = []
        self.state_checks = 0
        self.patch_keys = set()  # top-level keys any patch carried

    def on_delta(self, msg, size, quiet):
        """`quiet`: nothing else is waiting on the stream, so a `state` request now sees the
        same gimbal data as this push unless gimbal bytes arrive meanwhile."""
        merged = self.receiver.push(msg, size)
        if msg["full"]:
            self.full_times.append(time.monotonic())
        else:
            self.patch_keys.update(msg["state"])
            self.test.assertNotIn("protocol", msg["state"], "an unchanged key in a patch")
        if merged is None:
            return
        self.merged.append(json.loads(json.dumps(merged)))
        if not quiet:
            return
        reply = self.control.request("state", gimbal=msg["gimbal"])
        self.test.assertOk(reply)
        now = reply["state"]
        if now["link"]["rx_bytes"] != merged["link"]["rx_bytes"] or \
                now["link"]["tx_bytes"] != merged["link"]["tx_bytes"]:
            return  # the gimbal said something since the push: not the same data
        self.state_checks += 1
        diff = difference(comparable(merged), comparable(now))
        self.test.assertIsNone(diff, "merged pushes differ from `state`: %s" % diff)

    def on_plain(self, msg):
        self.test.assertNotIn("full", msg)
        self.plain[link_key(msg["state"])] = msg["state"]

    def verify(self):
        t = self.test
        t.assertGreater(self.receiver.patches, 20, "too few patches")
        t.assertGreaterEqual(self.state_checks, 3, "no quiet moment to compare with `state`")
        # Deep changes: telemetry moved; age_s alone never makes a key a change.
        t.assertIn("telemetry", self.patch_keys)
        t.assertIn("link", self.patch_keys)
        t.assertGreaterEqual(len(self.full_times), 3)
        gaps = [b - a for a, b in zip(self.full_times, self.full_times[1:])]
        for gap in gaps:
            t.assertGreater(gap, self.full_every_s - 0.25, gaps)
            t.assertLess(gap, self.full_every_s + 1.0, gaps)
        if not self.plain:
            return  # no plain twin on this transport (MQTT has one stream per gimbal)
        twins = 0
        for merged in self.merged:
            plain = self.plain.get(link_key(merged))
            if plain is None:
                continue
            twins += 1
            diff = difference(strict(merged), strict(plain))
            t.assertIsNone(diff, "merged pushes differ from the plain push: %s" % diff)
        t.assertGreaterEqual(twins, len(self.merged) // 2, "plain and delta pushes never met")
