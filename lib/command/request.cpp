#include "command/request.hpp"

#include <atomic>
#include <cmath>
#include <stdexcept>

#include "command/params.hpp"
#include "command/request_limits.hpp"

namespace gimbal::command {

namespace {

std::atomic<std::uint64_t> parses{0};

std::string named(std::string_view key) {
    std::string out = "'";
    out += key;
    out += "'";
    return out;
}

Error bad(std::string message) {
    return {code::bad_request, std::move(message)};
}

Error out_of_range(std::string message) {
    return {code::out_of_range, std::move(message)};
}

std::string choices_of(const ParamSpec& p) {
    std::string list;
    for (auto c : p.choices) {
        if (!list.empty()) list += ", ";
        list += c;
    }
    return list;
}

std::string whole(double v) {
    return std::to_string(static_cast<std::int64_t>(v));
}

Status check_value(const ParamSpec& p, const nlohmann::json& j);

// A `points` item: an object of the spec's fields, each checked, none other.
Status check_point(const ParamSpec& p, const nlohmann::json& item, std::size_t index) {
    const std::string where = "points[" + std::to_string(index) + "]";
    if (!item.is_object()) return bad(where + " must be {\"lat\",\"lon\",\"alt\"}");
    for (const auto& field : p.fields) {
        const auto it = item.find(std::string(field.name));
        if (it == item.end() || it->is_null()) {
            if (field.required) return bad(where + ": missing parameter " + named(field.name));
            continue;
        }
        if (auto checked = check_value(field, *it); !checked)
            return Error{checked.error().code, where + ": " + checked.error().message};
    }
    for (const auto& [key, value] : item.items()) {
        bool declared = false;
        for (const auto& field : p.fields) declared = declared || field.name == key;
        if (!declared) return bad(where + ": unknown parameter " + named(key));
    }
    return {};
}

// One present (non-null) value against its ParamSpec, with the contract's messages.
Status check_value(const ParamSpec& p, const nlohmann::json& j) {
    const std::string key = named(p.name);
    switch (p.type) {
        case ParamType::number: {
            if (!j.is_number()) return bad(key + " must be a number");
            const double v = j.get<double>();
            if (!std::isfinite(v) || v < p.min || v > p.max)
                return out_of_range(key + " must be between " + format_number(p.min) + " and " +
                                    format_number(p.max));
            return {};
        }
        case ParamType::integer: {
            if (!j.is_number() ||
                (j.is_number_float() && j.get<double>() != std::floor(j.get<double>())))
                return bad(key + " must be an integer");
            const double v = j.get<double>();
            if (v < p.min || v > p.max)
                return out_of_range(key + " must be between " + whole(p.min) + " and " +
                                    whole(p.max));
            return {};
        }
        case ParamType::boolean:
            if (!j.is_boolean()) return bad(key + " must be true or false");
            return {};
        case ParamType::text: {
            if (!j.is_string()) return bad(key + " must be a string");
            const auto& v = j.get_ref<const std::string&>();
            if (static_cast<double>(v.size()) > p.max)
                return out_of_range(key + " must be at most " + whole(p.max) + " characters");
            for (const char ch : v) {
                const auto c = static_cast<unsigned char>(ch);
                if (c < 0x20 || c > 0x7E) return bad(key + " must be printable ASCII");
            }
            return {};
        }
        case ParamType::choice: {
            if (j.is_string())
                for (auto c : p.choices)
                    if (c == j.get_ref<const std::string&>()) return {};
            return bad(key + " must be one of " + choices_of(p));
        }
        case ParamType::numbers: {
            const std::string shape =
                key + " must be an array of " + std::to_string(p.count) + " numbers";
            if (!j.is_array() || j.size() != p.count) return bad(shape);
            for (const auto& item : j) {
                if (!item.is_number()) return bad(shape);
                const double v = item.get<double>();
                if (!std::isfinite(v) || v < p.min || v > p.max)
                    return out_of_range(key + " items must be between " + format_number(p.min) +
                                        " and " + format_number(p.max));
            }
            return {};
        }
        case ParamType::points: {
            const std::string most = whole(p.max);
            if (!j.is_array() || j.empty())
                return bad(key + " must be an array of 1 to " + most + " points");
            if (static_cast<double>(j.size()) > p.max)
                return out_of_range(key + " must hold 1 to " + most + " points");
            for (std::size_t i = 0; i < j.size(); ++i)
                if (auto checked = check_point(p, j[i], i); !checked) return checked;
            return {};
        }
        case ParamType::keys: {
            const std::string shape = key + " must be an array of STATE key names";
            if (!j.is_array()) return bad(shape);
            for (const auto& item : j)
                if (!item.is_string()) return bad(shape);
            return {};
        }
    }
    return Error{code::internal, key + " has a type the request reader does not know"};
}

const nlohmann::json* find_value(const nlohmann::json& object, std::string_view key) {
    if (!object.is_object()) return nullptr;
    const auto it = object.find(std::string(key));
    if (it == object.end() || it->is_null()) return nullptr;
    return &*it;
}

}  // namespace

bool is_envelope_key(std::string_view key) {
    return key == "cmd" || key == "id" || key == "gimbal" || key == "token" || key == "ts" ||
           key == "nonce";
}

std::optional<nlohmann::json> parse_object(std::string_view bytes) {
    parses.fetch_add(1, std::memory_order_relaxed);
    nlohmann::json j = nlohmann::json::parse(bytes, nullptr, false);
    if (j.is_discarded() || !j.is_object()) return std::nullopt;
    return j;
}

std::uint64_t request_parses() {
    return parses.load(std::memory_order_relaxed);
}

Echo echo_of(const nlohmann::json& doc) {
    Echo e;
    if (!doc.is_object()) return e;
    if (const auto it = doc.find("id"); it != doc.end()) e.id = *it;
    if (const auto it = doc.find("cmd"); it != doc.end() && it->is_string())
        e.cmd = it->get<std::string>();
    return e;
}

const ParamSpec& Params::spec_of(std::string_view key) const {
    if (spec_)
        if (const ParamSpec* p = find_param(*spec_, key)) return *p;
    throw std::logic_error("'" + std::string(spec_ ? spec_->name : "?") + "' has no parameter '" +
                           std::string(key) + "' in the catalogue");
}

bool Params::has(std::string_view key) const {
    (void)spec_of(key);
    return find_value(values_, key) != nullptr;
}

const nlohmann::json* Params::raw(std::string_view key) const {
    (void)spec_of(key);
    return find_value(values_, key);
}

std::optional<double> Params::number(std::string_view key) const {
    const auto* j = raw(key);
    if (!j) return std::nullopt;
    return j->get<double>();
}

std::optional<std::int64_t> Params::integer(std::string_view key) const {
    const auto* j = raw(key);
    if (!j) return std::nullopt;
    return static_cast<std::int64_t>(j->get<double>());
}

std::optional<bool> Params::boolean(std::string_view key) const {
    const auto* j = raw(key);
    if (!j) return std::nullopt;
    return j->get<bool>();
}

std::optional<std::string> Params::text(std::string_view key) const {
    const auto* j = raw(key);
    if (!j) return std::nullopt;
    return j->get<std::string>();
}

std::optional<std::string> Params::choice(std::string_view key) const {
    return text(key);
}

std::optional<std::vector<double>> Params::numbers(std::string_view key) const {
    const auto* j = raw(key);
    if (!j) return std::nullopt;
    std::vector<double> out;
    out.reserve(j->size());
    for (const auto& v : *j) out.push_back(v.get<double>());
    return out;
}

std::optional<std::vector<Point>> Params::points(std::string_view key) const {
    const auto* j = raw(key);
    if (!j) return std::nullopt;
    std::vector<Point> out;
    out.reserve(j->size());
    for (const auto& item : *j) {
        Point p;
        p.lat = item.at("lat").get<double>();
        p.lon = item.at("lon").get<double>();
        if (const auto* alt = find_value(item, "alt")) p.alt = alt->get<double>();
        out.push_back(p);
    }
    return out;
}

Status Params::set(std::string_view key, nlohmann::json value) {
    const ParamSpec& p = spec_of(key);
    if (!value.is_null())
        if (auto checked = check_value(p, value); !checked) return checked;
    values_[std::string(key)] = std::move(value);
    return {};
}

Result<Params> read_params(const CommandSpec& command, const nlohmann::json& doc) {
    Params out;
    out.spec_ = &command;
    for (const auto& p : command.params) {
        const nlohmann::json* j = find_value(doc, p.name);
        if (!j) {
            if (p.required) return bad("missing parameter " + named(p.name));
            continue;
        }
        if (auto checked = check_value(p, *j); !checked) return checked.error();
        out.values_[std::string(p.name)] = *j;
    }
    if (doc.is_object())
        for (const auto& [key, value] : doc.items())
            if (!is_envelope_key(key) && !find_param(command, key))
                return bad("unknown parameter " + named(key));
    return out;
}

Result<Envelope> read_envelope(const nlohmann::json& doc) {
    if (!doc.is_object()) return Error{code::bad_json, "the datagram is not a JSON object"};
    Envelope env;
    if (const auto it = doc.find("id"); it != doc.end()) env.id = *it;
    const auto cmd = doc.find("cmd");
    if (cmd == doc.end()) return Error{code::unknown_cmd, "missing 'cmd'"};
    if (!cmd->is_string()) return Error{code::unknown_cmd, "'cmd' must be a string"};
    env.spec = find_command(cmd->get_ref<const std::string&>());
    if (!env.spec)
        return Error{code::unknown_cmd,
                     "unknown command '" + cmd->get_ref<const std::string&>() + "'"};
    if (const auto* g = find_value(doc, "gimbal")) {
        if (!g->is_string()) return bad("'gimbal' must be a string");
        env.gimbal = g->get<std::string>();
    }
    if (const auto* t = find_value(doc, "token")) {
        if (!t->is_string()) return bad("'token' must be a string");
        env.token = t->get<std::string>();
    }
    return env;
}

Result<Request> read_request(const nlohmann::json& doc) {
    auto env = read_envelope(doc);
    if (!env) return env.error();
    auto params = read_params(*env->spec, doc);
    if (!params) return params.error();
    Request r;
    static_cast<Envelope&>(r) = std::move(env).value();
    r.params = std::move(params).value();
    return r;
}

Result<Request> parse_request(std::string_view bytes) {
    if (auto refused = check_request_limits(bytes)) return std::move(*refused);
    auto doc = parse_object(bytes);
    if (!doc) return Error{code::bad_json, "the datagram is not a JSON object"};
    return read_request(*doc);
}

nlohmann::json request_object(const Request& request) {
    nlohmann::json out = request.params.values();
    out["cmd"] = request.cmd();
    if (request.id) out["id"] = *request.id;
    if (request.gimbal) out["gimbal"] = *request.gimbal;
    if (request.token) out["token"] = *request.token;
    return out;
}

Result<Request> make_request(std::string_view cmd, nlohmann::json params,
                             std::optional<std::string> gimbal) {
    const CommandSpec* spec = find_command(cmd);
    if (!spec) return Error{code::unknown_cmd, "unknown command '" + std::string(cmd) + "'"};
    auto read = read_params(*spec, params);
    if (!read) return read.error();
    Request r;
    r.spec = spec;
    r.gimbal = std::move(gimbal);
    r.params = std::move(read).value();
    return r;
}

}  // namespace gimbal::command
