// The vocabulary SIYI message declarations are written in. Each message is a struct with
//
//   static constexpr std::uint8_t cmd;           // CMD_ID
//   static constexpr std::string_view name;      // snake_case name used in JSON and logs
//   template <class V> void fields(V& v);        // the SDK table, row by row
//
// and fields() calls, in wire order (every integer little-endian):
//
//   v.field(key, member, enc [, scale] [, Unit::radians])
//       raw = member x scale, rounded half away from zero and saturated to `enc` on encode;
//       member = raw / scale on decode. `enc` is u8 ... u64, i8 ... i32 or f32.
//   v.reserved(enc)                 written as zero, skipped on decode, not in JSON
//   v.text(key, string, bytes)      zero-padded ASCII in exactly `bytes` bytes
//   v.version(key, u32)             firmware version word: byte 0 patch, 1 minor, 2 major,
//                                   3 ignored ("0x6E030203 -> v3.2.3")
//   v.zoom(key, ratio)              two bytes: integer part, then tenths (0x0F, 0x16, 0x18)
//   v.optional()                    every later field is an optional trailing field
//
// Structs hold the SDK's physical units (degrees, metres, radians where the SDK sends
// floats in radians); JSON shows contract units (degrees, metres). The encoder, decoder,
// sizer and JSON writer (codec.hpp, json.hpp) are visitors of this vocabulary.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <type_traits>

namespace gimbal::siyi {

template <class Raw>
struct Enc {
    using raw_type = Raw;
    static constexpr std::size_t size = sizeof(Raw);
};

inline constexpr Enc<std::uint8_t> u8{};
inline constexpr Enc<std::int8_t> i8{};
inline constexpr Enc<std::uint16_t> u16{};
inline constexpr Enc<std::int16_t> i16{};
inline constexpr Enc<std::uint32_t> u32{};
inline constexpr Enc<std::int32_t> i32{};
inline constexpr Enc<std::uint64_t> u64{};
inline constexpr Enc<float> f32{};

// How a JSON value relates to the member: radians in the struct are degrees in JSON.
enum class Unit : std::uint8_t { none, radians };

inline constexpr double pi = 3.14159265358979323846;
inline constexpr double rad2deg = 180.0 / pi;

// Enumeration names: every enum used in a message provides
//   constexpr std::span<const EnumName<E>> enum_names(E);
// found by ADL. JSON shows the name, or the number for a value the SDK does not list.
template <class E>
struct EnumName {
    E value;
    std::string_view name;
};

template <class E>
std::string_view enum_name(E value) {
    for (const auto& entry : enum_names(value))
        if (entry.value == value) return entry.name;
    return {};
}

// A list of message types, for dispatch by CMD_ID (messages.hpp).
template <class... M>
struct MessageList {};

}  // namespace gimbal::siyi
