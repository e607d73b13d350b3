#!/usr/bin/env python3
"""The flight recorder (contract section 12, docs/recording.md) end to end: a real gimbald
records a real gimbal-sim over TCP, a MAVLink vehicle feed and JSON requests; tshark reads
the files; a small pcapng parser written here from the pcapng spec checks the bytes.

Checks: interfaces and dissector names, direction flags, JSON request/reply pairs, the
inbound Orion PDUs are whole checksum-valid frames whose byte total equals STATE rx_bytes,
the outbound ones equal what the simulator received, rotation and the total-size cap,
kill -9 and a file cut mid-block, STATE `record`, and configuration errors.
"""

import glob
import resource
import json
import os
import shutil
import signal
import socket
import struct
import subprocess
import time
import unittest

import gimbaltest as gt
import skipping

TSHARK = shutil.which("tshark")
JSON_REPLY_KEYS = ("ok", "id")


# --- a minimal pcapng reader (test only) -----------------------------------------------------

def read_blocks(data):
    """[(type, body)] of every whole block, and the offset where whole blocks end."""
    blocks, at = [], 0
    while len(data) - at >= 12:
        btype, blen = struct.unpack_from("<II", data, at)
        if blen < 12 or blen % 4 or at + blen > len(data):
            break
        if struct.unpack_from("<I", data, at + blen - 4)[0] != blen:
            raise AssertionError("block at %d: trailing length differs" % at)
        blocks.append((btype, data[at + 8:at + blen - 4]))
        at += blen
    return blocks, at


def options(body):
    out, at = {}, 0
    while at + 4 <= len(body):
        code, length = struct.unpack_from("<HH", body, at)
        if code == 0:
            break
        out.setdefault(code, []).append(body[at + 4:at + 4 + length])
        at += 4 + (length + 3) // 4 * 4
    return out


def parse(path):
    """{"interfaces": [(name, description, linktype, tsresol)], "packets": [dict]}"""
    with open(path, "rb") as f:
        data = f.read()
    blocks, end = read_blocks(data)
    result = {"interfaces": [], "packets": [], "whole_bytes": end, "size": len(data),
              "userappl": None}
    for btype, body in blocks:
        if btype == 0x0A0D0D0A:
            magic, major, minor = struct.unpack_from("<IHH", body, 0)
            assert (magic, major, minor) == (0x1A2B3C4D, 1, 0), (magic, major, minor)
            result["userappl"] = options(body[16:]).get(4, [b""])[0].decode()
        elif btype == 1:
            linktype, _, snaplen = struct.unpack_from("<HHI", body, 0)
            opts = options(body[8:])
            result["interfaces"].append((opts[2][0].decode(), opts[3][0].decode(), linktype,
                                         opts[9][0][0], snaplen))
        elif btype == 6:
            iface, hi, lo, caplen, origlen = struct.unpack_from("<IIIII", body, 0)
            pkt = body[20:20 + caplen]
            flags = struct.unpack("<I", options(body[20 + (caplen + 3) // 4 * 4:])[2][0])[0]
            # exported-PDU TLVs, big-endian; the length counts the NUL padding
            at, dissector = 0, None
            while True:
                tag, length = struct.unpack_from(">HH", pkt, at)
                value = pkt[at + 4:at + 4 + length]
                at += 4 + length
                if tag == 0:
                    break
                if tag == 12:
                    dissector = value.rstrip(b"\0").decode()
            result["packets"].append({"iface": iface, "ts_us": (hi << 32) | lo,
                                      "caplen": caplen, "origlen": origlen, "flags": flags,
                                      "dissector": dissector, "pdu": pkt[at:]})
        else:
            raise AssertionError("unexpected block type %#x" % btype)
    return result


def fletcher_ok(frame):
    return gt.frame(frame[2], frame[4:-2]) == frame


def tshark_fields(path, *fields):
    """(exit code, rows, stderr) of tshark -T fields."""
    args = [TSHARK, "-r", path, "-T", "fields"]
    for f in fields:
        args += ["-e", f]
    proc = subprocess.run(args, capture_output=True, timeout=60)
    rows = [line.split("\t") for line in proc.stdout.decode().splitlines()]
    return proc.returncode, rows, proc.stderr.decode()


def mavlink_heartbeat(seq):
    """A MAVLink v2 HEARTBEAT (id 0, CRC_EXTRA 50) from system 1."""
    payload = struct.pack("<IBBBBB", 0, 2, 3, 0, 4, 3)
    body = struct.pack("<BBBBBB", len(payload), 0, 0, seq, 1, 1) + b"\0\0\0" + payload
    crc = 0xFFFF
    for b in body + bytes([50]):
        tmp = b ^ (crc & 0xFF)
        tmp = (tmp ^ (tmp << 4)) & 0xFF
        crc = ((crc >> 8) ^ (tmp << 8) ^ (tmp << 3) ^ (tmp >> 4)) & 0xFFFF
    return b"\xfd" + body + struct.pack("<H", crc)


class LimitedDaemon(gt.Daemon):
    """gimbald under a file-size limit (ulimit -f): its writes past `limit` bytes fail with
    EFBIG, as on a full disk."""

    limit = 0

    def _launch(self):
        limit = self.limit

        def preexec():
            resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))
        real_popen = subprocess.Popen
        subprocess.Popen = lambda *a, **k: real_popen(*a, preexec_fn=preexec, **k)
        try:
            super()._launch()
        finally:
            subprocess.Popen = real_popen


def recordings(directory):
    return sorted(glob.glob(os.path.join(directory, "gimbald-*.pcapng")))


class Recording(gt.GimbaldTestCase):
    def setUp(self):
        super().setUp()
        if not TSHARK:
            skipping.need(self, "tshark not installed (scripts/install-deps.sh)")
        self.dir = os.path.join(self.workdir, "rec")
        os.mkdir(self.dir)

    def record_config(self, sim_port, **record):
        config = {"gimbals": [gt.orion_tcp("main", sim_port)],
                  "record": dict({"dir": self.dir}, **record)}
        return config

    def test_a_flight_is_recorded_completely(self):
        sim = self.start_sim("--junk-every", "25")
        mav_port = gt.free_port()
        config = self.record_config(sim.port)
        config["vehicle"] = {"source": {"type": "udp", "bind": "127.0.0.1", "port": mav_port}}
        config["mavlink"] = {"gimbal_manager": True}  # gimbald answers on the vehicle link
        daemon = self.start_daemon(config)
        c = self.client(daemon)
        self.wait_connected(c)

        sent_ids = []
        reply = c.request("geopoint", lat=45.71, lon=-121.49, alt=120.0)
        self.assertOk(reply)
        sent_ids.append(reply["id"])
        mav = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.addCleanup(mav.close)
        heartbeats = [mavlink_heartbeat(i) for i in range(5)]
        for hb in heartbeats:
            mav.sendto(hb, ("127.0.0.1", mav_port))
            time.sleep(0.1)
        mav.settimeout(2.0)
        heard = [mav.recv(1024) for _ in range(3)]  # gimbald's frames to the peer it heard
        for _ in range(3):
            reply = c.request("state")
            self.assertOk(reply)
            sent_ids.append(reply["id"])
        time.sleep(1.0)

        record = c.request("state")["state"]["record"]
        self.assertEqual(set(record), {"file", "bytes", "dropped"})
        self.assertEqual(os.path.dirname(record["file"]), self.dir)
        self.assertRegex(os.path.basename(record["file"]),
                         r"^gimbald-\d{8}T\d{6}Z-\d{4,}\.pcapng$")
        self.assertEqual(record["dropped"], 0)
        self.assertTrue(gt.wait_for(
            lambda: c.request("state")["state"]["record"]["bytes"] > record["bytes"], 3.0),
            "STATE record.bytes does not grow")

        # Silence the gimbal, then read the link counters the recording must match.
        sim.stop()
        link = gt.wait_for(lambda: (lambda s: s if not s["connected"] else None)(
            c.request("state")["state"]["link"]), 5.0)
        self.assertTrue(link, "link never went down")
        self.assertEqual(daemon.stop(signal.SIGTERM), 0)

        files = recordings(self.dir)
        self.assertEqual(files, [record["file"]])
        self.assertEqual(os.stat(files[0]).st_mode & 0o777 & ~0o640, 0, "readable by others")
        rec = parse(files[0])
        self.assertEqual(rec["whole_bytes"], rec["size"], "SIGTERM left a partial block")
        self.assertTrue(rec["userappl"].startswith("gimbald "))
        self.assertEqual([(i[0], i[2], i[3], i[4]) for i in rec["interfaces"]],
                         [("gimbal:main", 252, 6, 0), ("mavlink", 252, 6, 0),
                          ("json", 252, 6, 0)])
        self.assertEqual(rec["interfaces"][0][1], "orion tcp 127.0.0.1:%d" % sim.port)
        packets = rec["packets"]
        for p in packets:
            self.assertEqual(p["caplen"], p["origlen"])
            self.assertIn(p["flags"], (1, 2))
        now_us = time.time() * 1e6
        self.assertTrue(all(now_us - 120e6 < p["ts_us"] <= now_us for p in packets))
        self.assertEqual([p["ts_us"] for p in packets], sorted(p["ts_us"] for p in packets))

        # The gimbal link, inbound: whole frames plus the junk between them, every byte.
        inbound = [p for p in packets if p["iface"] == 0 and p["flags"] == 1]
        self.assertEqual({p["dissector"] for p in inbound}, {"orion", "data"})
        frames = [p["pdu"] for p in inbound if p["dissector"] == "orion"]
        self.assertTrue(all(f[:2] == b"\xd0\x0d" and fletcher_ok(f) for f in frames))
        self.assertEqual(len(frames), link["rx_packets"])
        self.assertEqual(sum(len(p["pdu"]) for p in inbound), link["rx_bytes"])
        self.assertEqual(sum(len(p["pdu"]) for p in inbound if p["dissector"] == "data"),
                         link["dropped_bytes"])
        # Outbound: exactly the frames the simulator received, in order.
        outbound = [p for p in packets if p["iface"] == 0 and p["flags"] == 2]
        self.assertEqual({p["dissector"] for p in outbound}, {"orion"})
        self.assertEqual([p["pdu"].hex() for p in outbound], [e["hex"] for e in sim.rx()])
        self.assertIn("geopoint_cmd", [e["name"] for e in sim.rx()])

        # MAVLink: the datagrams as sent.
        mav_in = [p["pdu"] for p in packets if p["iface"] == 1 and p["flags"] == 1]
        self.assertEqual(mav_in, heartbeats)
        self.assertTrue(all(p["dissector"] == "mavlink" for p in packets if p["iface"] == 1))
        mav_out = [p["pdu"] for p in packets if p["iface"] == 1 and p["flags"] == 2]
        self.assertTrue(all(f[0] == 0xFD for f in mav_out))
        self.assertIn(heard[0], mav_out)
        start = mav_out.index(heard[0])
        self.assertEqual(mav_out[start:start + len(heard)], heard)

        # JSON: every request inbound, its reply outbound right after it.
        js = [p for p in packets if p["iface"] == 2]
        self.assertTrue(all(p["dissector"] == "gimbald-json" for p in js))
        requests = [json.loads(p["pdu"]) for p in js if p["flags"] == 1]
        replies = [json.loads(p["pdu"]) for p in js if p["flags"] == 2]
        for request_id in sent_ids:
            self.assertIn(request_id, [r.get("id") for r in requests])
            self.assertIn(request_id, [r.get("id") for r in replies])
        self.assertEqual([r.get("id") for r in requests], [r.get("id") for r in replies])
        geopoint = next(r for r in requests if r.get("cmd") == "geopoint")
        self.assertEqual(geopoint["lat"], 45.71)

        # tshark agrees: no error, same interfaces, dissector names and directions.
        code, rows, err = tshark_fields(files[0], "frame.interface_id", "frame.interface_name",
                                        "exported_pdu.prot_name",
                                        "frame.packet_flags_direction")
        self.assertEqual(code, 0, err)
        self.assertEqual(len(rows), len(packets))
        names = ["gimbal:main", "mavlink", "json"]
        for row, p in zip(rows, packets):
            self.assertEqual(int(row[0]), p["iface"])
            self.assertEqual(row[1], names[p["iface"]])
            self.assertEqual(row[2], p["dissector"])
            self.assertEqual(int(row[3], 0), p["flags"])

    def test_rotation_and_total_cap(self):
        sim = self.start_sim()
        daemon = self.start_daemon(self.record_config(sim.port, max_file_mb=0.02,
                                                      max_total_mb=0.07))
        c = self.client(daemon)
        self.wait_connected(c)
        # Enough files for the cap to delete some: about 5 files' worth of telemetry.
        self.assertTrue(gt.wait_for(lambda: daemon.events("record_file")
                                    and len(daemon.events("record_file")) >= 6, 60.0, 0.2),
                        "fewer than 6 files opened: %s" % daemon.events("record_file"))
        self.assertEqual(daemon.stop(signal.SIGTERM), 0)
        opened = [e["file"] for e in daemon.events("record_file")]
        # Every file started is logged once, in order: sequence numbers 1..N.
        self.assertEqual([int(f.rsplit("-", 1)[1].split(".")[0]) for f in opened],
                         list(range(1, len(opened) + 1)))
        files = recordings(self.dir)
        self.assertEqual(files, sorted(files))
        self.assertEqual(files, opened[-len(files):], "newest files kept, in name order")
        self.assertNotIn(opened[0], files, "oldest file not deleted")
        self.assertLessEqual(sum(os.path.getsize(f) for f in files), 70000)
        for f in files:
            rec = parse(f)
            self.assertEqual(rec["whole_bytes"], rec["size"])
            self.assertLessEqual(rec["size"], 20000)
            self.assertEqual([i[0] for i in rec["interfaces"]], ["gimbal:main", "json"])
            code, rows, err = tshark_fields(f, "frame.interface_id")
            self.assertEqual(code, 0, err)
            self.assertEqual(len(rows), len(rec["packets"]))
            self.assertGreater(len(rows), 0)

    def test_kill_9_leaves_a_readable_file(self):
        sim = self.start_sim()
        daemon = self.start_daemon(self.record_config(sim.port))
        c = self.client(daemon)
        self.wait_connected(c)
        path = c.request("state")["state"]["record"]["file"]
        self.assertTrue(gt.wait_for(lambda: os.path.getsize(path) > 4000, 10.0))
        daemon.stop(signal.SIGKILL)
        rec = parse(path)
        self.assertGreater(len(rec["packets"]), 10)
        self.assertEqual(rec["whole_bytes"], rec["size"], "partial block after kill -9")
        code, rows, err = tshark_fields(path, "frame.interface_id")
        self.assertEqual(code, 0, err)
        self.assertEqual(len(rows), len(rec["packets"]))

        # A copy cut in the middle of its last block (power loss before the block was
        # complete): every whole block is still listed.
        cut = os.path.join(self.workdir, "cut.pcapng")
        with open(path, "rb") as f:
            data = f.read()
        last_len = struct.unpack_from("<I", data, len(data) - 4)[0]
        with open(cut, "wb") as f:
            f.write(data[:len(data) - last_len // 2])
        whole = parse(cut)
        self.assertEqual(len(whole["packets"]), len(rec["packets"]) - 1)
        code, rows, err = tshark_fields(cut, "frame.interface_id")
        self.assertEqual(len(rows), len(whole["packets"]), err)
        # tshark reports the cut block (exit 2, "cut short in the middle of a packet") but
        # lists every whole one first.
        self.assertIn(code, (0, 2))
        if code:
            self.assertIn("cut short", err)

    def test_disk_full_is_logged_and_counted_and_gimbald_keeps_running(self):
        sim = self.start_sim()
        LimitedDaemon.limit = 16000  # the recording reaches it in a few seconds
        daemon = LimitedDaemon(self.workdir, self.record_config(sim.port))
        self.addCleanup(gt.finish_daemon, daemon)
        c = self.client(daemon)
        self.wait_connected(c)
        error = daemon.wait_log(lambda e: e.get("event") == "record_write_error", 30.0)
        self.assertTrue(error, "no record_write_error: %s" % daemon.log_text()[-2000:])
        self.assertIn("File too large", error["error"])
        self.assertIn(self.dir, error["error"])
        record = c.request("state")["state"]["record"]
        self.assertGreater(record["dropped"], 0)
        self.assertTrue(daemon.running())
        # Still serving: the gimbal link and the command socket are unaffected.
        before = c.request("state")["state"]["link"]["rx_packets"]
        self.assertTrue(gt.wait_for(
            lambda: c.request("state")["state"]["link"]["rx_packets"] > before + 5, 5.0))
        self.assertEqual(daemon.stop(signal.SIGTERM), 0)
        rec = parse(record["file"])
        self.assertEqual(rec["whole_bytes"], rec["size"], "a failed write left a partial block")
        self.assertLessEqual(rec["size"], 16000)
        code, rows, err = tshark_fields(record["file"], "frame.interface_id")
        self.assertEqual(code, 0, err)
        self.assertEqual(len(rows), len(rec["packets"]))

    def test_a_nearly_full_disk_keeps_what_fits(self):
        # Contract section 14: one chunk larger than the room left is written as far as whole
        # blocks fit, not dropped whole (a 512 KiB filesystem stayed at 6,268 bytes).
        sim = self.start_sim()
        LimitedDaemon.limit = 16000
        daemon = LimitedDaemon(self.workdir, self.record_config(sim.port))
        self.addCleanup(gt.finish_daemon, daemon)
        c = self.client(daemon)
        self.wait_connected(c)
        before = c.request("state")["state"]["record"]["bytes"]
        self.assertLess(before, 8000)
        # One burst of requests, recorded with their replies: ~30 KB in one writer chunk.
        for i in range(15):
            c.send({"cmd": "ping", "id": i, "pad": "x" * 1000})
        self.assertTrue(daemon.wait_log(lambda e: e.get("event") == "record_write_error", 5.0))
        record = c.request("state")["state"]["record"]
        # Within one block (the largest here is a ~1.1 KB request) of the limit at once.
        self.assertGreater(record["bytes"], 16000 - 1500, record)
        self.assertLessEqual(record["bytes"], 16000)
        self.assertEqual(daemon.stop(signal.SIGTERM), 0)
        rec = parse(record["file"])
        self.assertEqual(rec["whole_bytes"], rec["size"], "a block was cut")
        self.assertGreater(rec["size"], 16000 - 1500)

    def test_configuration_errors_name_the_path(self):
        missing = os.path.join(self.workdir, "no-such-dir")
        a_file = os.path.join(self.workdir, "a-file")
        with open(a_file, "w") as f:
            f.write("x")
        cases = [(missing, "No such file"), (a_file, "not a directory")]
        if os.geteuid() != 0:  # root writes anywhere
            read_only = os.path.join(self.workdir, "read-only")
            os.mkdir(read_only, 0o500)
            cases.append((read_only, "not writable: Permission denied"))
        for directory, reason in cases:
            config_path = os.path.join(self.workdir, "bad.json")
            with open(config_path, "w") as f:
                json.dump({"gimbals": [gt.orion_tcp("main", 1)], "record": {"dir": directory}},
                          f)
            for extra in (["--check-config"], []):  # start-up: exit 1 before opening anything
                proc = subprocess.run([gt.GIMBALD, "-c", config_path] + extra,
                                      capture_output=True, timeout=20)
                text = (proc.stdout + proc.stderr).decode()
                self.assertEqual(proc.returncode, 1, text)
                self.assertIn("record.dir", text)
                self.assertIn(directory, text)
                self.assertIn(reason, text)
        bad = {"gimbals": [gt.orion_tcp("main", 1)],
               "record": {"dir": self.dir, "max_file_mb": 10, "max_total_mb": 5, "x": 1}}
        with open(config_path, "w") as f:
            json.dump(bad, f)
        proc = subprocess.run([gt.GIMBALD, "-c", config_path, "--check-config"],
                              capture_output=True, timeout=20)
        text = (proc.stdout + proc.stderr).decode()
        self.assertEqual(proc.returncode, 1)
        self.assertIn("record.max_total_mb", text)
        self.assertIn("record.x", text)

    def test_viewpro_and_sim_links(self):
        daemon = self.start_daemon({"record": {"dir": self.dir}}, ("--sim", "orion,viewpro"))
        c = self.client(daemon)
        self.wait_connected(c, "sim-orion")
        self.wait_connected(c, "sim-viewpro", telemetry=False)
        self.assertTrue(gt.wait_for(
            lambda: c.request("state", gimbal="sim-viewpro")["state"].get("output"), 5.0))
        time.sleep(1.5)  # a few more output frames
        self.assertEqual(daemon.stop(signal.SIGTERM), 0)
        files = recordings(self.dir)
        self.assertEqual(len(files), 1)
        rec = parse(files[0])
        self.assertEqual([i[:2] for i in rec["interfaces"]],
                         [("gimbal:sim-orion", "orion sim"), ("gimbal:sim-viewpro", "viewpro sim"),
                          ("json", "gimbald JSON requests and replies")])
        viewpro_in = [p for p in rec["packets"] if p["iface"] == 1 and p["flags"] == 1]
        self.assertGreater(len(viewpro_in), 5)
        self.assertEqual({p["dissector"] for p in viewpro_in}, {"viewpro"})
        self.assertTrue(all(p["pdu"][0] == 0xFE for p in viewpro_in))
        viewpro_out = [p for p in rec["packets"] if p["iface"] == 1 and p["flags"] == 2]
        self.assertEqual({p["dissector"] for p in viewpro_out}, {"viewpro"})
        self.assertTrue(viewpro_out, "the mode command sent on connect is not recorded")
        orion_in = [p for p in rec["packets"] if p["iface"] == 0 and p["flags"] == 1]
        self.assertTrue(all(fletcher_ok(p["pdu"]) for p in orion_in))
        code, rows, err = tshark_fields(files[0], "frame.interface_name",
                                        "exported_pdu.prot_name")
        self.assertEqual(code, 0, err)
        self.assertEqual(len(rows), len(rec["packets"]))

    def test_state_record_is_null_when_off(self):
        daemon = self.start_daemon({"gimbals": [{"name": "sim", "protocol": "orion",
                                                 "link": {"type": "sim"}}]})
        c = self.client(daemon)
        self.wait_connected(c)
        self.assertIsNone(c.request("state")["state"]["record"])
        self.assertEqual(recordings(self.dir), [])


if __name__ == "__main__":
    gt.main()
