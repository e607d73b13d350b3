#!/usr/bin/env python3
"""The targets of scripts/bench.sh's Google Benchmark programs, judged from their JSON
reports (--benchmark_out): one line per target, "met" or "MISSED", and the names of the
missed ones on the last line (RESULT missed=...). Timings are judged, never enforced: the
exit code is 0 unless a report cannot be read. Usage: bench-targets.py bench_orion.json
bench_klv.json"""

import json
import os
import sys

# (program, benchmark name, what, measured from the run, comparison, limit, unit)
TARGETS = [
    ("bench_orion", "BM_FramerThroughput/4096", "Orion framer, 4 KiB reads",
     lambda b: b["bytes_per_second"] / 1e9, ">=", 1.0, "GB/s"),
    ("bench_orion", "BM_DecodeTelemetry", "GeolocateTelemetry decode",
     lambda b: ns(b), "<", 100.0, "ns"),
    ("bench_orion", "BM_EncodeTelemetry", "GeolocateTelemetry encode",
     lambda b: ns(b), "<", 100.0, "ns"),
    ("bench_klv", "BM_GenerateTypicalSet", "ST 0601 set generated (30 Hz under 0.2 % of a core)",
     lambda b: ns(b) / 1000, "<", 67.0, "us"),
]

SCALE = {"ns": 1.0, "us": 1e3, "ms": 1e6, "s": 1e9}


def ns(b):
    return b["real_time"] * SCALE[b.get("time_unit", "ns")]


def main(paths):
    runs = {}
    for path in paths:
        program = os.path.basename(path).rsplit(".", 1)[0]
        try:
            with open(path) as f:
                runs[program] = {b["name"]: b for b in json.load(f)["benchmarks"]}
        except (OSError, ValueError, KeyError) as e:
            print("bench-targets: cannot read %s: %s" % (path, e))
            return 1
    missed = []
    for program, name, what, measure, op, limit, unit in TARGETS:
        bench = runs.get(program, {}).get(name)
        if bench is None:
            continue
        value = measure(bench)
        met = value >= limit if op == ">=" else value < limit
        print("  %-55s %8.3g %s (target %s %g %s: %s)" %
              (what, value, unit, op, limit, unit, "met" if met else "MISSED"))
        if not met:
            missed.append(name)
    print("RESULT missed=%s" % (",".join(missed) or "none"))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
