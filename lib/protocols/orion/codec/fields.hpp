// The vocabulary packet declarations are written in. Each packet is a struct with
//
//   static constexpr std::uint8_t id;            // ORION_PKT_... value
//   static constexpr std::string_view name;      // snake_case name used in JSON and logs
//   static constexpr std::size_t min_length, max_length;
//   template <class V> void fields(V& v);        // the ICD table, row by row
//
// and fields() calls, in ICD order:
//
//   v.field(key, member, enc [, Scale{factor, offset}] [, Unit::radians])
//       scalar, std::array (fixed repeat) or std::vector (repeat sized by an earlier count)
//   v.bits(key, member, width)          B1..B31, packed MSB first, may cross bytes
//   v.reserved(enc) / v.reserved_bits(width)   written as zero, skipped on decode
//   v.count(key, vector, enc, max)      the count field of a later repeat
//   v.group(key, vector_of_structs)     a repeated structure (each element has fields())
//   v.string(key, s, max_bytes)         zero-terminated, variable length, <= max_bytes
//   v.fixed_string(key, s, bytes)       zero-terminated in exactly `bytes` bytes
//   v.ipv4(key, u32_member)             U32 address, dotted string in JSON
//   v.optional()                        every later field is an optional trailing field
//
// "Only included if X is non-zero" is a plain `if (x) { ... }` around the fields: by the time
// the visitor reaches it, x has been decoded (or is about to be encoded).
// The encoder, decoder, JSON writer and JSON reader are visitors of this vocabulary.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string_view>
#include <type_traits>
#include <vector>

#include "protocols/orion/codec/wire.hpp"

namespace gimbal::orion {

// A list of packet types, for dispatch by id (packets.hpp).
template <class... P>
struct PacketList {};

// Enumeration names: every enum used in a packet provides
//   constexpr std::span<const EnumName<E>> enum_names(E);
// found by ADL. The first entry for a value is its canonical name; later entries are aliases.
template <class E>
struct EnumName {
    E value;
    std::string_view name;
};

template <class T>
inline constexpr bool is_std_array = false;
template <class T, std::size_t N>
inline constexpr bool is_std_array<std::array<T, N>> = true;

template <class T>
inline constexpr bool is_std_vector = false;
template <class T, class A>
inline constexpr bool is_std_vector<std::vector<T, A>> = true;

// A scalar a field can hold: arithmetic, bool or enum.
template <class T>
concept WireScalar = std::is_arithmetic_v<T> || std::is_enum_v<T>;

template <class E>
std::string_view enum_name(E value) {
    for (const auto& entry : enum_names(value))
        if (entry.value == value) return entry.name;
    return {};
}

template <class E>
bool enum_from_name(std::string_view name, E& out) {
    for (const auto& entry : enum_names(E{}))
        if (entry.name == name) {
            out = entry.value;
            return true;
        }
    return false;
}

// Converts a member value to the raw integer the wire carries (before saturation).
template <class T>
double to_raw_double(T value, Scale s) {
    if constexpr (std::is_enum_v<T>)
        return static_cast<double>(static_cast<std::underlying_type_t<T>>(value));
    else if constexpr (std::is_same_v<T, bool>)
        return value ? 1.0 : 0.0;
    else
        return (static_cast<double>(value) - s.offset) * s.factor;
}

template <class T>
T from_raw_double(double raw, Scale s) {
    if constexpr (std::is_enum_v<T>)
        return static_cast<T>(static_cast<std::underlying_type_t<T>>(raw));
    else if constexpr (std::is_same_v<T, bool>)
        return raw != 0.0;
    else if constexpr (std::is_floating_point_v<T>)
        return static_cast<T>(raw / s.factor + s.offset);
    else
        return static_cast<T>(raw);
}

}  // namespace gimbal::orion
