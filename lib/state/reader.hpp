// The read twin of JsonWriter (writer.hpp), for STATE gimbald wrote itself and reads back: a
// recording's STATE `track` (lib/record/track_records.hpp). The one fields() declaration of a
// part then serves both ways; a part that is read back declares it over a const or non-const
// part (part.hpp).
//
// Lenient, as a reader of a newer gimbald's output must be: unknown keys are ignored and a
// missing key leaves its member as it was; a key of the wrong type (or an integer outside its
// member's range) leaves it too and makes ok() false. null is an empty std::optional, and NaN
// in a plain number (the writer's null for a non-finite value). Pure: nlohmann only.
#pragma once

#include <cstdint>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>

#include "state/part.hpp"

namespace gimbal::state {

class JsonReader {
  public:
    static constexpr bool writing = false;

    explicit JsonReader(const nlohmann::json& in) : in_(&in), ok_(in.is_object()) {}

    // Every key read had the type its member needs.
    bool ok() const { return ok_; }

    // The units only matter when writing: every one reads a number.
    void latlon(std::string_view key, double& deg) { number(key, deg); }
    void angle(std::string_view key, double& deg) { number(key, deg); }
    void metres(std::string_view key, double& m) { number(key, m); }
    void seconds(std::string_view key, double& s) { number(key, s); }
    void decimals(std::string_view key, double& v, int /*decimals*/) { number(key, v); }
    void number(std::string_view key, double& v) { read(key, v); }
    template <class Int>
    requires std::is_integral_v<Int> &&
        (!std::is_same_v<Int, bool>)void integer(std::string_view key, Int& n) {
        read(key, n);
    }
    void boolean(std::string_view key, bool& b) { read(key, b); }
    void string(std::string_view key, std::string& s) { read(key, s); }

    template <class T>
    void latlon(std::string_view key, std::optional<T>& v) {
        read(key, v);
    }
    template <class T>
    void angle(std::string_view key, std::optional<T>& v) {
        read(key, v);
    }
    template <class T>
    void metres(std::string_view key, std::optional<T>& v) {
        read(key, v);
    }
    template <class T>
    void seconds(std::string_view key, std::optional<T>& v) {
        read(key, v);
    }
    template <class T>
    void decimals(std::string_view key, std::optional<T>& v, int /*decimals*/) {
        read(key, v);
    }
    template <class T>
    void number(std::string_view key, std::optional<T>& v) {
        read(key, v);
    }
    template <class Int>
    void integer(std::string_view key, std::optional<Int>& n) {
        read(key, n);
    }
    template <class T>
    void boolean(std::string_view key, std::optional<T>& b) {
        read(key, b);
    }
    template <class T>
    void string(std::string_view key, std::optional<T>& s) {
        read(key, s);
    }

    // A part of its own, read by its fields(); std::optional: null empties it.
    template <class T>
    void object(std::string_view key, T& part) {
        if (const auto* value = find(key)) ok_ = read_part(*value, part) && ok_;
    }
    template <class T>
    void object(std::string_view key, std::optional<T>& part) {
        const auto* value = find(key);
        if (value == nullptr) return;
        if (value->is_null()) {
            part.reset();
            return;
        }
        T read = part.value_or(T{});
        if (read_part(*value, read))
            part = std::move(read);
        else
            ok_ = false;
    }

  private:
    const nlohmann::json* find(std::string_view key) const {
        const auto it = in_->find(std::string(key));
        return it == in_->end() ? nullptr : &*it;
    }

    template <class T>
    void read(std::string_view key, T& out) {
        if (const auto* value = find(key)) ok_ = read_value(*value, out) && ok_;
    }

    template <class T>
    static bool read_part(const nlohmann::json& value, T& part) {
        if (!value.is_object()) return false;
        JsonReader nested(value);
        fields(nested, part);
        return nested.ok();
    }

    template <class T>
    static bool read_value(const nlohmann::json& value, std::optional<T>& out) {
        if (value.is_null()) {
            out.reset();
            return true;
        }
        T read{};
        if (!read_value(value, read)) return false;
        out = std::move(read);
        return true;
    }
    static bool read_value(const nlohmann::json& value, double& out) {
        if (value.is_null()) {  // the writer's non-finite number
            out = std::numeric_limits<double>::quiet_NaN();
            return true;
        }
        if (!value.is_number()) return false;
        out = value.get<double>();
        return true;
    }
    template <class Int>
    requires std::is_integral_v<Int> &&
        (!std::is_same_v<Int, bool>)static bool read_value(const nlohmann::json& value, Int& out) {
        if (value.is_number_unsigned()) {
            const auto n = value.get<std::uint64_t>();
            if (!std::in_range<Int>(n)) return false;
            out = static_cast<Int>(n);
            return true;
        }
        if (!value.is_number_integer()) return false;
        const auto n = value.get<std::int64_t>();
        if (!std::in_range<Int>(n)) return false;
        out = static_cast<Int>(n);
        return true;
    }
    static bool read_value(const nlohmann::json& value, bool& out) {
        if (!value.is_boolean()) return false;
        out = value.get<bool>();
        return true;
    }
    static bool read_value(const nlohmann::json& value, std::string& out) {
        if (!value.is_string()) return false;
        out = value.get<std::string>();
        return true;
    }

    const nlohmann::json* in_;
    bool ok_;
};

// A part read from a JSON object; nullopt when `in` is not an object or a key has the wrong
// type.
template <class T>
std::optional<T> read(const nlohmann::json& in) {
    T part{};
    JsonReader r(in);
    if (!r.ok()) return std::nullopt;
    fields(r, part);
    if (!r.ok()) return std::nullopt;
    return part;
}

}  // namespace gimbal::state
