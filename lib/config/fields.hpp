// The generic configuration reader and writer. A configuration section is declared once, next
// to the code it configures, as
//
//     template <class V> void fields(V& v, SectionConfig& c) {
//         v.number("rate_hz", c.rate_hz, {0.1, 50});
//         v.choice("mode", c.mode, mode_names);
//         v.section("output", [&](auto& o) { o.boolean("serial", c.serial); });
//     }
//
// and visited by a Fields (reads JSON into the struct, collecting every problem with its JSON
// path and reporting unknown keys with a "did you mean") or by a Writer (the struct back to
// JSON, every key present). Checks that only make sense while reading go under
// `if constexpr (V::reading)`. Pure: nlohmann only.
#pragma once

#include <algorithm>
#include <cstdint>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace gimbal::config {

// One problem found in a configuration. `path` is empty for file-level problems (unreadable
// file, JSON syntax).
struct Problem {
    std::string path;
    std::string message;
    std::string text() const;  // "gimbals[1].link.baud: must be one of ..."
    bool operator==(const Problem&) const = default;
};

class Problems {
  public:
    explicit Problems(std::vector<Problem>& out) : out_(&out) {}
    void add(std::string path, std::string message) {
        out_->push_back({std::move(path), std::move(message)});
    }

  private:
    std::vector<Problem>* out_;
};

struct Range {
    double min;
    double max;
};

struct IntRange {
    long long min;
    long long max;
};

enum class Presence { optional, required };

// A choice's spelling in the file and its value.
template <class E>
struct Named {
    std::string_view name;
    E value;
};

std::string join_path(std::string_view path, std::string_view key);  // "a.b"
std::string index_path(std::string_view path, std::size_t index);    // "a[3]"
std::string format_number(double value);                             // as printf's %g
std::string quoted_list(std::span<const std::string_view> names);    // "\"a\", \"b\""
std::size_t edit_distance(std::string_view a, std::string_view b);

// One JSON object being read. Every key looked up is "known"; finish() reports the others as
// unknown, so a typo in any section is an error wherever it is. Each reader returns true when
// the key was present and valid (and `out` was set); otherwise `out` keeps its default.
class Fields {
  public:
    static constexpr bool reading = true;

    Fields(const nlohmann::json& value, std::string path, Problems& problems);

    bool is_object() const { return value_->is_object(); }
    std::string path(std::string_view key) const { return join_path(path_, key); }
    Problems& problems() { return *problems_; }
    void problem(std::string_view key, std::string message) {
        problems_->add(path(key), std::move(message));
    }

    // The value of `key` (null included), or nullptr when absent.
    const nlohmann::json* find(std::string_view key);
    const nlohmann::json* required(std::string_view key);
    const nlohmann::json* lookup(std::string_view key, Presence presence) {
        return presence == Presence::required ? required(key) : find(key);
    }

    bool string(std::string_view key, std::string& out, Presence presence = Presence::optional);
    bool boolean(std::string_view key, bool& out);
    bool number(std::string_view key, double& out, Range range,
                Presence presence = Presence::optional);

    template <class Int>
    bool integer(std::string_view key, Int& out, IntRange range,
                 Presence presence = Presence::optional) {
        const nlohmann::json* value = lookup(key, presence);
        if (value == nullptr || !integer_in_range(key, *value, range)) return false;
        out = static_cast<Int>(value->get<std::int64_t>());
        return true;
    }

    // null (or absent) is "not set".
    bool optional_string(std::string_view key, std::optional<std::string>& out,
                         std::string_view message = "must be null or a non-empty string");
    bool optional_number(std::string_view key, std::optional<double>& out, Range range);
    template <class Int>
    bool optional_integer(std::string_view key, std::optional<Int>& out, IntRange range) {
        const nlohmann::json* value = find(key);
        if (value == nullptr || value->is_null()) return false;
        Int read{};
        if (!integer(key, read, range)) return false;
        out = read;
        return true;
    }

    bool choice(std::string_view key, std::string& out,
                std::initializer_list<std::string_view> options,
                Presence presence = Presence::optional);
    // `options`: Named<E> values (an array or span).
    template <class E, class Options>
    bool choice(std::string_view key, E& out, const Options& options,
                Presence presence = Presence::optional) {
        const nlohmann::json* value = lookup(key, presence);
        if (value == nullptr) return false;
        if (value->is_string()) {
            const auto& text = value->get_ref<const std::string&>();
            for (const auto& option : options) {
                if (option.name != text) continue;
                out = option.value;
                return true;
            }
        }
        std::vector<std::string_view> names;
        for (const auto& option : options) names.push_back(option.name);
        problem(key, "must be one of " + quoted_list(names));
        return false;
    }

    // An array of strings, each kept when `valid(item)`; `shape` is the message for a value
    // that is not an array (or an empty one, with `non_empty`), `item_message` for a bad item
    // (reported at "key[i]"). A valid array replaces `out`.
    template <class Valid>
    bool string_list(std::string_view key, std::vector<std::string>& out, Valid&& valid,
                     std::string_view shape, std::string_view item_message,
                     Presence presence = Presence::optional, bool non_empty = false) {
        const nlohmann::json* value = lookup(key, presence);
        if (value == nullptr) return false;
        if (!value->is_array() || (non_empty && value->empty())) {
            problem(key, std::string(shape));
            return false;
        }
        std::vector<std::string> read;
        bool all = true;
        for (std::size_t i = 0; i < value->size(); ++i) {
            const nlohmann::json& item = (*value)[i];
            if (item.is_string() && valid(item.get_ref<const std::string&>())) {
                read.push_back(item.get<std::string>());
            } else {
                problems_->add(index_path(path(key), i), std::string(item_message));
                all = false;
            }
        }
        out = std::move(read);
        return all;
    }

    // The nested object under `key`; a present non-object is reported.
    std::optional<Fields> object(std::string_view key, Presence presence = Presence::optional);
    // The nested object under `key` visited by `visit(Fields&)`, its unknown keys reported.
    template <class Visit>
    void section(std::string_view key, Visit&& visit) {
        if (auto nested = object(key)) {
            visit(*nested);
            nested->finish();
        }
    }

    // This object's valid keys cannot be known (e.g. its `type` is wrong): skip finish().
    void keep_unknown_keys() { check_unknown_ = false; }
    void finish();

  private:
    bool integer_in_range(std::string_view key, const nlohmann::json& value, IntRange range);
    std::string suggestion(std::string_view key) const;

    const nlohmann::json* value_;
    std::string path_;
    Problems* problems_;
    std::set<std::string, std::less<>> known_;
    bool check_unknown_ = true;
};

// The same visit writing a section back: every key, with its value or null. Its methods
// return false (nothing was read), so a check written as `if (v.string(...) && ...)` runs
// only while reading.
class Writer {
  public:
    static constexpr bool reading = false;

    void problem(std::string_view, const std::string&) {}
    bool string(std::string_view key, const std::string& value, Presence = Presence::optional) {
        return set(key, value);
    }
    bool boolean(std::string_view key, bool value) { return set(key, value); }
    bool number(std::string_view key, double value, Range, Presence = Presence::optional) {
        return set(key, value);
    }
    template <class Int>
    bool integer(std::string_view key, Int value, IntRange, Presence = Presence::optional) {
        return set(key, value);
    }
    bool optional_string(std::string_view key, const std::optional<std::string>& value,
                         std::string_view = {}) {
        return set(key, value ? nlohmann::json(*value) : nlohmann::json(nullptr));
    }
    bool optional_number(std::string_view key, const std::optional<double>& value, Range) {
        return set(key, value ? nlohmann::json(*value) : nlohmann::json(nullptr));
    }
    template <class Int>
    bool optional_integer(std::string_view key, const std::optional<Int>& value, IntRange) {
        return set(key, value ? nlohmann::json(*value) : nlohmann::json(nullptr));
    }
    template <class E, class Options>
    bool choice(std::string_view key, E value, const Options& options,
                Presence = Presence::optional) {
        for (const auto& option : options)
            if (option.value == value) return set(key, std::string(option.name));
        return set(key, nullptr);
    }
    template <class Valid>
    bool string_list(std::string_view key, const std::vector<std::string>& value, Valid&&,
                     std::string_view, std::string_view, Presence = Presence::optional,
                     bool = false) {
        return set(key, value);
    }
    template <class Visit>
    void section(std::string_view key, Visit&& visit) {
        Writer nested;
        visit(nested);
        set(key, nested.take());
    }

    // A key whose JSON the section builds itself (a list of its own shape).
    void set_json(std::string_view key, nlohmann::json value) { set(key, std::move(value)); }

    nlohmann::json take() { return std::move(out_); }

  private:
    bool set(std::string_view key, nlohmann::json value) {
        out_[std::string(key)] = std::move(value);
        return false;
    }
    nlohmann::json out_ = nlohmann::json::object();
};

// A section's struct from JSON already checked (a session reading the configuration the
// daemon validated and wrote back): problems are not collected, a bad key keeps its default.
template <class T>
T read_checked(const nlohmann::json& value) {
    std::vector<Problem> ignored;
    Problems problems(ignored);
    Fields f(value, "", problems);
    T out{};
    fields(f, out);
    return out;
}

// A section's struct as JSON, every key present.
template <class T>
nlohmann::json write(const T& value) {
    Writer w;
    T copy = value;  // fields() takes the struct by reference for both directions
    fields(w, copy);
    return w.take();
}

// A section read with its problems reported (through `f`) and written back whole: the JSON the
// code it configures then reads with read_checked.
template <class T>
nlohmann::json read_and_write(Fields& f) {
    T read{};
    fields(f, read);
    return write(read);
}

}  // namespace gimbal::config
