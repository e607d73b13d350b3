#!/usr/bin/env python3
"""The attack suite of issue 25: "no untrusted byte may delay a cease-fire".

Each attack runs against a fresh gimbald (release build for figures) with a simulated Orion
(gimbal-sim over TCP) whose laser is fired once and never renewed, `laser.fire_timeout_s` 2.
The principle (contract section 14 v4), measured under every attack:

- the cease-fire reaches the gimbal within fire_timeout + 0.25 s of the client's last fire
  (timed at the simulator: gimbal-sim --rx-log);
- a concurrent UDP `ping` from another address (127.0.0.2, every 20 ms) has p99 under 50 ms
  (a lost ping counts as infinitely late);
- gimbald's RSS stays under 128 MB and comes back within 16 MB of its start (VmRSS; the
  anonymous memory of smaps_rollup is shown beside it);
- and each attack's own checks (a reply instead of silence, no credentials to another host,
  lines rolled up, `--check-config` refusing, ...).

One row per attack: cease-fire delay after the last fire (s; the worst of its fires), ping
p50/p99/max (ms) and lost pings, RSS start/peak/end (MB), anonymous memory start/end (MB),
verdict. Exit 1 when any verdict fails.

    attack.py [--brief | --seconds N] [--only REGEX] [--list] [--json FILE] [--keep]

--brief: every attack, scaled down in time and volume (about 3 s each; the suite in about
90 s); the default runs each for --seconds (10). Binaries: --gimbald/--gimbalctl/--gimbal-sim
or GIMBALD, GIMBALCTL, GIMBAL_SIM. Under CI=true a missing tool (ffmpeg, gdal_create) fails
the attacks that need it instead of skipping them. Python 3 standard library only.
"""

import argparse
import contextlib
import json
import os
import re
import shutil
import sys
import tempfile
import time
import traceback

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

import attack_config as C  # noqa: E402
import attack_figures as F  # noqa: E402
import attack_http as H  # noqa: E402
import attack_mavlink as M  # noqa: E402
import attack_rig as R  # noqa: E402
import attack_rtsp as P  # noqa: E402
import attack_streams as S  # noqa: E402
import attack_terrain as T  # noqa: E402
import attack_video as V  # noqa: E402

# (name, function, what it does, whether it held on the code issue 25 was filed against)
ATTACKS = [
    ("klv_huge_valid", lambda s, f: V.klv_huge(s, f, False),
     "8 MB KLV set, 2 M unknown tags, every second (item 1)", False),
    ("klv_huge_bad_checksum", lambda s, f: V.klv_huge(s, f, True),
     "the same with a wrong checksum (item 1)", False),
    ("klv_sync_middle", V.klv_sync_middle,
     "ST 1402 'middle' fragments without end, 40 MB/s (item 2)", False),
    ("klv_state_size", V.klv_state_size,
     "valid 46.5 KB set; state and subscriptions answered (item 1)", False),
    ("klv_foreign_source", V.klv_foreign,
     "KLV from a foreign address beside the camera's (item 10)", False),
    ("dem_vsicurl_stall", T.vsicurl_stall, "VRT over /vsicurl/ to a stalling server (item 3)",
     False),
    ("dem_sparse_1e6", T.sparse_huge_tif, "sparse 1e6 x 1e6 GeoTIFF (item 4)", False),
    ("dem_vrt_2e9", T.huge_vrt, "2e9 x 2e9 VRT (item 4)", False),
    ("dem_raw_passwd", T.raw_passwd, "VRT raw band over /etc/passwd (item 5)", False),
    ("dem_vrt_as_tif", T.vrt_as_tif, "that VRT saved as .tif (item 5)", False),
    ("dem_fifo", T.fifo_dem, "a FIFO as DEM (item 12)", False),
    ("rtsp_content_length", P.content_length, "DESCRIBE with Content-Length 2e9 (item 6)",
     False),
    ("rtsp_endless_frame", P.endless_frame, "an endless fragmented frame (item 6)", False),
    ("rtsp_redirect_auth", P.redirect_credentials,
     "credentials and a redirect to another host (item 7)", False),
    ("rtsp_redirect_loop", P.redirect_loop, "a redirect loop (item 11)", False),
    ("mavlink_junk_peers", M.junk_peers, "24 junk senders vs a signed ground station (item 8)",
     False),
    ("log_flood_mavlink_refused", M.refused_flood, "1,600 refused commands/s (item 9)", False),
    ("log_flood_video_viewer", H.viewer_flood, "video viewers joining and leaving (item 9)",
     False),
    ("mavlink_device_limits", M.device_limits, "device limits +-5.7e39 deg, inverted (item 13)",
     False),
    ("config_dev_zero", C.dev_zero, "/dev/zero as configuration (item 12)", False),
    ("config_fifo", C.fifo, "a FIFO as configuration (item 12)", False),
    ("config_text_after_nul", C.text_after_nul, "text after a NUL (item 12)", False),
    ("config_unclosed_array", C.unclosed_array, "5 MB unclosed array (item 12)", False),
    ("ts_junk", V.ts_junk, "junk TS datagrams, 3,030/s (held: 30,300)", True),
    ("ts_every_pid", V.ts_pid_flood, "every PID flooded, programs changing (held)", True),
    # The issue counts it as held (cease-fire on time, RSS flat while it lasts); by the
    # principle's return-to-start measure the demultiplexer keeps its 16 MiB PES buffer.
    ("pes_16mib", V.pes_16mib, "16 MiB + 100 KiB video PES every 2 s", False),
    ("sps_hostile", V.sps_hostile, "hostile SPS, 500/s (held: 5,000)", True),
    ("klv_hostile", V.klv_hostile, "hostile KLV sets, 280/s (held: ~2,800)", True),
    ("video_stalled_viewers", H.stalled_viewers, "50 video viewers that never read (held)",
     True),
    ("mavlink_requests", M.requests_flood, "MAVLink requests, 6,565/s (held: 262,600)", True),
    ("mavlink_device_attitudes", M.device_attitudes, "forged device attitudes at 11 kHz (held)",
     True),
]


class Suite:
    def __init__(self, args):
        self.args = args
        self.gimbald, self.gimbal_sim = args.gimbald, args.gimbal_sim
        self.brief = args.brief
        self.seconds = 2.3 if args.brief else args.seconds
        self.ci = os.environ.get("CI", "").lower() in ("1", "true", "yes")
        self.workdir = tempfile.mkdtemp(prefix="gimbald-attack-")
        self.cache = {}

    def attack_dir(self, name):
        path = os.path.join(self.workdir, name)
        os.makedirs(path, exist_ok=True)
        return path

    def cached(self, key, make):
        if key not in self.cache:
            self.cache[key] = make()
        return self.cache[key]

    def volume(self, brief, full):
        return int(brief if self.brief else full)

    def count(self, per_second, at_least):
        """How many distinct items an attack sending `per_second` needs (no repeats within
        a run, and at least the issue's count in a full run)."""
        return int(per_second * (self.seconds + 2)) if self.brief else \
            max(at_least, int(per_second * (self.seconds + 5)))

    def h264_units(self):
        if not shutil.which("ffmpeg"):
            raise R.AttackSkipped("ffmpeg is not installed (the camera's H.264 comes from it)")
        return self.cached("h264", lambda: S.h264_units(self.workdir))

    @contextlib.contextmanager
    def rig(self, figures, **options):
        rig = R.Rig(self, figures, **options)
        try:
            rig.start()
            yield rig
        finally:
            rig.stop()


HEADER = "%-26s %8s %22s %5s %17s %11s  %s" % (
    "attack", "cease s", "ping p50/p99/max ms", "lost", "RSS st/peak/end MB", "anon st/end",
    "verdict")


def mb(kb):
    return "-" if kb is None else "%.0f" % (kb / 1024.0)


def row(f):
    if f.skipped and not f.failures:
        return "%-26s %s" % (f.name, "skipped: " + f.skipped)
    cease = "-"
    if f.cease_s:
        cease = "never" if None in f.cease_s else "%.2f" % max(f.cease_s)
        if len(f.cease_s) > 1:
            cease += "x%d" % len(f.cease_s)
    stats = f.ping_stats()
    ping = lost = "-"
    if stats and f.runtime:
        ping = "%s/%s/%s" % (F.fmt_ms(stats["p50"]), F.fmt_ms(stats["p99"]),
                             F.fmt_ms(stats["max"]))
        lost = str(stats["lost"])
    rss = "%s/%s/%s" % (mb(f.rss_start_kb), mb(f.rss_peak_kb), mb(f.rss_end_kb))
    anon = "%s/%s" % (mb(f.anon_start_kb), mb(f.anon_end_kb))
    verdict = "ok" if not f.failures else "FAILED: " + "; ".join(f.failures)
    return "%-26s %8s %22s %5s %17s %11s  %s" % (f.name, cease, ping, lost, rss, anon, verdict)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--gimbald", default=os.environ.get("GIMBALD"))
    p.add_argument("--gimbalctl", default=os.environ.get("GIMBALCTL"))
    p.add_argument("--gimbal-sim", default=os.environ.get("GIMBAL_SIM"))
    p.add_argument("--brief", action="store_true", help="every attack, short (CI)")
    p.add_argument("--seconds", type=float, default=10.0, help="per attack (default 10)")
    p.add_argument("--only", help="run the attacks whose name matches this regex")
    p.add_argument("--list", action="store_true", help="list the attacks and exit")
    p.add_argument("--json", help="also write the figures to this file")
    p.add_argument("--keep", action="store_true", help="keep the work directory (logs)")
    a = p.parse_args()
    if a.list:
        for name, _, what, held in ATTACKS:
            print("%-26s %s%s" % (name, what, "" if not held else " [held before]"))
        return 0
    if not (a.gimbald and a.gimbal_sim):
        p.error("--gimbald and --gimbal-sim (or GIMBALD, GIMBAL_SIM) are needed")
    if a.seconds < 2.3:
        p.error("--seconds must leave room for one fire and its cease-fire (at least 2.3)")
    suite = Suite(a)
    chosen = [x for x in ATTACKS if not a.only or re.search(a.only, x[0])]
    print("attack suite: %d attacks, %s; fire_timeout_s %.0f; targets: cease-fire <= %.2f s, "
          "ping p99 < %.0f ms, RSS < %.0f MB and back within %.0f MB, SIGTERM < %.0f s" % (
              len(chosen), "brief (%.1f s each)" % suite.seconds if a.brief else
              "%.0f s each" % suite.seconds, F.FIRE_TIMEOUT_S, F.CEASE_LIMIT_S,
              F.PING_P99_LIMIT_MS, F.RSS_PEAK_LIMIT_MB, F.RSS_RETURN_MB, F.STOP_LIMIT_S),
          flush=True)
    print(HEADER, flush=True)
    results = []
    began = time.monotonic()
    for name, fn, what, held in chosen:
        f = F.Figures(name)
        t0 = time.monotonic()
        try:
            fn(suite, f)
        except R.AttackSkipped as e:
            f.skipped = str(e)
            if suite.ci:
                f.fail("cannot run under CI=true: " + str(e))
        except Exception as e:  # an attack that cannot run is a failure, never a pass
            f.fail("attack crashed: %s: %s" % (type(e).__name__, e))
            f.note(traceback.format_exc().strip().splitlines()[-3])
        if not f.skipped:
            f.judge()
        f.elapsed_s = time.monotonic() - t0
        results.append((f, held))
        print(row(f), flush=True)
        for n in f.notes:
            print("%28s%s" % ("", n), flush=True)
    failed = [f.name for f, _ in results if f.failures]
    regressions = [f.name for f, held in results if f.failures and held]
    skipped = [f.name for f, _ in results if f.skipped and not f.failures]
    print("attack suite: %d attacks in %.0f s, %d FAILED%s%s" % (
        len(results), time.monotonic() - began, len(failed),
        (": " + ", ".join(failed)) if failed else "",
        ("; skipped: " + ", ".join(skipped)) if skipped else ""), flush=True)
    if regressions:
        print("REGRESSION: attacks that held before fail now: " + ", ".join(regressions),
              flush=True)
    if a.json:
        with open(a.json, "w") as out:
            json.dump({"brief": a.brief, "seconds": suite.seconds,
                       "attacks": [dict(f.as_json(), held_before=held) for f, held in results]},
                      out, indent=1)
    if a.keep:
        print("work directory: " + suite.workdir)
    else:
        shutil.rmtree(suite.workdir, ignore_errors=True)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
