"""A small MAVLink 2 peer for the gimbald integration tests, written from common.xml and the
MAVLink guide (serialization, message signing), independent of the product's codec.

Only what the tests need: COMMAND_LONG out, COMMAND_ACK and a few gimbal messages in, frames of
any shape (for garbage tests), and MAVLink 2 signing.
"""

import hashlib
import math
import select
import socket
import struct
import time

MAGIC_V2 = 0xFD
# CRC_EXTRA of the messages used here (common.xml, the MAVLink guide's algorithm).
CRC_EXTRA = {0: 50, 30: 39, 33: 104, 75: 158, 76: 152, 77: 143, 259: 92, 275: 126, 276: 18,
             280: 70, 281: 48, 285: 137}
SIGNING_EPOCH = 1420070400  # 2015-01-01

MAV_CMD_DO_SET_ROI_LOCATION = 195
MAV_CMD_REQUEST_MESSAGE = 512
MAV_CMD_DO_GIMBAL_MANAGER_PITCHYAW = 1000
MAV_CMD_DO_GIMBAL_MANAGER_CONFIGURE = 1001
MAV_RESULT = {0: "ACCEPTED", 1: "TEMPORARILY_REJECTED", 2: "DENIED", 3: "UNSUPPORTED",
              4: "FAILED"}


def crc_x25(data, crc=0xFFFF):
    """CRC-16/MCRF4XX, as MAVLink computes it."""
    for b in data:
        tmp = b ^ (crc & 0xFF)
        tmp = (tmp ^ (tmp << 4)) & 0xFF
        crc = ((crc >> 8) ^ (tmp << 8) ^ (tmp << 3) ^ (tmp >> 4)) & 0xFFFF
    return crc


def signing_timestamp(unix_s=None):
    """10 us units since 2015-01-01."""
    return int(((time.time() if unix_s is None else unix_s) - SIGNING_EPOCH) * 1e5)


def frame(msgid, payload, sysid=255, compid=190, seq=0, key=None, link_id=0, timestamp=None):
    """A MAVLink 2 frame (trailing zero bytes of the payload cut, at least one kept); signed
    with `key` (32 bytes) at `timestamp` when a key is given."""
    payload = payload.rstrip(b"\0") or b"\0"
    incompat = 0x01 if key else 0x00
    header = struct.pack("<BBBBBB", len(payload), incompat, 0, seq & 0xFF, sysid, compid)
    header += struct.pack("<I", msgid)[:3]
    body = header + payload
    crc = crc_x25(body + bytes([CRC_EXTRA[msgid]]))
    out = bytes([MAGIC_V2]) + body + struct.pack("<H", crc)
    if key:
        ts = signing_timestamp() if timestamp is None else timestamp
        tail = bytes([link_id]) + struct.pack("<Q", ts)[:6]
        out += tail + hashlib.sha256(key + out + tail).digest()[:6]
    return out


def command_long(command, params, target_system=1, target_component=154, confirmation=0):
    """COMMAND_LONG (76) payload: param1..7 (float), command, target system/component."""
    p = [float(x) for x in params] + [0.0] * (7 - len(params))
    return struct.pack("<7fHBBB", *p, command, target_system, target_component, confirmation)


def command_int(command, params4, x, y, z, frame_id, target_system=1, target_component=154):
    """COMMAND_INT (75) payload: param1..4, x, y (int32), z, command, targets, frame, ..."""
    p = [float(v) for v in params4]
    return struct.pack("<4fiifHBBBBB", *p, x, y, z, command, target_system, target_component,
                       frame_id, 0, 0)


def parse(datagram):
    """Every CRC-valid frame of ids in CRC_EXTRA: (sysid, compid, msgid, payload)."""
    out = []
    i = 0
    while i < len(datagram):
        if datagram[i] != MAGIC_V2 or i + 12 > len(datagram):
            i += 1
            continue
        length, incompat = datagram[i + 1], datagram[i + 2]
        msgid = datagram[i + 7] | (datagram[i + 8] << 8) | (datagram[i + 9] << 16)
        total = 12 + length + (13 if incompat & 1 else 0)
        if msgid not in CRC_EXTRA or i + total > len(datagram):
            i += 1
            continue
        body = datagram[i + 1:i + 10 + length]
        crc = struct.unpack("<H", datagram[i + 10 + length:i + 12 + length])[0]
        if crc != crc_x25(body + bytes([CRC_EXTRA[msgid]])):
            i += 1
            continue
        payload = datagram[i + 10:i + 10 + length]
        out.append((datagram[i + 5], datagram[i + 6], msgid, payload))
        i += total
    return out


def ack_of(payload):
    """(command, result) of a COMMAND_ACK payload (zero tail restored)."""
    payload = payload + b"\0" * (10 - len(payload))
    command, result = struct.unpack("<HB", payload[:3])
    return command, result


class Peer:
    """A ground station on its own UDP socket, talking to gimbald's vehicle endpoint."""

    def __init__(self, port, sysid=255, compid=190, key=None):
        self.address = ("127.0.0.1", port)
        self.sysid, self.compid, self.key = sysid, compid, key
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.sock.bind(("127.0.0.1", 0))
        self.seq = 0
        self.last_ts = 0
        self.received = []  # (monotonic time, sysid, compid, msgid, payload)

    def close(self):
        self.sock.close()

    def send_raw(self, data):
        self.sock.sendto(data, self.address)

    def timestamp(self):
        self.last_ts = max(self.last_ts + 1, signing_timestamp())
        return self.last_ts

    def make(self, msgid, payload, sign=None):
        """A frame from this peer (signed when it has a key, unless sign=False)."""
        key = self.key if sign is None else (self.key if sign else None)
        self.seq += 1
        return frame(msgid, payload, self.sysid, self.compid, self.seq, key,
                     timestamp=self.timestamp() if key else None)

    def send(self, msgid, payload, sign=None):
        data = self.make(msgid, payload, sign)
        self.send_raw(data)
        return data

    def pump(self, timeout):
        """Waits up to `timeout` seconds for datagrams; reads every one that is there."""
        wait = timeout
        while True:
            ready, _, _ = select.select([self.sock], [], [], wait)
            if not ready:
                return
            try:
                data = self.sock.recv(65536)
            except ConnectionRefusedError:
                continue
            now = time.monotonic()
            for sysid, compid, msgid, payload in parse(data):
                self.received.append((now, sysid, compid, msgid, payload))
            wait = 0.0  # drain what has arrived, then return

    def wait(self, predicate, timeout=3.0, since=0.0):
        """The first received (t, sysid, compid, msgid, payload) with predicate true, or None."""
        deadline = time.monotonic() + timeout
        while True:
            for m in self.received:
                if m[0] >= since and predicate(m):
                    return m
            left = deadline - time.monotonic()
            if left <= 0:
                return None
            self.pump(min(left, 0.05))

    def ack(self, command, timeout=3.0, since=None, component=None):
        """The result of the next COMMAND_ACK for `command` (from `component` if given)."""
        since = time.monotonic() if since is None else since
        m = self.wait(lambda m: m[3] == 77 and ack_of(m[4])[0] == command and
                      (component is None or m[2] == component), timeout, since)
        return None if m is None else ack_of(m[4])[1]

    def command(self, command, params, target_component=154, sign=None, timeout=3.0):
        """Sends a COMMAND_LONG and returns the ACK's result (None: no ACK)."""
        since = time.monotonic()
        self.send(76, command_long(command, params, 1, target_component), sign)
        return self.ack(command, timeout, since)


NAN = math.nan
