// Reading the parameters of one JSON command: required and optional values with types and
// ranges checked, every key accounted for. The first problem wins and names the key.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "command/result.hpp"

namespace gimbal::command {

class JsonParams {
  public:
    // `params` is the request object; `envelope` keys (cmd, id, gimbal, token, ts, nonce) are not
    // parameters and are ignored here.
    explicit JsonParams(const nlohmann::json& params);

    bool ok() const { return !error_; }
    const Error& error() const { return *error_; }

    // Fails with bad_request naming the first key no getter asked for.
    void reject_unknown();

    bool has(std::string_view key) const;

    std::optional<double> number(std::string_view key, double lo, double hi, bool required);
    double number_or(std::string_view key, double lo, double hi, double fallback) {
        return number(key, lo, hi, false).value_or(fallback);
    }
    std::optional<std::int64_t> integer(std::string_view key, std::int64_t lo, std::int64_t hi,
                                        bool required);
    std::int64_t integer_or(std::string_view key, std::int64_t lo, std::int64_t hi,
                            std::int64_t fallback) {
        return integer(key, lo, hi, false).value_or(fallback);
    }
    std::optional<bool> boolean(std::string_view key, bool required);
    bool boolean_or(std::string_view key, bool fallback) {
        return boolean(key, false).value_or(fallback);
    }
    // A string that must be one of `choices`.
    std::optional<std::string> choice(std::string_view key,
                                      std::span<const std::string_view> choices, bool required);
    std::optional<std::string> text(std::string_view key, std::size_t max_chars, bool required);
    // A fixed-length array of numbers, each within [lo, hi].
    std::optional<std::vector<double>> numbers(std::string_view key, std::size_t count, double lo,
                                               double hi, bool required);
    // Raw access for structured parameters (path points); marks the key as used.
    const nlohmann::json* raw(std::string_view key);

    void fail(ErrorCode code, std::string message);

  private:
    const nlohmann::json* take(std::string_view key, bool required);

    const nlohmann::json& params_;
    std::set<std::string, std::less<>> used_;
    std::optional<Error> error_;
};

std::string format_number(double v);

}  // namespace gimbal::command
