// Encoder and decoder visitors over packet declarations (see fields.hpp), and the
// encode()/decode() entry points. Header-only so a decode inlines into straight-line code.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include "orion/fields.hpp"
#include "orion/wire.hpp"

namespace gimbal::orion {

inline constexpr std::size_t max_data_length = 140;

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

// --- encoder ---------------------------------------------------------------------------

class Encoder {
  public:
    explicit Encoder(Payload& out) : out_(out) { out_.size = 0; }

    // True when every field fit in 140 bytes.
    bool ok() const { return !overflow_; }

    template <class T, class E>
    void field(std::string_view, const T& member, E enc, Scale s = {}, Unit = Unit::none) {
        if constexpr (is_std_array<T> || is_std_vector<T>) {
            for (const auto& item : member) put(item, enc, s);
        } else {
            put(member, enc, s);
        }
    }

    template <class T>
    void bits(std::string_view, const T& member, int width) {
        std::uint64_t raw;
        if constexpr (std::is_enum_v<T>)
            raw = static_cast<std::uint64_t>(member);
        else
            raw = static_cast<std::uint64_t>(member);
        put_bits(raw, width);
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
        put(static_cast<std::uint64_t>(std::min(items.size(), max)), enc, Scale{});
    }

    template <class G>
    void group(std::string_view, const std::vector<G>& items) {
        for (const auto& item : items) const_cast<G&>(item).fields(*this);
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
    bool room(std::size_t n) {
        if (out_.size + n > max_data_length) {
            overflow_ = true;
            return false;
        }
        return true;
    }

    // Bitfields leave a partly filled byte; the next whole-byte field starts on a new byte.
    void align() { bit_ = 0; }

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
    void put(const T& value, IntEnc<B, S>, Scale s) {
        using Enc = IntEnc<B, S>;
        align();
        if (!room(Enc::size)) return;
        std::uint64_t raw;
        if constexpr (std::is_integral_v<T> && !std::is_same_v<T, bool>) {
            // Exact path for plain integers; still saturate to the field's width.
            if constexpr (std::is_signed_v<T>) {
                const auto lim = static_cast<std::int64_t>(Enc::max_raw);
                const std::int64_t v = std::clamp<std::int64_t>(value, S ? -lim : 0, lim);
                raw = static_cast<std::uint64_t>(v);
            } else {
                const auto v = static_cast<std::uint64_t>(value);
                raw = (B == 8 || v <= static_cast<std::uint64_t>(Enc::max_raw))
                          ? v
                          : static_cast<std::uint64_t>(Enc::max_raw);
            }
            (void)s;
        } else {
            const double r = round_saturate(to_raw_double(value, s), Enc::min_raw, Enc::max_raw);
            raw = S ? static_cast<std::uint64_t>(static_cast<std::int64_t>(r))
                    : static_cast<std::uint64_t>(r);
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
};

// --- decoder ---------------------------------------------------------------------------

class Decoder {
  public:
    explicit Decoder(std::span<const std::uint8_t> data) : data_(data) {}

    bool ok() const { return !failed_; }
    const DecodeError& error() const { return error_; }

    template <class T, class E>
    void field(std::string_view key, T& member, E enc, Scale s = {}, Unit = Unit::none) {
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

    void string(std::string_view key, std::string& s, std::size_t max_bytes) {
        bit_ = 0;
        if (!need(key, 1)) return;
        std::size_t n = 0;
        const std::size_t limit = std::min(max_bytes, data_.size() - pos_);
        while (n < limit && data_[pos_ + n] != 0) ++n;
        s.assign(reinterpret_cast<const char*>(data_.data() + pos_), n);
        pos_ += (n < limit) ? n + 1 : n;  // consume the terminator when there is one
    }

    void fixed_string(std::string_view key, std::string& s, std::size_t bytes) {
        if (!need(key, bytes)) return;
        const auto* p = reinterpret_cast<const char*>(data_.data() + pos_);
        s.assign(p, strnlen(p, bytes));
        pos_ += bytes;
    }

    void ipv4(std::string_view key, std::uint32_t& addr) { field(key, addr, u32); }

    void optional() { optional_ = true; }

  private:
    bool stopped() const { return failed_ || absent_; }

    // Checks that n whole bytes remain. Running out in the optional tail is not an error:
    // the rest of the fields keep their ICD defaults.
    bool need(std::string_view key, std::size_t n) {
        bit_ = 0;
        if (stopped()) return false;
        if (pos_ + n <= data_.size()) return true;
        if (optional_) {
            absent_ = true;
        } else {
            failed_ = true;
            error_ = DecodeError{"packet too short", key, pos_, data_.size()};
        }
        return false;
    }

    bool need_bits(std::string_view key, int width) {
        if (stopped()) return false;
        const std::size_t bits_left = (data_.size() - pos_) * 8 - static_cast<std::size_t>(bit_);
        if (pos_ <= data_.size() && bits_left >= static_cast<std::size_t>(width)) return true;
        const int saved = bit_;
        need(key, data_.size() + 1);  // records the failure (or the absent optional tail)
        bit_ = saved;
        return false;
    }

    std::uint64_t take_bits(int width) {
        std::uint64_t raw = 0;
        for (int i = 0; i < width; ++i) {
            const unsigned bit = (data_[pos_] >> (7 - bit_)) & 1u;
            raw = (raw << 1) | bit;
            if (++bit_ == 8) {
                bit_ = 0;
                ++pos_;
            }
        }
        return raw;
    }

    template <class T, int B, bool S>
    void get(T& member, IntEnc<B, S>, Scale s) {
        const std::uint64_t raw = load_be(data_.data() + pos_, B);
        pos_ += B;
        if constexpr (std::is_integral_v<T> && !std::is_same_v<T, bool>) {
            if constexpr (S)
                member = static_cast<T>(sign_extend(raw, 8 * B));
            else
                member = static_cast<T>(raw);
            (void)s;
        } else {
            const double r =
                S ? static_cast<double>(sign_extend(raw, 8 * B)) : static_cast<double>(raw);
            member = from_raw_double<T>(r, s);
        }
    }

    template <class T, int B, int Sig>
    void get(T& member, SmallFloatEnc<B, Sig>, Scale s) {
        const auto raw = static_cast<std::uint32_t>(load_be(data_.data() + pos_, B));
        pos_ += B;
        member = from_raw_double<T>(small_to_float(raw, 8 * B, Sig), s);
    }

    template <class T>
    void get(T& member, F32Enc, Scale s) {
        const auto raw = static_cast<std::uint32_t>(load_be(data_.data() + pos_, 4));
        pos_ += 4;
        member = from_raw_double<T>(static_cast<double>(std::bit_cast<float>(raw)), s);
    }

    template <class T>
    void get(T& member, F64Enc, Scale s) {
        const std::uint64_t raw = load_be(data_.data() + pos_, 8);
        pos_ += 8;
        member = from_raw_double<T>(std::bit_cast<double>(raw), s);
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
