#include "track/wire/assembler.hpp"

#include <algorithm>

#include "track/wire/codec.hpp"

namespace gimbal::track::wire {

std::vector<std::vector<std::uint8_t>> encode_access_unit(std::int64_t pts_90k, bool key,
                                                          Codec codec,
                                                          std::span<const std::uint8_t> bytes,
                                                          std::size_t piece_bytes) {
    std::vector<std::vector<std::uint8_t>> out;
    if (bytes.size() > max_access_unit_bytes || piece_bytes == 0) return out;
    AccessUnit piece;
    piece.pts_90k = pts_90k;
    piece.key = key;
    piece.codec = codec;
    piece.total_bytes = static_cast<std::uint32_t>(bytes.size());
    std::size_t at = 0;
    do {
        const std::size_t n = std::min(piece_bytes, bytes.size() - at);
        piece.offset = static_cast<std::uint32_t>(at);
        piece.bytes = bytes.subspan(at, n);
        std::vector<std::uint8_t> datagram;
        if (!encode(Message{piece}, datagram)) return {};
        out.push_back(std::move(datagram));
        at += n;
    } while (at < bytes.size());
    return out;
}

bool AccessUnitAssembler::continues(const AccessUnit& piece) const {
    return active_ && piece.pts_90k == head_.pts_90k && piece.key == head_.key &&
           piece.codec == head_.codec && piece.total_bytes == head_.total_bytes &&
           piece.offset == buffer_.size();
}

std::optional<AccessUnitAssembler::Unit> AccessUnitAssembler::add(const AccessUnit& piece) {
    if (std::uint64_t{piece.offset} + piece.bytes.size() > piece.total_bytes ||
        piece.total_bytes > max_access_unit_bytes) {
        if (active_) ++dropped_;
        active_ = false;
        return std::nullopt;
    }
    if (!continues(piece)) {
        if (active_) ++dropped_;
        active_ = false;
        if (piece.offset != 0) {
            ++dropped_;  // the rest of a unit whose beginning we never saw
            return std::nullopt;
        }
        // Whole in one piece: no copy.
        if (piece.bytes.size() == piece.total_bytes)
            return Unit{piece.pts_90k, piece.key, piece.codec, piece.bytes};
        head_ = piece;
        head_.bytes = {};
        buffer_.clear();
        buffer_.reserve(piece.total_bytes);
        active_ = true;
    }
    buffer_.insert(buffer_.end(), piece.bytes.begin(), piece.bytes.end());
    if (buffer_.size() < head_.total_bytes) return std::nullopt;
    active_ = false;
    return Unit{head_.pts_90k, head_.key, head_.codec, buffer_};
}

}  // namespace gimbal::track::wire
