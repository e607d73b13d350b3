// Encoder, decoder and sizer visitors over message declarations (fields.hpp), and the
// per-message encode()/decode() entry points. Header-only: a message decodes in straight-line
// code.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "protocols/siyi/codec/fields.hpp"
#include "protocols/siyi/codec/frame.hpp"

namespace gimbal::siyi {

enum class DecodeError : std::uint8_t {
    none,
    too_short,        // shorter than the message's required fields
    unknown_command,  // no message of this CMD_ID in this direction
};

std::string_view to_string(DecodeError e);

template <class M>
struct Decoded {
    M value{};
    DecodeError error = DecodeError::none;
    bool ok() const { return error == DecodeError::none; }
    explicit operator bool() const { return ok(); }
};

// --- conversions without undefined behaviour ----------------------------------------------

// x rounded half away from zero and saturated to Raw; NaN is 0.
template <class Raw>
Raw round_saturate(double x) {
    static_assert(std::is_integral_v<Raw>);
    if (std::isnan(x)) return Raw{0};
    const double r = std::round(x);
    // 2^digits is the first value above max(); it and min() are exact doubles.
    constexpr double above_max =
        2.0 * static_cast<double>(std::uint64_t{1} << (std::numeric_limits<Raw>::digits - 1));
    if (r >= above_max) return std::numeric_limits<Raw>::max();
    if (r <= static_cast<double>(std::numeric_limits<Raw>::min()))
        return std::numeric_limits<Raw>::min();
    return static_cast<Raw>(r);
}

// An integer converted to another integer type, saturating.
template <class To, class From>
To saturate_int(From v) {
    if (std::cmp_less(v, std::numeric_limits<To>::min())) return std::numeric_limits<To>::min();
    if (std::cmp_greater(v, std::numeric_limits<To>::max())) return std::numeric_limits<To>::max();
    return static_cast<To>(v);
}

// The raw wire value of a member.
template <class Raw, class T>
Raw to_raw(const T& member, double scale) {
    if constexpr (std::is_enum_v<T>) {
        return saturate_int<Raw>(static_cast<std::underlying_type_t<T>>(member));
    } else if constexpr (std::is_same_v<T, bool>) {
        return static_cast<Raw>(member ? 1 : 0);
    } else if constexpr (std::is_floating_point_v<Raw>) {
        return static_cast<Raw>(static_cast<double>(member) * scale);
    } else if constexpr (std::is_floating_point_v<T>) {
        return round_saturate<Raw>(static_cast<double>(member) * scale);
    } else if (scale == 1.0) {
        return saturate_int<Raw>(member);
    } else {
        return round_saturate<Raw>(static_cast<double>(member) * scale);
    }
}

// A member from its raw wire value.
template <class T, class Raw>
T from_raw(Raw raw, double scale) {
    if constexpr (std::is_enum_v<T>) {
        return static_cast<T>(saturate_int<std::underlying_type_t<T>>(raw));
    } else if constexpr (std::is_same_v<T, bool>) {
        return raw != 0;
    } else if constexpr (std::is_floating_point_v<T>) {
        return static_cast<T>(static_cast<double>(raw) / scale);
    } else if constexpr (std::is_floating_point_v<Raw>) {
        return round_saturate<T>(static_cast<double>(raw) / scale);
    } else if (scale == 1.0) {
        return saturate_int<T>(raw);
    } else {
        return round_saturate<T>(static_cast<double>(raw) / scale);
    }
}

// Zoom ratio <-> (integer part, tenths).
inline std::uint16_t zoom_tenths(double ratio) {
    return std::min<std::uint16_t>(round_saturate<std::uint16_t>(ratio * 10.0), 255 * 10 + 9);
}

// --- sizer ----------------------------------------------------------------------------------

// Bytes of the required fields (min) and of all fields (max).
class Sizer {
  public:
    std::size_t min = 0, max = 0;

    template <class T, class Raw>
    void field(std::string_view, const T&, Enc<Raw>, double = 1.0, Unit = Unit::none) {
        add(sizeof(Raw));
    }
    template <class Raw>
    void reserved(Enc<Raw>) {
        add(sizeof(Raw));
    }
    void text(std::string_view, const std::string&, std::size_t bytes) { add(bytes); }
    void version(std::string_view, const std::uint32_t&) { add(4); }
    void zoom(std::string_view, const double&) { add(2); }
    void optional() { optional_ = true; }

  private:
    void add(std::size_t n) {
        max += n;
        if (!optional_) min += n;
    }
    bool optional_ = false;
};

template <class M>
std::size_t min_length() {
    M m{};
    Sizer s;
    m.fields(s);
    return s.min;
}

template <class M>
std::size_t max_length() {
    M m{};
    Sizer s;
    m.fields(s);
    return s.max;
}

// --- encoder --------------------------------------------------------------------------------

class Encoder {
  public:
    explicit Encoder(Payload& out) : out_(out) { out_.size = 0; }

    template <class T, class Raw>
    void field(std::string_view, const T& member, Enc<Raw>, double scale = 1.0, Unit = Unit::none) {
        put(to_raw<Raw>(member, scale));
    }
    template <class Raw>
    void reserved(Enc<Raw>) {
        put(Raw{0});
    }
    void text(std::string_view, const std::string& s, std::size_t bytes) {
        for (std::size_t i = 0; i < bytes; ++i)
            put(static_cast<std::uint8_t>(i < s.size() ? s[i] : '\0'));
    }
    void version(std::string_view, const std::uint32_t& word) { put(word); }
    void zoom(std::string_view, const double& ratio) {
        const std::uint16_t tenths = zoom_tenths(ratio);
        put(static_cast<std::uint8_t>(tenths / 10));
        put(static_cast<std::uint8_t>(tenths % 10));
    }
    void optional() {}

  private:
    template <class Raw>
    void put(Raw raw) {
        using U =
            std::make_unsigned_t<std::conditional_t<std::is_same_v<Raw, float>, std::int32_t, Raw>>;
        const auto bits = std::bit_cast<U>(raw);
        for (std::size_t i = 0; i < sizeof(U); ++i) {
            if (out_.size == out_.bytes.size()) return;  // no message is this long
            out_.bytes[out_.size++] = static_cast<std::uint8_t>(bits >> (8 * i));
        }
    }

    Payload& out_;
};

// --- decoder --------------------------------------------------------------------------------

// Lenient where the SDK allows (optional trailing fields absent keep their defaults; bytes
// past the known fields are ignored: newer firmware appends fields), strict on the required
// fields.
class Decoder {
  public:
    explicit Decoder(std::span<const std::uint8_t> in) : in_(in) {}

    DecodeError error() const { return error_; }

    template <class T, class Raw>
    void field(std::string_view, T& member, Enc<Raw>, double scale = 1.0, Unit = Unit::none) {
        Raw raw{};
        if (get(raw)) member = from_raw<T>(raw, scale);
    }
    template <class Raw>
    void reserved(Enc<Raw>) {
        Raw raw{};
        (void)get(raw);
    }
    void text(std::string_view, std::string& s, std::size_t bytes) {
        if (!take(bytes)) return;
        const auto* p = in_.data() + at_ - bytes;
        std::size_t n = 0;
        while (n < bytes && p[n] != 0) ++n;
        s.assign(reinterpret_cast<const char*>(p), n);
    }
    void version(std::string_view, std::uint32_t& word) { (void)get(word); }
    void zoom(std::string_view, double& ratio) {
        std::uint8_t whole = 0, tenths = 0;
        if (get(whole) && get(tenths)) ratio = whole + tenths / 10.0;
    }
    void optional() { optional_ = true; }

  private:
    // Claims n more bytes; false (and the field left as it is) when they are not there.
    bool take(std::size_t n) {
        if (ended_ || error_ != DecodeError::none) return false;
        if (in_.size() - at_ < n) {
            if (optional_)
                ended_ = true;
            else
                error_ = DecodeError::too_short;
            return false;
        }
        at_ += n;
        return true;
    }

    template <class Raw>
    bool get(Raw& raw) {
        if (!take(sizeof(Raw))) return false;
        using U =
            std::make_unsigned_t<std::conditional_t<std::is_same_v<Raw, float>, std::int32_t, Raw>>;
        U bits = 0;
        for (std::size_t i = 0; i < sizeof(U); ++i)
            bits = static_cast<U>(bits | static_cast<U>(U{in_[at_ - sizeof(U) + i]} << (8 * i)));
        raw = std::bit_cast<Raw>(bits);
        return true;
    }

    std::span<const std::uint8_t> in_;
    std::size_t at_ = 0;
    bool optional_ = false;
    bool ended_ = false;
    DecodeError error_ = DecodeError::none;
};

// --- entry points ---------------------------------------------------------------------------

template <class M>
Payload encode_payload(M m) {
    Payload out;
    Encoder e(out);
    m.fields(e);
    return out;
}

// The whole frame of message `m`.
template <class M>
std::vector<std::uint8_t> encode(const M& m, Header header) {
    return frame_bytes(header, M::cmd, encode_payload(m).view());
}

template <class M>
void append(std::vector<std::uint8_t>& out, const M& m, Header header) {
    append_frame(out, header, M::cmd, encode_payload(m).view());
}

template <class M>
Decoded<M> decode(std::span<const std::uint8_t> data) {
    Decoded<M> out;
    Decoder d(data);
    out.value.fields(d);
    out.error = d.error();
    return out;
}

}  // namespace gimbal::siyi
