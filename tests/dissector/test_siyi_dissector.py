"""tshark with lib/protocols/siyi/dissector/siyi.lua decodes SIYI frames exactly as the C++ codec.

usage: test_siyi_dissector.py SIYI_DISSECTOR_DATA SIYI_LUA

The SDK's golden frames and every message of both directions filled with random bytes
(printed with the codec's JSON by siyi-dissector-data --vectors) go into a pcapng of
exported-PDU records named `siyi`, requests outbound and replies inbound, as gimbald's
recordings hold them; tshark decodes it with the dissector (-T json). Every field of the
codec's JSON must be shown with the same value (numbers to 1e-9 relative), and the dissector
may show no message field the codec does not. A corrupted CRC gets the CRC warning; frames in a
live UDP capture (port 37260) are decoded by direction of the port.
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

# Keys of the codec's frame JSON that are the header, shown under siyi.* of their own.
HEADER = {"cmd": "siyi.cmd", "ctrl": "siyi.ctrl", "seq": "siyi.seq"}



def flatten(node, out, expert):
    for key, values in node.items():
        for v in values:
            if key == "_ws.expert":
                expert.append(v)
            if isinstance(v, dict):
                flatten(v, out, expert)
            else:
                out.setdefault(key, []).append(v)


def same(expected, shown):
    if isinstance(expected, bool):
        return shown in (("1", "True") if expected else ("0", "False"))
    if isinstance(expected, (int, float)):
        try:
            got = float(int(shown, 16)) if shown.startswith("0x") else float(shown)
        except ValueError:
            return str(expected) == shown
        return math.isclose(got, float(expected), rel_tol=1e-9, abs_tol=1e-12)
    return str(expected) == shown


def tshark_json(tshark, lua, path):
    proc = subprocess.run([tshark, "-X", f"lua_script:{lua}", "-r", path, "-T", "json"],
                          capture_output=True, text=True)
    if proc.returncode != 0 or "lua" in proc.stderr.lower():
        raise RuntimeError("tshark failed or reported a Lua problem:\n" + proc.stderr)
    return json.loads(proc.stdout, object_pairs_hook=tshark_tools.pairs_keep_duplicates)


def layer(pkt):
    layers = pkt["_source"][0]["layers"][0]
    shown, expert = {}, []
    if "siyi" in layers:
        for node in layers["siyi"]:
            if isinstance(node, dict):
                flatten(node, shown, expert)
    messages = [e.get("_ws.expert.message", [""])[0] for e in expert if isinstance(e, dict)]
    severities = [e.get("_ws.expert.severity", [""])[0] for e in expert if isinstance(e, dict)]
    return layers, shown, messages, severities


def compare(i, vector, shown, severities, messages):
    """Failures of one decoded frame against the codec's JSON."""
    failures, checked = [], 0
    codec = vector["codec"]
    if "error" in codec:
        if shown.get("siyi.error") != [codec["error"]]:
            failures.append(f"frame {i}: codec error {codec['error']}, dissector "
                            f"{shown.get('siyi.error')}")
        return failures, checked
    # Severity values: 0x00600000 warn, 0x00800000 error.
    if any(s in ("6291456", "8388608") for s in severities):
        failures.append(f"frame {i} ({codec['message']}): expert warnings: {messages}")
    if shown.get("siyi.message") != [codec["message"]]:
        failures.append(f"frame {i}: message {shown.get('siyi.message')}, codec "
                        f"{codec['message']}")
        return failures, checked
    if shown.get("siyi.crc.status") != ["good"]:
        failures.append(f"frame {i}: CRC {shown.get('siyi.crc.status')}")
    prefix = "siyi." + codec["message"] + "."
    for key, value in codec.items():
        if key == "message":
            continue
        field = HEADER.get(key, prefix + key)
        got = shown.get(field)
        if got is None and vector.get("partial"):
            continue  # an optional field the frame does not carry: the codec shows its default
        if got is None or len(got) != 1:
            failures.append(f"frame {i}: {field}: codec {value}, dissector {got}")
            continue
        checked += 1
        if not same(value, got[0]):
            failures.append(f"frame {i}: {field}: codec {value!r}, dissector {got[0]!r}")
    for field in shown:
        if field.startswith(prefix) and field[len(prefix):] not in codec:
            failures.append(f"frame {i}: {field} shown by the dissector, not in the codec's JSON")
    return failures, checked


def main():
    data_tool, lua = sys.argv[1], sys.argv[2]
    tshark, status = tshark_tools.find_tshark()
    if not tshark:
        return status

    out = subprocess.run([data_tool, "--vectors", "7"], check=True, capture_output=True,
                         text=True).stdout
    vectors = [json.loads(line) for line in out.split("\n") if line.strip()]
    directions = {v["direction"] for v in vectors}
    decoded = sum(1 for v in vectors if "error" not in v["codec"])
    if len(vectors) < 100 or directions != {"to_gimbal", "from_gimbal"} or decoded < 90:
        print(f"too few vectors: {len(vectors)} ({decoded} decoded, {directions})")
        return 1

    # A corrupted CRC, and the attitude reply as one UDP datagram from the camera's port.
    attitude = next(v for v in vectors if v["codec"].get("message") == "gimbal_attitude")
    good = bytes.fromhex(attitude["hex"])
    bad = good[:-1] + bytes([good[-1] ^ 0x5A])

    tmp = tempfile.mkdtemp(prefix="siyi-dissector-test-")
    path = os.path.join(tmp, "siyi.pcapng")
    w = pcapng_writer.Writer(path, [("gimbal:siyi", "siyi sim")])
    t = 1_764_000_000_000_000
    for i, v in enumerate(vectors):
        direction = pcapng_writer.INBOUND if v["direction"] == "from_gimbal" else \
            pcapng_writer.OUTBOUND
        w.packet(0, t + i * 1000, "siyi", bytes.fromhex(v["hex"]), direction)
    w.packet(0, t + len(vectors) * 1000, "siyi", bad, pcapng_writer.INBOUND)
    w.close()

    failures, checked = [], 0
    packets = tshark_json(tshark, lua, path)
    if len(packets) != len(vectors) + 1:
        print(f"tshark read {len(packets)} packets of {len(vectors) + 1}")
        return 1
    for i, (pkt, vector) in enumerate(zip(packets, vectors)):
        layers, shown, messages, severities = layer(pkt)
        if "siyi" not in layers or "_ws.malformed" in layers:
            failures.append(f"frame {i}: not decoded or malformed: {list(layers)}")
            continue
        f, n = compare(i, vector, shown, severities, messages)
        failures += f
        checked += n
    _, shown, messages, _ = layer(packets[-1])
    if shown.get("siyi.crc.status") != ["bad"] or not any("CRC" in m for m in messages):
        failures.append(f"corrupted CRC: status {shown.get('siyi.crc.status')}, {messages}")

    # Live capture: the same reply as a UDP datagram from 192.168.144.25:37260.
    txt, pcap = os.path.join(tmp, "udp.txt"), os.path.join(tmp, "udp.pcap")
    with open(txt, "w") as f:
        f.write("000000 " + " ".join("%02x" % b for b in good) + "\n")
    text2pcap = shutil.which("text2pcap")
    if not text2pcap:
        failures.append("text2pcap missing (wireshark-common)")
    else:
        subprocess.run([text2pcap, "-q", "-u", "37260,40000", txt, pcap], check=True,
                       capture_output=True)
        udp = tshark_json(tshark, lua, pcap)
        layers, shown, messages, severities = layer(udp[0])
        f, n = compare("udp", attitude, shown, severities, messages)
        failures += f
        checked += n

    print(f"{len(packets)} recorded frames and 1 UDP datagram, {checked} field values "
          f"compared ({decoded} frames decoded by the codec)")
    for f in failures[:40]:
        print("FAIL", f)
    shutil.rmtree(tmp)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
