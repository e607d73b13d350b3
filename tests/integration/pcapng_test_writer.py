"""Test-only pcapng writer following docs/recording.md (standard library only).

Used by the replay/export tests to make recordings without gimbald (and to write the
fuzz seed corpus). It writes what gimbald's recorder writes: an SHB, one IDB per
interface (link type 252, if_tsresol 6) and EPBs holding exported-PDU TLVs (dissector
name, end tag) then the PDU, with the direction in epb_flags."""

import struct

INBOUND = 1
OUTBOUND = 2


def _pad(data):
    return data + b"\0" * (-len(data) % 4)


def _option(code, value, endian):
    return struct.pack(endian + "HH", code, len(value)) + _pad(value)


def _block(block_type, body, endian):
    total = len(body) + 12
    return struct.pack(endian + "II", block_type, total) + body + struct.pack(endian + "I", total)


def exported_pdu(dissector, pdu):
    name = dissector.encode()
    return struct.pack(">HH", 12, len(name)) + _pad(name) + struct.pack(">HH", 0, 0) + pdu


class PcapngWriter:
    def __init__(self, path, interfaces, big_endian=False):
        """interfaces: list of (if_name, if_description)."""
        self.endian = ">" if big_endian else "<"
        self.file = open(path, "wb")
        e = self.endian
        shb = struct.pack(e + "IHHq", 0x1A2B3C4D, 1, 0, -1)
        shb += _option(4, b"gimbald test writer", e) + struct.pack(e + "HH", 0, 0)
        self.file.write(_block(0x0A0D0D0A, shb, e))
        for name, description in interfaces:
            body = struct.pack(e + "HHI", 252, 0, 0)
            body += _option(2, name.encode(), e) + _option(3, description.encode(), e)
            body += _option(9, b"\x06", e) + struct.pack(e + "HH", 0, 0)
            self.file.write(_block(1, body, e))
        self.file.flush()

    def packet(self, interface, time_us, dissector, pdu, direction):
        e = self.endian
        data = exported_pdu(dissector, pdu)
        body = struct.pack(e + "IIIII", interface, time_us >> 32, time_us & 0xFFFFFFFF,
                           len(data), len(data))
        body += _pad(data) + _option(2, struct.pack(e + "I", direction), e)
        body += struct.pack(e + "HH", 0, 0)
        self.file.write(_block(6, body, e))

    def close(self):
        self.file.close()


def split_orion(buffer):
    """Splits bytes into whole Orion frames (D0 0D id len data ck ck) and junk runs.
    Returns (pieces, rest): pieces are (dissector, bytes), rest an unfinished frame."""
    pieces = []
    junk = bytearray()
    i = 0
    while i < len(buffer):
        if buffer[i] != 0xD0 or (i + 1 < len(buffer) and buffer[i + 1] != 0x0D):
            junk.append(buffer[i])
            i += 1
            continue
        if len(buffer) - i < 4:
            break
        total = 4 + buffer[i + 3] + 2
        if buffer[i + 3] > 140:
            junk.append(buffer[i])
            i += 1
            continue
        if len(buffer) - i < total:
            break
        if junk:
            pieces.append(("data", bytes(junk)))
            junk = bytearray()
        pieces.append(("orion", bytes(buffer[i:i + total])))
        i += total
    if junk:
        pieces.append(("data", bytes(junk)))
    return pieces, bytes(buffer[i:])
