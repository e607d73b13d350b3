// Little-endian field access and the contract's scaling rule for the Viewpro frames.
// Internal to the Viewpro codec.
#pragma once

#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <type_traits>

namespace gimbal::viewpro::le {

inline constexpr double pi = 3.14159265358979323846;
inline constexpr double deg2rad = pi / 180.0;
inline constexpr double rad2deg = 180.0 / pi;

template <class T>
void put(std::span<std::uint8_t> out, std::size_t at, T value) {
    static_assert(std::is_arithmetic_v<T>);
    using U = std::conditional_t<
        sizeof(T) == 1, std::uint8_t,
        std::conditional_t<sizeof(T) == 2, std::uint16_t,
                           std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>>>;
    auto raw = std::bit_cast<U>(value);
    for (std::size_t k = 0; k < sizeof(T); ++k) {
        out[at + k] = static_cast<std::uint8_t>(raw & 0xFFu);
        raw = static_cast<U>(raw >> 8);
    }
}

template <class T>
T get(std::span<const std::uint8_t> in, std::size_t at) {
    static_assert(std::is_arithmetic_v<T>);
    using U = std::conditional_t<
        sizeof(T) == 1, std::uint8_t,
        std::conditional_t<sizeof(T) == 2, std::uint16_t,
                           std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>>>;
    std::uint64_t raw = 0;
    for (std::size_t k = sizeof(T); k-- > 0;) raw = (raw << 8) | in[at + k];
    return std::bit_cast<T>(static_cast<U>(raw));
}

// value x scale, rounded half away from zero, saturated at T's limits; NaN encodes as 0.
template <class T>
T scaled(double value, double scale) {
    static_assert(std::is_integral_v<T>);
    const double x = std::round(value * scale);
    if (std::isnan(x)) return 0;
    constexpr auto lo = static_cast<double>(std::numeric_limits<T>::min());
    constexpr auto hi = static_cast<double>(std::numeric_limits<T>::max());
    if (x <= lo) return std::numeric_limits<T>::min();
    if (x >= hi) return std::numeric_limits<T>::max();
    return static_cast<T>(x);
}

}  // namespace gimbal::viewpro::le
