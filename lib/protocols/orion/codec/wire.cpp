#include "protocols/orion/codec/wire.hpp"

#include <bit>

namespace gimbal::orion {
namespace {

constexpr std::uint32_t kF32SigBits = 23;
constexpr std::uint32_t kF32SigMask = 0x007FFFFFu;
constexpr std::uint32_t kF32ExpMask = 0x7F800000u;
constexpr std::uint32_t kF32SignMask = 0x80000000u;
constexpr std::int32_t kF32Bias = 127;

// Right shift with round-half-up, clipped at `max` (the significand never carries into the
// exponent: that is how the gimbal's own encoder behaves, so we match it bit for bit).
std::uint32_t shift_round(std::uint32_t in, std::uint32_t shift, std::uint32_t max) {
    if (shift == 0) return in > max ? max : in;
    const std::uint64_t rounded = (std::uint64_t{in} + (std::uint64_t{1} << (shift - 1))) >> shift;
    return rounded > max ? max : static_cast<std::uint32_t>(rounded);
}

// 2^(exponent bits - 1) - 1, with exponent bits = total - 1 - sig.
std::int32_t small_bias(int total_bits, int sig_bits) {
    return (std::int32_t{1} << (total_bits - 2 - sig_bits)) - 1;
}

}  // namespace

std::uint32_t float_to_small(double v, int total_bits, int sig_bits) {
    const float f = static_cast<float>(v);
    if (f != f) return 0;  // NaN has no representation: send zero
    const std::uint32_t bits = std::bit_cast<std::uint32_t>(f);
    const std::uint32_t sign = (bits & kF32SignMask) ? std::uint32_t{1} << (total_bits - 1) : 0;
    if ((bits & ~kF32SignMask) == 0) return sign;  // +-0

    const auto sig = static_cast<std::uint32_t>(sig_bits);
    const std::int32_t bias = small_bias(total_bits, sig_bits);
    const std::uint32_t max_sig = (1u << sig) - 1;
    std::int32_t exponent =
        static_cast<std::int32_t>((bits & kF32ExpMask) >> kF32SigBits) - kF32Bias;
    if (exponent < -bias) return sign;  // underflow (float32 denormals included)

    std::uint32_t out = shift_round(bits & kF32SigMask, kF32SigBits - sig, max_sig);
    if (exponent > bias) {  // too large or infinite: the largest finite value
        exponent = bias;
        out = max_sig;
    }
    out |= static_cast<std::uint32_t>(exponent + bias) << sig;
    return out | sign;
}

double small_to_float(std::uint32_t raw, int total_bits, int sig_bits) {
    const std::uint32_t sign_bit = 1u << (total_bits - 1);
    const std::uint32_t magnitude = raw & (sign_bit - 1);
    if (magnitude == 0) return (raw & sign_bit) ? -0.0 : 0.0;
    const auto sig = static_cast<std::uint32_t>(sig_bits);
    const std::int32_t bias = small_bias(total_bits, sig_bits);
    const std::uint32_t biased_exp = magnitude >> sig;
    const std::uint32_t mantissa = magnitude & ((1u << sig) - 1);
    const double value = std::ldexp(static_cast<double>(mantissa | (1u << sig)),
                                    static_cast<int>(biased_exp) - bias - sig_bits);
    return (raw & sign_bit) ? -value : value;
}

}  // namespace gimbal::orion
