"""Helpers of the delta-stream tests (contract section 14): a JSON Merge Patch (RFC 7396)
receiver written from the RFC, independent of gimbald's C++, and the comparison of a merged
STATE with a `state` reply."""

import copy
import json

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
