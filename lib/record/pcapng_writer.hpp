// pcapng encoder for gimbald recordings (docs/recording.md): the blocks of a recording as
// bytes, no I/O. Little-endian, one section per file: SHB, then every IDB, then Enhanced
// Packet Blocks whose data is Wireshark "exported PDU" TLVs naming the dissector, then the
// PDU. Every block is a multiple of 4 bytes long, as pcapng requires.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace gimbal::record {

using Bytes = std::vector<std::uint8_t>;

inline constexpr std::uint32_t shb_block_type = 0x0A0D0D0A;
inline constexpr std::uint32_t idb_block_type = 0x00000001;
inline constexpr std::uint32_t epb_block_type = 0x00000006;
inline constexpr std::uint32_t byte_order_magic = 0x1A2B3C4D;
// LINKTYPE_WIRESHARK_UPPER_PDU: packet data starts with exported-PDU TLVs.
inline constexpr std::uint16_t linktype_upper_pdu = 252;

// Option codes (pcapng spec) and exported-PDU tags (Wireshark wsutil/exported_pdu_tlvs.h).
namespace option {
inline constexpr std::uint16_t end_of_opt = 0;
inline constexpr std::uint16_t shb_userappl = 4;
inline constexpr std::uint16_t if_name = 2;
inline constexpr std::uint16_t if_description = 3;
inline constexpr std::uint16_t if_tsresol = 9;
inline constexpr std::uint16_t epb_flags = 2;
}  // namespace option
namespace exported_pdu_tag {
inline constexpr std::uint16_t end_of_opt = 0;
inline constexpr std::uint16_t dissector_name = 12;
}  // namespace exported_pdu_tag

// epb_flags bits 0-1.
enum class Direction : std::uint32_t { inbound = 1, outbound = 2 };

struct Interface {
    std::string name;         // if_name: "gimbal:main", "mavlink", "json"
    std::string description;  // if_description: "orion tcp 127.0.0.1:8747"
};

// One record: which interface, when (microseconds since the Unix epoch), which way, which
// dissector, and the PDU bytes exactly as on the wire.
struct Packet {
    std::uint32_t interface_id = 0;
    std::uint64_t timestamp_us = 0;
    Direction direction = Direction::inbound;
    std::string_view dissector;
    std::span<const std::uint8_t> pdu;
};

constexpr std::size_t padded4(std::size_t n) {
    return (n + 3) & ~std::size_t{3};
}

// Section Header Block with shb_userappl = `user_application`.
void append_section_header(Bytes& out, std::string_view user_application);
// Interface Description Block: linktype 252, snaplen 0, if_name, if_description, if_tsresol 6.
void append_interface(Bytes& out, const Interface& interface);
// SHB followed by one IDB per interface: how every file starts.
Bytes file_header(std::string_view user_application, std::span<const Interface> interfaces);

// Exported-PDU TLVs: dissector name (NUL-padded to 4 bytes; the length field counts the
// padding, as Wireshark writes it), then end-of-options.
void append_exported_pdu_tags(Bytes& out, std::string_view dissector);
std::size_t exported_pdu_tags_size(std::string_view dissector);

// Enhanced Packet Block with the exported-PDU TLVs + PDU as packet data and epb_flags.
void append_packet(Bytes& out, const Packet& packet);
std::size_t packet_block_size(std::string_view dissector, std::size_t pdu_size);

// The total length field of the block starting at `block` (at least 8 bytes), or 0.
std::uint32_t block_length(std::span<const std::uint8_t> block);

}  // namespace gimbal::record
