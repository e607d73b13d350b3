"""An independent MISB ST 0601 (UAS Datalink Local Set) decoder, standard library only.

Written from the standard's own item table (ST 0601.19 section 8: item name, KLV format,
range/map and special values), not from gimbald's C++ table, so that the integration test can
check lib/klv against a second reading of the standard. Output: one dict keyed by the item
names in snake_case, in the units of the gimbald interface contract (section 1): degrees,
metres, m/s, seconds; time stamps as ISO-8601 UTC with microseconds; enumerations by name;
flags as dicts of booleans; nested sets and packs as upper-case hex; unknown tags under
"unknown" and items of an impossible length under "invalid"; a zero-length item, a reserved
"out of range" value or an IMAPB special value as None.

    python3 st0601.py FILE...   prints each set's status and JSON
"""

import datetime
import json
import math
import sys

UAS_LS_KEY = bytes.fromhex("060E2B34020B01010E01030101000000")

# ST 0601.19 items as the standard lists them: (tag, item name, format, map).
#   "uintN a..b"   : map 0..(2^N)-1 onto a..b
#   "intN +-a"     : map -(2^(N-1)-1)..(2^(N-1)-1) onto +-a; -(2^(N-1)) is reserved
#   "IMAPB(a, b)"  : MISB ST 1201 with the item's length
#   "uintN", "int" : the integer as it is; "uint" and "int" are variable length
#   "us"           : microseconds since 1970 (uint64); "uint us": the same, 1 to 8 bytes
#   "utf8", "set" (kept as hex), "enum:<name>", "flags:<name>", "nibbles:<name>",
#   "oids", "frame_rate", "active_bits"
ITEMS = [
    (1, "Checksum", "uint16", None),
    (2, "Precision Time Stamp", "us", None),
    (3, "Mission ID", "utf8", None),
    (4, "Platform Tail Number", "utf8", None),
    (5, "Platform Heading Angle", "uint16", "0..360"),
    (6, "Platform Pitch Angle", "int16", "+-20"),
    (7, "Platform Roll Angle", "int16", "+-50"),
    (8, "Platform True Airspeed", "uint8", "0..255"),
    (9, "Platform Indicated Airspeed", "uint8", "0..255"),
    (10, "Platform Designation", "utf8", None),
    (11, "Image Source Sensor", "utf8", None),
    (12, "Image Coordinate System", "utf8", None),
    (13, "Sensor Latitude", "int32", "+-90"),
    (14, "Sensor Longitude", "int32", "+-180"),
    (15, "Sensor True Altitude", "uint16", "-900..19000"),
    (16, "Sensor Horizontal Field of View", "uint16", "0..180"),
    (17, "Sensor Vertical Field of View", "uint16", "0..180"),
    (18, "Sensor Relative Azimuth Angle", "uint32", "0..360"),
    (19, "Sensor Relative Elevation Angle", "int32", "+-180"),
    (20, "Sensor Relative Roll Angle", "uint32", "0..360"),
    (21, "Slant Range", "uint32", "0..5000000"),
    (22, "Target Width", "uint16", "0..10000"),
    (23, "Frame Center Latitude", "int32", "+-90"),
    (24, "Frame Center Longitude", "int32", "+-180"),
    (25, "Frame Center Elevation", "uint16", "-900..19000"),
    (26, "Offset Corner Latitude Point 1", "int16", "+-0.075"),
    (27, "Offset Corner Longitude Point 1", "int16", "+-0.075"),
    (28, "Offset Corner Latitude Point 2", "int16", "+-0.075"),
    (29, "Offset Corner Longitude Point 2", "int16", "+-0.075"),
    (30, "Offset Corner Latitude Point 3", "int16", "+-0.075"),
    (31, "Offset Corner Longitude Point 3", "int16", "+-0.075"),
    (32, "Offset Corner Latitude Point 4", "int16", "+-0.075"),
    (33, "Offset Corner Longitude Point 4", "int16", "+-0.075"),
    (34, "Icing Detected", "enum:icing", None),
    (35, "Wind Direction", "uint16", "0..360"),
    (36, "Wind Speed", "uint8", "0..100"),
    (37, "Static Pressure", "uint16", "0..5000"),
    (38, "Density Altitude", "uint16", "-900..19000"),
    (39, "Outside Air Temperature", "int8", None),
    (40, "Target Location Latitude", "int32", "+-90"),
    (41, "Target Location Longitude", "int32", "+-180"),
    (42, "Target Location Elevation", "uint16", "-900..19000"),
    (43, "Target Track Gate Width", "uint8", "0..510"),
    (44, "Target Track Gate Height", "uint8", "0..510"),
    (45, "Target Error Estimate - CE90", "uint16", "0..4095"),
    (46, "Target Error Estimate - LE90", "uint16", "0..4095"),
    (47, "Generic Flag Data", "flags:generic", None),
    (48, "Security Local Set", "set", None),
    (49, "Differential Pressure", "uint16", "0..5000"),
    (50, "Platform Angle of Attack", "int16", "+-20"),
    (51, "Platform Vertical Speed", "int16", "+-180"),
    (52, "Platform Sideslip Angle", "int16", "+-20"),
    (53, "Airfield Barometric Pressure", "uint16", "0..5000"),
    (54, "Airfield Elevation", "uint16", "-900..19000"),
    (55, "Relative Humidity", "uint8", "0..100"),
    (56, "Platform Ground Speed", "uint8", "0..255"),
    (57, "Ground Range", "uint32", "0..5000000"),
    (58, "Platform Fuel Remaining", "uint16", "0..10000"),
    (59, "Platform Call Sign", "utf8", None),
    (60, "Weapon Load", "nibbles:load", None),
    (61, "Weapon Fired", "nibbles:fired", None),
    (62, "Laser PRF Code", "uint16", None),
    (63, "Sensor Field of View Name", "enum:fov", None),
    (64, "Platform Magnetic Heading", "uint16", "0..360"),
    (65, "UAS Datalink LS Version Number", "uint8", None),
    (66, "Target Location Covariance Matrix", "set", None),
    (67, "Alternate Platform Latitude", "int32", "+-90"),
    (68, "Alternate Platform Longitude", "int32", "+-180"),
    (69, "Alternate Platform Altitude", "uint16", "-900..19000"),
    (70, "Alternate Platform Name", "utf8", None),
    (71, "Alternate Platform Heading", "uint16", "0..360"),
    (72, "Event Start Time - UTC", "us", None),
    (73, "RVT Local Set", "set", None),
    (74, "VMTI Local Set", "set", None),
    (75, "Sensor Ellipsoid Height", "uint16", "-900..19000"),
    (76, "Alternate Platform Ellipsoid Height", "uint16", "-900..19000"),
    (77, "Operational Mode", "enum:opmode", None),
    (78, "Frame Center Height Above Ellipsoid", "uint16", "-900..19000"),
    (79, "Sensor North Velocity", "int16", "+-327"),
    (80, "Sensor East Velocity", "int16", "+-327"),
    (81, "Image Horizon Pixel Pack", "set", None),
    (82, "Corner Latitude Point 1 (Full)", "int32", "+-90"),
    (83, "Corner Longitude Point 1 (Full)", "int32", "+-180"),
    (84, "Corner Latitude Point 2 (Full)", "int32", "+-90"),
    (85, "Corner Longitude Point 2 (Full)", "int32", "+-180"),
    (86, "Corner Latitude Point 3 (Full)", "int32", "+-90"),
    (87, "Corner Longitude Point 3 (Full)", "int32", "+-180"),
    (88, "Corner Latitude Point 4 (Full)", "int32", "+-90"),
    (89, "Corner Longitude Point 4 (Full)", "int32", "+-180"),
    (90, "Platform Pitch Angle (Full)", "int32", "+-90"),
    (91, "Platform Roll Angle (Full)", "int32", "+-90"),
    (92, "Platform Angle of Attack (Full)", "int32", "+-90"),
    (93, "Platform Sideslip Angle (Full)", "int32", "+-180"),
    (94, "MIIS Core Identifier", "set", None),
    (95, "SAR Motion Imagery Local Set", "set", None),
    (96, "Target Width Extended", "IMAPB(0, 1500000)", None),
    (97, "Range Image Local Set", "set", None),
    (98, "Geo-Registration Local Set", "set", None),
    (99, "Composite Imaging Local Set", "set", None),
    (100, "Segment Local Set", "sets", None),
    (101, "Amend Local Set", "sets", None),
    (102, "SDCC-FLP", "sets", None),
    (103, "Density Altitude Extended", "IMAPB(-900, 40000)", None),
    (104, "Sensor Ellipsoid Height Extended", "IMAPB(-900, 40000)", None),
    (105, "Alternate Platform Ellipsoid Height Extended", "IMAPB(-900, 40000)", None),
    (106, "Stream Designator", "utf8", None),
    (107, "Operational Base", "utf8", None),
    (108, "Broadcast Source", "utf8", None),
    (109, "Range To Recovery Location", "IMAPB(0, 21000) km", None),
    (110, "Time Airborne", "uint", None),
    (111, "Propulsion Unit Speed", "uint", None),
    (112, "Platform Course Angle", "IMAPB(0, 360)", None),
    (113, "Altitude Above Ground Level", "IMAPB(-900, 40000)", None),
    (114, "Radar Altimeter", "IMAPB(-900, 40000)", None),
    (115, "Control Command", "sets", None),
    (116, "Control Command Verification List", "oids", None),
    (117, "Sensor Azimuth Rate", "IMAPB(-1000, 1000)", None),
    (118, "Sensor Elevation Rate", "IMAPB(-1000, 1000)", None),
    (119, "Sensor Roll Rate", "IMAPB(-1000, 1000)", None),
    (120, "On-board MI Storage Percent Full", "IMAPB(0, 100)", None),
    (121, "Active Wavelength List", "oids", None),
    (122, "Country Codes", "set", None),
    (123, "Number of NAVSATs in View", "uint8", None),
    (124, "Positioning Method Source", "flags:positioning", None),
    (125, "Platform Status", "enum:status", None),
    (126, "Sensor Control Mode", "enum:control", None),
    (127, "Sensor Frame Rate Pack", "frame_rate", None),
    (128, "Wavelengths List", "set", None),
    (129, "Target ID", "utf8", None),
    (130, "Airbase Locations", "set", None),
    (131, "Take-off Time", "uint us", None),
    (132, "Transmission Frequency", "IMAPB(1, 99999)", None),
    (133, "On-board MI Storage Capacity", "uint", None),
    (134, "Zoom Percentage", "IMAPB(0, 100)", None),
    (135, "Communications Method", "utf8", None),
    (136, "Leap Seconds", "int", None),
    (137, "Correction Offset", "int us", None),
    (138, "Payload List", "set", None),
    (139, "Active Payloads", "active_bits", None),
    (140, "Weapons Stores", "set", None),
    (141, "Waypoint List", "set", None),
    (142, "View Domain", "set", None),
    (143, "Metadata Substream ID Pack", "set", None),
]

LABELS = {
    "icing": ["Detector off", "No icing Detected", "Icing Detected"],
    "fov": ["Ultranarrow", "Narrow", "Medium", "Wide", "Ultrawide", "Narrow Medium",
            "2x Ultranarrow", "4x Ultranarrow", "Continuous Zoom"],
    "opmode": ["Other", "Operational", "Training", "Exercise", "Maintenance", "Test"],
    "status": ["Active", "Pre-flight", "Pre-flight-Taxiing", "Run-up", "Take-off", "Ingress",
               "Manual Operation", "Automated-orbit", "Transitioning", "Egress", "Landing",
               "Landing-Taxiing", "Landed-Parked"],
    "control": ["Off", "Home Position", "Uncontrolled", "Manual Control", "Calibrating",
                "Auto - Holding Position", "Auto - Tracking"],
    # Flags: bit 0 first.
    "generic": ["Laser Range", "Auto-Track", "IR Polarity", "Icing Status", "Slant Range",
                "Image Invalid"],
    "positioning": ["On-board INS", "GPS", "Galileo", "QZSS", "NAVIC", "GLONASS", "BeiDou-1",
                    "BeiDou-2"],
    # Nibbles: most significant first.
    "load": ["Station Number", "Substation Number", "Weapon Type", "Weapon Variant"],
    "fired": ["Station Number", "Substation Number"],
}


def snake(text):
    """ST 0601 item or value name -> snake_case ("Target Error Estimate - CE90" ->
    "target_error_estimate_ce90", "Pre-flight-Taxiing" -> "preflight_taxiing")."""
    text = text.replace("Pre-flight", "Preflight").replace("Take-off", "Take off")
    text = text.replace("On-board", "On board").replace("Run-up", "Run up")
    text = text.replace("(Full)", "Full").replace("Geo-Registration", "Geo Registration")
    text = text.replace("Auto-Track", "Auto Track").replace("Landed-Parked", "Landed Parked")
    text = text.replace("BeiDou-", "BeiDou ").replace("SDCC-FLP", "SDCC FLP")
    words = "".join(c if c.isalnum() else " " for c in text).split()
    return "_".join(w.lower() for w in words)


def ber_length(data, at):
    """(value, next offset) of the BER length at data[at]; raises ValueError."""
    if at >= len(data):
        raise ValueError("truncated length")
    first = data[at]
    if first < 0x80:
        return first, at + 1
    count = first & 0x7F
    if count == 0 or count > 8:
        raise ValueError("invalid BER length")
    if at + 1 + count > len(data):
        raise ValueError("truncated length")
    return int.from_bytes(data[at + 1:at + 1 + count], "big"), at + 1 + count


def ber_oid(data, at, end):
    value = 0
    if at < end and data[at] == 0x80:
        raise ValueError("padded BER-OID")
    for i in range(at, end):
        value = (value << 7) | (data[i] & 0x7F)
        if not data[i] & 0x80:
            return value, i + 1
    raise ValueError("truncated BER-OID")


def running_sum(data):
    """ST 0601 item 1: the 16-bit sum of big-endian words."""
    total = 0
    for i, byte in enumerate(data):
        total += byte << 8 if i % 2 == 0 else byte
    return total & 0xFFFF


def iso_utc(microseconds):
    moment = datetime.datetime(1970, 1, 1, tzinfo=datetime.timezone.utc) + \
        datetime.timedelta(microseconds=microseconds)
    return moment.strftime("%Y-%m-%dT%H:%M:%S.%fZ")


def imapb_value(a, b, raw):
    """MISB ST 1201 reverse IMAPB; None for a special value (top bit set)."""
    length = len(raw)
    y = int.from_bytes(raw, "big")
    if y >> (8 * length - 1):
        return None
    b_pow = math.ceil(math.log2(b - a))
    d_pow = 8 * length - 1
    s_f = 2.0 ** (d_pow - b_pow)
    z_offset = s_f * a - math.floor(s_f * a) if a < 0 else 0.0
    return (2.0 ** (b_pow - d_pow)) * (y - z_offset) + a


def text(raw):
    raw = raw.split(b"\0", 1)[0]
    out = raw.decode("utf-8", errors="replace").replace("\ufffd", "?")
    return "".join("?" if ord(c) < 0x20 or c == "\x7f" else c for c in out)


class Invalid(Exception):
    pass


def decode_value(fmt, mapping, raw):
    """One item's value; raises Invalid for a length its format cannot have."""
    if not raw:
        return None  # ST 0601: a zero-length item means "unknown"
    if fmt in ("set", "sets"):
        return raw.hex().upper()
    if fmt == "utf8":
        return text(raw)
    if fmt in ("us", "uint us"):  # "us": exactly 8 bytes; "uint us": 1 to 8
        if len(raw) > 8 or (fmt == "us" and len(raw) != 8):
            raise Invalid()
        return iso_utc(int.from_bytes(raw, "big"))
    if fmt.startswith("IMAPB"):
        inside = fmt[fmt.index("(") + 1:fmt.index(")")]
        a, b = (float(x) for x in inside.split(","))
        if len(raw) > 8:
            raise Invalid()
        value = imapb_value(a, b, raw)
        if value is not None and fmt.endswith("km"):
            value *= 1000.0
        return value
    if fmt.startswith("uint") or fmt.startswith("int"):
        signed = fmt.startswith("int")
        bits = "".join(c for c in fmt.split()[0] if c.isdigit())
        if bits:
            if len(raw) * 8 != int(bits):
                raise Invalid()
        elif len(raw) > 8:
            raise Invalid()
        n = len(raw) * 8
        integer = int.from_bytes(raw, "big", signed=signed)
        if mapping is None:
            if fmt.endswith("us"):
                return integer / 1e6
            return integer
        if mapping.startswith("+-"):
            limit = float(mapping[2:])
            if integer == -(1 << (n - 1)):
                return None  # the reserved "out of range" / "N/A" value
            return integer * (2 * limit) / ((1 << n) - 2)
        low, high = (float(x) for x in mapping.split(".."))
        return low + integer * (high - low) / ((1 << n) - 1)
    if fmt.startswith("enum:"):
        if len(raw) != 1:
            raise Invalid()
        labels = LABELS[fmt[5:]]
        return snake(labels[raw[0]]) if raw[0] < len(labels) else raw[0]
    if fmt.startswith("flags:"):
        if len(raw) != 1:
            raise Invalid()
        out = {}
        for bit in range(8):
            labels = LABELS[fmt[6:]]
            on = bool(raw[0] >> bit & 1)
            if bit < len(labels):
                out[snake(labels[bit])] = on
            elif on:
                out["bit_%d" % bit] = True
        return out
    if fmt.startswith("nibbles:"):
        labels = LABELS[fmt[8:]]
        if len(raw) * 2 != len(labels):
            raise Invalid()
        integer = int.from_bytes(raw, "big")
        return {snake(label): (integer >> 4 * (len(labels) - 1 - i)) & 0xF
                for i, label in enumerate(labels)}
    if fmt in ("oids", "frame_rate"):
        values, at = [], 0
        try:
            while at < len(raw):
                value, at = ber_oid(raw, at, len(raw))
                values.append(value)
        except ValueError:
            raise Invalid()
        if fmt == "oids":
            return values
        if len(values) > 2 or (len(values) == 2 and values[1] == 0):
            raise Invalid()
        return {"numerator": values[0], "denominator": values[1] if len(values) > 1 else 1}
    if fmt == "active_bits":
        integer = int.from_bytes(raw, "big")
        return [i for i in range(8 * len(raw)) if integer >> i & 1]
    raise AssertionError(fmt)


TABLE = {tag: (snake(name), fmt, mapping) for tag, name, fmt, mapping in ITEMS}


def decode(data):
    """(status, reason, items dict) of the local set at the start of `data`.
    status: "ok", "bad_checksum" or "malformed"."""
    if data[:16] != UAS_LS_KEY:
        return "malformed", "not the UAS Datalink LS key", {}
    try:
        length, at = ber_length(data, 16)
    except ValueError as e:
        return "malformed", str(e), {}
    end = at + length
    if end > len(data):
        return "malformed", "truncated", {}
    items = []
    try:
        while at < end:
            tag, at = ber_oid(data, at, end)
            size, at = ber_length(data[:end], at)
            if at + size > end:
                return "malformed", "tag %d runs past the set" % tag, {}
            items.append((tag, at, bytes(data[at:at + size])))
            at += size
    except ValueError as e:
        return "malformed", str(e), {}
    if not items or items[-1][0] != 1 or len(items[-1][2]) != 2:
        return "malformed", "no checksum last", {}
    out = {}
    for tag, _, raw in items:
        if tag not in TABLE:
            out.setdefault("unknown", {})[str(tag)] = raw.hex().upper()
            continue
        name, fmt, mapping = TABLE[tag]
        try:
            value = decode_value(fmt, mapping, raw)
        except Invalid:
            out.setdefault("invalid", {})[str(tag)] = raw.hex().upper()
            continue
        if fmt == "sets":
            out.setdefault(name, []).append(value)
        else:
            out[name] = value
    stored = int.from_bytes(items[-1][2], "big")
    computed = running_sum(data[:items[-1][1]])
    if stored != computed:
        return "bad_checksum", "checksum 0x%04X, computed 0x%04X" % (stored, computed), out
    return "ok", "", out


def main(paths):
    for path in paths:
        with open(path, "rb") as f:
            status, reason, items = decode(f.read())
        print(path, status, reason)
        print(json.dumps(items, indent=1, sort_keys=True))


if __name__ == "__main__":
    main(sys.argv[1:])
