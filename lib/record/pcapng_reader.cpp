#include "record/pcapng_reader.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>

namespace gimbal::record {

namespace {

constexpr std::uint32_t block_section_header = 0x0A0D0D0A;
constexpr std::uint32_t block_interface = 0x00000001;
constexpr std::uint32_t block_enhanced_packet = 0x00000006;
constexpr std::size_t block_overhead = 12;  // type, total length, trailing total length

constexpr std::uint16_t opt_end = 0;
constexpr std::uint16_t shb_userappl = 4;
constexpr std::uint16_t if_name = 2;
constexpr std::uint16_t if_description = 3;
constexpr std::uint16_t if_tsresol = 9;
constexpr std::uint16_t if_tsoffset = 14;
constexpr std::uint16_t epb_flags = 2;

constexpr std::uint16_t exp_pdu_end_of_opt = 0;
constexpr std::uint16_t exp_pdu_dissector_name = 12;

std::uint16_t load16(const std::uint8_t* p, bool big) {
    return big ? static_cast<std::uint16_t>(p[0] << 8 | p[1])
               : static_cast<std::uint16_t>(p[1] << 8 | p[0]);
}

std::uint32_t load32(const std::uint8_t* p, bool big) {
    const std::uint32_t hi = load16(p + (big ? 0 : 2), big);
    const std::uint32_t lo = load16(p + (big ? 2 : 0), big);
    return hi << 16 | lo;
}

std::uint64_t load64(const std::uint8_t* p, bool big) {
    const std::uint64_t hi = load32(p + (big ? 0 : 4), big);
    const std::uint64_t lo = load32(p + (big ? 4 : 0), big);
    return hi << 32 | lo;
}

constexpr std::size_t pad4(std::size_t n) {
    return (n + 3) & ~std::size_t{3};
}

// Calls on_option(code, value) for each option until opt_endofopt or the end of `options`.
// A malformed option (running past the block) ends the list: what came before still counts.
template <class F>
void for_each_option(std::span<const std::uint8_t> options, bool big, F&& on_option) {
    std::size_t at = 0;
    while (options.size() - at >= 4) {
        const std::uint16_t code = load16(options.data() + at, big);
        const std::size_t length = load16(options.data() + at + 2, big);
        at += 4;
        if (code == opt_end) return;
        if (length > options.size() - at) return;
        on_option(code, options.subspan(at, length));
        at += std::min(pad4(length), options.size() - at);
    }
}

std::string as_text(std::span<const std::uint8_t> value) {
    std::string s(value.begin(), value.end());
    if (const auto zero = s.find('\0'); zero != std::string::npos) s.resize(zero);
    return s;
}

// ticks / ticks_per_second + offset, in microseconds, saturated to int64.
std::int64_t to_microseconds(std::uint64_t ticks, const RecordedInterface& itf) {
    constexpr auto max = std::numeric_limits<std::int64_t>::max();
    constexpr auto min = std::numeric_limits<std::int64_t>::min();
    const std::uint64_t whole_s = ticks / itf.ticks_per_second;
    const std::uint64_t rest = ticks % itf.ticks_per_second;
    const auto fraction_us = static_cast<std::int64_t>(static_cast<double>(rest) * 1e6 /
                                                       static_cast<double>(itf.ticks_per_second));
    // |offset_s| and whole_s kept below 9.2e12 s so the products fit.
    constexpr std::int64_t limit_s = max / 1'000'000 - 1;
    if (whole_s > static_cast<std::uint64_t>(limit_s)) return max;
    const std::int64_t offset_s = std::clamp<std::int64_t>(itf.offset_s, -limit_s, limit_s);
    const std::int64_t seconds = static_cast<std::int64_t>(whole_s) + offset_s;  // fits: 2x limit
    if (seconds > limit_s) return max;
    if (seconds < -limit_s) return min;
    return seconds * 1'000'000 + fraction_us;
}

}  // namespace

const char* to_string(Stop s) {
    switch (s) {
        case Stop::none:
            return "none";
        case Stop::end:
            return "end";
        case Stop::truncated:
            return "truncated";
        case Stop::corrupt:
            return "corrupt";
    }
    return "?";
}

void parse_exported_pdu(std::span<const std::uint8_t> data, RecordedPacket& packet) {
    packet.dissector.clear();
    packet.pdu = {};
    packet.pdu_error.clear();
    std::size_t at = 0;
    while (true) {
        if (data.size() - at < 4) {
            packet.pdu_error = "exported PDU: tags run past the packet (no end-of-options tag)";
            return;
        }
        const std::uint16_t tag = load16(data.data() + at, true);
        const std::size_t length = load16(data.data() + at + 2, true);
        at += 4;
        if (tag == exp_pdu_end_of_opt) break;  // its length is 0 by definition; ignore any
        if (pad4(length) > data.size() - at) {
            packet.pdu_error = "exported PDU: tag " + std::to_string(tag) + " runs past the packet";
            return;
        }
        if (tag == exp_pdu_dissector_name) packet.dissector = as_text(data.subspan(at, length));
        at += pad4(length);
    }
    packet.pdu = data.subspan(at);
}

bool PcapngReader::fail(Stop why, std::string message) {
    stop_ = why;
    stop_message_ = std::move(message);
    return false;
}

bool PcapngReader::next(RecordedPacket& packet) {
    while (stop_ == Stop::none) {
        const std::size_t left = bytes_.size() - offset_;
        if (left == 0)
            return offset_ == 0 ? fail(Stop::truncated, "empty file") : fail(Stop::end, "");
        const std::uint8_t* p = bytes_.data() + offset_;
        const std::string where = " at offset " + std::to_string(offset_);
        if (left < 4) return fail(Stop::truncated, "block header cut short" + where);
        const std::uint32_t type_le = load32(p, false);
        if (type_le == block_section_header) {
            // The byte order comes from the magic after the length.
            if (left < block_overhead)
                return fail(Stop::truncated, "block header cut short" + where);
            const std::uint32_t magic = load32(p + 8, false);
            if (magic == byte_order_magic)
                big_endian_ = false;
            else if (load32(p + 8, true) == byte_order_magic)
                big_endian_ = true;
            else
                return fail(Stop::corrupt, "bad byte-order magic in section header" + where);
        } else if (!in_section_) {
            return fail(Stop::corrupt, "not a pcapng file (no section header block" + where + ")");
        }
        if (left < 8) return fail(Stop::truncated, "block header cut short" + where);
        const std::uint32_t type = load32(p, big_endian_);
        const std::uint32_t total = load32(p + 4, big_endian_);
        if (total < block_overhead || total % 4 != 0)
            return fail(Stop::corrupt, "bad block length " + std::to_string(total) + where);
        if (total > left)
            return fail(Stop::truncated, "last block cut short (" + std::to_string(left) + " of " +
                                             std::to_string(total) + " bytes)" + where);
        if (load32(p + total - 4, big_endian_) != total)
            return fail(Stop::corrupt, "block lengths at start and end differ" + where);
        const std::span<const std::uint8_t> block(p, total);
        const auto body = block.subspan(8, total - block_overhead);
        bool got_packet = false;
        if (type == block_section_header) {
            if (!read_section_header(block)) return fail(Stop::corrupt, stop_message_ + where);
        } else if (type == block_interface) {
            if (!read_interface(body)) return fail(Stop::corrupt, stop_message_ + where);
        } else if (type == block_enhanced_packet) {
            if (!read_packet(body, packet)) return fail(Stop::corrupt, stop_message_ + where);
            got_packet = true;
        } else {
            ++skipped_blocks_;
        }
        offset_ += total;
        if (got_packet) {
            ++packets_;
            return true;
        }
    }
    return false;
}

bool PcapngReader::read_section_header(std::span<const std::uint8_t> block) {
    // magic u32, major u16, minor u16, section length i64, options
    if (block.size() < block_overhead + 16) {
        stop_message_ = "section header too short";
        return false;
    }
    const auto body = block.subspan(8, block.size() - block_overhead);
    const std::uint16_t major = load16(body.data() + 4, big_endian_);
    if (major != 1) {
        stop_message_ = "unsupported pcapng version " + std::to_string(major);
        return false;
    }
    in_section_ = true;
    ++sections_;
    interfaces_.clear();
    for_each_option(body.subspan(16), big_endian_, [&](std::uint16_t code, auto value) {
        if (code == shb_userappl) user_application_ = as_text(value);
    });
    return true;
}

bool PcapngReader::read_interface(std::span<const std::uint8_t> body) {
    // link type u16, reserved u16, snaplen u32, options
    if (body.size() < 8) {
        stop_message_ = "interface description too short";
        return false;
    }
    RecordedInterface itf;
    itf.link_type = load16(body.data(), big_endian_);
    itf.snaplen = load32(body.data() + 4, big_endian_);
    bool ok = true;
    for_each_option(body.subspan(8), big_endian_, [&](std::uint16_t code, auto value) {
        if (code == if_name) itf.name = as_text(value);
        if (code == if_description) itf.description = as_text(value);
        if (code == if_tsoffset && value.size() == 8)
            itf.offset_s = static_cast<std::int64_t>(load64(value.data(), big_endian_));
        if (code == if_tsresol && value.size() == 1) {
            const unsigned exponent = value[0] & 0x7Fu;
            const bool binary = (value[0] & 0x80u) != 0;
            if (binary ? exponent > 63 : exponent > 19) {
                ok = false;
                return;
            }
            std::uint64_t tps = 1;
            for (unsigned i = 0; i < exponent; ++i) tps *= binary ? 2 : 10;
            itf.ticks_per_second = tps;
        }
    });
    if (!ok) {
        stop_message_ =
            "interface " + std::to_string(interfaces_.size()) + ": if_tsresol out of range";
        return false;
    }
    interfaces_.push_back(std::move(itf));
    return true;
}

bool PcapngReader::read_packet(std::span<const std::uint8_t> body, RecordedPacket& packet) {
    // interface u32, timestamp high u32, low u32, captured u32, original u32, data, options
    if (body.size() < 20) {
        stop_message_ = "enhanced packet block too short";
        return false;
    }
    const std::uint32_t interface_id = load32(body.data(), big_endian_);
    if (interface_id >= interfaces_.size()) {
        stop_message_ = "packet names interface " + std::to_string(interface_id) + " of " +
                        std::to_string(interfaces_.size());
        return false;
    }
    const std::size_t captured = load32(body.data() + 12, big_endian_);
    if (captured > body.size() - 20) {
        stop_message_ = "packet data runs past its block";
        return false;
    }
    const RecordedInterface& itf = interfaces_[interface_id];
    packet = RecordedPacket{};
    packet.interface_id = interface_id;
    const std::uint64_t ticks = std::uint64_t{load32(body.data() + 4, big_endian_)} << 32 |
                                load32(body.data() + 8, big_endian_);
    packet.timestamp_us = to_microseconds(ticks, itf);
    packet.original_length = load32(body.data() + 16, big_endian_);
    packet.data = body.subspan(20, captured);
    const std::size_t options_at = std::min(20 + pad4(captured), body.size());
    for_each_option(body.subspan(options_at), big_endian_, [&](std::uint16_t code, auto value) {
        if (code == epb_flags && value.size() == 4) {
            packet.has_flags = true;
            packet.flags = load32(value.data(), big_endian_);
        }
    });
    const std::uint32_t direction = packet.flags & 3u;  // 3 is not defined
    packet.direction = direction == 1   ? RecordedDirection::inbound
                       : direction == 2 ? RecordedDirection::outbound
                                        : RecordedDirection::unknown;
    if (itf.link_type == linktype_upper_pdu) parse_exported_pdu(packet.data, packet);
    return true;
}

bool read_file(const std::string& path, std::vector<std::uint8_t>& out, std::string& error) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        error = std::string("cannot open: ") + std::strerror(errno);
        return false;
    }
    out.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    if (in.bad()) {
        error = std::string("read error: ") + std::strerror(errno);
        return false;
    }
    return true;
}

}  // namespace gimbal::record
