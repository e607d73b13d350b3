"""A minimal pcapng writer for dissector tests: exported-PDU records as /work/RECORD_FORMAT.md
fixes them (linktype 252, TLVs tag/length big-endian, values zero padded to 4 bytes, tag 12 = dissector name, tag 0 ends)."""
import struct

LINKTYPE_WIRESHARK_UPPER_PDU = 252
EXP_PDU_TAG_END_OF_OPT = 0
EXP_PDU_TAG_DISSECTOR_NAME = 12
INBOUND, OUTBOUND = 1, 2


def _pad4(b):
    return b + b"\0" * (-len(b) % 4)


def _option(code, value):
    return struct.pack("<HH", code, len(value)) + _pad4(value)


def _block(block_type, body):
    length = 12 + len(body)
    return struct.pack("<II", block_type, length) + body + struct.pack("<I", length)


def exported_pdu(dissector, pdu):
    # Wireshark reads `length` bytes of value and goes on after them, so the length field
    # counts the zero padding too (as Wireshark's own exporter writes it).
    name = _pad4(dissector.encode())
    tlv = struct.pack(">HH", EXP_PDU_TAG_DISSECTOR_NAME, len(name)) + name
    tlv += struct.pack(">HH", EXP_PDU_TAG_END_OF_OPT, 0)
    return tlv + pdu


class Writer:
    def __init__(self, path, interfaces):
        """interfaces: list of (if_name, if_description)."""
        self.f = open(path, "wb")
        shb = struct.pack("<IHHq", 0x1A2B3C4D, 1, 0, -1)
        shb += _option(4, b"gimbald dissector test") + _option(0, b"")
        self.f.write(_block(0x0A0D0D0A, shb))
        for name, desc in interfaces:
            idb = struct.pack("<HHI", LINKTYPE_WIRESHARK_UPPER_PDU, 0, 0)
            idb += _option(2, name.encode()) + _option(3, desc.encode())
            idb += _option(9, b"\x06") + _option(0, b"")
            self.f.write(_block(0x00000001, idb))

    def packet(self, interface, time_us, dissector, pdu, direction=INBOUND):
        data = exported_pdu(dissector, pdu)
        body = struct.pack("<IIIII", interface, time_us >> 32, time_us & 0xFFFFFFFF,
                           len(data), len(data))
        body += _pad4(data) + _option(2, struct.pack("<I", direction)) + _option(0, b"")
        self.f.write(_block(0x00000006, body))

    def close(self):
        self.f.close()
