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

#include "command/catalogue.hpp"
#include "command/result.hpp"

namespace gimbal::command {

// Ranges, choices, lengths and counts come from the command catalogue (catalogue.hpp): they
// are declared there once and a planner reads values without them (docs/architecture.md "A
// request parsed once"). Whether a parameter is required stays the reader's: the daemon fills
// some in (a geopoint's `alt` from the terrain) before a planner needs them.
class JsonParams {
  public:
    // `params` is the request object of catalogue command `cmd`, whose ParamSpecs apply.
    // `envelope` keys (cmd, id, gimbal, token, ts, nonce) are not parameters.
    JsonParams(const nlohmann::json& params, std::string_view cmd);
    // An object inside a parameter (a path point) read against that parameter's `fields`.
    JsonParams(const nlohmann::json& params, std::span<const ParamSpec> specs);

    bool ok() const { return !error_; }
    const Error& error() const { return *error_; }

    // Fails with bad_request naming the first key no getter asked for.
    void reject_unknown();

    bool has(std::string_view key) const;

    std::optional<double> number(std::string_view key, bool required);
    double number_or(std::string_view key, double fallback) {
        return number(key, false).value_or(fallback);
    }
    std::optional<std::int64_t> integer(std::string_view key, bool required);
    std::int64_t integer_or(std::string_view key, std::int64_t fallback) {
        return integer(key, false).value_or(fallback);
    }
    std::optional<bool> boolean(std::string_view key, bool required);
    bool boolean_or(std::string_view key, bool fallback) {
        return boolean(key, false).value_or(fallback);
    }
    // A string that must be one of the catalogue's choices.
    std::optional<std::string> choice(std::string_view key, bool required);
    // Printable ASCII of at most the catalogue's length.
    std::optional<std::string> text(std::string_view key, bool required);
    // An array of the catalogue's count of numbers, each within its range.
    std::optional<std::vector<double>> numbers(std::string_view key, bool required);
    // Raw access for structured parameters (path points); marks the key as used.
    const nlohmann::json* raw(std::string_view key);
    // The catalogue's fields of structured parameter `key` (a path point's lat, lon, alt), to
    // read each of its objects with JsonParams(object, fields).
    std::span<const ParamSpec> fields_of(std::string_view key);

    void fail(ErrorCode code, std::string message);

  private:
    const nlohmann::json* take(std::string_view key, bool required);
    // The catalogue's declaration of `key`; nullptr (and an `internal` failure: a planner
    // reading a parameter its command does not declare is a bug) when there is none.
    const ParamSpec* spec_of(std::string_view key);

    const nlohmann::json& params_;
    std::span<const ParamSpec> specs_;
    std::string_view command_;  // for the internal failure's message
    std::set<std::string, std::less<>> used_;
    std::optional<Error> error_;
};

std::string format_number(double v);

}  // namespace gimbal::command
