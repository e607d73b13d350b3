// Program-specific information (ISO/IEC 13818-1 2.4.4): the program association and
// program map tables, their descriptors of interest here, and the assembly of sections
// from transport packets. Sections are checked with their CRC-32.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace gimbal::video {

struct PatProgram {
    std::uint16_t program_number = 0;  // 0: the network PID, not a program
    std::uint16_t pmt_pid = 0;
};

struct Pat {
    std::uint16_t transport_stream_id = 0;
    std::uint8_t version = 0;
    std::vector<PatProgram> programs;
};

struct PmtStream {
    std::uint8_t stream_type = 0;
    std::uint16_t pid = 0;
    std::vector<std::uint8_t> descriptors;  // ES_info
};

struct Pmt {
    std::uint16_t program_number = 0;
    std::uint8_t version = 0;
    std::uint16_t pcr_pid = 0;
    std::vector<std::uint8_t> program_descriptors;  // program_info
    std::vector<PmtStream> streams;
};

// A whole section from table_id through CRC_32; nullopt for a wrong table_id, a bad CRC,
// a section that is not current, or lengths that do not add up.
std::optional<Pat> parse_pat(std::span<const std::uint8_t> section);
std::optional<Pmt> parse_pmt(std::span<const std::uint8_t> section);

std::vector<std::uint8_t> build_pat(const Pat& pat);
std::vector<std::uint8_t> build_pmt(const Pmt& pmt);

// Descriptors (2.6): registration_descriptor (tag 5) and its format_identifier, and the
// metadata_descriptor (tag 0x26, 2.6.60) naming KLV (metadata_format 0xFF with
// metadata_format_identifier 'KLVA', as MISB ST 1402 sets it).
inline constexpr std::uint32_t format_klva = 0x4B4C5641;  // 'KLVA'
std::optional<std::uint32_t> registration_format(std::span<const std::uint8_t> descriptors);
bool has_klva_metadata_descriptor(std::span<const std::uint8_t> descriptors);

// Collects PSI sections of one PID from transport packet payloads (pointer_field, sections
// spanning packets, several sections in a packet, 0xFF stuffing).
class SectionAssembler {
  public:
    // Calls on_section(section) for each complete section in this payload.
    template <class F>
    void push(std::span<const std::uint8_t> payload, bool unit_start, F&& on_section) {
        if (unit_start) {
            if (payload.empty()) return reset();
            const std::size_t pointer = payload[0];
            if (1 + pointer > payload.size()) return reset();
            if (active_) feed(payload.subspan(1, pointer), on_section);
            reset();
            active_ = true;
            feed(payload.subspan(1 + pointer), on_section);
        } else if (active_) {
            feed(payload, on_section);
        }
    }
    // After a lost packet: the partial section cannot be completed.
    void reset() {
        buffer_.clear();
        active_ = false;
    }

  private:
    template <class F>
    void feed(std::span<const std::uint8_t> bytes, F& on_section) {
        while (!bytes.empty()) {
            if (buffer_.empty() && bytes[0] == 0xFF) {  // stuffing: no more sections here
                active_ = false;
                return;
            }
            std::size_t want = 3;
            if (buffer_.size() >= 3) {
                want = 3 + (((buffer_[1] & 0x0Fu) << 8) | buffer_[2]);
                if (want == 3) return reset();  // an empty section: nothing valid follows
            }
            const std::size_t take = std::min(want - buffer_.size(), bytes.size());
            buffer_.insert(buffer_.end(), bytes.begin(), bytes.begin() + static_cast<long>(take));
            bytes = bytes.subspan(take);
            if (buffer_.size() == want && want > 3) {
                on_section(std::span<const std::uint8_t>(buffer_));
                buffer_.clear();
            }
        }
    }

    std::vector<std::uint8_t> buffer_;
    bool active_ = false;
};

}  // namespace gimbal::video
