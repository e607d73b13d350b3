// STATE is typed inside gimbald. Each part of it - the link, the shared telemetry, the video,
// a protocol's own keys - is a struct declared once, beside the code that fills it, with a
// fields() visit that names its keys and their units:
//
//     template <class V> void fields(V& v, const LinkState& l) {
//         v.string("type", l.type);
//         v.integer("rx_bytes", l.rx_bytes);
//         v.seconds("last_rx_age_s", l.last_rx_age_s);  // std::optional: null when empty
//     }
//
// Consumers read the structs. JSON is written only at the edges (replies, pushes, MQTT, HTTP,
// recordings) by the one visitor here, JsonWriter, with contract section 1's precision
// (precision.hpp) picked by the unit the visit names; delta patches are merge patches of two
// written snapshots (merge_patch.hpp). Pure: nlohmann only.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>

#include "state/precision.hpp"

namespace gimbal::state {

class JsonWriter {
  public:
    static constexpr bool writing = true;

    // Writes members into `out`, which becomes an object if it is not one.
    explicit JsonWriter(nlohmann::json& out) : out_(&out) {
        if (!out_->is_object()) *out_ = nlohmann::json::object();
    }

    // Numbers in the contract's units and precision: latitude and longitude 1e-7 degree,
    // other angles 1e-4 degree, lengths 1e-3 m, durations 1e-3 s. Non-finite: null.
    void latlon(std::string_view key, double deg) { put(key, latlon_deg(deg)); }
    void angle(std::string_view key, double deg) { put(key, angle_deg(deg)); }
    void metres(std::string_view key, double m) { put(key, state::metres(m)); }
    void seconds(std::string_view key, double s) { put(key, state::seconds(s)); }
    // A number with `decimals` decimals (a rate, a frame rate).
    void decimals(std::string_view key, double v, int decimals) {
        put(key, round_decimals(v, decimals));
    }
    // A number already at its precision (a value the gimbal reports as it is).
    void number(std::string_view key, double v) { put(key, v); }
    // An integer keeps its type (a count stays unsigned).
    template <class Int>
    requires std::is_integral_v<Int> &&
        (!std::is_same_v<Int, bool>)void integer(std::string_view key, Int n) {
        (*out_)[std::string(key)] = n;
    }
    void boolean(std::string_view key, bool b) { (*out_)[std::string(key)] = b; }
    void string(std::string_view key, std::string_view s) {
        (*out_)[std::string(key)] = std::string(s);
    }
    void null(std::string_view key) { (*out_)[std::string(key)] = nullptr; }

    // std::optional of any of the above: null when empty.
    template <class T>
    void latlon(std::string_view key, const std::optional<T>& v) {
        v ? latlon(key, *v) : null(key);
    }
    template <class T>
    void angle(std::string_view key, const std::optional<T>& v) {
        v ? angle(key, *v) : null(key);
    }
    template <class T>
    void metres(std::string_view key, const std::optional<T>& v) {
        v ? metres(key, *v) : null(key);
    }
    template <class T>
    void seconds(std::string_view key, const std::optional<T>& v) {
        v ? seconds(key, *v) : null(key);
    }
    template <class T>
    void decimals(std::string_view key, const std::optional<T>& v, int n) {
        v ? decimals(key, *v, n) : null(key);
    }
    template <class T>
    void number(std::string_view key, const std::optional<T>& v) {
        v ? number(key, *v) : null(key);
    }
    template <class Int>
    void integer(std::string_view key, const std::optional<Int>& n) {
        n ? integer(key, *n) : null(key);
    }
    template <class T>
    void boolean(std::string_view key, const std::optional<T>& b) {
        b ? boolean(key, *b) : null(key);
    }
    template <class T>
    void string(std::string_view key, const std::optional<T>& s) {
        s ? string(key, *s) : null(key);
    }

    // A part of its own: fields(w, part) into a nested object; std::optional: null when empty.
    template <class T>
    void object(std::string_view key, const T& part) {
        nlohmann::json& sub = (*out_)[std::string(key)] = nlohmann::json::object();
        JsonWriter w(sub);
        fields(w, part);
    }
    template <class T>
    void object(std::string_view key, const std::optional<T>& part) {
        part ? object(key, *part) : null(key);
    }
    // A nested object written in place: write(w) with a writer of it.
    template <class F>
    requires std::is_invocable_v<F, JsonWriter&>
    void object(std::string_view key, F&& write) {
        nlohmann::json& sub = (*out_)[std::string(key)] = nlohmann::json::object();
        JsonWriter w(sub);
        write(w);
    }
    // An array: each item written by each(items[i]) -> a JSON value, typically an object
    // made with write(item) or a number in its unit.
    template <class Items, class F>
    void array(std::string_view key, const Items& items, F&& each) {
        nlohmann::json arr = nlohmann::json::array();
        for (const auto& item : items) arr.push_back(each(item));
        (*out_)[std::string(key)] = std::move(arr);
    }
    template <class Items>
    void array(std::string_view key, const Items& items) {
        array(key, items, [](const auto& item) { return nlohmann::json(item); });
    }

    // A value a codec's own JSON writer made from a decoded packet (a protocol's packet
    // structs are declared, and written, by their codec).
    void json(std::string_view key, nlohmann::json value) {
        (*out_)[std::string(key)] = std::move(value);
    }
    // Every member of `object` (a packet as its codec writes it), beside the others.
    void members(const nlohmann::json& object) {
        for (const auto& [k, v] : object.items()) (*out_)[k] = v;
    }

  private:
    void put(std::string_view key, double v) { (*out_)[std::string(key)] = v; }

    nlohmann::json* out_;
};

// A part written as a JSON object.
template <class T>
nlohmann::json write(const T& part) {
    nlohmann::json out = nlohmann::json::object();
    JsonWriter w(out);
    fields(w, part);
    return out;
}

// One number in its unit, as an array item: JSON of latlon/angle/metres/seconds precision.
inline nlohmann::json latlon_json(double deg) {
    return latlon_deg(deg);
}
inline nlohmann::json angle_json(double deg) {
    return angle_deg(deg);
}

}  // namespace gimbal::state
