// JSON views of packet declarations (interface contract section 1: degrees, metres,
// snake_case keys, enum names as strings). to_json() writes every decoded field; from_json()
// reads a client's object into a packet, rejecting unknown keys, wrong types and values the
// wire field cannot carry.
#pragma once

#include <bit>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <type_traits>
#include <utility>

#include "protocols/orion/codec/fields.hpp"
#include "protocols/orion/codec/wire.hpp"
#include "result/result.hpp"

namespace gimbal::orion {

// Text from the wire as a JSON-safe string: printable ASCII kept, anything else becomes '?'.
std::string printable(std::string_view s);
std::string ipv4_to_string(std::uint32_t addr);
bool ipv4_from_string(std::string_view s, std::uint32_t& addr);

// How many digits a number from a scaled or narrow wire field gets.
enum class Digits {
    exact,     // the decoded double as it is (round trips, codec tests)
    shortest,  // contract section 1: the fewest decimals that encode to the same wire value
};

class JsonWriter {
  public:
    explicit JsonWriter(nlohmann::json& obj, Digits digits = Digits::exact)
        : obj_(obj), digits_(digits) {
        if (!obj_.is_object()) obj_ = nlohmann::json::object();
    }

    template <class T, class E>
    void field(std::string_view key, const T& member, E enc, Scale s = {}, Unit unit = Unit::none) {
        if constexpr (is_std_array<T> || is_std_vector<T>) {
            auto arr = nlohmann::json::array();
            for (const auto& item : member) arr.push_back(value(item, enc, s, unit));
            obj_[std::string(key)] = std::move(arr);
        } else {
            obj_[std::string(key)] = value(member, enc, s, unit);
        }
    }

    // A field's JSON value. With Digits::shortest a number from a scaled or narrow wire field
    // carries no more digits than the wire holds: the fewest decimals that still encode to
    // the same wire value (and stay inside the field's range, which the JSON reader checks),
    // found by re-encoding candidates with the field's own encoding.
    template <class T, class E>
    nlohmann::json value(const T& v, E enc, Scale s, Unit unit) const {
        if constexpr (std::is_floating_point_v<T> && !std::is_same_v<E, F64Enc>) {
            if (digits_ == Digits::exact) return scalar(v, unit);
            const double to_json = unit == Unit::radians ? rad2deg : 1.0;
            const double exact = static_cast<double>(v) * to_json;
            if (!std::isfinite(exact)) return nullptr;
            const double target = wire_value(v, enc, s);
            double scale = 1.0;
            for (int decimals = 0; decimals <= 15; ++decimals, scale *= 10.0) {
                // Division by an exact power of ten gives the double nearest the short
                // decimal, which nlohmann prints as that decimal.
                const double candidate = std::round(exact * scale) / scale;
                if (in_range(candidate, enc, s, to_json) &&
                    wire_value(static_cast<T>(candidate / to_json), enc, s) == target) {
                    // A whole number prints without ".0" (JSON has one number type).
                    if (decimals == 0 && std::abs(candidate) < 1e15)
                        return static_cast<std::int64_t>(candidate);
                    return candidate;
                }
            }
            return exact;
        } else {
            return scalar(v, unit);
        }
    }

    template <class T>
    void bits(std::string_view key, const T& member, int) {
        obj_[std::string(key)] = scalar(member, Unit::none);
    }

    template <class E>
    void reserved(E) {}
    void reserved_bits(int) {}

    template <class T, class E>
    void count(std::string_view, const std::vector<T>&, E, std::size_t) {}

    template <class G>
    void group(std::string_view key, const std::vector<G>& items) {
        auto arr = nlohmann::json::array();
        for (const auto& item : items) {
            nlohmann::json sub = nlohmann::json::object();
            JsonWriter w(sub, digits_);
            const_cast<G&>(item).fields(w);
            arr.push_back(std::move(sub));
        }
        obj_[std::string(key)] = std::move(arr);
    }

    void string(std::string_view key, const std::string& s, std::size_t) {
        obj_[std::string(key)] = printable(s);
    }
    void fixed_string(std::string_view key, const std::string& s, std::size_t) {
        obj_[std::string(key)] = printable(s);
    }
    void ipv4(std::string_view key, const std::uint32_t& addr) {
        obj_[std::string(key)] = ipv4_to_string(addr);
    }
    void optional() {}

    template <class T>
    static nlohmann::json scalar(const T& v, Unit unit) {
        if constexpr (std::is_enum_v<T>) {
            const auto name = enum_name(v);
            if (!name.empty()) return std::string(name);
            return static_cast<std::int64_t>(static_cast<std::underlying_type_t<T>>(v));
        } else if constexpr (std::is_same_v<T, bool>) {
            return v;
        } else if constexpr (std::is_floating_point_v<T>) {
            const double d =
                unit == Unit::radians ? static_cast<double>(v) * rad2deg : static_cast<double>(v);
            return std::isfinite(d) ? nlohmann::json(d) : nlohmann::json(nullptr);
        } else {
            return v;
        }
    }

  private:
    // What the encoder would put on the wire for `v` (as a double: exact for every scaled
    // field), without writing it.
    template <class T, int B, bool S>
    static double wire_value(T v, IntEnc<B, S>, Scale s) {
        using Enc = IntEnc<B, S>;
        return round_saturate(to_raw_double(v, s), Enc::min_raw, Enc::max_raw);
    }
    template <class T, int B, int Sig>
    static double wire_value(T v, SmallFloatEnc<B, Sig>, Scale s) {
        return static_cast<double>(float_to_small(to_raw_double(v, s), 8 * B, Sig));
    }
    template <class T>
    static double wire_value(T v, F32Enc, Scale s) {
        return static_cast<double>(
            std::bit_cast<std::uint32_t>(static_cast<float>(to_raw_double(v, s))));
    }
    // The limits JsonReader::scalar enforces for an integer field, in JSON units.
    template <int B, bool S>
    static bool in_range(double json_value, IntEnc<B, S>, Scale s, double to_json) {
        using Enc = IntEnc<B, S>;
        double lo = (Enc::min_raw / s.factor + s.offset) * to_json;
        double hi = (Enc::max_raw / s.factor + s.offset) * to_json;
        if (lo > hi) std::swap(lo, hi);
        return json_value >= lo && json_value <= hi;
    }
    template <class E>
    static bool in_range(double, E, Scale, double) {
        return true;
    }

    nlohmann::json& obj_;
    Digits digits_ = Digits::exact;
};

// What a packet's JSON reader refuses: bad_request or out_of_range (contract section 4),
// gimbald's one error type.
using JsonError = Error;

class JsonReader {
  public:
    // `prefix` names the object in messages ("points[2].lat").
    explicit JsonReader(const nlohmann::json& obj, std::string prefix = {})
        : obj_(obj), prefix_(std::move(prefix)) {}

    bool ok() const { return !error_; }
    const JsonError& error() const { return *error_; }

    // Call after fields(): every key of the object must have been a field.
    void reject_unknown_keys(const std::set<std::string>& also_allowed = {}) {
        if (!ok() || !obj_.is_object()) return;
        for (const auto& item : obj_.items())
            if (!seen_.count(item.key()) && !also_allowed.count(item.key()))
                fail(code::bad_request, "unknown key '" + path(item.key()) + "'");
    }

    template <class T, class E>
    void field(std::string_view key, T& member, E enc, Scale s = {}, Unit unit = Unit::none) {
        const nlohmann::json* j = find(key);
        if (!j) return;
        if constexpr (is_std_array<T>) {
            if (!j->is_array() || j->size() != member.size())
                return fail(code::bad_request, path(key) + ": must be an array of " +
                                                   std::to_string(member.size()) + " numbers");
            for (std::size_t i = 0; i < member.size() && ok(); ++i)
                scalar((*j)[i], member[i], enc, s, unit, path(key) + "[" + std::to_string(i) + "]");
        } else if constexpr (is_std_vector<T>) {
            if (!j->is_array()) return fail(code::bad_request, path(key) + ": must be an array");
            const std::size_t max = pending_max_.value_or(0);
            pending_max_.reset();
            if (j->size() > max)
                return fail(code::out_of_range,
                            path(key) + ": at most " + std::to_string(max) + " items");
            member.resize(j->size());
            for (std::size_t i = 0; i < member.size() && ok(); ++i) {
                typename T::value_type item{};
                scalar((*j)[i], item, enc, s, unit, path(key) + "[" + std::to_string(i) + "]");
                member[i] = item;
            }
        } else {
            scalar(*j, member, enc, s, unit, path(key));
        }
    }

    template <class T>
    void bits(std::string_view key, T& member, int width) {
        const nlohmann::json* j = find(key);
        if (!j) return;
        const double max = std::ldexp(1.0, width) - 1.0;
        if constexpr (std::is_same_v<T, bool>) {
            if (!j->is_boolean())
                return fail(code::bad_request, path(key) + ": must be true or false");
            member = j->template get<bool>();
        } else if constexpr (std::is_enum_v<T>) {
            enum_value(*j, member, 0.0, max, path(key));
        } else {
            double v = 0;
            if (!integer(*j, v, 0.0, max, path(key))) return;
            member = static_cast<T>(v);
        }
    }

    template <class E>
    void reserved(E) {}
    void reserved_bits(int) {}

    template <class T, class E>
    void count(std::string_view key, std::vector<T>&, E, std::size_t max) {
        seen_.insert(std::string(key));  // accepted but derived from the array's length
        pending_max_ = max;
    }

    template <class G>
    void group(std::string_view key, std::vector<G>& items) {
        const nlohmann::json* j = find(key);
        if (!j) return;
        if (!j->is_array()) return fail(code::bad_request, path(key) + ": must be an array");
        if (!pending_max_) {
            // A fixed repeat (no count field before it): the declaration sized the vector.
            if (j->size() != items.size())
                return fail(code::bad_request, path(key) + ": must hold exactly " +
                                                   std::to_string(items.size()) + " items");
        } else if (j->size() > *pending_max_) {
            return fail(code::out_of_range,
                        path(key) + ": at most " + std::to_string(*pending_max_) + " items");
        }
        pending_max_.reset();
        items.assign(j->size(), G{});
        for (std::size_t i = 0; i < items.size() && ok(); ++i) {
            const std::string where = path(key) + "[" + std::to_string(i) + "]";
            if (!(*j)[i].is_object()) return fail(code::bad_request, where + ": must be an object");
            JsonReader sub((*j)[i], where);
            items[i].fields(sub);
            sub.reject_unknown_keys();
            if (!sub.ok()) error_ = sub.error();
        }
    }

    void string(std::string_view key, std::string& s, std::size_t max_bytes) {
        text(key, s, max_bytes - 1);
    }
    void fixed_string(std::string_view key, std::string& s, std::size_t bytes) {
        text(key, s, bytes - 1);
    }
    void ipv4(std::string_view key, std::uint32_t& addr) {
        const nlohmann::json* j = find(key);
        if (!j) return;
        if (!j->is_string() || !ipv4_from_string(j->template get<std::string>(), addr))
            fail(code::bad_request, path(key) + ": must be a dotted IPv4 address");
    }
    void optional() {}

  private:
    const nlohmann::json* find(std::string_view key) {
        if (!ok() || !obj_.is_object()) return nullptr;
        auto it = obj_.find(std::string(key));
        if (it == obj_.end()) return nullptr;
        seen_.insert(std::string(key));
        return &*it;
    }

    std::string path(std::string_view key) const {
        return prefix_.empty() ? std::string(key) : prefix_ + "." + std::string(key);
    }

    void fail(ErrorCode c, std::string message) {
        if (ok()) error_ = JsonError{c, std::move(message)};
    }

    static std::string num(double v) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.10g", v);
        return buf;
    }

    bool number(const nlohmann::json& j, double& out, const std::string& where) {
        if (!j.is_number()) {
            fail(code::bad_request, where + ": must be a number");
            return false;
        }
        out = j.template get<double>();
        if (!std::isfinite(out)) {
            fail(code::bad_request, where + ": must be finite");
            return false;
        }
        return true;
    }

    bool in_range(double v, double lo, double hi, const std::string& where) {
        const double eps = 1e-9 * std::max(1.0, std::fabs(hi - lo));
        if (v < lo - eps || v > hi + eps) {
            fail(code::out_of_range, where + ": must be between " + num(lo) + " and " + num(hi));
            return false;
        }
        return true;
    }

    bool integer(const nlohmann::json& j, double& out, double lo, double hi,
                 const std::string& where) {
        if (!number(j, out, where)) return false;
        if (out != std::floor(out)) {
            fail(code::bad_request, where + ": must be an integer");
            return false;
        }
        // Integers are exact in a double: no tolerance, or -1 would pass for a U32.
        if (out < lo || out > hi) {
            fail(code::out_of_range, where + ": must be between " + num(lo) + " and " + num(hi));
            return false;
        }
        return true;
    }

    template <class T>
    void enum_value(const nlohmann::json& j, T& member, double lo, double hi,
                    const std::string& where) {
        if (j.is_string()) {
            if (!enum_from_name(j.template get<std::string>(), member)) {
                std::string names;
                for (const auto& e : enum_names(T{}))
                    names += (names.empty() ? "" : ", ") + std::string(e.name);
                fail(code::bad_request, where + ": must be one of " + names);
            }
            return;
        }
        double v = 0;
        if (integer(j, v, lo, hi, where))
            member = static_cast<T>(static_cast<std::underlying_type_t<T>>(v));
    }

    template <class T, class E>
    void scalar(const nlohmann::json& j, T& member, E, Scale s, Unit unit,
                const std::string& where) {
        if constexpr (std::is_same_v<T, bool>) {
            if (!j.is_boolean()) return fail(code::bad_request, where + ": must be true or false");
            member = j.template get<bool>();
        } else if constexpr (std::is_enum_v<T>) {
            if constexpr (is_int_enc<E>) enum_value(j, member, E::min_raw, E::max_raw, where);
        } else if constexpr (std::is_integral_v<T>) {
            double v = 0;
            if constexpr (is_int_enc<E>) {
                if (integer(j, v, E::min_raw, E::max_raw, where)) member = static_cast<T>(v);
            }
        } else {
            double v = 0;
            if (!number(j, v, where)) return;
            const double to_json = unit == Unit::radians ? rad2deg : 1.0;
            if constexpr (is_int_enc<E>) {
                double lo = (E::min_raw / s.factor + s.offset) * to_json;
                double hi = (E::max_raw / s.factor + s.offset) * to_json;
                if (lo > hi) std::swap(lo, hi);
                if (!in_range(v, lo, hi, where)) return;
            }
            member = static_cast<T>(v / to_json);
        }
    }

    void text(std::string_view key, std::string& s, std::size_t max_chars) {
        const nlohmann::json* j = find(key);
        if (!j) return;
        if (!j->is_string()) return fail(code::bad_request, path(key) + ": must be a string");
        auto v = j->template get<std::string>();
        if (v.size() > max_chars)
            return fail(code::out_of_range,
                        path(key) + ": at most " + std::to_string(max_chars) + " characters");
        for (const char ch : v) {
            const auto c = static_cast<unsigned char>(ch);
            if (c < 0x20 || c > 0x7E)
                return fail(code::bad_request, path(key) + ": printable ASCII only");
        }
        s = std::move(v);
    }

    const nlohmann::json& obj_;
    std::string prefix_;
    std::set<std::string> seen_;
    std::optional<std::size_t> pending_max_;  // set by count(), used by the next repeat
    std::optional<JsonError> error_;
};

// Every field of a packet as a JSON object; Digits::shortest for what clients are sent.
template <class P>
nlohmann::json to_json(const P& packet, Digits digits = Digits::exact) {
    nlohmann::json obj = nlohmann::json::object();
    JsonWriter w(obj, digits);
    const_cast<P&>(packet).fields(w);  // fields() only reads through a JsonWriter
    return obj;
}

// Reads a packet from a JSON object. Absent keys keep the packet's defaults; unknown keys,
// wrong types and values outside the wire field's range are errors.
// The JSON of one field, found by its address (field_json below).
class FieldPicker : public JsonWriter {
  public:
    FieldPicker(nlohmann::json& scratch, const void* target, Digits digits)
        : JsonWriter(scratch, digits), scratch_(scratch), target_(target) {}
    template <class M, class E>
    void field(std::string_view key, const M& m, E enc, Scale s = {}, Unit unit = Unit::none) {
        if (static_cast<const void*>(&m) != target_) return;
        JsonWriter::field(key, m, enc, s, unit);
        found = std::move(scratch_[std::string(key)]);
    }
    template <class M>
    void bits(std::string_view key, const M& m, int n) {
        if (static_cast<const void*>(&m) != target_) return;
        JsonWriter::bits(key, m, n);
        found = std::move(scratch_[std::string(key)]);
    }
    nlohmann::json found = nullptr;

  private:
    nlohmann::json& scratch_;
    const void* target_;
};

// One field of a packet as to_json() writes it: `member` (a member of `packet`, found by its
// address, so no key is spelled twice) as JSON - a number with the digits `digits` gives it,
// an array for an array field; null when `member` is not one of the packet's fields.
template <class P, class T>
nlohmann::json field_json(const P& packet, const T& member, Digits digits = Digits::exact) {
    nlohmann::json scratch = nlohmann::json::object();
    FieldPicker picker(scratch, &member, digits);
    const_cast<P&>(packet).fields(picker);  // fields() only reads through a JsonWriter
    return std::move(picker.found);
}

template <class P>
bool from_json(const nlohmann::json& obj, P& packet, JsonError& error) {
    if (!obj.is_object()) {
        error = JsonError{code::bad_request, "packet must be a JSON object"};
        return false;
    }
    JsonReader r(obj);
    packet.fields(r);
    r.reject_unknown_keys();
    if (!r.ok()) error = r.error();
    return r.ok();
}

}  // namespace gimbal::orion
