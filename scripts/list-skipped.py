#!/usr/bin/env python3
"""Lists what a ctest run skipped, from its JUnit report (ctest --output-junit FILE): the
tests ctest reports as not run (exit code 77: a tool they need could not be had), and the
test cases a passing test skipped inside itself (Python unittest's "... skipped 'why'",
a shell or benchmark part's "skipped: why", a Catch2 WARN "... skipped ..."). scripts/test.sh
runs it after every ctest run, passed or failed, so lost coverage is always said aloud.
Python 3 standard library only. Usage: list-skipped.py JUNIT.xml"""

import re
import sys
import xml.etree.ElementTree as ET

UNITTEST = re.compile(r"^(test\w*) \(([\w.]+)\)\s*\.\.\. skipped '(.*)'\s*$")
STATED = re.compile(r"^\s*(?:skip|skipped|SKIP)\s*:\s*(.+)$")
CATCH_WARN = re.compile(r"^\s*warning:\s*$")


def reasons(text):
    """The skips a test's output tells of: [(case or None, reason)]."""
    out = []
    lines = (text or "").splitlines()
    for i, line in enumerate(lines):
        m = UNITTEST.match(line)
        if m:
            # "test_x (module.Class.test_x)" (Python 3.11) or "test_x (module.Class)"
            where = m.group(2).split(".")
            if where[-1] != m.group(1):
                where.append(m.group(1))
            out.append((".".join(where[-2:]), m.group(3)))
            continue
        m = STATED.match(line)
        if m:
            out.append((None, m.group(1).strip()))
            continue
        if CATCH_WARN.match(line) and i + 1 < len(lines) and "skipped" in lines[i + 1]:
            out.append((None, lines[i + 1].strip()))
    return out


def main(path):
    try:
        root = ET.parse(path).getroot()
    except (OSError, ET.ParseError) as e:
        print("skipped tests: cannot read %s (%s)" % (path, e))
        return 1
    whole, partly = [], []
    for case in root.iter("testcase"):
        name = case.get("name")
        output = "\n".join((e.text or "") for e in case.iter("system-out"))
        skipped = case.find("skipped")
        if skipped is not None or case.get("status") in ("notrun", "skipped"):
            why = [r for _, r in reasons(output)]
            message = skipped.get("message") if skipped is not None else None
            whole.append((name, why[-1] if why else message or "no reason given"))
        else:
            for sub, why in reasons(output):
                partly.append((name, sub, why))
    if not whole and not partly:
        print("skipped tests: none")
        return 0
    print("skipped tests: %d whole, %d test cases inside passing tests "
          "(with CI=true a missing tool fails instead: tests/integration/skipping.py)"
          % (len(whole), len(partly)))
    for name, why in whole:
        print("  SKIPPED  %s: %s" % (name, why))
    for name, sub, why in partly:
        print("  skipped  %s%s: %s" % (name, " / " + sub if sub else "", why))
    return 0


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__.split("Usage: ")[1])
    sys.exit(main(sys.argv[1]))
