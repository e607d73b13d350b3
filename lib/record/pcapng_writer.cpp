#include "record/pcapng_writer.hpp"

#include <cstring>

namespace gimbal::record {

namespace {

void put_u16le(Bytes& out, std::uint16_t v) {
    out.push_back(static_cast<std::uint8_t>(v));
    out.push_back(static_cast<std::uint8_t>(v >> 8));
}

void put_u32le(Bytes& out, std::uint32_t v) {
    for (int shift = 0; shift < 32; shift += 8)
        out.push_back(static_cast<std::uint8_t>(v >> shift));
}

void put_u16be(Bytes& out, std::uint16_t v) {
    out.push_back(static_cast<std::uint8_t>(v >> 8));
    out.push_back(static_cast<std::uint8_t>(v));
}

void put_bytes_padded(Bytes& out, std::span<const std::uint8_t> bytes) {
    out.insert(out.end(), bytes.begin(), bytes.end());
    out.resize(out.size() + padded4(bytes.size()) - bytes.size(), 0);
}

std::span<const std::uint8_t> as_bytes(std::string_view s) {
    return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()};
}

// pcapng option: code, length (unpadded), value padded to 4 bytes.
void put_option(Bytes& out, std::uint16_t code, std::span<const std::uint8_t> value) {
    put_u16le(out, code);
    put_u16le(out, static_cast<std::uint16_t>(value.size()));
    put_bytes_padded(out, value);
}

void put_end_of_options(Bytes& out) {
    put_u16le(out, option::end_of_opt);
    put_u16le(out, 0);
}

// Writes the type and a placeholder length; finish_block() fills both length fields.
std::size_t begin_block(Bytes& out, std::uint32_t type) {
    const std::size_t start = out.size();
    put_u32le(out, type);
    put_u32le(out, 0);
    return start;
}

void finish_block(Bytes& out, std::size_t start) {
    const auto total = static_cast<std::uint32_t>(out.size() - start + 4);
    put_u32le(out, total);
    for (int i = 0; i < 4; ++i)
        out[start + 4 + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(total >> (8 * i));
}

// Options are limited to 65535 bytes; longer text is cut (names are short in practice).
std::string_view clip(std::string_view s) {
    return s.substr(0, 0xFFFC);
}

}  // namespace

void append_section_header(Bytes& out, std::string_view user_application) {
    const std::size_t start = begin_block(out, shb_block_type);
    put_u32le(out, byte_order_magic);
    put_u16le(out, 1);           // major version
    put_u16le(out, 0);           // minor version
    put_u32le(out, 0xFFFFFFFF);  // section length -1 (64 bits): not known in advance
    put_u32le(out, 0xFFFFFFFF);
    put_option(out, option::shb_userappl, as_bytes(clip(user_application)));
    put_end_of_options(out);
    finish_block(out, start);
}

void append_interface(Bytes& out, const Interface& interface) {
    const std::size_t start = begin_block(out, idb_block_type);
    put_u16le(out, linktype_upper_pdu);
    put_u16le(out, 0);  // reserved
    put_u32le(out, 0);  // snaplen: no limit
    put_option(out, option::if_name, as_bytes(clip(interface.name)));
    put_option(out, option::if_description, as_bytes(clip(interface.description)));
    const std::uint8_t microseconds = 6;
    put_option(out, option::if_tsresol, {&microseconds, 1});
    put_end_of_options(out);
    finish_block(out, start);
}

Bytes file_header(std::string_view user_application, std::span<const Interface> interfaces) {
    Bytes out;
    append_section_header(out, user_application);
    for (const auto& i : interfaces) append_interface(out, i);
    return out;
}

std::size_t exported_pdu_tags_size(std::string_view dissector) {
    return 4 + padded4(dissector.size()) + 4;
}

void append_exported_pdu_tags(Bytes& out, std::string_view dissector) {
    put_u16be(out, exported_pdu_tag::dissector_name);
    put_u16be(out, static_cast<std::uint16_t>(padded4(dissector.size())));
    put_bytes_padded(out, as_bytes(dissector));
    put_u16be(out, exported_pdu_tag::end_of_opt);
    put_u16be(out, 0);
}

std::size_t packet_block_size(std::string_view dissector, std::size_t pdu_size) {
    // header 8 + fixed fields 20 + data (padded) + epb_flags 8 + end 4 + trailing length 4
    return 28 + padded4(exported_pdu_tags_size(dissector) + pdu_size) + 16;
}

void append_packet(Bytes& out, const Packet& p) {
    out.reserve(out.size() + packet_block_size(p.dissector, p.pdu.size()));
    const std::size_t start = begin_block(out, epb_block_type);
    const auto captured =
        static_cast<std::uint32_t>(exported_pdu_tags_size(p.dissector) + p.pdu.size());
    put_u32le(out, p.interface_id);
    put_u32le(out, static_cast<std::uint32_t>(p.timestamp_us >> 32));
    put_u32le(out, static_cast<std::uint32_t>(p.timestamp_us));
    put_u32le(out, captured);  // captured length
    put_u32le(out, captured);  // original length
    append_exported_pdu_tags(out, p.dissector);
    put_bytes_padded(out, p.pdu);
    // The TLVs are a multiple of 4 long, so padding the PDU pads the whole packet data.
    const auto flags = static_cast<std::uint32_t>(p.direction);
    std::uint8_t value[4];
    for (int i = 0; i < 4; ++i) value[i] = static_cast<std::uint8_t>(flags >> (8 * i));
    put_option(out, option::epb_flags, value);
    put_end_of_options(out);
    finish_block(out, start);
}

std::uint32_t block_length(std::span<const std::uint8_t> block) {
    if (block.size() < 8) return 0;
    std::uint32_t v = 0;
    for (int i = 3; i >= 0; --i) v = (v << 8) | block[4 + static_cast<std::size_t>(i)];
    return v;
}

}  // namespace gimbal::record
