"""Helpers of the video integration tests (test_gimbald_video*.py), standard library only.

- H.264 access units made by FFmpeg's libx264 (the `ffmpeg` tool), split here;
- an MPEG-TS writer written from ISO/IEC 13818-1 (PAT, PMT with a KLVA registration
  descriptor, PES, continuity counters, CRC-32/MPEG-2), so a test can craft exactly the
  stream it needs: junk, lost packets, a PID change, a restarted encoder, a KLV set with a
  wrong checksum;
- MISB ST 0601 sets built by hand (key, BER length, items, running-sum checksum);
- a UDP collector and a small TS reader that pulls the KLV PES payloads out of an output;
- ffprobe and GStreamer (tsdemux -> meta/x-klv) runners: tools nobody here wrote.
"""

import json
import os
import shutil
import socket
import struct
import subprocess
import threading
import time

UAS_LS_KEY = bytes.fromhex("060E2B34020B01010E01030101000000")
PTS_HZ = 90000


def have(tool):
    return shutil.which(tool) is not None


# --- H.264 -----------------------------------------------------------------------------------

def h264_access_units(workdir, width=320, height=240, fps=15, seconds=2, name="clip"):
    """Access units (Annex B bytes) of a libx264 test clip: an AUD first in each, SPS and PPS
    before every key frame (one a second)."""
    path = os.path.join(workdir, "%s-%dx%d.h264" % (name, width, height))
    if not os.path.exists(path):
        subprocess.run(
            ["ffmpeg", "-v", "error", "-y", "-f", "lavfi", "-i",
             "testsrc=size=%dx%d:rate=%d" % (width, height, fps), "-t", str(seconds),
             "-pix_fmt", "yuv420p", "-c:v", "libx264", "-profile:v", "baseline",
             "-preset", "ultrafast",
             "-g", str(fps), "-x264-params", "aud=1:repeat-headers=1", "-bsf:v",
             "h264_mp4toannexb", "-f", "h264", path],
            check=True, capture_output=True, timeout=60)
    with open(path, "rb") as f:
        data = f.read()
    starts = []
    i = 0
    while True:
        i = data.find(b"\x00\x00\x01", i)
        if i < 0:
            break
        starts.append(i)
        i += 3
    units = []
    current_start = None
    for s in starts:
        nal_type = data[s + 3] & 0x1F
        begin = s - 1 if s > 0 and data[s - 1] == 0 else s
        if nal_type == 9:  # access unit delimiter: a new access unit
            if current_start is not None:
                units.append(data[current_start:begin])
            current_start = begin
    if current_start is not None:
        units.append(data[current_start:])
    return units


# --- MPEG-TS ---------------------------------------------------------------------------------

def crc32_mpeg(data):
    crc = 0xFFFFFFFF
    for byte in data:
        crc ^= byte << 24
        for _ in range(8):
            crc = ((crc << 1) ^ 0x04C11DB7) if crc & 0x80000000 else (crc << 1)
            crc &= 0xFFFFFFFF
    return crc


def _timestamp(prefix, ts):
    ts &= (1 << 33) - 1
    return bytes([(prefix << 4) | (((ts >> 30) & 0x07) << 1) | 1,
                  (ts >> 22) & 0xFF, (((ts >> 15) & 0x7F) << 1) | 1,
                  (ts >> 7) & 0xFF, ((ts & 0x7F) << 1) | 1])


class TsWriter:
    """One program: H.264 video and (unless klv=False) KLV - an asynchronous KLVA data
    stream, or with sync=True a synchronous metadata stream (ST 1402; ISO 13818-1 2.12:
    stream_type 0x15, a metadata_descriptor naming KLVA, PES stream_id 0xFC carrying
    metadata access unit cells)."""

    def __init__(self, video_pid=0x100, klv_pid=0x101, pmt_pid=0x1000, program=1,
                 version=0, klv=True, sync=False):
        self.video_pid, self.klv_pid, self.pmt_pid = video_pid, klv_pid, pmt_pid
        self.program, self.version, self.klv, self.sync = program, version, klv, sync
        self.cc = {}
        self.cell_sequence = 0

    def _packet(self, pid, payload, start, adaptation=b""):
        cc = self.cc.get(pid, 0)
        self.cc[pid] = (cc + 1) & 0x0F
        header = bytes([0x47, (0x40 if start else 0) | (pid >> 8), pid & 0xFF])
        room = 184 - len(adaptation)
        if len(payload) < room:
            # Stuff with an adaptation field so the packet is exactly 188 bytes.
            fill = room - len(payload)
            if adaptation:
                adaptation = bytes([adaptation[0] + fill]) + adaptation[1:] + b"\xFF" * fill
            elif fill == 1:
                adaptation = b"\x00"
            else:
                adaptation = bytes([fill - 1, 0x00]) + b"\xFF" * (fill - 2)
        control = 0x30 if adaptation else 0x10
        return header + bytes([control | cc]) + adaptation + payload

    def _section(self, pid, table):
        section = table + struct.pack(">I", crc32_mpeg(table))
        return self._packet(pid, b"\x00" + section, True)

    def psi(self):
        pat_body = struct.pack(">HH", self.program, 0xE000 | self.pmt_pid)
        pat = bytes([0x00]) + struct.pack(">H", 0xB000 | (5 + len(pat_body) + 4)) + \
            struct.pack(">H", 1) + bytes([0xC1 | (self.version << 1), 0, 0]) + pat_body
        streams = bytes([0x1B]) + struct.pack(">HH", 0xE000 | self.video_pid, 0xF000)
        if self.klv and self.sync:
            # metadata_descriptor: application format 0xFFFF + "KLVA", format 0xFF + "KLVA",
            # service id 0, no decoder config, no DSM-CC.
            body_26 = struct.pack(">H", 0xFFFF) + b"KLVA" + b"\xFF" + b"KLVA" + bytes([0, 0x0F])
            desc = bytes([0x26, len(body_26)]) + body_26
            streams += bytes([0x15]) + struct.pack(">HH", 0xE000 | self.klv_pid, 0xF000 | len(desc)) + desc
        elif self.klv:
            reg = bytes([0x05, 4]) + b"KLVA"
            streams += bytes([0x06]) + struct.pack(">HH", 0xE000 | self.klv_pid, 0xF000 | len(reg)) + reg
        body = struct.pack(">HH", 0xE000 | self.video_pid, 0xF000) + streams
        pmt = bytes([0x02]) + struct.pack(">H", 0xB000 | (5 + len(body) + 4)) + \
            struct.pack(">H", self.program) + bytes([0xC1 | (self.version << 1), 0, 0]) + body
        return self._section(0, pat) + self._section(self.pmt_pid, pmt)

    def _pes(self, pid, stream_id, payload, pts, pcr=None, bounded=False):
        header = _timestamp(0x2, pts)
        pes = b"\x00\x00\x01" + bytes([stream_id])
        body_len = 3 + len(header) + len(payload)
        pes += struct.pack(">H", body_len if bounded and body_len < 65536 else 0)
        pes += bytes([0x84 if stream_id == 0xE0 else 0x80, 0x80, len(header)]) + header + payload
        out = b""
        first = True
        while pes:
            adaptation = b""
            if first and pcr is not None:
                base = pcr & ((1 << 33) - 1)
                adaptation = bytes([7, 0x10]) + struct.pack(
                    ">IH", base >> 1, ((base & 1) << 15) | 0x7E00)
            room = 184 - len(adaptation)
            out += self._packet(pid, pes[:room], first, adaptation)
            pes = pes[room:]
            first = False
        return out

    def video(self, au, pts):
        return self._pes(self.video_pid, 0xE0, au, pts, pcr=pts - 9000)

    def klv_pes(self, data, pts):
        if self.sync:
            # One whole cell (fragment indication 11, random access): service id 0, sequence
            # number, flags, 16-bit length.
            cell = bytes([0, self.cell_sequence & 0xFF, 0xDF]) + struct.pack(">H", len(data))
            self.cell_sequence += 1
            return self._pes(self.klv_pid, 0xFC, cell + data, pts, bounded=True)
        return self._pes(self.klv_pid, 0xBD, data, pts, bounded=True)


def datagrams(ts, size=7 * 188):
    return [ts[i:i + size] for i in range(0, len(ts), size)]


# --- MISB ST 0601 sets -----------------------------------------------------------------------

def ber_length(n):
    if n < 128:
        return bytes([n])
    body = n.to_bytes((n.bit_length() + 7) // 8, "big")
    return bytes([0x80 | len(body)]) + body


def signed_map(value, limit, size):
    top = (1 << (8 * size - 1)) - 1
    return int(round(value / limit * top)).to_bytes(size, "big", signed=True)


def klv_set(time_us, lat, lon, mission=None, alt_msl=None, bad_checksum=False):
    """A UAS Datalink LS with tags 2, (3), 13, 14, (15), 65 and the checksum."""
    items = bytes([2, 8]) + time_us.to_bytes(8, "big")
    if mission:
        items += bytes([3]) + ber_length(len(mission)) + mission.encode()
    items += bytes([13, 4]) + signed_map(lat, 90, 4)
    items += bytes([14, 4]) + signed_map(lon, 180, 4)
    if alt_msl is not None:
        items += bytes([15, 2]) + int(round((alt_msl + 900) / 19900 * 65535)).to_bytes(2, "big")
    items += bytes([65, 1, 19])
    body = items + bytes([1, 2])
    packet = UAS_LS_KEY + ber_length(len(body) + 2) + body
    total = 0
    for i, b in enumerate(packet):
        total += b << (8 if i % 2 == 0 else 0)
    checksum = total & 0xFFFF
    if bad_checksum:
        checksum ^= 0x5A5A
    return packet + checksum.to_bytes(2, "big")


# --- receiving -------------------------------------------------------------------------------

class UdpCollector:
    """Receives datagrams on 127.0.0.1:port in a thread, keeping them with arrival times."""

    def __init__(self, port=0):
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.sock.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4 << 20)
        self.sock.bind(("127.0.0.1", port))
        self.sock.settimeout(0.2)
        self.port = self.sock.getsockname()[1]
        self.items = []
        self.lock = threading.Lock()
        self.running = True
        self.thread = threading.Thread(target=self._run, daemon=True)
        self.thread.start()

    def _run(self):
        while self.running:
            try:
                data = self.sock.recv(65536)
            except socket.timeout:
                continue
            except OSError:
                return
            with self.lock:
                self.items.append((time.monotonic(), data))

    def count(self):
        with self.lock:
            return len(self.items)

    def data(self, since=0):
        with self.lock:
            return [d for _, d in self.items[since:]]

    def close(self):
        self.running = False
        self.thread.join(timeout=2)
        self.sock.close()


class TsReader:
    """Just enough of a demultiplexer for the tests: PAT -> PMT -> the KLV PID (stream_type
    0x06 with a KLVA registration descriptor) and the video PID; KLV PES payloads out, PTS
    included."""

    def __init__(self):
        self.pmt_pid = None
        self.klv_pid = None
        self.video_pid = None
        self.video_type = None
        self.pending = {}
        self.klv = []  # (pts, payload)
        self.video_units = 0

    def push(self, data):
        for i in range(0, len(data) - 187, 188):
            self._packet(data[i:i + 188])

    def _packet(self, p):
        if p[0] != 0x47:
            return
        pid = ((p[1] & 0x1F) << 8) | p[2]
        start = bool(p[1] & 0x40)
        control = (p[3] >> 4) & 3
        at = 4
        if control & 2:
            at += 1 + p[4]
        if not control & 1 or at >= 188:
            return
        payload = p[at:]
        if pid == 0 and start:
            section = payload[1 + payload[0]:]
            self.pmt_pid = ((section[10] & 0x1F) << 8) | section[11]
        elif pid == self.pmt_pid and start:
            s = payload[1 + payload[0]:]
            length = ((s[1] & 0x0F) << 8) | s[2]
            info = ((s[10] & 0x0F) << 8) | s[11]
            at = 12 + info
            end = 3 + length - 4
            while at + 5 <= end:
                stype = s[at]
                spid = ((s[at + 1] & 0x1F) << 8) | s[at + 2]
                es_len = ((s[at + 3] & 0x0F) << 8) | s[at + 4]
                desc = s[at + 5:at + 5 + es_len]
                if stype == 0x06 and b"KLVA" in desc:
                    self.klv_pid = spid
                elif stype in (0x1B, 0x24):
                    self.video_pid, self.video_type = spid, stype
                at += 5 + es_len
        elif pid in (self.klv_pid, self.video_pid):
            if start:
                self._finish(pid)
                self.pending[pid] = bytearray(payload)
            elif pid in self.pending:
                self.pending[pid] += payload

    def _finish(self, pid):
        pes = self.pending.pop(pid, None)
        if not pes or pes[:3] != b"\x00\x00\x01":
            return
        if pid == self.video_pid:
            self.video_units += 1
            return
        header_len = pes[8]
        pts = None
        if pes[7] & 0x80:
            t = pes[9:14]
            pts = (((t[0] >> 1) & 7) << 30) | (t[1] << 22) | ((t[2] >> 1) << 15) | \
                  (t[3] << 7) | (t[4] >> 1)
        length = struct.unpack(">H", pes[4:6])[0]
        body = bytes(pes[9 + header_len:6 + length] if length else pes[9 + header_len:])
        self.klv.append((pts, body))

    def flush(self):
        for pid in list(self.pending):
            self._finish(pid)


def split_sets(data):
    """The UAS Datalink sets in a KLV payload, whole."""
    sets = []
    at = data.find(UAS_LS_KEY)
    while at >= 0 and at + 17 <= len(data):
        first = data[at + 16]
        if first < 128:
            length, head = first, 17
        else:
            n = first & 0x7F
            length = int.from_bytes(data[at + 17:at + 17 + n], "big")
            head = 17 + n
        end = at + head + length
        if end > len(data):
            break
        sets.append(data[at:end])
        at = data.find(UAS_LS_KEY, end)
    return sets


# --- tools nobody here wrote -----------------------------------------------------------------

def ffprobe_streams(url, timeout=30):
    """The streams ffprobe finds in a live UDP TS: [{"codec_type", "codec_name", ...}]."""
    r = subprocess.run(
        ["ffprobe", "-v", "quiet", "-analyzeduration", "3000000", "-probesize", "2000000",
         "-show_entries", "stream=codec_type,codec_name,width,height", "-of", "json", url],
        capture_output=True, text=True, timeout=timeout)
    return json.loads(r.stdout or "{}").get("streams", [])


def gst_klv_buffers(port, timeout=20):
    """The first KLV buffer GStreamer's tsdemux gives as meta/x-klv on a UDP TS, as bytes,
    or None. gst-launch prints it with fakesink dump=true."""
    try:
        r = subprocess.run(
            ["gst-launch-1.0", "-q", "udpsrc", "port=%d" % port, "address=127.0.0.1", "!",
             "tsdemux", "!", "meta/x-klv", "!", "fakesink", "dump=true", "num-buffers=1"],
            capture_output=True, text=True, timeout=timeout)
        out = r.stdout
    except subprocess.TimeoutExpired as e:
        out = (e.stdout or b"").decode(errors="replace") if isinstance(e.stdout, bytes) \
            else (e.stdout or "")
    data = bytearray()
    for line in out.splitlines():
        # "00000000 (0x7f...): 06 0e 2b 34 ...  ..+4"
        if "): " not in line:
            continue
        hexpart = line.split("): ", 1)[1][:16 * 3]
        for token in hexpart.split():
            if len(token) == 2:
                data.append(int(token, 16))
    return bytes(data) if data else None
