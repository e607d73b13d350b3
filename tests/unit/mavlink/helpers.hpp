// Shared by the MAVLink unit tests: byte helpers, hand-built frames of any id and flags, and
// random messages.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

#include "mavlink/mavlink.hpp"

namespace mavtest {

using Bytes = std::vector<std::uint8_t>;
using namespace gimbal::mavlink;

// Appends by resize and copy: vector::insert at the end of a vector built from a brace list
// makes GCC 12 -O3 on aarch64 report a false -Warray-bounds in its reallocation path.
inline void append(Bytes& out, const Bytes& more) {
    const auto at = out.size();
    out.resize(at + more.size());
    std::copy(more.begin(), more.end(), out.begin() + static_cast<std::ptrdiff_t>(at));
}

inline Bytes concat(const std::vector<Bytes>& parts) {
    Bytes out;
    for (const auto& p : parts) append(out, p);
    return out;
}

// A v1 frame with any id and payload, checksummed with `crc_extra` (so it may be a frame of
// an id this codec does not know).
inline Bytes raw_v1(std::uint8_t msgid, const Bytes& payload, std::uint8_t crc_extra,
                    std::uint8_t seq = 0, std::uint8_t sysid = 1, std::uint8_t compid = 1) {
    Bytes f{magic_v1, static_cast<std::uint8_t>(payload.size()), seq, sysid, compid, msgid};
    append(f, payload);
    const std::uint16_t crc = frame_crc(std::span<const std::uint8_t>(f).subspan(1), crc_extra);
    f.push_back(static_cast<std::uint8_t>(crc & 0xFF));
    f.push_back(static_cast<std::uint8_t>(crc >> 8));
    return f;
}

// A v2 frame as written (no truncation applied), with any incompat flags; a signed frame gets
// `signature` (13 bytes) appended after the CRC.
inline Bytes raw_v2(std::uint32_t msgid, const Bytes& payload, std::uint8_t crc_extra,
                    std::uint8_t incompat = 0, const Bytes& signature = {}, std::uint8_t seq = 0,
                    std::uint8_t sysid = 1, std::uint8_t compid = 1) {
    Bytes f{magic_v2,
            static_cast<std::uint8_t>(payload.size()),
            incompat,
            0,
            seq,
            sysid,
            compid,
            static_cast<std::uint8_t>(msgid & 0xFF),
            static_cast<std::uint8_t>((msgid >> 8) & 0xFF),
            static_cast<std::uint8_t>((msgid >> 16) & 0xFF)};
    append(f, payload);
    const std::uint16_t crc = frame_crc(std::span<const std::uint8_t>(f).subspan(1), crc_extra);
    f.push_back(static_cast<std::uint8_t>(crc & 0xFF));
    f.push_back(static_cast<std::uint8_t>(crc >> 8));
    append(f, signature);
    return f;
}

// A 13-byte signature block: link id, 48-bit timestamp, 48-bit signature (not checked).
inline Bytes fake_signature() {
    return {0x01, 0x10, 0x20, 0x30, 0x40, 0x50, 0x60, 0xDE, 0xAD, 0xBE, 0xEF, 0xFE, 0xFD};
}

inline Bytes payload_of(const Payload& p) {
    const PayloadBytes b = encode_payload(p);
    return Bytes(b.view().begin(), b.view().end());
}

// Random values for every field; `zero_tail` clears the fields at the end of the wire order so
// that MAVLink 2 truncation has something to cut.
inline Payload random_payload(std::mt19937& rng, std::size_t which, bool zero_tail = false) {
    auto u = [&]<class T>(T) { return static_cast<T>(rng()); };
    std::uniform_real_distribution<float> angle(-3.14159f, 3.14159f);
    switch (which % 5) {
        case 0: {
            Heartbeat m{u(std::uint32_t{}), u(std::uint8_t{}), u(std::uint8_t{}),
                        u(std::uint8_t{}),  u(std::uint8_t{}), u(std::uint8_t{})};
            if (zero_tail) m.system_status = m.mavlink_version = 0;
            return m;
        }
        case 1: {
            SystemTime m{(std::uint64_t{rng()} << 32) | rng(), u(std::uint32_t{})};
            if (zero_tail) m.time_boot_ms = 0;
            return m;
        }
        case 2: {
            Attitude m{u(std::uint32_t{}), angle(rng), angle(rng), angle(rng),
                       angle(rng),         angle(rng), angle(rng)};
            if (zero_tail) m.pitchspeed = m.yawspeed = 0;
            return m;
        }
        case 3: {
            GlobalPositionInt m{u(std::uint32_t{}), u(std::int32_t{}), u(std::int32_t{}),
                                u(std::int32_t{}),  u(std::int32_t{}), u(std::int16_t{}),
                                u(std::int16_t{}),  u(std::int16_t{}), u(std::uint16_t{})};
            if (zero_tail) m.vz = 0, m.hdg = 0;
            return m;
        }
        default: {
            RcChannels m;
            m.time_boot_ms = u(std::uint32_t{});
            m.chancount = static_cast<std::uint8_t>(rng() % 19);
            for (auto& c : m.chan_raw) c = static_cast<std::uint16_t>(1000 + rng() % 1001);
            m.rssi = u(std::uint8_t{});
            if (zero_tail) {
                for (std::size_t i = 12; i < m.chan_raw.size(); ++i) m.chan_raw[i] = 0;
                m.chancount = m.rssi = 0;
            }
            return m;
        }
    }
}

}  // namespace mavtest
