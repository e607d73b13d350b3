"""tshark with dissectors/gimbald.lua decodes every golden vector exactly as the C++ codecs do.

usage: test_golden_vectors.py CODEC_JSON GIMBALD_LUA

Every Orion golden vector of tests/unit/orion and every Viewpro frame of tests/unit/viewpro
(printed by codec-json) goes into a pcapng of exported-PDU records; tshark decodes it with the
dissector (-T json); every field of the codec's JSON for the same bytes must be there with the
same value (numbers to 1e-9 relative: both sides compute the same double), and the dissector
may show nothing the codec does not. Valid packets get no expert warnings or errors; a
corrupted checksum gets the checksum warning.
"""
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import pcapng_writer  # noqa: E402
import tshark_tools  # noqa: E402

# Fields of the dissector that are not packet content (header, checksum, counts).
HEADER_FIELDS = {"orion.sync", "orion.id", "orion.packet", "orion.length", "orion.request",
                 "orion.checksum", "orion.checksum.computed", "orion.checksum.status",
                 "viewpro.frame", "viewpro.header", "viewpro.id", "viewpro.checksum",
                 "viewpro.checksum.computed", "viewpro.checksum.status", "viewpro.end",
                 "viewpro.flag", "mavlink.magic", "mavlink.len", "mavlink.incompat_flags",
                 "mavlink.compat_flags", "mavlink.msgname", "mavlink.payload", "mavlink.crc"}
COUNT_KEYS = {"num_lasers", "num_cores", "num_threads", "num_cameras", "size", "length",
              "num_points"}


def fletcher251(data):
    a, b = 1, 0
    for x in data:
        a = (a + x) % 251
        b = (b + a) % 251
    return bytes([a, b])



def flatten_tshark(node, out, expert):
    """Every (field, value) under a tshark -T json layer, in order; '_tree' keys recurse."""
    for key, values in node.items():
        for v in values:
            if key == "_ws.expert":
                expert.append(v)
                if isinstance(v, dict):
                    flatten_tshark(v, out, expert)
                continue
            if isinstance(v, dict):
                flatten_tshark(v, out, expert)
            else:
                out.setdefault(key, []).append(v)


def flatten_codec(prefix, value, out):
    if isinstance(value, dict):
        for k, v in value.items():
            flatten_codec(prefix + "." + k, v, out)
    elif isinstance(value, list) and value and isinstance(value[0], dict):
        for item in value:
            flatten_codec(prefix, item, out)  # groups: children in item order
    elif isinstance(value, list):
        out.setdefault(prefix, []).extend(value)
    else:
        out.setdefault(prefix, []).append(value)


def same(expected, shown):
    if isinstance(expected, bool):
        return shown in (("1", "True") if expected else ("0", "False"))
    if isinstance(expected, int) and not isinstance(expected, bool):
        try:
            return float(shown) == expected
        except ValueError:
            return str(expected) == shown
    if isinstance(expected, float):
        try:
            got = float(shown)
        except ValueError:
            return False
        return math.isclose(got, expected, rel_tol=1e-9, abs_tol=1e-12)
    return str(expected) == shown


def check_tcp_stream(tshark, lua, tmp, frames):
    """Orion frames as one TCP stream from port 8747, cut into 97-byte segments: tshark must
    reassemble and decode every frame, each checksum good. Returns a list of failures."""
    stream = b"".join(frames)
    text = []
    for start in range(0, len(stream), 97):
        seg = stream[start:start + 97]
        for i in range(0, len(seg), 16):
            text.append("%06x " % i + " ".join("%02x" % b for b in seg[i:i + 16]))
        text.append("")
    txt, pcap = os.path.join(tmp, "tcp.txt"), os.path.join(tmp, "tcp.pcap")
    with open(txt, "w") as f:
        f.write("\n".join(text) + "\n")
    text2pcap = shutil.which("text2pcap")
    if not text2pcap:
        return ["text2pcap missing (wireshark-common)"]
    subprocess.run([text2pcap, "-q", "-T", "8747,40000", txt, pcap], check=True,
                   capture_output=True)
    proc = subprocess.run([tshark, "-X", f"lua_script:{lua}", "-r", pcap, "-T", "fields",
                           "-e", "orion.packet", "-e", "orion.checksum.status"],
                          capture_output=True, text=True)
    names, statuses = [], []
    for line in proc.stdout.split("\n"):
        if line.strip():
            n, st = line.split("\t")
            names += n.split(",")
            statuses += st.split(",")
    if len(names) != len(frames) or set(statuses) != {"good"}:
        return [f"TCP stream: {len(frames)} frames sent, tshark decoded {len(names)} "
                f"({set(statuses)})"]
    return []


def main():
    codec_json, lua = sys.argv[1], sys.argv[2]
    tshark, status = tshark_tools.find_tshark()
    if not tshark:
        return status

    vectors = subprocess.run([codec_json, "vectors"], check=True, capture_output=True,
                             text=True).stdout.split("\n")
    lines = [line.split() for line in vectors if line.strip()]
    records = [(x[0], x[1]) for x in lines]
    subset = [len(x) > 2 and x[2] == "subset" for x in lines]
    invalid = [len(x) > 2 and x[2] == "invalid" for x in lines]
    n_orion = sum(1 for d, _ in records if d == "orion")
    if n_orion < 46:
        print(f"only {n_orion} Orion vectors")
        return 1
    # A valid packet with unknown trailing bytes, and a corrupted checksum.
    first = bytes.fromhex(records[0][1])
    data = first[4:-2] + b"\xa5\x5a\x01"
    extra = bytes([0xD0, 0x0D, first[2], len(data)]) + data
    extra += fletcher251(extra)
    bad = first[:-1] + bytes([first[-1] ^ 0x55])
    # geolocate_telemetry is 46..89 bytes: 45 is too short; id 250 has no layout.
    short = bytes([0xD0, 0x0D, 212, 45]) + bytes(45)
    short += fletcher251(short)
    unknown = bytes([0xD0, 0x0D, 250, 3, 1, 2, 3])
    unknown += fletcher251(unknown)
    out1 = bytes.fromhex(next(h for d, h in records if d == "viewpro"))
    bad_viewpro = out1[:-1] + bytes([out1[-1] ^ 0x01])
    specials = [("orion", extra.hex(), "extra"), ("orion", bad.hex(), "bad_checksum"),
                ("viewpro", bad_viewpro.hex(), "bad_checksum"),
                ("gimbald-json", b'{"id": 7, "cmd": "state"}'.hex(), "json"),
                ("orion", short.hex(), "too_short"), ("orion", unknown.hex(), "unknown_id")]

    decoded = subprocess.run([codec_json, "decode"], check=True, capture_output=True, text=True,
                             input="\n".join(f"{d} {h}" for d, h in records) + "\n"
                             ).stdout.split("\n")
    expected = [json.loads(line) for line in decoded if line.strip()]

    tmp = tempfile.mkdtemp(prefix="dissector-test-")
    path = os.path.join(tmp, "golden.pcapng")
    w = pcapng_writer.Writer(path, [("gimbal:golden", "orion sim"), ("json", "json")])
    t = 1_764_000_000_000_000
    for i, (d, h) in enumerate(records + [(d, h) for d, h, _ in specials]):
        w.packet(0, t + i * 1000, d, bytes.fromhex(h))
    w.close()

    proc = subprocess.run([tshark, "-X", f"lua_script:{lua}", "-r", path, "-T", "json"],
                          capture_output=True, text=True)
    if proc.returncode != 0:
        print(proc.stderr)
        return 1
    if "Lua" in proc.stderr or "lua" in proc.stderr:
        print("tshark reported a Lua problem:\n" + proc.stderr)
        return 1
    packets = json.loads(proc.stdout, object_pairs_hook=tshark_tools.pairs_keep_duplicates)
    failures = []
    checked = 0
    for i, pkt in enumerate(packets):
        layers = pkt["_source"][0]["layers"][0]
        d = (records + [(d, h) for d, h, _ in specials])[i][0]
        lenient = i >= len(records) or invalid[i]
        if (not lenient and "_ws.malformed" in layers) or d not in layers:
            failures.append(f"packet {i + 1} ({d}): not decoded or malformed: {list(layers)}")
            continue
        shown, expert = {}, []
        if isinstance(layers[d][0], dict):
            flatten_tshark(layers[d][0], shown, expert)
        severities = [e.get("_ws.expert.severity", [""])[0] for e in expert
                      if isinstance(e, dict)]
        messages = [e.get("_ws.expert.message", [""])[0] for e in expert
                    if isinstance(e, dict)]
        if i >= len(records):
            kind = specials[i - len(records)][2]
            if kind == "bad_checksum" and not any("checksum" in m.lower() for m in messages):
                failures.append(f"corrupted checksum: no checksum warning ({messages})")
            if kind == "too_short" and not any(s == "8388608" for s in severities):
                failures.append(f"a packet too short for its fields: no expert error ({messages})")
            if kind == "unknown_id" and ("orion.data" not in shown or any(
                    s in ("6291456", "8388608") for s in severities)):
                failures.append(f"unknown id: data not shown, or a warning ({messages})")
            if kind == "json" and "json" not in layers:
                failures.append(f"gimbald-json not handed to the json dissector: {list(layers)}")
            if kind == "extra" and "orion.extra" not in shown:
                failures.append("extra bytes not shown as orion.extra")
            continue
        exp = expected[i]
        if invalid[i]:
            # The codec rejects it: the dissector must say so with an expert error.
            if "error" not in exp or "8388608" not in severities:
                failures.append(f"packet {i + 1}: codec {exp.get('error')}, dissector {messages}")
            continue
        # Severity values: 0x00600000 warn, 0x00800000 error.
        if any(s in ("6291456", "8388608") for s in severities):
            failures.append(f"packet {i + 1}: expert warnings on a valid packet: {messages}")
        if "fields" not in exp:
            failures.append(f"packet {i + 1}: the codec does not decode it: {exp}")
            continue
        if d == "orion":
            prefix = "orion." + exp["name"]
        elif d == "mavlink":
            prefix = "mavlink"
            if shown.get("mavlink.msgname", ["MSG"])[0].startswith("MSG"):
                failures.append(f"packet {i + 1}: MAVLink message {exp['fields']['msgid']} "
                                "has no name in the dissector")
        else:
            prefix = "viewpro"
            if shown.get("viewpro.frame") != [exp["kind"]]:
                failures.append(f"packet {i + 1}: frame {shown.get('viewpro.frame')}, "
                                f"codec {exp['kind']}")
        want = {}
        flatten_codec(prefix, exp["fields"], want)
        for field, values in want.items():
            got = shown.get(field)
            if subset[i] and got is None:
                continue  # absent from the optional tail: the codec reports its default
            if got is None or len(got) != len(values):
                failures.append(f"{field}: codec {values}, dissector {got}")
                continue
            for e, g in zip(values, got):
                checked += 1
                if not same(e, g):
                    failures.append(f"{field}: codec {e}, dissector {g}")
        for field in shown:
            if field in HEADER_FIELDS or field in want or field.startswith("_ws"):
                continue
            if field.split(".")[-1] in COUNT_KEYS:
                continue
            if field.endswith("_tree") or field in ("orion." + exp.get("name", ""),):
                continue
            failures.append(f"{field}: shown by the dissector, not in the codec's JSON")
    orion_frames = [bytes.fromhex(h) for d, h in records if d == "orion"]
    failures += check_tcp_stream(tshark, lua, tmp, orion_frames)
    print(f"{len(packets)} packets, {checked} field values compared, "
          f"{len(orion_frames)} Orion frames over TCP")
    for f in failures:
        print("FAIL", f)
    if len(packets) != len(records) + len(specials):
        print(f"tshark read {len(packets)} packets of {len(records) + len(specials)}")
        return 1
    shutil.rmtree(tmp)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
