"""An independent MISB ST 0903 VMTI (Video Moving Target Indicator) Local Set decoder,
standard library only, for the value of MISB ST 0601 tag 74.

Written from ST 0903's tables as the open-source jmisb library quotes them (ST 0903.5:
VmtiMetadataKey, VTargetMetadataKey, VTargetSeries, TargetCentroid, TargetConfidenceLevel,
TargetLocation), not from gimbald's C++ (lib/klv/vmti*), so that the integration tests check
what gimbald writes against a second reading of the standard.

  VMTI LS: items of BER-OID tag, BER length, value.
    2 precision time stamp (uint64 us), 4 version (uint), 5 total targets, 6 reported
    targets, 7 frame number, 8 frame width, 9 frame height (uint), 101 VTarget series.
  VTarget series: VTarget packs, each preceded by its BER length.
  VTarget pack: target id (BER-OID), then items of BER-OID tag, BER length, value.
    1 centroid, 2 bounding box top left, 3 bottom right: pixel numbers (uint), where
      pixel = column + (row - 1) * frame width, row and column from 1 at the top left;
    5 confidence level (uint8, percent 0..100);
    17 target location: ST 1201 IMAPB latitude (-90, 90) 4 bytes, longitude (-180, 180)
      4 bytes, height above the ellipsoid (-900, 19000) 2 bytes (then optional sigmas/rhos);
    19 centroid row, 20 centroid column (uint).

    python3 st0903.py HEX...   prints each set decoded as JSON
"""

import json
import math
import sys

SET_NAMES = {2: "time_us", 4: "version", 5: "total_targets", 6: "reported_targets",
             7: "frame_number", 8: "frame_width", 9: "frame_height"}
PIXEL_ITEMS = {1: "centroid", 2: "top_left", 3: "bottom_right"}


def read_ber_length(data, at, end):
    if at >= end:
        raise ValueError("truncated BER length")
    first = data[at]
    if first < 0x80:
        return first, at + 1
    count = first & 0x7F
    if count == 0 or count > 8 or at + 1 + count > end:
        raise ValueError("bad BER length")
    return int.from_bytes(data[at + 1:at + 1 + count], "big"), at + 1 + count


def read_ber_oid(data, at, end):
    value = 0
    for i in range(at, end):
        value = (value << 7) | (data[i] & 0x7F)
        if not data[i] & 0x80:
            return value, i + 1
    raise ValueError("truncated BER-OID")


def local_set_items(data, at, end):
    """[(tag, bytes)] of the local set filling data[at:end]."""
    items = []
    while at < end:
        tag, at = read_ber_oid(data, at, end)
        length, at = read_ber_length(data, at, end)
        if at + length > end:
            raise ValueError("tag %d runs past its set" % tag)
        items.append((tag, bytes(data[at:at + length])))
        at += length
    return items


def reverse_imapb(a, b, raw):
    """MISB ST 1201 section 8: x = 2^(bPow - dPow) * (y - zOffset) + a."""
    length = len(raw)
    y = int.from_bytes(raw, "big")
    if y >> (8 * length - 1):
        raise ValueError("IMAPB special value")
    b_pow = math.ceil(math.log2(b - a))
    d_pow = 8 * length - 1
    s_f = 2.0 ** (d_pow - b_pow)
    z_offset = s_f * a - math.floor(s_f * a) if a < 0 else 0.0
    return (y - z_offset) / s_f + a


def pixel(number, width):
    p = {"pixel": number}
    if width:
        p["row"] = (number - 1) // width + 1
        p["column"] = (number - 1) % width + 1
    return p


def vtarget(pack, width):
    target_id, at = read_ber_oid(pack, 0, len(pack))
    target = {"id": target_id}
    for tag, value in local_set_items(pack, at, len(pack)):
        if tag in PIXEL_ITEMS:
            target[PIXEL_ITEMS[tag]] = pixel(int.from_bytes(value, "big"), width)
        elif tag == 5:
            if len(value) != 1 or value[0] > 100:
                raise ValueError("confidence level must be one byte, 0..100")
            target["confidence_level"] = value[0]
        elif tag == 17:
            if len(value) not in (10, 16, 22):
                raise ValueError("target location must be 10, 16 or 22 bytes")
            target["location"] = {"lat": reverse_imapb(-90.0, 90.0, value[0:4]),
                                  "lon": reverse_imapb(-180.0, 180.0, value[4:8]),
                                  "hae": reverse_imapb(-900.0, 19000.0, value[8:10])}
        elif tag == 19:
            target["centroid_row"] = int.from_bytes(value, "big")
        elif tag == 20:
            target["centroid_column"] = int.from_bytes(value, "big")
        else:
            target.setdefault("other", {})[str(tag)] = value.hex().upper()
    return target


def decode(data):
    """The VMTI LS in `data` (ST 0601 tag 74's value) as a dict; raises ValueError."""
    data = bytes(data)
    items = local_set_items(data, 0, len(data))
    out = {"targets": []}
    series = None
    for tag, value in items:
        if tag in SET_NAMES:
            out[SET_NAMES[tag]] = int.from_bytes(value, "big")
        elif tag == 101:
            series = value
        else:
            out.setdefault("other", {})[str(tag)] = value.hex().upper()
    if series is not None:
        at = 0
        while at < len(series):
            length, at = read_ber_length(series, at, len(series))
            if at + length > len(series):
                raise ValueError("a VTarget pack runs past its series")
            out["targets"].append(vtarget(series[at:at + length], out.get("frame_width")))
            at += length
    return out


def tag74_of_st0601(packet):
    """The value of tag 74 in an ST 0601 packet (16-byte key, BER length, items), or None."""
    at = 16
    length, at = read_ber_length(packet, at, len(packet))
    for tag, value in local_set_items(packet, at, at + length):
        if tag == 74:
            return value
    return None


if __name__ == "__main__":
    for arg in sys.argv[1:]:
        print(json.dumps(decode(bytes.fromhex(arg)), indent=1))
