"""lib/klv against an independent decoder: klv_sample_sets (C++, lib/klv) writes ST 0601 sets
with every tag at random values inside its range, at the range ends and with the reserved
values; st0601.py (written separately from the standard's item table) decodes each one, and
the two decodings must agree with each other and with the values that were encoded:
angles and other mapped numbers within one mapping step, positions within 0.5 m, everything
else exactly. Tag 74 holds a MISB ST 0903 VMTI set: lib/klv decodes it under "vmti",
st0601.py keeps its hex, and st0903.py (written separately from ST 0903's tables) decodes
that hex; the targets must agree the same way. Registered by tests/CMakeLists.txt (it needs the tool's path):
    klv_st0601_agreement.py --tool build/debug/tests/klv_sample_sets
"""

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import st0601  # noqa: E402
import st0903  # noqa: E402

# One IMAPB step of each part of a VMTI target location (ST 0903 VTarget tag 17).
VMTI_LOCATION_STEPS = {"lat": 2.0 ** -23, "lon": 2.0 ** -22, "hae": 1.0}

METRES_PER_DEGREE = 111320.0  # at the equator; the largest a degree of longitude gets


def mapping_step(fmt, mapping, raw):
    """One wire step of an item, from the standard's description of its map."""
    if fmt.startswith("IMAPB"):
        inside = fmt[fmt.index("(") + 1:fmt.index(")")]
        a, b = (float(x) for x in inside.split(","))
        step = 2.0 ** (math.ceil(math.log2(b - a)) - (8 * len(raw) - 1))
        return step * 1000.0 if fmt.endswith("km") else step
    if mapping is None:
        return 1e-6 if fmt == "int us" else 0.0
    bits = 8 * len(raw)
    if mapping.startswith("+-"):
        return 2 * float(mapping[2:]) / ((1 << bits) - 2)
    low, high = (float(x) for x in mapping.split(".."))
    return (high - low) / ((1 << bits) - 1)


def raw_items(data):
    """tag -> value bytes of every item (last one wins), read with st0601's own helpers."""
    length, at = st0601.ber_length(data, 16)
    end, items = at + length, {}
    while at < end:
        tag, at = st0601.ber_oid(data, at, end)
        size, at = st0601.ber_length(data, at)
        items[tag] = data[at:at + size]
        at += size
    return items


def compare(name, ours, theirs, step, what, problems, position=False):
    if isinstance(ours, bool) or not isinstance(ours, (int, float)) or theirs is None:
        if ours != theirs:
            problems.append("%s: %s %r != %r" % (name, what, ours, theirs))
        return
    if not isinstance(theirs, (int, float)):
        problems.append("%s: %s %r != %r" % (name, what, ours, theirs))
        return
    difference = abs(float(ours) - float(theirs))
    if difference > step + 1e-9 * max(1.0, abs(float(theirs))):
        problems.append("%s: %s %r vs %r, %.3g apart, one step is %.3g"
                        % (name, what, ours, theirs, difference, step))
    if position and difference * METRES_PER_DEGREE > 0.5:
        problems.append("%s: %s %r vs %r, %.3f m apart" % (name, what, ours, theirs,
                                                           difference * METRES_PER_DEGREE))


def check_vmti(label, py_hex, theirs, given, problems):
    """Tag 74: st0903.py's decoding of st0601.py's hex against lib/klv's JSON and the set
    that was encoded (given as lib/klv's JSON of it)."""
    if py_hex is None or theirs is None:
        problems.append("%s: tag 74: python hex %r, lib/klv vmti %r" % (label, py_hex, theirs))
        return
    try:
        py = st0903.decode(bytes.fromhex(py_hex))
    except ValueError as e:
        problems.append("%s: tag 74: st0903.py refused it: %s" % (label, e))
        return
    for key in ("version", "total_targets", "reported_targets", "frame_width", "frame_height"):
        for what, other in (("lib/klv", theirs), ("encoded", given)):
            if py.get(key) != other.get(key):
                problems.append("%s: vmti %s: st0903.py %r, %s %r"
                                % (label, key, py.get(key), what, other.get(key)))
    for what, other in (("lib/klv", theirs), ("encoded", given)):
        if len(py["targets"]) != len(other["targets"]):
            problems.append("%s: vmti targets: st0903.py %d, %s %d"
                            % (label, len(py["targets"]), what, len(other["targets"])))
            continue
        for i, (a, b) in enumerate(zip(py["targets"], other["targets"])):
            where = "%s vmti target %d" % (label, i)
            for key in ("id", "centroid", "top_left", "bottom_right", "confidence_level"):
                if a.get(key) != b.get(key):
                    problems.append("%s: %s st0903.py %r, %s %r"
                                    % (where, key, a.get(key), what, b.get(key)))
            if ("location" in a) != ("location" in b):
                problems.append("%s: location in one decoding only" % where)
            elif "location" in a:
                for part, step in VMTI_LOCATION_STEPS.items():
                    compare("%s location %s" % (where, part), a["location"][part],
                            b["location"][part], step, "st0903.py vs " + what, problems,
                            position=part != "hae")


def check_set(base, problems):
    with open(base + ".klv", "rb") as f:
        data = f.read()
    with open(base + ".input.json") as f:
        given = json.load(f)
    with open(base + ".decoded.json") as f:
        cpp = json.load(f)
    status, reason, py = st0601.decode(data)
    label = os.path.basename(base)
    if status != "ok" or cpp["status"] != "ok":
        problems.append("%s: python %s (%s), lib/klv %s (%s)"
                        % (label, status, reason, cpp["status"], cpp["reason"]))
        return
    theirs = cpp["json"]
    if "vmti" in given:
        check_vmti(label, py.pop("vmti_local_set", None), theirs.pop("vmti", None),
                   given["vmti"], problems)
    if set(py) != set(theirs):
        problems.append("%s: keys differ: python only %s, lib/klv only %s"
                        % (label, sorted(set(py) - set(theirs)), sorted(set(theirs) - set(py))))
    raws = raw_items(data)
    for tag, (name, fmt, mapping) in st0601.TABLE.items():
        if name not in py or tag == 1:
            continue
        step = mapping_step(fmt, mapping, raws[tag])
        position = name.endswith("latitude") or name.endswith("longitude") or \
            "_latitude_" in name or "_longitude_" in name
        where = "%s %s" % (label, name)
        compare(where, py[name], theirs.get(name), step, "python vs lib/klv", problems, position)
        expected = given.get(name)
        if fmt.startswith("enum:") or fmt.startswith("flags:") or fmt.startswith("nibbles:"):
            expected = st0601.decode_value(fmt, mapping, raws[tag]) \
                if isinstance(expected, int) else expected
            if fmt.startswith("flags:") or fmt.startswith("nibbles:"):
                width = len(raws[tag])
                expected = st0601.decode_value(fmt, mapping, given[name].to_bytes(width, "big"))
        elif fmt in ("us", "uint us"):
            expected = st0601.iso_utc(given[name])
        elif fmt == "frame_rate":
            expected = {"numerator": given[name][0],
                        "denominator": given[name][1] if len(given[name]) > 1 else 1}
        elif fmt == "active_bits":
            expected = sorted(given[name])
        compare(where, py[name], expected, step, "decoded vs encoded", problems, position)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--tool", required=True, help="the klv_sample_sets program")
    parser.add_argument("--count", type=int, default=60)
    args = parser.parse_args()

    # The decoder itself first, on a packet the standard publishes (MISB ST 0902.5,
    # "dynamic only" example, checksum 0xC850).
    example = bytes.fromhex(
        "060E2B34020B01010E0103010100000061020800046050584E0180050271C20602FD3D070208B80D04"
        "5595B66D0E045B5360C40F02C2211002CD9C1102D9171204724A0A20130487F84B86140400000000"
        "15040383092616021281170 4F101A229180414BC082B190234F3410106 0102C850".replace(" ", ""))
    status, reason, items = st0601.decode(example)
    assert status == "ok", reason
    assert items["precision_time_stamp"] == "2009-01-12T22:08:22.000000Z", items
    assert abs(items["sensor_latitude"] - 60.176822966978335) < 1e-12, items
    assert abs(items["frame_center_elevation"] - 3216.0372) < 1e-3, items
    assert items["uas_datalink_ls_version_number"] == 6, items
    broken = bytearray(example)
    broken[-1] ^= 1
    assert st0601.decode(bytes(broken))[0] == "bad_checksum"

    problems = []
    with tempfile.TemporaryDirectory() as folder:
        subprocess.run([args.tool, folder, str(args.count)], check=True)
        for n in range(args.count):
            check_set(os.path.join(folder, str(n)), problems)
    for line in problems[:40]:
        print(line)
    print("klv_st0601_agreement: %d sets, %d tags each, %d disagreements"
          % (args.count, len(st0601.TABLE), len(problems)))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
