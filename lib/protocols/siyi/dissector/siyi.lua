-- siyi.lua: Wireshark dissector for SIYI gimbal cameras' SDK protocol (docs/siyi.md), in
-- gimbald recordings and in live UDP captures.
--
--   tshark -X lua_script:siyi.lua -r flight.pcapng
--   or copy beside gimbald.lua into ~/.local/lib/wireshark/plugins/ (docs/wireshark.md);
--   the Debian package installs both into Wireshark's global plugin folder.
--
-- Registers the dissector `siyi`, which gimbald's recordings name for SIYI frames (the
-- registry entry's `dissector`), and UDP port 37260 (the camera's SDK port). A frame is
-- STX 0x6655, CTRL, data length, SEQ, CMD_ID, data, CRC16 (all little-endian; CRC-16/XMODEM
-- over everything before it). A CMD_ID names a request on the way to the camera and its
-- reply or push on the way back: the direction comes from the recording (inbound: from the
-- camera) or, live, from the source port (37260: from the camera).
--
-- Every field is shown as gimbald's codec shows it in JSON (degrees, metres, enum names,
-- versions "major.minor.patch"), under siyi.<message>.<key>, e.g.
-- siyi.gimbal_attitude.yaw. The table between the GENERATED markers is generated from the
-- codec's message declarations (lib/protocols/siyi/codec/*_gimbal.hpp) by
-- tests/dissector/siyi_dissector_data.cpp; a ctest fails when it is stale.

local siyi_proto = Proto("siyi", "SIYI gimbal camera SDK protocol")
local siyi_udp_port = 37260

-- BEGIN GENERATED SIYI SCHEMA (tests/dissector/siyi_dissector_data.cpp from lib/protocols/siyi/codec/*_gimbal.hpp; do not edit by hand:
-- build/debug/tests/dissector/siyi-dissector-data --write lib/protocols/siyi/dissector/siyi.lua)
local siyi_enums = {
  [1] = { [-1] = "out", [0] = "stop", [1] = "in", },
  [2] = { [-1] = "near", [0] = "stop", [1] = "far", },
  [3] = { [1] = "one_key_center", [2] = "center_down", [3] = "center", [4] = "down", },
  [4] = { [0] = "take_photo", [1] = "hdr_toggle", [2] = "record_toggle", [3] = "lock_mode", [4] = "follow_mode", [5] = "fpv_mode", [6] = "hdmi_output", [7] = "cvbs_output", [8] = "video_output_off", [9] = "tilt_down", [10] = "zoom_linkage", },
  [5] = { [1] = "attitude", [2] = "laser_range", [3] = "magnetic_encoder", [4] = "motor_voltage", },
  [6] = { [0] = "off", [1] = "2hz", [2] = "4hz", [3] = "5hz", [4] = "10hz", [5] = "20hz", [6] = "50hz", [7] = "100hz", },
  [7] = { [0] = "off", [1] = "recording", [2] = "no_card", [3] = "data_loss", },
  [8] = { [0] = "lock", [1] = "follow", [2] = "fpv", },
  [9] = { [0] = "reserved", [1] = "normal", [2] = "inverted", },
  [10] = { [0] = "hdmi", [1] = "cvbs", },
  [11] = { [0] = "photo_ok", [1] = "photo_failed", [2] = "hdr_on", [3] = "hdr_off", [4] = "record_failed", [5] = "record_started", [6] = "record_stopped", },
}
local siyi_messages = {
  to_gimbal = {
    [0x00] = { name = "tcp_heartbeat", rows = {
      { k = "reserved", enc = "u8" },
    } },
    [0x01] = { name = "firmware_version_request", rows = {
    } },
    [0x02] = { name = "hardware_id_request", rows = {
    } },
    [0x04] = { name = "auto_focus", rows = {
      { k = "field", key = "trigger", enc = "u8", scale = 1, kind = "bool" },
      { k = "optional" },
      { k = "field", key = "touch_x", enc = "u16", scale = 1, kind = "int", min = 0, max = 65535 },
      { k = "field", key = "touch_y", enc = "u16", scale = 1, kind = "int", min = 0, max = 65535 },
    } },
    [0x05] = { name = "manual_zoom", rows = {
      { k = "field", key = "zoom", enc = "i8", scale = 1, kind = "enum", enum = 1, min = -128, max = 127 },
    } },
    [0x06] = { name = "manual_focus", rows = {
      { k = "field", key = "focus", enc = "i8", scale = 1, kind = "enum", enum = 2, min = -128, max = 127 },
    } },
    [0x07] = { name = "gimbal_rotation", rows = {
      { k = "field", key = "turn_yaw", enc = "i8", scale = 1, kind = "int", min = -128, max = 127 },
      { k = "field", key = "turn_pitch", enc = "i8", scale = 1, kind = "int", min = -128, max = 127 },
    } },
    [0x08] = { name = "center", rows = {
      { k = "field", key = "position", enc = "u8", scale = 1, kind = "enum", enum = 3, min = 0, max = 255 },
    } },
    [0x0A] = { name = "camera_system_info_request", rows = {
    } },
    [0x0C] = { name = "capture", rows = {
      { k = "field", key = "function", enc = "u8", scale = 1, kind = "enum", enum = 4, min = 0, max = 255 },
    } },
    [0x0D] = { name = "gimbal_attitude_request", rows = {
    } },
    [0x0E] = { name = "set_gimbal_attitude", rows = {
      { k = "field", key = "yaw", enc = "i16", scale = 10, kind = "double" },
      { k = "field", key = "pitch", enc = "i16", scale = 10, kind = "double" },
    } },
    [0x0F] = { name = "absolute_zoom", rows = {
      { k = "zoom", key = "zoom" },
    } },
    [0x15] = { name = "laser_distance_request", rows = {
    } },
    [0x16] = { name = "zoom_range_request", rows = {
    } },
    [0x17] = { name = "laser_target_request", rows = {
    } },
    [0x18] = { name = "current_zoom_request", rows = {
    } },
    [0x19] = { name = "gimbal_mode_request", rows = {
    } },
    [0x22] = { name = "aircraft_attitude", rows = {
      { k = "field", key = "time_boot_ms", enc = "u32", scale = 1, kind = "int", min = 0, max = 4294967295 },
      { k = "field", key = "roll", enc = "f32", scale = 1, kind = "f32", degrees = true },
      { k = "field", key = "pitch", enc = "f32", scale = 1, kind = "f32", degrees = true },
      { k = "field", key = "yaw", enc = "f32", scale = 1, kind = "f32", degrees = true },
      { k = "field", key = "roll_rate", enc = "f32", scale = 1, kind = "f32", degrees = true },
      { k = "field", key = "pitch_rate", enc = "f32", scale = 1, kind = "f32", degrees = true },
      { k = "field", key = "yaw_rate", enc = "f32", scale = 1, kind = "f32", degrees = true },
    } },
    [0x25] = { name = "data_stream_request", rows = {
      { k = "field", key = "type", enc = "u8", scale = 1, kind = "enum", enum = 5, min = 0, max = 255 },
      { k = "field", key = "rate", enc = "u8", scale = 1, kind = "enum", enum = 6, min = 0, max = 255 },
    } },
    [0x30] = { name = "set_utc_time", rows = {
      { k = "field", key = "unix_time_us", enc = "u64", scale = 1, kind = "int", min = 0, max = 1.8446744073709552e+19 },
    } },
    [0x3E] = { name = "raw_gps", rows = {
      { k = "field", key = "time_boot_ms", enc = "u32", scale = 1, kind = "int", min = 0, max = 4294967295 },
      { k = "field", key = "lat", enc = "i32", scale = 10000000, kind = "double" },
      { k = "field", key = "lon", enc = "i32", scale = 10000000, kind = "double" },
      { k = "field", key = "alt_msl", enc = "i32", scale = 100, kind = "double" },
      { k = "field", key = "alt_ellipsoid", enc = "i32", scale = 100, kind = "double" },
      { k = "field", key = "vn", enc = "i32", scale = 1000, kind = "double" },
      { k = "field", key = "ve", enc = "i32", scale = 1000, kind = "double" },
      { k = "field", key = "vd", enc = "i32", scale = 1000, kind = "double" },
    } },
  },
  from_gimbal = {
    [0x01] = { name = "firmware_version", rows = {
      { k = "version", key = "camera" },
      { k = "version", key = "gimbal" },
      { k = "optional" },
      { k = "version", key = "zoom" },
    } },
    [0x02] = { name = "hardware_id", rows = {
      { k = "text", key = "id", bytes = 12 },
    } },
    [0x04] = { name = "auto_focus_reply", rows = {
      { k = "field", key = "ok", enc = "u8", scale = 1, kind = "bool" },
    } },
    [0x05] = { name = "manual_zoom_reply", rows = {
      { k = "field", key = "zoom", enc = "u16", scale = 10, kind = "double" },
    } },
    [0x06] = { name = "manual_focus_reply", rows = {
      { k = "field", key = "ok", enc = "u8", scale = 1, kind = "bool" },
    } },
    [0x07] = { name = "gimbal_rotation_reply", rows = {
      { k = "field", key = "ok", enc = "u8", scale = 1, kind = "bool" },
    } },
    [0x08] = { name = "center_reply", rows = {
      { k = "field", key = "ok", enc = "u8", scale = 1, kind = "bool" },
    } },
    [0x0A] = { name = "camera_system_info", rows = {
      { k = "reserved", enc = "u8" },
      { k = "field", key = "hdr", enc = "u8", scale = 1, kind = "bool" },
      { k = "reserved", enc = "u8" },
      { k = "field", key = "record", enc = "u8", scale = 1, kind = "enum", enum = 7, min = 0, max = 255 },
      { k = "field", key = "motion_mode", enc = "u8", scale = 1, kind = "enum", enum = 8, min = 0, max = 255 },
      { k = "optional" },
      { k = "field", key = "mounting", enc = "u8", scale = 1, kind = "enum", enum = 9, min = 0, max = 255 },
      { k = "field", key = "video_output", enc = "u8", scale = 1, kind = "enum", enum = 10, min = 0, max = 255 },
      { k = "field", key = "zoom_linkage", enc = "u8", scale = 1, kind = "bool" },
    } },
    [0x0B] = { name = "function_feedback", rows = {
      { k = "field", key = "info", enc = "u8", scale = 1, kind = "enum", enum = 11, min = 0, max = 255 },
    } },
    [0x0D] = { name = "gimbal_attitude", rows = {
      { k = "field", key = "yaw", enc = "i16", scale = 10, kind = "double" },
      { k = "field", key = "pitch", enc = "i16", scale = 10, kind = "double" },
      { k = "field", key = "roll", enc = "i16", scale = 10, kind = "double" },
      { k = "field", key = "yaw_rate", enc = "i16", scale = 10, kind = "double" },
      { k = "field", key = "pitch_rate", enc = "i16", scale = 10, kind = "double" },
      { k = "field", key = "roll_rate", enc = "i16", scale = 10, kind = "double" },
    } },
    [0x0E] = { name = "set_gimbal_attitude_reply", rows = {
      { k = "field", key = "yaw", enc = "i16", scale = 10, kind = "double" },
      { k = "field", key = "pitch", enc = "i16", scale = 10, kind = "double" },
      { k = "field", key = "roll", enc = "i16", scale = 10, kind = "double" },
    } },
    [0x0F] = { name = "absolute_zoom_reply", rows = {
      { k = "field", key = "ok", enc = "u8", scale = 1, kind = "bool" },
    } },
    [0x15] = { name = "laser_distance", rows = {
      { k = "field", key = "distance", enc = "u16", scale = 10, kind = "double" },
    } },
    [0x16] = { name = "zoom_range", rows = {
      { k = "zoom", key = "zoom_max" },
    } },
    [0x17] = { name = "laser_target", rows = {
      { k = "field", key = "lon", enc = "i32", scale = 10000000, kind = "double" },
      { k = "field", key = "lat", enc = "i32", scale = 10000000, kind = "double" },
    } },
    [0x18] = { name = "current_zoom", rows = {
      { k = "zoom", key = "zoom" },
    } },
    [0x19] = { name = "gimbal_mode", rows = {
      { k = "field", key = "mode", enc = "u8", scale = 1, kind = "enum", enum = 8, min = 0, max = 255 },
    } },
    [0x25] = { name = "data_stream_reply", rows = {
      { k = "field", key = "type", enc = "u8", scale = 1, kind = "enum", enum = 5, min = 0, max = 255 },
    } },
    [0x26] = { name = "magnetic_encoder", rows = {
      { k = "field", key = "yaw", enc = "i16", scale = 10, kind = "double" },
      { k = "field", key = "pitch", enc = "i16", scale = 10, kind = "double" },
      { k = "field", key = "roll", enc = "i16", scale = 10, kind = "double" },
    } },
    [0x30] = { name = "set_utc_time_reply", rows = {
      { k = "field", key = "ok", enc = "i8", scale = 1, kind = "bool" },
    } },
  },
}
-- END GENERATED SIYI SCHEMA

local sf = {
    stx = ProtoField.uint16("siyi.stx", "STX", base.HEX),
    ctrl = ProtoField.uint8("siyi.ctrl", "CTRL", base.HEX),
    need_ack = ProtoField.bool("siyi.ctrl.need_ack", "need_ack", 8, nil, 0x01),
    ack_pack = ProtoField.bool("siyi.ctrl.ack_pack", "ack_pack", 8, nil, 0x02),
    length = ProtoField.uint16("siyi.length", "Data length", base.DEC),
    seq = ProtoField.uint16("siyi.seq", "SEQ", base.DEC),
    cmd = ProtoField.uint8("siyi.cmd", "CMD_ID", base.HEX),
    message = ProtoField.string("siyi.message", "Message"),
    direction = ProtoField.string("siyi.direction", "Direction"),
    error = ProtoField.string("siyi.error", "Decode error"),
    data = ProtoField.bytes("siyi.data", "Data"),
    crc = ProtoField.uint16("siyi.crc", "CRC16", base.HEX),
    crc_computed = ProtoField.uint16("siyi.crc.computed", "Computed CRC16", base.HEX),
    crc_status = ProtoField.string("siyi.crc.status", "CRC16 status"),
}

-- One field per message key: siyi.<message>.<key>.
local message_fields = {}
local function field_type(row)
    if row.k == "field" then
        if row.kind == "bool" then return "bool" end
        if row.kind == "int" then return "int" end
        if row.kind == "enum" then return "string" end
        return "double"
    end
    if row.k == "zoom" then return "double" end
    return "string"  -- text, version
end
for direction, messages in pairs(siyi_messages) do
    for _, m in pairs(messages) do
        message_fields[m.name] = message_fields[m.name] or {}
        for _, row in ipairs(m.rows) do
            if row.key and not message_fields[m.name][row.key] then
                local abbr = "siyi." .. m.name .. "." .. row.key
                local t = field_type(row)
                local f
                if t == "bool" then
                    f = ProtoField.bool(abbr, row.key)
                elseif t == "int" and row.enc == "u64" then
                    f = ProtoField.uint64(abbr, row.key, base.DEC)
                elseif t == "int" and row.enc:sub(1, 1) == "i" then
                    f = ProtoField.int32(abbr, row.key, base.DEC)
                elseif t == "int" then
                    f = ProtoField.uint32(abbr, row.key, base.DEC)
                elseif t == "double" then
                    f = ProtoField.double(abbr, row.key)
                else
                    f = ProtoField.string(abbr, row.key)
                end
                message_fields[m.name][row.key] = f
            end
        end
    end
end

local all_fields = {}
for _, f in pairs(sf) do all_fields[#all_fields + 1] = f end
for _, fields in pairs(message_fields) do
    for _, f in pairs(fields) do all_fields[#all_fields + 1] = f end
end
siyi_proto.fields = all_fields

local siyi_expert = {
    bad_crc = ProtoExpert.new("siyi.expert.bad_crc", "Bad SIYI CRC16", expert.group.CHECKSUM,
                              expert.severity.WARN),
    truncated = ProtoExpert.new("siyi.expert.truncated", "Not a complete SIYI frame",
                                expert.group.MALFORMED, expert.severity.ERROR),
    undecoded = ProtoExpert.new("siyi.expert.undecoded", "SIYI message not decoded",
                                expert.group.UNDECODED, expert.severity.NOTE),
}
siyi_proto.experts = { siyi_expert.bad_crc, siyi_expert.truncated, siyi_expert.undecoded }

-- CRC-16/XMODEM: polynomial 0x1021, initial 0, no reflection, no final XOR.
local function crc16(tvb, offset, length)
    local crc = 0
    for i = offset, offset + length - 1 do
        crc = bit32.bxor(crc, bit32.lshift(tvb(i, 1):uint(), 8))
        for _ = 1, 8 do
            if bit32.band(crc, 0x8000) ~= 0 then
                crc = bit32.band(bit32.bxor(bit32.lshift(crc, 1), 0x1021), 0xFFFF)
            else
                crc = bit32.band(bit32.lshift(crc, 1), 0xFFFF)
            end
        end
    end
    return crc
end

local enc_size = { u8 = 1, i8 = 1, u16 = 2, i16 = 2, u32 = 4, i32 = 4, u64 = 8, f32 = 4 }

local function read_raw(range, enc)
    if enc == "f32" then return range:le_float() end
    if enc:sub(1, 1) == "i" then return range:le_int() end
    return range:le_uint()
end

local function round_half_away(v)
    if v < 0 then return -math.floor(-v + 0.5) end
    return math.floor(v + 0.5)
end

local function clamp(v, lo, hi)
    if v < lo then return lo end
    if v > hi then return hi end
    return v
end

-- A float member holds raw / scale as a 32-bit float: round it as the codec's cast does.
local function as_float32(v)
    return Struct.unpack("<f", Struct.pack("<f", v))
end

-- What the codec's JSON shows for a field row and its raw wire value.
local function field_value(row, raw)
    if row.kind == "bool" then return raw ~= 0 end
    if row.kind == "enum" then
        local v = clamp(raw, row.min, row.max)
        return siyi_enums[row.enum][v] or tostring(v)
    end
    if row.kind == "int" then
        if row.scale == 1 then return clamp(raw, row.min, row.max) end
        return clamp(round_half_away(raw / row.scale), row.min, row.max)
    end
    local v = raw / row.scale
    if row.kind == "f32" then v = as_float32(v) end
    if row.degrees then v = v * 180 / math.pi end
    return v
end

local function printable(range, bytes)
    local out = {}
    for i = 0, bytes - 1 do
        local b = range(i, 1):uint()
        if b == 0 then break end
        if b >= 0x20 and b < 0x7F then
            out[#out + 1] = string.char(b)
        else
            out[#out + 1] = string.format("\\x%02X", b)
        end
    end
    return table.concat(out)
end

-- Decodes `data` (a TvbRange, or nil when empty) by the message's rows into `tree`, as the
-- codec's decoder does: optional trailing fields may be absent, bytes past the known fields
-- are ignored. Returns nil, or "too_short".
local function dissect_message(m, data, tree)
    local fields = message_fields[m.name]
    local size = data and data:len() or 0
    local at, optional = 0, false
    for _, row in ipairs(m.rows) do
        if row.k == "optional" then
            optional = true
        else
            local n
            if row.k == "field" or row.k == "reserved" then
                n = enc_size[row.enc]
            elseif row.k == "text" then
                n = row.bytes
            elseif row.k == "version" then
                n = 4
            else
                n = 2  -- zoom
            end
            if size - at < n then
                if optional then return nil end
                return "too_short"
            end
            local range = data(at, n)
            if row.k == "field" and row.kind == "int" and row.enc == "u64" then
                tree:add_le(fields[row.key], range)  -- a UInt64 (a Lua number loses bits)
            elseif row.k == "field" then
                local value = field_value(row, read_raw(range, row.enc))
                local item = tree:add(fields[row.key], range, value)
                if type(value) == "number" and math.floor(value) ~= value then
                    item:set_text(row.key .. ": " .. string.format("%.10g", value))
                end
            elseif row.k == "text" then
                tree:add(fields[row.key], range, printable(range, n))
            elseif row.k == "version" then
                tree:add(fields[row.key], range, string.format("%d.%d.%d", range(2, 1):uint(),
                                                               range(1, 1):uint(),
                                                               range(0, 1):uint()))
            elseif row.k == "zoom" then
                tree:add(fields[row.key], range, range(0, 1):uint() + range(1, 1):uint() / 10.0)
            end
            at = at + n
        end
    end
    return nil
end

local function from_camera(pinfo)
    if pinfo.p2p_dir == P2P_DIR_RECV then return true end
    if pinfo.p2p_dir == P2P_DIR_SENT then return false end
    return pinfo.src_port == siyi_udp_port
end

-- One frame at offset: returns the bytes it used (0: not a frame start) and its info text.
local function dissect_frame(tvb, pinfo, tree, offset, inbound)
    local left = tvb:len() - offset
    if left < 10 or tvb(offset, 1):uint() ~= 0x55 or tvb(offset + 1, 1):uint() ~= 0x66 then
        return 0, nil
    end
    local length = tvb(offset + 3, 2):le_uint()
    local size = 8 + length + 2
    if left < size then
        local t = tree:add(siyi_proto, tvb(offset), "SIYI (truncated)")
        t:add_proto_expert_info(siyi_expert.truncated)
        return left, "not a complete frame"
    end
    local direction = inbound and "from_gimbal" or "to_gimbal"
    local cmd = tvb(offset + 7, 1):uint()
    local m = siyi_messages[direction][cmd]
    local name = m and m.name or string.format("0x%02X", cmd)
    local t = tree:add(siyi_proto, tvb(offset, size), "SIYI " .. name)
    t:add_le(sf.stx, tvb(offset, 2))
    local ctrl = t:add(sf.ctrl, tvb(offset + 2, 1))
    ctrl:add(sf.need_ack, tvb(offset + 2, 1))
    ctrl:add(sf.ack_pack, tvb(offset + 2, 1))
    t:add_le(sf.length, tvb(offset + 3, 2))
    t:add_le(sf.seq, tvb(offset + 5, 2))
    t:add(sf.cmd, tvb(offset + 7, 1))
    t:add(sf.direction, tvb(offset + 7, 1), direction):set_generated()
    local data = length > 0 and tvb(offset + 8, length) or nil
    if m then
        t:add(sf.message, tvb(offset + 7, 1), m.name):set_generated()
        local error = dissect_message(m, data, t)
        if error then
            t:add(sf.error, tvb(offset + 7, 1), error):set_generated()
            t:add_proto_expert_info(siyi_expert.undecoded, "SIYI " .. m.name .. ": " .. error)
        end
    else
        t:add(sf.error, tvb(offset + 7, 1), "unknown_command"):set_generated()
        t:add_proto_expert_info(siyi_expert.undecoded,
                                string.format("SIYI CMD_ID 0x%02X is not decoded", cmd))
    end
    if data then t:add(sf.data, data) end
    local crc_range = tvb(offset + 8 + length, 2)
    local computed = crc16(tvb, offset, 8 + length)
    t:add_le(sf.crc, crc_range)
    t:add(sf.crc_computed, crc_range, computed):set_generated()
    local info = name
    if crc_range:le_uint() == computed then
        t:add(sf.crc_status, crc_range, "good"):set_generated()
    else
        t:add(sf.crc_status, crc_range, "bad"):set_generated()
        t:add_proto_expert_info(siyi_expert.bad_crc, string.format(
            "Bad SIYI CRC16: 0x%04x, expected 0x%04x", crc_range:le_uint(), computed))
        info = info .. " [bad CRC]"
    end
    return size, info
end

function siyi_proto.dissector(tvb, pinfo, tree)
    pinfo.cols.protocol = "SIYI"
    local inbound = from_camera(pinfo)
    local offset, infos = 0, {}
    while offset < tvb:len() do
        local used, info = dissect_frame(tvb, pinfo, tree, offset, inbound)
        if used == 0 then
            local t = tree:add(siyi_proto, tvb(offset), "SIYI (not a frame)")
            t:add_proto_expert_info(siyi_expert.truncated)
            infos[#infos + 1] = "not a frame"
            break
        end
        infos[#infos + 1] = info
        offset = offset + used
    end
    pinfo.cols.info = table.concat(infos, ", ")
    return tvb:len()
end

DissectorTable.get("udp.port"):add(siyi_udp_port, siyi_proto)
