#include "klv/imapb.hpp"

#include <algorithm>
#include <cmath>

namespace gimbal::klv {

int Imapb::scale_exponent() const {
    const int b_pow = static_cast<int>(std::ceil(std::log2(b - a)));
    const int d_pow = 8 * length - 1;
    return d_pow - b_pow;
}

double Imapb::z_offset() const {
    if (a >= 0) return 0.0;
    const double sfa = std::ldexp(a, scale_exponent());
    return sfa - std::floor(sfa);
}

std::uint64_t Imapb::encode(double x) const {
    if (std::isnan(x)) x = a;
    x = std::clamp(x, a, b);
    const double y = std::floor(std::ldexp(x - a, scale_exponent()) + z_offset());
    // The top bit flags special values; a value at b must stay below it.
    const double top = std::ldexp(1.0, 8 * length - 1) - 1.0;
    return static_cast<std::uint64_t>(std::clamp(y, 0.0, top));
}

std::optional<double> Imapb::decode(std::uint64_t y) const {
    if (length < 1 || length > 8) return std::nullopt;
    if ((y >> (8 * length - 1)) & 1u) return std::nullopt;
    return std::ldexp(static_cast<double>(y) - z_offset(), -scale_exponent()) + a;
}

double Imapb::step() const {
    return std::ldexp(1.0, -scale_exponent());
}

}  // namespace gimbal::klv
