#include "protocols/siyi/codec/messages.hpp"

#include <array>

namespace gimbal::siyi {

namespace {

// Every CMD_ID appears once per direction, or dispatch would be ambiguous.
template <class... M>
constexpr bool unique_commands(MessageList<M...>) {
    constexpr std::array<std::uint8_t, sizeof...(M)> ids{M::cmd...};
    for (std::size_t i = 0; i < ids.size(); ++i)
        for (std::size_t j = i + 1; j < ids.size(); ++j)
            if (ids[i] == ids[j]) return false;
    return true;
}
static_assert(unique_commands(ToGimbalList{}));
static_assert(unique_commands(FromGimbalList{}));

template <class Variant, class List>
Decoded<Variant> decode_any(List list, std::uint8_t cmd, std::span<const std::uint8_t> data) {
    Decoded<Variant> out;
    out.error = DecodeError::unknown_command;
    for_each_message(list, [&]<class M>(M*) {
        if (M::cmd != cmd) return;
        const Decoded<M> d = decode<M>(data);
        out.value = d.value;
        out.error = d.error;
    });
    return out;
}

template <class List>
std::string_view name_in(List list, std::uint8_t cmd) {
    std::string_view name;
    for_each_message(list, [&]<class M>(M*) {
        if (M::cmd == cmd) name = M::name;
    });
    return name;
}

}  // namespace

std::string_view to_string(DecodeError e) {
    switch (e) {
        case DecodeError::none:
            return "none";
        case DecodeError::too_short:
            return "too_short";
        case DecodeError::unknown_command:
            return "unknown_command";
    }
    return "unknown";
}

double stream_rate_hz(StreamRate rate) {
    switch (rate) {
        case StreamRate::off:
            return 0;
        case StreamRate::hz2:
            return 2;
        case StreamRate::hz4:
            return 4;
        case StreamRate::hz5:
            return 5;
        case StreamRate::hz10:
            return 10;
        case StreamRate::hz20:
            return 20;
        case StreamRate::hz50:
            return 50;
        case StreamRate::hz100:
            return 100;
    }
    return 0;
}

Decoded<ToGimbal> decode_to_gimbal(std::uint8_t cmd, std::span<const std::uint8_t> data) {
    return decode_any<ToGimbal>(ToGimbalList{}, cmd, data);
}

Decoded<FromGimbal> decode_from_gimbal(std::uint8_t cmd, std::span<const std::uint8_t> data) {
    return decode_any<FromGimbal>(FromGimbalList{}, cmd, data);
}

std::vector<std::uint8_t> encode(const ToGimbal& m, Header header) {
    return std::visit([&](const auto& msg) { return encode(msg, header); }, m);
}

std::vector<std::uint8_t> encode(const FromGimbal& m, Header header) {
    return std::visit([&](const auto& msg) { return encode(msg, header); }, m);
}

void append(std::vector<std::uint8_t>& out, const ToGimbal& m, Header header) {
    std::visit([&](const auto& msg) { append(out, msg, header); }, m);
}

void append(std::vector<std::uint8_t>& out, const FromGimbal& m, Header header) {
    std::visit([&](const auto& msg) { append(out, msg, header); }, m);
}

std::uint8_t command_of(const ToGimbal& m) {
    return std::visit([](const auto& msg) { return std::decay_t<decltype(msg)>::cmd; }, m);
}

std::uint8_t command_of(const FromGimbal& m) {
    return std::visit([](const auto& msg) { return std::decay_t<decltype(msg)>::cmd; }, m);
}

std::string_view name_of(const ToGimbal& m) {
    return std::visit([](const auto& msg) { return std::decay_t<decltype(msg)>::name; }, m);
}

std::string_view name_of(const FromGimbal& m) {
    return std::visit([](const auto& msg) { return std::decay_t<decltype(msg)>::name; }, m);
}

std::string_view message_name(Direction direction, std::uint8_t cmd) {
    return direction == Direction::to_gimbal ? name_in(ToGimbalList{}, cmd)
                                             : name_in(FromGimbalList{}, cmd);
}

}  // namespace gimbal::siyi
