#include "config/fields.hpp"

#include <cstdio>

namespace gimbal::config {

using nlohmann::json;

std::string Problem::text() const {
    return path.empty() ? message : path + ": " + message;
}

std::string join_path(std::string_view path, std::string_view key) {
    return path.empty() ? std::string(key) : std::string(path) + "." + std::string(key);
}

std::string index_path(std::string_view path, std::size_t index) {
    return std::string(path) + "[" + std::to_string(index) + "]";
}

std::string format_number(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    return text;
}

std::string quoted_list(std::span<const std::string_view> names) {
    std::string list;
    for (auto name : names) {
        if (!list.empty()) list += ", ";
        list += "\"" + std::string(name) + "\"";
    }
    return list;
}

std::size_t edit_distance(std::string_view a, std::string_view b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t above = row[j];
            row[j] =
                std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0u : 1u)});
            diagonal = above;
        }
    }
    return row[b.size()];
}

Fields::Fields(const json& value, std::string path, Problems& problems)
    : value_(&value), path_(std::move(path)), problems_(&problems) {
    if (!value.is_object()) problems_->add(path_, "must be an object");
}

const json* Fields::find(std::string_view key) {
    known_.emplace(key);
    if (!is_object()) return nullptr;
    const auto it = value_->find(key);
    return it == value_->end() ? nullptr : &*it;
}

const json* Fields::required(std::string_view key) {
    const json* value = find(key);
    if (value == nullptr && is_object()) problem(key, "required");
    return value;
}

bool Fields::string(std::string_view key, std::string& out, Presence presence) {
    const json* value = lookup(key, presence);
    if (value == nullptr) return false;
    if (!value->is_string()) {
        problem(key, "must be a string");
        return false;
    }
    out = value->get<std::string>();
    return true;
}

bool Fields::boolean(std::string_view key, bool& out) {
    const json* value = find(key);
    if (value == nullptr) return false;
    if (!value->is_boolean()) {
        problem(key, "must be true or false");
        return false;
    }
    out = value->get<bool>();
    return true;
}

bool Fields::number(std::string_view key, double& out, Range range, Presence presence) {
    const json* value = lookup(key, presence);
    if (value == nullptr) return false;
    const std::string between = format_number(range.min) + " and " + format_number(range.max);
    if (!value->is_number()) {
        problem(key, "must be a number between " + between);
        return false;
    }
    const double number = value->get<double>();
    if (!(number >= range.min && number <= range.max)) {
        problem(key, "must be between " + between);
        return false;
    }
    out = number;
    return true;
}

bool Fields::integer_in_range(std::string_view key, const json& value, IntRange range) {
    const std::string between = std::to_string(range.min) + " and " + std::to_string(range.max);
    if (!value.is_number_integer()) {
        problem(key, "must be an integer between " + between);
        return false;
    }
    // nlohmann keeps non-negative integers as unsigned: compare each kind as itself.
    const bool in_range =
        value.is_number_unsigned()
            ? (range.min <= 0 ||
               value.get<std::uint64_t>() >= static_cast<std::uint64_t>(range.min)) &&
                  value.get<std::uint64_t>() <= static_cast<std::uint64_t>(range.max)
            : value.get<std::int64_t>() >= range.min && value.get<std::int64_t>() <= range.max;
    if (!in_range) problem(key, "must be between " + between);
    return in_range;
}

bool Fields::optional_string(std::string_view key, std::optional<std::string>& out,
                             std::string_view message) {
    const json* value = find(key);
    if (value == nullptr || value->is_null()) return false;
    if (!value->is_string() || value->get_ref<const std::string&>().empty()) {
        problem(key, std::string(message));
        return false;
    }
    out = value->get<std::string>();
    return true;
}

bool Fields::optional_number(std::string_view key, std::optional<double>& out, Range range) {
    const json* value = find(key);
    if (value == nullptr || value->is_null()) return false;
    double read = 0;
    if (!number(key, read, range)) return false;
    out = read;
    return true;
}

bool Fields::choice(std::string_view key, std::string& out,
                    std::initializer_list<std::string_view> options, Presence presence) {
    const json* value = lookup(key, presence);
    if (value == nullptr) return false;
    if (value->is_string() && std::find(options.begin(), options.end(),
                                        value->get_ref<const std::string&>()) != options.end()) {
        out = value->get<std::string>();
        return true;
    }
    problem(key, "must be one of " + quoted_list({options.begin(), options.size()}));
    return false;
}

std::optional<Fields> Fields::object(std::string_view key, Presence presence) {
    const json* value = lookup(key, presence);
    if (value == nullptr) return std::nullopt;
    Fields nested(*value, path(key), *problems_);
    if (!nested.is_object()) return std::nullopt;
    return nested;
}

void Fields::finish() {
    if (!is_object() || !check_unknown_) return;
    for (const auto& item : value_->items()) {
        if (known_.count(item.key()) != 0) continue;
        problem(item.key(), "unknown key" + suggestion(item.key()));
    }
}

std::string Fields::suggestion(std::string_view key) const {
    for (const auto& known : known_) {
        if (edit_distance(key, known) <= 2 && known.size() > 2)
            return " (did you mean \"" + known + "\"?)";
    }
    return {};
}

}  // namespace gimbal::config
