"""Hostile MPEG-TS, KLV and H.264 for the attack suite, built from the standards (ISO/IEC
13818-1, MISB ST 0601 / ST 1402, ITU-T H.264 7.3.2.1) - not from the product's code.

The PSI (PAT/PMT, with the KLVA registration or metadata descriptors) and the small ST 0601
sets come from tests/integration/videotest.py; the packetizer here is a fast one (memoryview
slices) because the attacks push megabytes a second through it.
"""

import array
import os
import random
import socket
import struct
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "integration"))
import videotest as vt  # noqa: E402

UAS_LS_KEY = vt.UAS_LS_KEY
UdpCollector = vt.UdpCollector
VIDEO_PID, KLV_PID = 0x100, 0x101
DATAGRAM = 7 * 188


# --- MPEG-TS ---------------------------------------------------------------------------------

class Ts:
    """TS packets of one program: PSI from videotest.TsWriter, PES packetized here."""

    def __init__(self, sync_klv=False, klv=True):
        self.psi_writer = vt.TsWriter(video_pid=VIDEO_PID, klv_pid=KLV_PID, klv=klv,
                                      sync=sync_klv)
        self.cc = {}

    def psi(self):
        return self.psi_writer.psi()

    def packets(self, pid, payload, stuff_last=True):
        """`payload` (a whole PES) cut into 188-byte packets; the last one stuffed with an
        adaptation field (what marks the end of an unbounded PES) unless it is exactly full."""
        out = bytearray()
        mv = memoryview(payload)
        n = len(payload)
        at = 0
        first = True
        cc = self.cc.get(pid, 0)
        while at < n:
            chunk = mv[at:at + 184]
            at += len(chunk)
            head = bytes([0x47, (0x40 if first else 0) | (pid >> 8), pid & 0xFF])
            if len(chunk) == 184:
                out += head + bytes([0x10 | cc]) + chunk
            else:
                fill = 184 - len(chunk)
                adaptation = b"\x00" if fill == 1 else bytes([fill - 1, 0]) + b"\xFF" * (fill - 2)
                out += head + bytes([0x30 | cc]) + adaptation + chunk
            cc = (cc + 1) & 0x0F
            first = False
        self.cc[pid] = cc
        return bytes(out)

    def pes(self, pid, stream_id, payload, pts, bounded=True):
        header = b"\x00\x00\x01" + bytes([stream_id])
        body = 3 + 5 + len(payload)
        header += struct.pack(">H", body if bounded and body <= 0xFFFF else 0)
        header += bytes([0x84 if stream_id == 0xE0 else 0x80, 0x80, 5]) + vt._timestamp(0x2, pts)
        return self.packets(pid, header + payload)

    def klv(self, data, pts):
        return self.pes(KLV_PID, 0xBD, data, pts)

    def video(self, au, pts):
        return self.pes(VIDEO_PID, 0xE0, au, pts, bounded=False)


def free_udp_port():
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def datagrams(ts):
    return [ts[i:i + DATAGRAM] for i in range(0, len(ts), DATAGRAM)]


class UdpSender:
    """A UDP socket aimed at one port, from a chosen source address, that counts."""

    def __init__(self, port, source="127.0.0.1", rig=None, key="datagrams"):
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.sock.setsockopt(socket.SOL_SOCKET, socket.SO_SNDBUF, 1 << 21)
        self.sock.bind((source, 0))
        self.sock.connect(("127.0.0.1", port))
        self.rig, self.key = rig, key
        self.sent = self.bytes = 0

    def send(self, data):
        try:
            self.sock.send(data)
        except (BlockingIOError, ConnectionRefusedError, OSError):
            return
        self.sent += 1
        self.bytes += len(data)

    def send_all(self, items):
        for d in items:
            self.send(d)

    def flush_counts(self):
        if self.rig is not None:
            self.rig.count(self.key, self.sent)
            self.rig.count("MB sent", round(self.bytes / 1e6, 1))
        self.sent = self.bytes = 0

    def close(self):
        self.flush_counts()
        self.sock.close()


def paced(stop, items_per_s, produce, burst_s=0.01):
    """Calls produce(n) for n items every `burst_s` until `stop` is set."""
    start = time.monotonic()
    done = 0
    while not stop.is_set():
        due = int((time.monotonic() - start) * items_per_s) - done
        if due > 0:
            produce(due)
            done += due
        time.sleep(burst_s)


# --- KLV ---------------------------------------------------------------------------------------

def ber_oid(tag):
    out = [tag & 0x7F]
    tag >>= 7
    while tag:
        out.append(0x80 | (tag & 0x7F))
        tag >>= 7
    return bytes(reversed(out))


def checksum16(data):
    """ST 0601 tag 1: the sum of 16-bit big-endian words (a last odd byte is a high byte)."""
    if len(data) % 2:
        data = data + b"\x00"
    words = array.array("H")
    words.frombytes(data)
    if sys.byteorder == "little":
        words.byteswap()
    return sum(words) & 0xFFFF


def finish_set(items, bad_checksum=False):
    """Key + BER length + items + the checksum item."""
    body = bytes(items) + b"\x01\x02"
    packet = UAS_LS_KEY + vt.ber_length(len(body) + 2) + body
    checksum = checksum16(packet)
    if bad_checksum:
        checksum ^= 0x5A5A
    return packet + struct.pack(">H", checksum)


def unknown_tags_set(count, first_tag, value_size, bad_checksum=False, rng=None, pad_to=None):
    """A set of `count` distinct unknown tags (BER-OID) with values of `value_size` bytes,
    after a time stamp (tag 2); `pad_to` adds one more unknown item so the set has exactly
    that many bytes (within a few)."""
    rng = rng or random.Random(7)
    items = bytearray(bytes([2, 8]) + int(time.time() * 1e6).to_bytes(8, "big"))
    if value_size == 0 and first_tag % (1 << 14) == 0 and first_tag >= 1 << 14:
        # The fast path of the 8 MB set: 3-byte tags, zero-length values, built from
        # repeated byte patterns (a Python loop over 2 M items would take seconds).
        top = first_tag >> 14
        block = bytearray(4 * count)
        block[0::4] = b"".join(bytes([0x80 | (top + k)]) * (1 << 14)
                               for k in range(-(-count // (1 << 14))))[:count]
        middle = b"".join(bytes([0x80 | j]) * 128 for j in range(128))
        block[1::4] = (middle * (-(-count // len(middle))))[:count]
        block[2::4] = (bytes(range(128)) * (-(-count // 128)))[:count]
        items += block
    else:
        for i in range(count):
            items += ber_oid(first_tag + i) + vt.ber_length(value_size) + \
                rng.getrandbits(8 * value_size).to_bytes(value_size, "big")
    if pad_to is not None:
        filler = ber_oid(first_tag + count)
        size = 0
        for _ in range(4):
            trial = items + filler + vt.ber_length(size) + b"\xA5" * size
            total = len(UAS_LS_KEY) + len(vt.ber_length(len(trial) + 4)) + len(trial) + 4
            if total == pad_to or size + pad_to - total < 0:
                break
            size += pad_to - total
        items = trial
    return finish_set(items, bad_checksum)


def huge_set_for_packets(items, bad_checksum):
    """The 8 MB set: `items` unknown tags, sized so that its unbounded PES (14 header bytes)
    fills 16*k packets, the last one stuffed: the continuity counters wrap, so the same
    datagrams can be sent again and again, and the stuffing ends the PES."""
    approx = 16 + 4 + 10 + 4 * items + 4
    packets = -(-(14 + approx) // 184)
    target_packets = -(-(packets + 1) // 16) * 16
    target_len = 184 * (target_packets - 1) + 100 - 14
    return unknown_tags_set(items, 1 << 14, 0, bad_checksum=bad_checksum, pad_to=target_len)


def legit_set(mission, lat=45.7, lon=-121.5):
    return vt.klv_set(int(time.time() * 1e6), lat, lon, mission=mission, alt_msl=1500.0)


def hostile_klv_sets(n, seed=25):
    """`n` malformed or hostile ST 0601 sets of many shapes (the held attack of ~2,800)."""
    rng = random.Random(seed)
    good = legit_set("HOSTILE")
    shapes = []

    def huge_ber(_):
        return UAS_LS_KEY + bytes([0x84]) + b"\xFF\xFF\xFF\xFF" + os.urandom(rng.randint(0, 64))

    def eight_byte_ber(_):
        return UAS_LS_KEY + bytes([0x88]) + b"\x7F" + b"\xFF" * 7 + os.urandom(32)

    def indefinite(_):
        return UAS_LS_KEY + bytes([rng.choice([0x80, 0xFF, 0x89, 0x8F])]) + os.urandom(40)

    def endless_oid(_):
        return finish_set(b"\xFF" * rng.randint(5, 300) + b"\x01\x00")

    def item_past_end(_):
        return finish_set(bytes([13, 0x82, 0xFF, 0xF0]) + os.urandom(8))

    def wrong_lengths(_):
        items = bytearray()
        for tag in rng.sample(range(2, 143), 30):
            size = rng.choice([0, 1, 3, 5, 9, 17, 127, 200])
            items += ber_oid(tag) + vt.ber_length(size) + os.urandom(size)
        return finish_set(items)

    def nested_garbage(_):
        inner = UAS_LS_KEY + b"\x84\x7F\xFF\xFF\xFF" + os.urandom(60)
        items = bytearray()
        for tag in (48, 74, 94, 73, 102):
            items += ber_oid(tag) + vt.ber_length(len(inner)) + inner
        return finish_set(items)

    def mutated(_):
        b = bytearray(good)
        for _ in range(rng.randint(1, 12)):
            b[rng.randrange(17, len(b))] = rng.randrange(256)
        items = bytes(b[17:-4])
        return finish_set(items) if rng.random() < 0.7 else bytes(b)

    def no_checksum(_):
        return UAS_LS_KEY + vt.ber_length(10) + bytes([2, 8]) + os.urandom(8)

    def empty(_):
        return UAS_LS_KEY + b"\x00"

    def repeated_keys(_):
        return (UAS_LS_KEY * rng.randint(2, 50)) + b"\x83\x00\x10\x00" + os.urandom(16)

    def many_strings(_):
        items = bytearray()
        for tag in (3, 4, 10, 11, 12, 59, 70, 105, 106, 128):
            size = rng.choice([127, 255, 1000])
            items += ber_oid(tag) + vt.ber_length(size) + bytes(rng.choice([0, 0xFF, 0x22, 0x5C])
                                                                 for _ in range(size))
        return finish_set(items)

    shapes = [huge_ber, eight_byte_ber, indefinite, endless_oid, item_past_end, wrong_lengths,
              nested_garbage, mutated, no_checksum, empty, repeated_keys, many_strings]
    return [shapes[i % len(shapes)](i) for i in range(n)]


# --- synchronous KLV (ST 1402 metadata AU cells) -----------------------------------------------

def sync_cell(fragment, data, sequence=0):
    """A metadata AU cell: service id 0, sequence number, fragment indication (11 whole, 10
    first, 00 middle, 01 last), decoder config flag 0, random access 1, reserved 1111."""
    flags = (fragment << 6) | 0x1F
    return bytes([0, sequence & 0xFF, flags]) + struct.pack(">H", len(data)) + data


def sync_middle_pes(ts, size=61805):
    """One bounded metadata PES (stream_id 0xFC) holding one "middle" cell of `size` bytes;
    the default makes the PES exactly 336 packets (21 x 16: the counters wrap, so the same
    bytes may be resent forever)."""
    return ts.pes(KLV_PID, 0xFC, sync_cell(0, b"\x5A" * size), 90000)


# --- H.264 -------------------------------------------------------------------------------------

class BitWriter:
    def __init__(self):
        self.bits = []

    def u(self, n, v):
        for i in range(n - 1, -1, -1):
            self.bits.append((v >> i) & 1)

    def ue(self, v):
        v += 1
        n = v.bit_length()
        self.u(n - 1, 0)
        self.u(n, v)

    def se(self, v):
        self.ue(2 * v - 1 if v > 0 else -2 * v)

    def rbsp(self):
        self.bits.append(1)
        while len(self.bits) % 8:
            self.bits.append(0)
        out = bytearray()
        for i in range(0, len(self.bits), 8):
            byte = 0
            for b in self.bits[i:i + 8]:
                byte = (byte << 1) | b
            out.append(byte)
        return bytes(out)


def emulation_prevent(rbsp):
    out = bytearray()
    zeros = 0
    for b in rbsp:
        if zeros >= 2 and b <= 3:
            out.append(3)
            zeros = 0
        out.append(b)
        zeros = zeros + 1 if b == 0 else 0
    return bytes(out)


def hostile_sps(rng, i):
    """An H.264 SPS NAL (with its start code) that is absurd in one of many ways."""
    shape = i % 8
    if shape == 0:  # random bytes after a plausible head
        body = bytes([rng.choice([66, 77, 100, 110, 122, 244]), rng.randrange(256),
                      rng.randrange(256)]) + os.urandom(rng.randint(0, 120))
        return b"\x00\x00\x00\x01\x67" + emulation_prevent(body)
    if shape == 1:  # truncated
        return b"\x00\x00\x00\x01\x67" + os.urandom(rng.randint(0, 3))
    if shape == 2:  # exp-Golomb runs of 32+ zero bits (overflow)
        return b"\x00\x00\x00\x01\x67\x64\x00\x28" + b"\x00\x00\x03" * rng.randint(3, 60) + b"\x01"
    w = BitWriter()
    profile = rng.choice([66, 100, 110, 122, 244])
    w.u(8, profile)
    w.u(8, 0)
    w.u(8, rng.choice([0, 10, 51, 255]))
    w.ue(rng.choice([0, 31, 32, 1000]))  # seq_parameter_set_id (max 31)
    if profile in (100, 110, 122, 244):
        chroma = rng.choice([0, 1, 3, 7])
        w.ue(chroma)
        if chroma == 3:
            w.u(1, 1)
        w.ue(rng.choice([0, 6, 14, 1000]))  # bit_depth_luma_minus8
        w.ue(rng.choice([0, 6, 14, 1000]))
        w.u(1, 0)
        scaling = shape == 3
        w.u(1, 1 if scaling else 0)
        if scaling:
            for _ in range(12 if chroma == 3 else 8):
                w.u(1, 1)
                for _ in range(64):
                    w.se(rng.choice([-128, 127, 255, -255, 0]))
    w.ue(rng.choice([0, 12, 100, 1 << 20]))  # log2_max_frame_num_minus4
    poc_type = rng.choice([0, 1, 2, 3, 100])
    w.ue(poc_type)
    if poc_type == 0:
        w.ue(rng.choice([0, 12, 1 << 16]))
    elif poc_type == 1:
        w.u(1, 0)
        w.se(rng.choice([-(1 << 30), 1 << 30]))
        w.se(rng.choice([-(1 << 30), 1 << 30]))
        cycle = rng.choice([255, 256, 10000]) if shape == 4 else 3
        w.ue(cycle)
        for _ in range(min(cycle, 300)):
            w.se(rng.choice([-(1 << 30), 1 << 30, 0]))
    w.ue(rng.choice([0, 16, 17, 1 << 16]))  # max_num_ref_frames
    w.u(1, 0)
    big = shape == 5
    w.ue(rng.choice([(1 << 24) - 1, (1 << 30), 65535]) if big else rng.randint(0, 300))
    w.ue(rng.choice([(1 << 24) - 1, (1 << 30), 65535]) if big else rng.randint(0, 300))
    w.u(1, rng.randrange(2))  # frame_mbs_only
    w.u(1, 0)
    crop = shape == 6
    w.u(1, 1 if crop else 0)
    if crop:
        for _ in range(4):
            w.ue(rng.choice([0, 1 << 20, 65535, (1 << 31) - 2]))
    vui = shape == 7
    w.u(1, 1 if vui else 0)
    if vui:
        w.u(1, 1)  # aspect_ratio_info_present
        w.u(8, 255)
        w.u(16, 0)
        w.u(16, 0)
        w.u(1, 0)
        w.u(1, 0)
        w.u(1, 0)
        w.u(1, 1)  # timing_info_present
        w.u(32, rng.choice([0, 1, 0xFFFFFFFF]))
        w.u(32, rng.choice([0, 1, 0xFFFFFFFF]))
        w.u(1, 1)
        w.u(1, 1)  # nal_hrd
        w.ue(rng.choice([31, 32, 1000]))
        w.u(4, 15)
        w.u(4, 15)
        for _ in range(33):
            w.ue(rng.choice([0, (1 << 32) - 2]))
            w.ue(rng.choice([0, (1 << 32) - 2]))
            w.u(1, 1)
    return b"\x00\x00\x00\x01\x67" + emulation_prevent(w.rbsp())


def hostile_sps_units(n, seed=25):
    """`n` access units, each AUD + a hostile SPS + a PPS + a small IDR slice of noise."""
    rng = random.Random(seed)
    aud = b"\x00\x00\x00\x01\x09\xF0"
    pps = b"\x00\x00\x00\x01\x68\xCE\x38\x80"
    return [aud + hostile_sps(rng, i) + pps + b"\x00\x00\x00\x01\x65\x88\x84" +
            os.urandom(rng.randint(10, 200)).replace(b"\x00\x00", b"\x00\x01")
            for i in range(n)]


def h264_units(workdir, width=640, height=360, fps=30):
    """A libx264 clip's access units (videotest: FFmpeg; SPS/PPS before each key frame)."""
    return vt.h264_access_units(workdir, width=width, height=height, fps=fps, seconds=2,
                                name="attack")


def parameter_sets(units):
    """(SPS, PPS) NAL units (without start codes) of the first key frame."""
    sps = pps = None
    for au in units:
        for nal in au.split(b"\x00\x00\x01")[1:]:
            nal = nal.rstrip(b"\x00")
            if nal and nal[0] & 0x1F == 7 and sps is None:
                sps = nal
            elif nal and nal[0] & 0x1F == 8 and pps is None:
                pps = nal
        if sps and pps:
            return sps, pps
    raise RuntimeError("no SPS/PPS in the clip")


class LegitStream:
    """A camera's stream: H.264 at the clip's frame rate with one ST 0601 set per frame, PSI
    every 250 ms; `send_frame()` sends the next one."""

    def __init__(self, units, sender, mission="LEGIT", fps=30, klv=True):
        self.units, self.sender, self.mission, self.fps = units, sender, mission, fps
        self.ts = Ts(klv=klv)
        self.klv = klv
        self.n = 0
        self.last_psi = 0.0

    def send_frame(self):
        now = time.monotonic()
        if now - self.last_psi >= 0.25:
            self.sender.send_all(datagrams(self.ts.psi()))
            self.last_psi = now
        pts = (90000 + self.n * 90000 // self.fps) % (1 << 33)
        au = self.units[self.n % len(self.units)]
        data = self.ts.video(au, pts)
        if self.klv:
            data += self.ts.klv(legit_set(self.mission), pts)
        self.sender.send_all(datagrams(data))
        self.n += 1

    def run(self, stop):
        period = 1.0 / self.fps
        next_at = time.monotonic()
        while not stop.is_set():
            self.send_frame()
            next_at += period
            delay = next_at - time.monotonic()
            if delay > 0:
                time.sleep(delay)
            else:
                next_at = time.monotonic()
