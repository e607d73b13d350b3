#!/usr/bin/env python3
"""STATE is typed inside gimbald (docs/architecture.md, "Typed STATE").

A gimbal's STATE is typed structs inside the daemon; its JSON is written at the edges only
(replies, pushes, MQTT, HTTP, recordings) by one generic writer. No code outside a protocol's
home reads STATE JSON by key: consumers read the typed fields (lib/state) and the protocol's
capabilities. This check counts the reads of STATE JSON by name in the C++ files under lib/
and daemon/ outside lib/protocols/<p>/ and fails when there are more than --max (default 0).
Clients of STATE (tools/, web/) read it from the wire, as any client does, and are not
counted; nor are the configuration's readers and writers (lib/config/, daemon/config.cpp,
*_config.*), whose sections share some names with STATE keys.

A read by name is

  - a call of a STATE JSON lookup helper (`state_at(`, `number_at(`);
  - a lookup on a JSON value named like STATE (`state`, `g.state`, `gimbal_state` ...):
    `.value(`, `.at(`, `.find(`, `.contains(`, `.count(` or `[` on it;
  - a lookup whose literal key is a top-level STATE key (`["telemetry"]`, `.find("output")`,
    `.value("stale", ...)` ...) on any value.

Writes (`state["video"] = ...`) are not reads.

Usage: check_state_reads.py [--max N] [--list] [SOURCE_DIR]
"""

import argparse
import os
import re
import sys

CXX = (".cpp", ".hpp", ".h", ".cc")

# The top-level keys of STATE (lib/state/messages.cpp, contract section 5).
STATE_KEYS = [
    "telemetry", "ins", "gps", "lasers", "diagnostics", "performance", "software",
    "network_diagnostics", "vibration", "retract", "stare", "cameras", "limits",
    "network_settings", "network_video", "uart_config", "ins_options", "versions",
    "reset_source", "boards", "output", "device", "vehicle", "command", "mavlink", "mqtt",
    "record", "capabilities", "video", "link", "stale", "protocol",
]

HELPERS = re.compile(r"\b(state_at|number_at)\s*\(")
NAMED_STATE = re.compile(
    r"\b\w*state\s*(?:\.|->)\s*(?:value|at|find|contains|count)\s*\(|\b\w*state\s*\[(?!\])")
KEY = "|".join(STATE_KEYS)
KEYED = re.compile(
    r'(?:\[\s*"(?:' + KEY + r')"\s*\]|'
    r'(?:\.|->)\s*(?:value|at|find|contains|count)\s*\(\s*"(?:' + KEY + r')"\s*[,)])')
# Receivers that are configuration readers and writers (lib/config), not STATE.
CONFIG_RECEIVER = re.compile(r'\b(?:f|v|fields)\s*(?:\.|->)\s*(?:value|at|find|contains|count)\s*\(')
COMMENT = re.compile(r"//.*$")


def protocols_of(lib):
    folder = os.path.join(lib, "protocols")
    return sorted(name for name in os.listdir(folder)
                  if os.path.exists(os.path.join(folder, name, name + "_entry.cpp")))


def in_home(path, protocols):
    parts = path.split("/")
    return len(parts) > 3 and parts[0] == "lib" and parts[1] == "protocols" and \
        parts[2] in protocols


def strip_strings_after_comment(line):
    """The line without its // comment (string literals holding // are rare enough here)."""
    out, quoted = [], False
    for i, c in enumerate(line):
        if c == '"' and (i == 0 or line[i - 1] != "\\"):
            quoted = not quoted
        if not quoted and line.startswith("//", i):
            break
        out.append(c)
    return "".join(out)


def is_write(code, end):
    """Whether the subscript ending at `end` (and any subscripts chained to it) is assigned."""
    i = end
    while True:
        while i < len(code) and code[i].isspace():
            i += 1
        if i < len(code) and code[i] == "[":
            depth = 0
            while i < len(code):
                depth += {"[": 1, "]": -1}.get(code[i], 0)
                i += 1
                if depth == 0:
                    break
            continue
        return code.startswith("=", i) and not code.startswith("==", i)


def subscript_end(code, start):
    """The index after the `]` closing the first `[` at or after `start`."""
    i = code.index("[", start)
    depth = 0
    while i < len(code):
        depth += {"[": 1, "]": -1}.get(code[i], 0)
        i += 1
        if depth == 0:
            return i
    return len(code)


def reads_in(line):
    code = strip_strings_after_comment(line)
    hits = len(HELPERS.findall(code))
    counted = []
    for m in NAMED_STATE.finditer(code):
        if m.group(0).endswith("[") and is_write(code, subscript_end(code, m.end() - 1)):
            continue
        counted.append(m.span())
        hits += 1
    for m in KEYED.finditer(code):
        start = max(0, m.start() - 12)
        if CONFIG_RECEIVER.search(code[start:m.end()]):
            continue
        if any(a <= m.start() <= b + 1 for a, b in counted):
            continue  # the same lookup, counted above
        if m.group(0).startswith("[") and is_write(code, m.end()):
            continue
        hits += 1
    return hits


def is_config(path):
    """The configuration's readers and writers name its sections, some spelled as STATE keys."""
    name = os.path.basename(path)
    return path.startswith("lib/config/") or name.startswith("config.") or "_config." in name


def scan(root, protocols, homes=False):
    """Every read found, outside the protocols' homes (or, with `homes`, inside them)."""
    found = []
    for top in ("lib", "daemon"):
        for folder, dirs, files in os.walk(os.path.join(root, top)):
            dirs.sort()
            for name in sorted(files):
                if not name.endswith(CXX):
                    continue
                path = os.path.relpath(os.path.join(folder, name), root).replace(os.sep, "/")
                if in_home(path, protocols) != homes or is_config(path):
                    continue
                with open(os.path.join(root, path), encoding="utf-8", errors="replace") as f:
                    for number, line in enumerate(f, 1):
                        n = reads_in(line)
                        if n:
                            found.append((path, number, n, line.strip()))
    return found


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--max", type=int, default=0, help="reads allowed (default 0)")
    parser.add_argument("--list", action="store_true", help="list every read found")
    parser.add_argument("root", nargs="?", default=os.path.join(here, "..", ".."))
    args = parser.parse_args()
    protocols = protocols_of(os.path.join(args.root, "lib"))
    found = scan(args.root, protocols)
    total = sum(n for _, _, n, _ in found)
    inside = sum(n for _, _, n, _ in scan(args.root, protocols, homes=True))
    if args.list or total > args.max:
        for path, number, n, line in found:
            print(f"{path}:{number}: {n} x {line}")
    summary = (f"{total} reads of STATE JSON by name under lib/ and daemon/ outside the homes "
               f"of {', '.join(protocols)}")
    if total > args.max:
        print(f"FAILED: {summary} (at most {args.max} allowed): read the typed STATE "
              f"(lib/state) or the gimbal's capabilities instead")
        return 1
    print(f"ok: {summary} (at most {args.max} allowed); {inside} inside the homes")
    return 0


if __name__ == "__main__":
    sys.exit(main())
