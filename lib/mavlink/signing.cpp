#include "mavlink/signing.hpp"

#include <openssl/sha.h>

#include <algorithm>

#include "mavlink/framing.hpp"

namespace gimbal::mavlink {

std::optional<SigningKey> parse_signing_key(std::string_view text) {
    SigningKey key{};
    if (text.size() == key.size()) {
        std::copy(text.begin(), text.end(), key.begin());
        return key;
    }
    const auto first = text.find_first_not_of(" \t\r\n");
    const auto last = text.find_last_not_of(" \t\r\n");
    if (first == std::string_view::npos) return std::nullopt;
    const std::string_view hex = text.substr(first, last - first + 1);
    if (hex.size() != 2 * key.size()) return std::nullopt;
    const auto nibble = [](char c) -> int {
        if (c >= '0' && c <= '9') return c - '0';
        if (c >= 'a' && c <= 'f') return c - 'a' + 10;
        if (c >= 'A' && c <= 'F') return c - 'A' + 10;
        return -1;
    };
    for (std::size_t i = 0; i < key.size(); ++i) {
        const int hi = nibble(hex[2 * i]), lo = nibble(hex[2 * i + 1]);
        if (hi < 0 || lo < 0) return std::nullopt;
        key[i] = static_cast<std::uint8_t>(hi * 16 + lo);
    }
    return key;
}

std::uint64_t signing_timestamp(double unix_s) {
    const double units = (unix_s - signing_epoch_unix_s) * 1e5;
    if (!(units > 0)) return 0;
    return static_cast<std::uint64_t>(units) & 0xFFFF'FFFF'FFFFull;
}

std::array<std::uint8_t, 6> signature48(const SigningKey& key, std::span<const std::uint8_t> frame,
                                        std::uint8_t link_id, std::uint64_t timestamp) {
    // key + frame + link id + timestamp fits in one small buffer: one SHA256() call.
    std::array<std::uint8_t, 32 + max_frame_size + 7> buffer{};
    if (frame.size() > max_frame_size) return {};
    std::size_t n = 0;
    for (const std::uint8_t b : key) buffer[n++] = b;
    for (const std::uint8_t b : frame) buffer[n++] = b;
    buffer[n++] = link_id;
    for (std::size_t i = 0; i < 6; ++i)
        buffer[n++] = static_cast<std::uint8_t>(timestamp >> (8 * i));
    std::array<std::uint8_t, SHA256_DIGEST_LENGTH> digest{};
    SHA256(buffer.data(), n, digest.data());
    std::array<std::uint8_t, 6> out{};
    std::copy_n(digest.begin(), out.size(), out.begin());
    return out;
}

void append_signature(std::vector<std::uint8_t>& frame, const SigningKey& key, std::uint8_t link_id,
                      std::uint64_t timestamp) {
    const auto sig = signature48(key, frame, link_id, timestamp);
    frame.push_back(link_id);
    for (std::size_t i = 0; i < 6; ++i)
        frame.push_back(static_cast<std::uint8_t>(timestamp >> (8 * i)));
    frame.insert(frame.end(), sig.begin(), sig.end());
}

bool verify_signature(const SigningKey& key, std::span<const std::uint8_t> frame) {
    if (frame.size() < header_size_v2 + checksum_size + signature_size) return false;
    if (frame[0] != magic_v2 || (frame[2] & incompat_signed) == 0) return false;
    const std::size_t body = frame.size() - signature_size;
    const std::uint8_t* sig = frame.data() + body;
    std::uint64_t timestamp = 0;
    for (std::size_t i = 0; i < 6; ++i) timestamp |= std::uint64_t{sig[1 + i]} << (8 * i);
    const auto expected = signature48(key, frame.first(body), sig[0], timestamp);
    std::uint8_t diff = 0;  // constant time
    for (std::size_t i = 0; i < 6; ++i)
        diff = static_cast<std::uint8_t>(diff | (expected[i] ^ sig[7 + i]));
    return diff == 0;
}

bool SigningStreams::accept(std::uint8_t sysid, std::uint8_t compid, std::uint8_t link_id,
                            std::uint64_t timestamp, std::uint64_t local_timestamp) {
    const auto key = std::make_tuple(sysid, compid, link_id);
    const auto it = last_.find(key);
    if (it == last_.end()) {
        if (timestamp + new_stream_window < local_timestamp) return false;
        if (last_.size() >= max_streams) return false;
        last_.emplace(key, timestamp);
        return true;
    }
    if (timestamp <= it->second) return false;
    it->second = timestamp;
    return true;
}

}  // namespace gimbal::mavlink

namespace gimbal::mavlink {

std::vector<SigningStreams::Stream> SigningStreams::streams() const {
    std::vector<Stream> out;
    out.reserve(last_.size());
    for (const auto& [key, timestamp] : last_)
        out.push_back(Stream{std::get<0>(key), std::get<1>(key), std::get<2>(key), timestamp});
    return out;
}

void SigningStreams::restore(const std::vector<Stream>& saved) {
    for (const Stream& s : saved) {
        const auto key = std::make_tuple(s.sysid, s.compid, s.link_id);
        const auto it = last_.find(key);
        if (it != last_.end()) {
            it->second = std::max(it->second, s.timestamp);
        } else if (last_.size() < max_streams) {
            last_.emplace(key, s.timestamp);
        }
    }
}

std::uint64_t SigningStreams::latest() const {
    std::uint64_t out = 0;
    for (const auto& [key, timestamp] : last_) out = std::max(out, timestamp);
    return out;
}

}  // namespace gimbal::mavlink
