// Encoder and decoder visitors over packet declarations (see fields.hpp), and the
// encode()/decode() entry points. Header-only so a decode inlines into straight-line code.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include "protocols/orion/codec/fields.hpp"
#include "protocols/orion/codec/wire.hpp"

namespace gimbal::orion {

inline constexpr std::size_t max_data_length = 140;

// A packet's fields() expands into one call per field; forcing these small helpers inline
// turns a decode into straight-line code (GCC otherwise gives up on large packets).
#define GIMBAL_CODEC_INLINE [[gnu::always_inline]] inline

// Data bytes of one packet, without sync, id, length or checksum.
struct Payload {
    std::array<std::uint8_t, max_data_length> bytes{};
    std::size_t size = 0;
    std::span<const std::uint8_t> view() const { return {bytes.data(), size}; }
};

struct DecodeError {
    const char* reason = "";  // static text
    std::string_view field;   // the field that could not be decoded
    std::size_t offset = 0;   // byte offset of that field
    std::size_t length = 0;   // data length of the packet
};

std::string to_string(const DecodeError& e);

template <class P>
struct Decoded {
    P value{};
    DecodeError error{};
    bool ok = false;
    explicit operator bool() const { return ok; }
};

// --- conversions without undefined behaviour ----------------------------------------------

// A double converted to an integer type: NaN is 0, out-of-range values saturate, the rest
// truncate toward zero (a plain cast is undefined behaviour out of range).
template <class T>
T saturate_cast(double x) {
    static_assert(std::is_integral_v<T>);
    using L = std::numeric_limits<T>;
    if (x != x) return T{0};
    // 2^digits is the first value above max(); it and min() are exact doubles.
    constexpr double above_max = 2.0 * static_cast<double>(std::uint64_t{1} << (L::digits - 1));
    if (x >= above_max) return L::max();
    if constexpr (std::is_signed_v<T>) {
        if (x <= static_cast<double>(L::min())) return L::min();
    } else {
        if (x <= -1.0) return T{0};
    }
    return static_cast<T>(x);
}

// The raw wire integer (two's complement in 64 bits) of a value already rounded and saturated
// to [Enc::min_raw, Enc::max_raw]. The 8-byte limits are not exact doubles, hence the care.
template <int B, bool S>
std::uint64_t raw_from_rounded(double r) {
    using Enc = IntEnc<B, S>;
    if constexpr (S) {
        if (r >= Enc::max_raw) return Enc::max_int;
        if (r <= Enc::min_raw) return std::uint64_t{0} - Enc::max_int;
        return static_cast<std::uint64_t>(static_cast<std::int64_t>(r));
    } else {
        if (r >= Enc::max_raw) return Enc::max_int;
        return static_cast<std::uint64_t>(r);
    }
}

// A member of type T from a decoded value: floating members get the scale, integers and enums
// saturate instead of overflowing.
template <class T>
GIMBAL_CODEC_INLINE T member_from_double(double v, Scale s) {
    if constexpr (std::is_enum_v<T>)
        return static_cast<T>(saturate_cast<std::underlying_type_t<T>>(v));
    else if constexpr (std::is_same_v<T, bool>)
        return v != 0.0;
    else if constexpr (std::is_integral_v<T>)
        return saturate_cast<T>(v);
    else  // from_raw_double(), with the division by a constant as a multiplication
        return static_cast<T>(v * (1.0 / s.factor) + s.offset);
}

// --- encoder ---------------------------------------------------------------------------

class Encoder {
  public:
    explicit Encoder(Payload& out) : out_(out) { out_.size = 0; }

    // True when every field fit in 140 bytes.
    bool ok() const { return !overflow_; }

    template <class T, class E>
    GIMBAL_CODEC_INLINE void field(std::string_view, const T& member, E enc, Scale s = {},
                                   Unit = Unit::none) {
        if constexpr (is_std_array<T>) {
            for (const auto& item : member) put(item, enc, s);
        } else if constexpr (is_std_vector<T>) {
            // Only as many items as the count field said (it saturates at its maximum).
            const std::size_t n = std::min(member.size(), take_repeat_limit());
            for (std::size_t i = 0; i < n; ++i) put(member[i], enc, s);
        } else {
            put(member, enc, s);
        }
    }

    // Values wider than the bitfield saturate at its maximum, like every other field.
    template <class T>
    void bits(std::string_view, const T& member, int width) {
        const std::uint64_t max = (std::uint64_t{1} << width) - 1;
        std::uint64_t raw;
        if constexpr (std::is_enum_v<T>) {
            const auto u = static_cast<std::underlying_type_t<T>>(member);
            raw = u < 0 ? 0 : static_cast<std::uint64_t>(u);
        } else if constexpr (std::is_same_v<T, bool>) {
            raw = member ? 1 : 0;
        } else if constexpr (std::is_floating_point_v<T>) {
            raw = saturate_cast<std::uint64_t>(std::round(static_cast<double>(member)));
        } else {
            raw = member < 0 ? 0 : static_cast<std::uint64_t>(member);
        }
        put_bits(std::min(raw, max), width);
    }

    template <class E>
    void reserved(E) {
        align();
        if (room(E::size)) {
            std::memset(out_.bytes.data() + out_.size, 0, E::size);
            out_.size += E::size;
        }
    }
    void reserved_bits(int width) { put_bits(0, width); }

    template <class T, class E>
    void count(std::string_view, const std::vector<T>& items, E enc, std::size_t max) {
        if (items.size() > max) overflow_ = true;  // the caller bounds repeats before encoding
        repeat_limit_ = std::min(items.size(), max);
        put(static_cast<std::uint64_t>(repeat_limit_), enc, Scale{});
    }

    template <class G>
    void group(std::string_view, const std::vector<G>& items) {
        const std::size_t n = std::min(items.size(), take_repeat_limit());
        for (std::size_t i = 0; i < n; ++i) const_cast<G&>(items[i]).fields(*this);
    }

    void string(std::string_view, const std::string& s, std::size_t max_bytes) {
        align();
        const std::size_t n = std::min(s.size(), max_bytes - 1);
        if (!room(n + 1)) return;
        std::memcpy(out_.bytes.data() + out_.size, s.data(), n);
        out_.bytes[out_.size + n] = 0;
        out_.size += n + 1;
    }

    void fixed_string(std::string_view, const std::string& s, std::size_t bytes) {
        align();
        if (!room(bytes)) return;
        const std::size_t n = std::min(s.size(), bytes - 1);
        std::memset(out_.bytes.data() + out_.size, 0, bytes);
        std::memcpy(out_.bytes.data() + out_.size, s.data(), n);
        out_.size += bytes;
    }

    void ipv4(std::string_view key, const std::uint32_t& addr) { field(key, addr, u32); }

    void optional() {}

  private:
    // The repeat after a count() writes at most that many items; the limit applies once.
    std::size_t take_repeat_limit() {
        const std::size_t n = repeat_limit_;
        repeat_limit_ = static_cast<std::size_t>(-1);
        return n;
    }

    GIMBAL_CODEC_INLINE bool room(std::size_t n) {
        if (out_.size + n > max_data_length) {
            overflow_ = true;
            return false;
        }
        return true;
    }

    // Bitfields leave a partly filled byte; the next whole-byte field starts on a new byte.
    GIMBAL_CODEC_INLINE void align() { bit_ = 0; }

    void put_bits(std::uint64_t raw, int width) {
        for (int i = width - 1; i >= 0; --i) {
            if (bit_ == 0) {
                if (!room(1)) return;
                out_.bytes[out_.size++] = 0;
            }
            if ((raw >> i) & 1u)
                out_.bytes[out_.size - 1] |= static_cast<std::uint8_t>(0x80u >> bit_);
            bit_ = (bit_ + 1) % 8;
        }
    }

    template <class T, int B, bool S>
    GIMBAL_CODEC_INLINE void put(const T& value, IntEnc<B, S>, Scale s) {
        using Enc = IntEnc<B, S>;
        align();
        if (!room(Enc::size)) return;
        std::uint64_t raw;
        if constexpr (std::is_integral_v<T> && !std::is_same_v<T, bool>) {
            // Exact path for plain integers; still saturate to the field's width.
            if constexpr (std::is_signed_v<T>) {
                const auto lim = static_cast<std::int64_t>(Enc::max_int);
                const std::int64_t v =
                    std::clamp<std::int64_t>(static_cast<std::int64_t>(value), S ? -lim : 0, lim);
                raw = static_cast<std::uint64_t>(v);
            } else {
                const auto v = static_cast<std::uint64_t>(value);
                raw = v <= Enc::max_int ? v : Enc::max_int;
            }
            (void)s;
        } else {
            const double r = round_saturate(to_raw_double(value, s), Enc::min_raw, Enc::max_raw);
            raw = raw_from_rounded<B, S>(r);
        }
        store_be(out_.bytes.data() + out_.size, raw, Enc::size);
        out_.size += Enc::size;
    }

    template <class T, int B, int Sig>
    void put(const T& value, SmallFloatEnc<B, Sig>, Scale s) {
        align();
        if (!room(B)) return;
        const double v = to_raw_double(value, s);
        store_be(out_.bytes.data() + out_.size, float_to_small(v, 8 * B, Sig), B);
        out_.size += B;
    }

    template <class T>
    void put(const T& value, F32Enc, Scale s) {
        align();
        if (!room(4)) return;
        const auto f = static_cast<float>(to_raw_double(value, s));
        store_be(out_.bytes.data() + out_.size, std::bit_cast<std::uint32_t>(f), 4);
        out_.size += 4;
    }

    template <class T>
    void put(const T& value, F64Enc, Scale s) {
        align();
        if (!room(8)) return;
        const double d = to_raw_double(value, s);
        store_be(out_.bytes.data() + out_.size, std::bit_cast<std::uint64_t>(d), 8);
        out_.size += 8;
    }

    Payload& out_;
    int bit_ = 0;
    bool overflow_ = false;
    std::size_t repeat_limit_ = static_cast<std::size_t>(-1);
};

// --- decoder ---------------------------------------------------------------------------

class Decoder {
  public:
    explicit Decoder(std::span<const std::uint8_t> data) : data_(data) {}

    bool ok() const { return !failed_; }
    const DecodeError& error() const { return error_; }

    template <class T, class E>
    GIMBAL_CODEC_INLINE void field(std::string_view key, T& member, E enc, Scale s = {},
                                   Unit = Unit::none) {
        if constexpr (is_std_array<T> || is_std_vector<T>) {
            if (!need(key, E::size * member.size())) return;
            for (auto& item : member) get(item, enc, s);
        } else {
            if (!need(key, E::size)) return;
            get(member, enc, s);
        }
    }

    template <class T>
    void bits(std::string_view key, T& member, int width) {
        if (!need_bits(key, width)) return;
        const std::uint64_t raw = take_bits(width);
        if constexpr (std::is_same_v<T, bool>)
            member = raw != 0;
        else
            member = static_cast<T>(raw);
    }

    template <class E>
    void reserved(E) {
        if (need("reserved", E::size)) pos_ += E::size;
    }
    void reserved_bits(int width) {
        if (need_bits("reserved", width)) take_bits(width);
    }

    template <class T, class E>
    void count(std::string_view key, std::vector<T>& items, E enc, std::size_t max) {
        std::uint64_t n = 0;
        if (!need(key, E::size)) return;
        get(n, enc, Scale{});
        items.resize(static_cast<std::size_t>(std::min<std::uint64_t>(n, max)));
    }

    template <class G>
    void group(std::string_view, std::vector<G>& items) {
        for (std::size_t i = 0; i < items.size(); ++i) {
            items[i].fields(*this);
            if (absent_) {  // the optional tail ended inside the repeat: keep whole items only
                items.resize(i);
                return;
            }
            if (failed_) return;
        }
    }

    // Like ProtoGen's stringFromBytes: at most max_bytes - 1 characters, then one byte for the
    // terminator (consumed even when it is not zero, as the encoder always writes one).
    void string(std::string_view key, std::string& s, std::size_t max_bytes) {
        if (!need(key, 1)) return;
        const std::size_t left = data_.size() - pos_;
        const std::size_t limit = std::min(max_bytes - 1, left);
        std::size_t n = 0;
        while (n < limit && data_[pos_ + n] != 0) ++n;
        s.assign(reinterpret_cast<const char*>(data_.data() + pos_), n);
        pos_ += (n < left) ? n + 1 : n;  // the data may end without a terminator
    }

    void fixed_string(std::string_view key, std::string& s, std::size_t bytes) {
        if (!need(key, bytes)) return;
        const auto* p = reinterpret_cast<const char*>(data_.data() + pos_);
        s.assign(p, strnlen(p, bytes - 1));  // the last byte is always the terminator
        pos_ += bytes;
    }

    void ipv4(std::string_view key, std::uint32_t& addr) { field(key, addr, u32); }

    void optional() { optional_ = true; }

  private:
    GIMBAL_CODEC_INLINE bool stopped() const { return failed_ || absent_; }

    // A whole-byte field after a bitfield that ended inside a byte starts on the next byte
    // (the encoder does the same).
    GIMBAL_CODEC_INLINE void align() {
        if (bit_ != 0) {
            bit_ = 0;
            ++pos_;
        }
    }

    // Running out in the optional tail is not an error: the rest of the fields keep their
    // ICD defaults.
    void ran_out(std::string_view key) {
        if (optional_) {
            absent_ = true;
        } else {
            failed_ = true;
            error_ = DecodeError{"packet too short", key, pos_, data_.size()};
        }
    }

    // Checks that n whole bytes remain.
    GIMBAL_CODEC_INLINE bool need(std::string_view key, std::size_t n) {
        if (stopped()) return false;
        align();
        if (pos_ <= data_.size() && n <= data_.size() - pos_) return true;
        ran_out(key);
        return false;
    }

    bool need_bits(std::string_view key, int width) {
        if (stopped()) return false;
        const std::size_t bits_left =
            pos_ < data_.size() ? (data_.size() - pos_) * 8 - static_cast<std::size_t>(bit_) : 0;
        if (bits_left >= static_cast<std::size_t>(width)) return true;
        ran_out(key);
        return false;
    }

    std::uint64_t take_bits(int width) {
        std::uint64_t raw = 0;
        for (int i = 0; i < width; ++i) {
            const unsigned bit = (static_cast<unsigned>(data_[pos_]) >> (7 - bit_)) & 1u;
            raw = (raw << 1) | bit;
            if (++bit_ == 8) {
                bit_ = 0;
                ++pos_;
            }
        }
        return raw;
    }

    template <class T, int B, bool S>
    GIMBAL_CODEC_INLINE void get(T& member, IntEnc<B, S>, Scale s) {
        const std::uint64_t raw = load_be(data_.data() + pos_, B);
        pos_ += B;
        if constexpr ((std::is_integral_v<T> && !std::is_same_v<T, bool>) || std::is_enum_v<T>) {
            // Integers and enums take the raw value exactly (no scale); a narrower member
            // keeps the low bits, as a C cast would.
            using I = typename std::conditional_t<std::is_enum_v<T>, std::underlying_type<T>,
                                                  std::type_identity<T>>::type;
            if constexpr (S)
                member = static_cast<T>(static_cast<I>(sign_extend(raw, 8 * B)));
            else
                member = static_cast<T>(static_cast<I>(raw));
            (void)s;
        } else {
            const double r =
                S ? static_cast<double>(sign_extend(raw, 8 * B)) : static_cast<double>(raw);
            member = member_from_double<T>(r, s);
        }
    }

    template <class T, int B, int Sig>
    void get(T& member, SmallFloatEnc<B, Sig>, Scale s) {
        const auto raw = static_cast<std::uint32_t>(load_be(data_.data() + pos_, B));
        pos_ += B;
        member = member_from_double<T>(small_to_float(raw, 8 * B, Sig), s);
    }

    template <class T>
    void get(T& member, F32Enc, Scale s) {
        const auto raw = static_cast<std::uint32_t>(load_be(data_.data() + pos_, 4));
        pos_ += 4;
        member = member_from_double<T>(static_cast<double>(std::bit_cast<float>(raw)), s);
    }

    template <class T>
    void get(T& member, F64Enc, Scale s) {
        const std::uint64_t raw = load_be(data_.data() + pos_, 8);
        pos_ += 8;
        member = member_from_double<T>(std::bit_cast<double>(raw), s);
    }

    std::span<const std::uint8_t> data_;
    std::size_t pos_ = 0;
    int bit_ = 0;
    bool optional_ = false;
    bool absent_ = false;
    bool failed_ = false;
    DecodeError error_{};
};

// --- entry points ------------------------------------------------------------------------

// Encodes every field in ICD order. Returns false if a repeat holds more items than its
// maximum or the packet would not fit in 140 bytes; the command parser checks both first.
template <class P>
bool encode(const P& packet, Payload& out) {
    Encoder enc(out);
    const_cast<P&>(packet).fields(enc);  // fields() only reads through an Encoder
    return enc.ok();
}

template <class P>
Payload encode(const P& packet) {
    Payload out;
    encode(packet, out);
    return out;
}

// Decodes the data bytes of a packet. Bytes beyond the known fields are ignored.
template <class P>
Decoded<P> decode(std::span<const std::uint8_t> data) {
    Decoded<P> result;
    Decoder dec(data);
    result.value.fields(dec);
    result.ok = dec.ok();
    if (!result.ok) result.error = dec.error();
    return result;
}

}  // namespace gimbal::orion

#undef GIMBAL_CODEC_INLINE
