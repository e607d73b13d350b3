"""What one attack measured and the principle's verdict on it (issue 25, contract section 14
v4): the cease-fire within fire_timeout + 0.25 s of the client's fire, a concurrent ping's
p99 under 50 ms, RSS under 128 MB and back within 16 MB of its start, and gimbald stopping
within 5 s of SIGTERM; plus each attack's own checks."""

import math

FIRE_TIMEOUT_S = 2.0
CEASE_LIMIT_S = FIRE_TIMEOUT_S + 0.25
PING_P99_LIMIT_MS = 50.0
RSS_PEAK_LIMIT_MB = 128.0
RSS_RETURN_MB = 16.0
STOP_LIMIT_S = 5.0


def percentile(values, p):
    """Nearest-rank percentile; math.inf stands for a lost ping."""
    if not values:
        return None
    ordered = sorted(values)
    rank = max(1, int(math.ceil(p / 100.0 * len(ordered))))
    return ordered[rank - 1]


class Figures:
    """One row of the table: what the rig measured, and the verdict's reasons."""

    def __init__(self, name):
        self.name = name
        self.cease_s = []  # one per fire; None: never ceased
        self.ping = None  # {"sent", "rtts_ms", "lost"}
        self.rss_start_kb = self.rss_peak_kb = self.rss_end_kb = None
        self.anon_start_kb = self.anon_end_kb = self.anon_peak_kb = None
        self.stop_s = None
        self.failures = []
        self.notes = []
        self.skipped = None
        self.runtime = True  # False: a --check-config attack (no daemon running under attack)
        self.elapsed_s = 0.0

    def fail(self, reason):
        self.failures.append(reason)

    def note(self, text):
        self.notes.append(text)

    def check(self, ok, reason):
        if not ok:
            self.fail(reason)
        return ok

    def ping_stats(self):
        if not self.ping or not self.ping["sent"]:
            return None
        values = list(self.ping["rtts_ms"]) + [math.inf] * self.ping["lost"]
        return {"p50": percentile(values, 50), "p99": percentile(values, 99),
                "max": max(values), "lost": self.ping["lost"], "sent": self.ping["sent"]}

    def judge(self):
        """The principle's verdict on what was measured (runtime attacks)."""
        if not self.runtime:
            return
        for i, delay in enumerate(self.cease_s):
            if delay is None:
                self.fail("fire %d never ceased at the gimbal" % (i + 1))
            elif delay > CEASE_LIMIT_S:
                self.fail("cease-fire %.2f s after the fire (limit %.2f)" % (delay, CEASE_LIMIT_S))
        stats = self.ping_stats()
        if stats is None:
            self.fail("no ping measured")
        elif stats["p99"] >= PING_P99_LIMIT_MS:
            self.fail("ping p99 %s (limit %.0f ms)%s" % (
                "lost" if stats["p99"] == math.inf else fmt_ms(stats["p99"]) + " ms",
                PING_P99_LIMIT_MS,
                ", %d of %d lost" % (stats["lost"], stats["sent"]) if stats["lost"] else ""))
        if self.rss_peak_kb is not None and self.rss_peak_kb / 1024.0 >= RSS_PEAK_LIMIT_MB:
            self.fail("RSS peak %.0f MB (limit %.0f)" % (self.rss_peak_kb / 1024.0,
                                                         RSS_PEAK_LIMIT_MB))
        if self.rss_start_kb is not None and self.rss_end_kb is not None and \
                (self.rss_end_kb - self.rss_start_kb) / 1024.0 > RSS_RETURN_MB:
            self.fail("RSS kept %.1f MB after the attack (limit %.0f)" % (
                (self.rss_end_kb - self.rss_start_kb) / 1024.0, RSS_RETURN_MB))
        if self.stop_s is not None and self.stop_s > STOP_LIMIT_S:
            self.fail("SIGTERM ignored (killed after %.0f s)" % STOP_LIMIT_S if
                      self.stop_s == math.inf else "SIGTERM took %.1f s" % self.stop_s)

    def as_json(self):
        return finite({
            "attack": self.name, "cease_s": self.cease_s, "ping": self.ping_stats(),
            "rss_kb": [self.rss_start_kb, self.rss_peak_kb, self.rss_end_kb],
            "anon_kb": [self.anon_start_kb, self.anon_peak_kb, self.anon_end_kb],
            "stop_s": self.stop_s, "failures": self.failures, "notes": self.notes,
            "skipped": self.skipped, "elapsed_s": round(self.elapsed_s, 2)})


def finite(v):
    """JSON has no infinity: a lost ping or an ignored SIGTERM becomes null."""
    if isinstance(v, float) and math.isinf(v):
        return None
    if isinstance(v, dict):
        return {k: finite(x) for k, x in v.items()}
    if isinstance(v, list):
        return [finite(x) for x in v]
    return v


def fmt_ms(v):
    if v is None:
        return "-"
    if v == math.inf:
        return "lost"
    return "%.1f" % v if v < 100 else "%.0f" % v
