// MISB ST 1201 IMAPB: a floating-point value in [a, b] mapped onto an L-byte unsigned integer
// (ST 0601 uses it for its "extended" and newer items, e.g. tags 96, 103-105, 109, 112-114,
// 117-120, 132, 134). bPow = ceil(log2(b - a)), dPow = 8L - 1, sF = 2^(dPow - bPow),
// zOffset = sF*a - floor(sF*a) when a < 0 (so that zero is exact), else 0;
// forward y = floor(sF*(x - a) + zOffset) - a truncation, as ST 1201 defines it and as the
// ST 0601 examples confirm (tag 103: 23456.24 m -> 0x2F921E); reverse x = (y - zOffset)/sF + a.
// Integers with the top bit set are ST 1201's special values (infinities, NaNs, reserved);
// they decode to "no value". Pure.
#pragma once

#include <cstdint>
#include <optional>

namespace gimbal::klv {

struct Imapb {
    double a = 0;
    double b = 0;
    int length = 0;  // bytes, 1..8

    // x is clamped into [a, b] first; NaN maps to a (callers reject NaN before).
    std::uint64_t encode(double x) const;
    // std::nullopt for a special value (top bit set).
    std::optional<double> decode(std::uint64_t y) const;
    // One integer step in value units (the mapping's resolution).
    double step() const;

  private:
    int scale_exponent() const;  // dPow - bPow: sF = 2^this
    double z_offset() const;
};

}  // namespace gimbal::klv
