"""Random Orion, Viewpro and MAVLink frames (fixed seed) never make the dissector fail.

usage: test_random_frames.py GIMBALD_LUA

Orion frames of every id with random data of every length (and some cut short), Viewpro
frames with every header and random lengths, MAVLink v1/v2 starts with random bytes: tshark
must read them all without a single "Lua Error" (a Lua error is what a range check the
interpreter forgot would look like).
"""
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import pcapng_writer  # noqa: E402
import tshark_tools  # noqa: E402


def fletcher251(data):
    a, b = 1, 0
    for x in data:
        a = (a + x) % 251
        b = (b + a) % 251
    return bytes([a, b])


def main():
    lua = sys.argv[1]
    tshark, status = tshark_tools.find_tshark()
    if not tshark:
        return status
    rng = random.Random(20261125)
    with open(lua) as f:
        ids = [int(x) for x in re.findall(r"^  \[(\d+)\] = \{ name", f.read(), re.M)]
    if len(ids) < 46:
        print(f"only {len(ids)} Orion packets in the schema")
        return 1
    tmp = tempfile.mkdtemp(prefix="dissector-random-")
    path = os.path.join(tmp, "random.pcapng")
    w = pcapng_writer.Writer(path, [("gimbal:random", "random")])
    t = 1_764_000_000_000_000
    count = 0

    def put(dissector, pdu):
        nonlocal count
        w.packet(0, t + count, dissector, pdu)
        count += 1

    for _ in range(3000):
        length = rng.randint(0, 140)
        frame = bytes([0xD0, 0x0D, rng.choice(ids + [0, 4, 250]), length])
        frame += rng.randbytes(length)
        frame += fletcher251(frame)
        if rng.random() < 0.1:
            frame = frame[:rng.randint(0, len(frame))]
        put("orion", frame)
    for _ in range(600):
        head = rng.choice([b"\xfe\xfb", b"\xfe\xfc", b"\xfe\xfd", b"\xf9\xfb", b"\xf9\xfc",
                           b"\xaa\x55"])
        length = rng.choice([5, 23, 34, 40, 60, 76, rng.randint(0, 80)])
        put("viewpro", (head + rng.randbytes(max(0, length - 2)))[:length])
    for _ in range(600):
        put("mavlink", bytes([rng.choice([0xFD, 0xFE])]) + rng.randbytes(rng.randint(0, 60)))
    w.close()

    proc = subprocess.run([tshark, "-X", f"lua_script:{lua}", "-r", path, "-V"],
                          capture_output=True, text=True)
    errors = sorted({line.strip() for line in proc.stdout.split("\n") if "Lua Error" in line})
    frames = proc.stdout.count("\nFrame ") + proc.stdout.startswith("Frame ")
    print(f"{count} random records, tshark showed {frames}, {len(errors)} distinct Lua errors")
    for e in errors[:20]:
        print("FAIL", e)
    if proc.returncode != 0 or "Lua" in proc.stderr:
        print(proc.stderr)
        return 1
    shutil.rmtree(tmp)
    return 1 if errors or frames != count else 0


if __name__ == "__main__":
    sys.exit(main())
