// Wire encodings of the OrionPublic ICD ("About this ICD" -> Encodings):
// big-endian integers of 1..8 bytes, scaled integers, F16:X floats, IEEE floats.
#pragma once

#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>

namespace gimbal::orion {

// Integer encoding of N bytes (UX / IX in the ICD).
template <int Bytes, bool Signed>
struct IntEnc {
    static constexpr std::size_t size = Bytes;
    static constexpr bool is_signed = Signed;
    // ProtoGen saturates signed fields symmetrically: I16 spans -32767..32767.
    static constexpr double max_raw =
        Signed ? static_cast<double>((std::uint64_t{1} << (8 * Bytes - 1)) - 1)
               : (Bytes == 8 ? 18446744073709551615.0
                             : static_cast<double>((std::uint64_t{1} << (8 * Bytes)) - 1));
    static constexpr double min_raw = Signed ? -max_raw : 0.0;
    // The same limits as integers (max_raw of an 8-byte field is not exact as a double).
    static constexpr std::uint64_t max_int =
        Signed ? (std::uint64_t{1} << (8 * Bytes - 1)) - 1
               : (Bytes == 8 ? ~std::uint64_t{0} : (std::uint64_t{1} << (8 * Bytes)) - 1);
};

// F16:X / F24:X: 1 sign bit, (bits-1-Sig) exponent bits, Sig significand bits.
template <int Bytes, int Sig>
struct SmallFloatEnc {
    static constexpr std::size_t size = Bytes;
};

struct F32Enc {
    static constexpr std::size_t size = 4;
};
struct F64Enc {
    static constexpr std::size_t size = 8;
};

inline constexpr IntEnc<1, false> u8{};
inline constexpr IntEnc<2, false> u16{};
inline constexpr IntEnc<3, false> u24{};
inline constexpr IntEnc<4, false> u32{};
inline constexpr IntEnc<8, false> u64{};
inline constexpr IntEnc<1, true> i8{};
inline constexpr IntEnc<2, true> i16{};
inline constexpr IntEnc<3, true> i24{};
inline constexpr IntEnc<4, true> i32{};
inline constexpr IntEnc<8, true> i64{};
inline constexpr SmallFloatEnc<2, 9> f16_9{};
inline constexpr F32Enc f32{};
inline constexpr F64Enc f64{};

template <class E>
inline constexpr bool is_int_enc = false;
template <int B, bool S>
inline constexpr bool is_int_enc<IntEnc<B, S>> = true;

// How a JSON value relates to the wire value: radians on the wire are degrees in JSON.
enum class Unit : std::uint8_t { none, radians };

// raw = round((value - offset) * factor). ProtoGen uses a non-zero offset when a
// field's range does not start at zero ("Scaled by 255/29.0 from 1.0 to 30.0").
struct Scale {
    double factor = 1.0;
    double offset = 0.0;
    constexpr Scale() = default;
    constexpr Scale(double f, double off = 0.0) : factor(f), offset(off) {}  // NOLINT: implicit
};

inline constexpr double pi = 3.14159265358979323846;
inline constexpr double rad2deg = 180.0 / pi;

// --- raw byte access ----------------------------------------------------------------------

// n is 1..8 (a compile-time constant after inlining): one load or store, not n byte moves.
inline std::uint64_t load_be(const std::uint8_t* p, std::size_t n) {
    if constexpr (std::endian::native == std::endian::little) {
        std::uint64_t v = 0;
        std::memcpy(&v, p, n);
        return __builtin_bswap64(v) >> (64 - 8 * n);
    } else {
        std::uint64_t v = 0;
        for (std::size_t i = 0; i < n; ++i) v = (v << 8) | p[i];
        return v;
    }
}

inline void store_be(std::uint8_t* p, std::uint64_t v, std::size_t n) {
    if constexpr (std::endian::native == std::endian::little) {
        const std::uint64_t swapped = __builtin_bswap64(v << (64 - 8 * n));
        std::memcpy(p, &swapped, n);
    } else {
        for (std::size_t i = n; i-- > 0;) {
            p[i] = static_cast<std::uint8_t>(v & 0xFF);
            v >>= 8;
        }
    }
}

// Sign-extends the low `bits` bits of v.
inline std::int64_t sign_extend(std::uint64_t v, int bits) {
    if (bits >= 64) return static_cast<std::int64_t>(v);
    const std::uint64_t m = std::uint64_t{1} << (bits - 1);
    v &= (std::uint64_t{1} << bits) - 1;
    return static_cast<std::int64_t>((v ^ m) - m);
}

// Round half away from zero, then saturate to [lo, hi] (the ICD reference encoder's rule).
// Same result as std::round, without the libm call it costs on baseline x86-64.
inline double round_saturate(double x, double lo, double hi) {
    if (x != x) return 0.0;  // NaN
    if (x >= hi) return hi;
    if (x <= lo) return lo;
    if (std::fabs(x) >= 4503599627370496.0) return x;  // 2^52 and up: already an integer
    const double truncated = static_cast<double>(static_cast<std::int64_t>(x));
    const double fraction = x - truncated;  // exact below 2^52
    if (fraction >= 0.5) return truncated + 1.0;
    if (fraction <= -0.5) return truncated - 1.0;
    return truncated;
}

// --- F16:X and friends (ProtoGen floatspecial.c) ------------------------------------------

// Encodes v into a float of `total_bits` bits with `sig_bits` significand bits, bit for bit
// like ProtoGen's float32ToFloat16: the significand is rounded half away from zero but never
// carries into the exponent; an exponent below -bias underflows to a signed zero (there are
// no denormals: a biased exponent of 0 is an ordinary number with an implied leading one);
// too large or infinite saturates to the largest finite value; NaN encodes as zero.
std::uint32_t float_to_small(double v, int total_bits, int sig_bits);
// The inverse, like ProtoGen's float16ToFloat32: only a zero magnitude is zero, every other
// pattern (biased exponent 0 and all-ones included) is (1 + m / 2^sig) * 2^(e - bias).
double small_to_float(std::uint32_t raw, int total_bits, int sig_bits);

}  // namespace gimbal::orion
