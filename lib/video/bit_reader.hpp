// Reads the bits of a NAL unit's RBSP (emulation-prevention bytes removed first) MSB first,
// with Exp-Golomb codes (H.264/H.265 clause 9.2). Reading past the end sets failed() and
// yields zeros, so a parser checks once at the end instead of after every field.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace gimbal::video {

// The RBSP of a NAL unit: every 00 00 03 becomes 00 00 (H.264 7.3.1, H.265 7.3.1.1).
std::vector<std::uint8_t> unescape_rbsp(std::span<const std::uint8_t> nal);

class BitReader {
  public:
    explicit BitReader(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}

    std::uint32_t bits(int n) {
        std::uint32_t v = 0;
        for (int i = 0; i < n; ++i) v = (v << 1) | bit();
        return v;
    }
    std::uint32_t bit() {
        if (pos_ >= bytes_.size() * 8) {
            failed_ = true;
            return 0;
        }
        const std::uint32_t b = (bytes_[pos_ / 8] >> (7 - pos_ % 8)) & 1u;
        ++pos_;
        return b;
    }
    void skip(std::size_t n) {
        pos_ += n;
        if (pos_ > bytes_.size() * 8) failed_ = true;
    }
    // ue(v); values beyond 32 bits mark the stream as failed (no valid SPS field needs them).
    std::uint32_t ue() {
        int zeros = 0;
        while (bit() == 0) {
            if (failed_ || ++zeros > 31) {
                failed_ = true;
                return 0;
            }
        }
        if (zeros == 0) return 0;
        return static_cast<std::uint32_t>((std::uint64_t{1} << zeros) - 1 + bits(zeros));
    }
    std::int32_t se() {
        const std::uint32_t k = ue();
        const auto magnitude = static_cast<std::int32_t>((k + 1) / 2);
        return (k & 1u) ? magnitude : -magnitude;
    }
    bool failed() const { return failed_; }
    void fail() { failed_ = true; }
    std::size_t position() const { return pos_; }

  private:
    std::span<const std::uint8_t> bytes_;
    std::size_t pos_ = 0;
    bool failed_ = false;
};

}  // namespace gimbal::video
