// MAVLink 2 message signing (mavlink.io/en/guide/message_signing.html): a signed v2 frame has
// incompat flag 0x01 and 13 more bytes - link id, a 48-bit timestamp (10 us units since
// 2015-01-01 00:00 UTC, little-endian) and the first 6 bytes of
// SHA-256(secret_key + header + payload + CRC + link id + timestamp). SHA-256 from OpenSSL's
// libcrypto. Pure: the caller passes the timestamps.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string_view>
#include <tuple>
#include <vector>

namespace gimbal::mavlink {

using SigningKey = std::array<std::uint8_t, 32>;

// A key file's text: 32 raw bytes, or 64 hex digits (white space around them ignored).
std::optional<SigningKey> parse_signing_key(std::string_view text);

// 1970-01-01 -> 2015-01-01 in seconds, and the timestamp for a UNIX time.
inline constexpr double signing_epoch_unix_s = 1420070400.0;
std::uint64_t signing_timestamp(double unix_s);

// The 6-byte signature of `frame` (a v2 frame from magic through CRC, incompat flag set) sent
// on `link_id` at `timestamp`.
std::array<std::uint8_t, 6> signature48(const SigningKey& key, std::span<const std::uint8_t> frame,
                                        std::uint8_t link_id, std::uint64_t timestamp);

// Appends link id, timestamp and signature to a frame made by encode_v2(..., true).
void append_signature(std::vector<std::uint8_t>& frame, const SigningKey& key, std::uint8_t link_id,
                      std::uint64_t timestamp);

// True when `frame` (a whole signed v2 frame, signature included) carries a valid signature.
bool verify_signature(const SigningKey& key, std::span<const std::uint8_t> frame);

// The replay check: per (sysid, compid, link id) stream a signed frame must carry a timestamp
// later than the stream's last accepted one; a stream not seen before must not be more than
// one minute (6,000,000 units) behind the local timestamp.
//
// The streams survive a restart when the caller saves streams() and restore()s them (the
// daemon keeps them in its state directory): a frame captured before the restart then stays
// a replay after it.
class SigningStreams {
  public:
    static constexpr std::uint64_t new_stream_window = 6'000'000;
    static constexpr std::size_t max_streams = 256;

    // Records the timestamp when accepted.
    bool accept(std::uint8_t sysid, std::uint8_t compid, std::uint8_t link_id,
                std::uint64_t timestamp, std::uint64_t local_timestamp);
    std::size_t size() const { return last_.size(); }

    struct Stream {
        std::uint8_t sysid = 0, compid = 0, link_id = 0;
        std::uint64_t timestamp = 0;  // the last one accepted
        bool operator==(const Stream&) const = default;
    };
    std::vector<Stream> streams() const;
    // Adds saved streams (a stream already known keeps the later timestamp), at most
    // max_streams in all.
    void restore(const std::vector<Stream>& saved);
    // The latest timestamp accepted on any stream (0: none).
    std::uint64_t latest() const;

  private:
    std::map<std::tuple<std::uint8_t, std::uint8_t, std::uint8_t>, std::uint64_t> last_;
};

// Outgoing timestamps: the local clock, but always at least one more than the last one sent
// (the spec's rule for bursts of more than one frame per 10 us).
class SigningClock {
  public:
    std::uint64_t next(std::uint64_t local_timestamp) {
        last_ = local_timestamp > last_ ? local_timestamp : last_ + 1;
        return last_;
    }
    // Never below `floor` again (the timestamp saved before a restart: the spec's rule that
    // timestamps do not go backwards, also when the system clock does).
    void raise_to(std::uint64_t floor) {
        if (floor > last_) last_ = floor;
    }
    std::uint64_t last() const { return last_; }

  private:
    std::uint64_t last_ = 0;
};

}  // namespace gimbal::mavlink
