// Reads gimbald recordings (docs/recording.md): pcapng sections of Section Header,
// Interface Description and Enhanced Packet Blocks, in either byte order, whose packets are
// Wireshark "exported PDU" records (TLVs naming the dissector, then the PDU bytes).
// Pure: works on bytes already in memory; packets are views into them.
//
// A file cut short (a crash while writing) is not an error: the reader stops at the last
// complete block and says so (Stop::truncated). Unknown block types are skipped.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "record/pcapng_writer.hpp"  // block types, option codes, linktype_upper_pdu

namespace gimbal::record {

enum class RecordedDirection : std::uint8_t { unknown = 0, inbound = 1, outbound = 2 };

struct RecordedInterface {
    std::uint16_t link_type = 0;
    std::uint32_t snaplen = 0;
    std::string name;                            // if_name
    std::string description;                     // if_description
    std::uint64_t ticks_per_second = 1'000'000;  // from if_tsresol (default: microseconds)
    std::int64_t offset_s = 0;                   // if_tsoffset
};

struct RecordedPacket {
    std::uint32_t interface_id = 0;
    std::int64_t timestamp_us = 0;  // microseconds since the Unix epoch
    std::uint32_t original_length = 0;
    std::span<const std::uint8_t> data;  // captured bytes: TLVs + PDU for upper-PDU links
    bool has_flags = false;
    std::uint32_t flags = 0;  // epb_flags
    RecordedDirection direction = RecordedDirection::unknown;
    // Exported-PDU view (link type 252 only): the dissector named by the TLVs and the bytes
    // after them. When the TLVs are malformed, pdu_error says why and pdu is empty.
    std::string dissector;
    std::span<const std::uint8_t> pdu;
    std::string pdu_error;
};

// Why next() returned false.
enum class Stop : std::uint8_t {
    none,       // not stopped yet
    end,        // clean end: the last block ended exactly at the end of the bytes
    truncated,  // the last block is incomplete (cut while writing); all before it was read
    corrupt,    // not pcapng, or a block is inconsistent; all before it was read
};

const char* to_string(Stop);

// Parses the exported-PDU TLVs at the start of `data`: tag u16 BE, length u16 BE, value
// padded to 4 bytes, ended by tag 0. Sets packet.dissector/pdu or packet.pdu_error.
void parse_exported_pdu(std::span<const std::uint8_t> data, RecordedPacket& packet);

class PcapngReader {
  public:
    // `bytes` must outlive the reader and every Packet it returns.
    explicit PcapngReader(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}

    // The next packet (EPB) in file order; false at the end of what can be read, then stop()
    // tells why.
    bool next(RecordedPacket& packet);

    Stop stop() const { return stop_; }
    const std::string& stop_message() const { return stop_message_; }
    // Offset of the first byte not read: the end, or the start of the bad/cut block.
    std::size_t offset() const { return offset_; }

    // Interfaces of the current section (a new Section Header Block starts a new list).
    const std::vector<RecordedInterface>& interfaces() const { return interfaces_; }
    std::size_t sections() const { return sections_; }
    std::uint64_t packets() const { return packets_; }
    std::uint64_t skipped_blocks() const { return skipped_blocks_; }
    const std::string& user_application() const { return user_application_; }  // shb_userappl

  private:
    bool fail(Stop why, std::string message);
    bool read_section_header(std::span<const std::uint8_t> block);
    bool read_interface(std::span<const std::uint8_t> body);
    bool read_packet(std::span<const std::uint8_t> body, RecordedPacket& packet);

    std::span<const std::uint8_t> bytes_;
    std::size_t offset_ = 0;
    bool big_endian_ = false;
    bool in_section_ = false;
    Stop stop_ = Stop::none;
    std::string stop_message_;
    std::vector<RecordedInterface> interfaces_;
    std::size_t sections_ = 0;
    std::uint64_t packets_ = 0;
    std::uint64_t skipped_blocks_ = 0;
    std::string user_application_;
};

// Reads a whole file into memory; false with `error` set when it cannot be read.
bool read_file(const std::string& path, std::vector<std::uint8_t>& out, std::string& error);

}  // namespace gimbal::record
