#include "video/ts_packet.hpp"

namespace gimbal::video {

std::optional<TsPacket> parse_ts_packet(std::span<const std::uint8_t> p) {
    if (p.size() != ts_packet_size || p[0] != ts_sync_byte) return std::nullopt;
    TsPacket t;
    t.transport_error = (p[1] & 0x80) != 0;
    t.payload_unit_start = (p[1] & 0x40) != 0;
    t.pid = static_cast<std::uint16_t>(((p[1] & 0x1F) << 8) | p[2]);
    t.scrambling = static_cast<std::uint8_t>(p[3] >> 6);
    const unsigned control = (p[3] >> 4) & 3u;
    t.continuity_counter = static_cast<std::uint8_t>(p[3] & 0x0F);
    t.has_payload = (control & 1u) != 0;
    std::size_t pos = 4;
    if (control & 2u) {
        const std::size_t length = p[4];
        pos = 5 + length;
        // 2.4.3.4: at most 183 bytes with a payload, exactly 183 without one.
        if (pos > ts_packet_size) return std::nullopt;
        t.stuffed = length == 0;  // a one-byte field is itself stuffing (2.4.3.4)
        if (length > 0) {
            const std::uint8_t flags = p[5];
            t.discontinuity = (flags & 0x80) != 0;
            t.random_access = (flags & 0x40) != 0;
            // The fields the flags announce (Table 2-6): PCR, OPCR, splice countdown,
            // private data, extension; what is left over is stuffing.
            std::size_t used = 1;
            if (flags & 0x10) used += 6;
            if (flags & 0x08) used += 6;
            if (flags & 0x04) used += 1;
            if ((flags & 0x02) && 4 + 1 + used < ts_packet_size && used < length)
                used += 1 + std::size_t{p[5 + used]};
            if ((flags & 0x01) && 4 + 1 + used < ts_packet_size && used < length)
                used += 1 + std::size_t{p[5 + used]};
            t.stuffed = used < length;
            if ((flags & 0x10) && length >= 7) {
                const std::uint64_t base =
                    (std::uint64_t{p[6]} << 25) | (std::uint64_t{p[7]} << 17) |
                    (std::uint64_t{p[8]} << 9) | (std::uint64_t{p[9]} << 1) | (p[10] >> 7);
                const std::uint64_t ext = ((std::uint64_t{p[10]} & 1u) << 8) | p[11];
                t.pcr = base * 300 + ext;
            }
        }
    }
    if (t.has_payload) t.payload = p.subspan(pos);
    return t;
}

}  // namespace gimbal::video
