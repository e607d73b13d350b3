#include "command/params.hpp"

#include "command/request.hpp"

#include <cmath>
#include <cstdio>

namespace gimbal::command {
std::string format_number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.10g", v);
    return buf;
}

JsonParams::JsonParams(const nlohmann::json& params, std::string_view cmd) : params_(params) {
    if (const CommandSpec* spec = find_command(cmd)) {
        specs_ = spec->params;
        command_ = spec->name;
    }
}

JsonParams::JsonParams(const nlohmann::json& params, std::span<const ParamSpec> specs)
    : params_(params), specs_(specs) {}

const ParamSpec* JsonParams::spec_of(std::string_view key) {
    for (const ParamSpec& spec : specs_)
        if (spec.name == key) return &spec;
    fail(code::internal, "parameter '" + std::string(key) + "' is not in the catalogue of '" +
                             std::string(command_) + "'");
    return nullptr;
}

void JsonParams::fail(ErrorCode c, std::string message) {
    if (!error_) error_ = Error{c, std::move(message)};
}

void JsonParams::reject_unknown() {
    if (error_ || !params_.is_object()) return;
    for (const auto& item : params_.items()) {
        if (is_envelope_key(item.key()) || used_.count(item.key())) continue;
        fail(code::bad_request, "unknown parameter '" + item.key() + "'");
        return;
    }
}

bool JsonParams::has(std::string_view key) const {
    return params_.is_object() && params_.contains(std::string(key));
}

const nlohmann::json* JsonParams::take(std::string_view key, bool required) {
    if (error_) return nullptr;
    used_.insert(std::string(key));
    auto it = params_.find(std::string(key));
    if (it == params_.end() || it->is_null()) {
        if (required) fail(code::bad_request, "missing parameter '" + std::string(key) + "'");
        return nullptr;
    }
    return &*it;
}

std::span<const ParamSpec> JsonParams::fields_of(std::string_view key) {
    const ParamSpec* spec = spec_of(key);
    return spec ? spec->fields : std::span<const ParamSpec>();
}

const nlohmann::json* JsonParams::raw(std::string_view key) {
    return take(key, false);
}

std::optional<double> JsonParams::number(std::string_view key, bool required) {
    const ParamSpec* spec = spec_of(key);
    const nlohmann::json* j = spec ? take(key, required) : nullptr;
    if (!j) return std::nullopt;
    const double lo = spec->min, hi = spec->max;
    if (!j->is_number()) {
        fail(code::bad_request, "'" + std::string(key) + "' must be a number");
        return std::nullopt;
    }
    const double v = j->get<double>();
    if (!std::isfinite(v) || v < lo || v > hi) {
        fail(code::out_of_range, "'" + std::string(key) + "' must be between " + format_number(lo) +
                                     " and " + format_number(hi));
        return std::nullopt;
    }
    return v;
}

std::optional<std::int64_t> JsonParams::integer(std::string_view key, bool required) {
    const ParamSpec* spec = spec_of(key);
    const nlohmann::json* j = spec ? take(key, required) : nullptr;
    if (!j) return std::nullopt;
    const auto lo = static_cast<std::int64_t>(spec->min);
    const auto hi = static_cast<std::int64_t>(spec->max);
    if (!j->is_number() ||
        (j->is_number_float() && j->get<double>() != std::floor(j->get<double>()))) {
        fail(code::bad_request, "'" + std::string(key) + "' must be an integer");
        return std::nullopt;
    }
    const double v = j->get<double>();
    if (v < static_cast<double>(lo) || v > static_cast<double>(hi)) {
        fail(code::out_of_range, "'" + std::string(key) + "' must be between " +
                                     std::to_string(lo) + " and " + std::to_string(hi));
        return std::nullopt;
    }
    return static_cast<std::int64_t>(v);
}

std::optional<bool> JsonParams::boolean(std::string_view key, bool required) {
    const nlohmann::json* j = spec_of(key) ? take(key, required) : nullptr;
    if (!j) return std::nullopt;
    if (!j->is_boolean()) {
        fail(code::bad_request, "'" + std::string(key) + "' must be true or false");
        return std::nullopt;
    }
    return j->get<bool>();
}

std::optional<std::string> JsonParams::choice(std::string_view key, bool required) {
    const ParamSpec* spec = spec_of(key);
    const nlohmann::json* j = spec ? take(key, required) : nullptr;
    if (!j) return std::nullopt;
    const std::span<const std::string_view> choices = spec->choices;
    std::string list;
    for (auto c : choices) list += (list.empty() ? "" : ", ") + std::string(c);
    if (!j->is_string()) {
        fail(code::bad_request, "'" + std::string(key) + "' must be one of " + list);
        return std::nullopt;
    }
    const auto v = j->get<std::string>();
    for (auto c : choices)
        if (c == v) return v;
    fail(code::bad_request, "'" + std::string(key) + "' must be one of " + list);
    return std::nullopt;
}

std::optional<std::string> JsonParams::text(std::string_view key, bool required) {
    const ParamSpec* spec = spec_of(key);
    const nlohmann::json* j = spec ? take(key, required) : nullptr;
    if (!j) return std::nullopt;
    const auto max_chars = static_cast<std::size_t>(spec->max);
    if (!j->is_string()) {
        fail(code::bad_request, "'" + std::string(key) + "' must be a string");
        return std::nullopt;
    }
    auto v = j->get<std::string>();
    if (v.size() > max_chars) {
        fail(code::out_of_range, "'" + std::string(key) + "' must be at most " +
                                     std::to_string(max_chars) + " characters");
        return std::nullopt;
    }
    for (const char ch : v) {
        const auto c = static_cast<unsigned char>(ch);
        if (c < 0x20 || c > 0x7E) {
            fail(code::bad_request, "'" + std::string(key) + "' must be printable ASCII");
            return std::nullopt;
        }
    }
    return v;
}

std::optional<std::vector<double>> JsonParams::numbers(std::string_view key, bool required) {
    const ParamSpec* spec = spec_of(key);
    const nlohmann::json* j = spec ? take(key, required) : nullptr;
    if (!j) return std::nullopt;
    const std::size_t count = spec->count;
    const double lo = spec->min, hi = spec->max;
    if (!j->is_array() || j->size() != count) {
        fail(code::bad_request, "'" + std::string(key) + "' must be an array of " +
                                    std::to_string(count) + " numbers");
        return std::nullopt;
    }
    std::vector<double> out;
    for (const auto& item : *j) {
        if (!item.is_number()) {
            fail(code::bad_request, "'" + std::string(key) + "' must be an array of " +
                                        std::to_string(count) + " numbers");
            return std::nullopt;
        }
        const double v = item.get<double>();
        if (!std::isfinite(v) || v < lo || v > hi) {
            fail(code::out_of_range, "'" + std::string(key) + "' items must be between " +
                                         format_number(lo) + " and " + format_number(hi));
            return std::nullopt;
        }
        out.push_back(v);
    }
    return out;
}

}  // namespace gimbal::command
