// The one result type of gimbald (docs/architecture.md "One result type"): a value, or an
// Error carrying a contract error code (section 4, a closed list: no code is added here) and
// a message for people. The lowest library: every other one may answer this way - commands,
// the auth layer, KLV, video URLs, terrain files, the simulated camera. `to_string` gives
// the wire spelling; nlohmann is here only for the code's to_json.
#pragma once

#include <array>
#include <concepts>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <utility>
#include <variant>

namespace gimbal {

// Error codes of the contract, section 4, in its order.
enum class ErrorCode : std::uint8_t {
    bad_json,
    too_large,
    unknown_cmd,
    bad_request,
    out_of_range,
    unknown_gimbal,
    unsupported,
    unavailable,
    link_down,
    forbidden,
    busy,
    rate_limited,
    internal,
};

// The spelling callers use: code::bad_request.
namespace code {
inline constexpr ErrorCode bad_json = ErrorCode::bad_json;
inline constexpr ErrorCode too_large = ErrorCode::too_large;
inline constexpr ErrorCode unknown_cmd = ErrorCode::unknown_cmd;
inline constexpr ErrorCode bad_request = ErrorCode::bad_request;
inline constexpr ErrorCode out_of_range = ErrorCode::out_of_range;
inline constexpr ErrorCode unknown_gimbal = ErrorCode::unknown_gimbal;
inline constexpr ErrorCode unsupported = ErrorCode::unsupported;
inline constexpr ErrorCode unavailable = ErrorCode::unavailable;
inline constexpr ErrorCode link_down = ErrorCode::link_down;
inline constexpr ErrorCode forbidden = ErrorCode::forbidden;
inline constexpr ErrorCode busy = ErrorCode::busy;
inline constexpr ErrorCode rate_limited = ErrorCode::rate_limited;
inline constexpr ErrorCode internal = ErrorCode::internal;
}  // namespace code

inline constexpr std::array<std::string_view, 13> error_code_names{
    "bad_json",       "too_large",    "unknown_cmd", "bad_request", "out_of_range",
    "unknown_gimbal", "unsupported",  "unavailable", "link_down",   "forbidden",
    "busy",           "rate_limited", "internal"};

constexpr std::string_view to_string(ErrorCode c) {
    return error_code_names[static_cast<std::size_t>(c)];
}

constexpr std::optional<ErrorCode> parse_error_code(std::string_view name) {
    for (std::size_t i = 0; i < error_code_names.size(); ++i)
        if (error_code_names[i] == name) return static_cast<ErrorCode>(i);
    return std::nullopt;
}

// The wire spelling compares equal to the code ("bad_request" == code::bad_request). Templates
// taking exactly an ErrorCode: nothing converts to one to reach them (a JSON value would).
template <std::same_as<ErrorCode> C>
constexpr bool operator==(C c, std::string_view name) {
    return to_string(c) == name;
}
template <std::same_as<ErrorCode> C>
std::ostream& operator<<(std::ostream& out, C c) {
    return out << to_string(c);
}
// JSON holds the wire spelling, never the number.
inline void to_json(nlohmann::json& j, ErrorCode c) {
    j = std::string(to_string(c));
}

struct Error {
    ErrorCode code = ErrorCode::internal;
    std::string message;
};

// A T, or the Error that stopped it. Result<void> is success or an Error.
template <class T>
class [[nodiscard]] Result {
  public:
    Result(T value) : v_(std::in_place_index<0>, std::move(value)) {}
    Result(Error error) : v_(std::in_place_index<1>, std::move(error)) {}
    Result(ErrorCode c, std::string message)
        : v_(std::in_place_index<1>, Error{c, std::move(message)}) {}

    bool ok() const { return v_.index() == 0; }
    explicit operator bool() const { return ok(); }

    const T& value() const& { return std::get<0>(v_); }
    T& value() & { return std::get<0>(v_); }
    T&& value() && { return std::get<0>(std::move(v_)); }
    const T& operator*() const& { return value(); }
    T& operator*() & { return value(); }
    const T* operator->() const { return &value(); }
    T* operator->() { return &value(); }

    const Error& error() const { return std::get<1>(v_); }

  private:
    std::variant<T, Error> v_;
};

template <>
class [[nodiscard]] Result<void> {
  public:
    Result() = default;
    Result(Error error) : error_(std::move(error)) {}
    Result(ErrorCode c, std::string message) : error_(Error{c, std::move(message)}) {}

    bool ok() const { return !error_; }
    explicit operator bool() const { return ok(); }
    const Error& error() const { return *error_; }

  private:
    std::optional<Error> error_;
};

using Status = Result<void>;

}  // namespace gimbal
