#include "track/wire/codec.hpp"

#include <bit>
#include <cmath>
#include <cstring>
#include <type_traits>

namespace gimbal::track::wire {

static_assert(std::endian::native == std::endian::little ||
              std::endian::native == std::endian::big);

std::string_view to_string(MessageType type) {
    switch (type) {
        case MessageType::hello:
            return "hello";
        case MessageType::start:
            return "start";
        case MessageType::au:
            return "au";
        case MessageType::stop:
            return "stop";
        case MessageType::box:
            return "box";
        case MessageType::ended:
            return "ended";
        case MessageType::error:
            return "error";
    }
    return "unknown";
}

namespace {

constexpr std::size_t header_bytes = 2;  // version, type

template <class T>
void put_le(std::vector<std::uint8_t>& out, T value) {
    using U = std::make_unsigned_t<T>;
    auto u = static_cast<U>(value);
    for (std::size_t i = 0; i < sizeof(T); ++i) {
        out.push_back(static_cast<std::uint8_t>(u & 0xFFu));
        if constexpr (sizeof(T) > 1) u = static_cast<U>(u >> 8);
    }
}

template <class T>
T get_le(const std::uint8_t* p) {
    using U = std::make_unsigned_t<T>;
    U u = 0;
    for (std::size_t i = sizeof(T); i-- > 0;) u = static_cast<U>((u << 8) | p[i]);
    return static_cast<T>(u);
}

// Checks every field against its declaration (encode and decode share it).
struct Rules {
    std::string error;
    std::string_view message;

    bool fail(std::string_view field, std::string_view what) {
        if (!error.empty()) return false;
        error = std::string(message);
        if (!field.empty()) error += "." + std::string(field);
        error += ": " + std::string(what);
        return false;
    }
    bool number(std::string_view field, double value, double min, double max) {
        if (!std::isfinite(value)) return fail(field, "not a finite number");
        if (value < min || value > max) return fail(field, "out of range");
        return true;
    }
    bool text(std::string_view field, const std::string& s) {
        if (s.size() > max_text_bytes) return fail(field, "too long");
        return true;
    }
};

// Writes the fields (after the rules passed).
class Writer {
  public:
    static constexpr bool checking = true;
    Writer(std::vector<std::uint8_t>& out, Rules& rules) : out_(out), rules_(rules) {}

    void u16(std::string_view, std::uint16_t& x, const char*) { put_le(out_, x); }
    void u16(std::string_view f, std::uint16_t& x, int min, int max, const char*) {
        rules_.number(f, x, min, max);
        put_le(out_, x);
    }
    void u32(std::string_view, std::uint32_t& x, const char*) { put_le(out_, x); }
    void u32(std::string_view f, std::uint32_t& x, double min, double max, const char*) {
        rules_.number(f, x, min, max);
        put_le(out_, x);
    }
    void i64(std::string_view, std::int64_t& x, const char*) { put_le(out_, x); }
    void f32(std::string_view f, float& x, double min, double max, const char*) {
        rules_.number(f, x, min, max);
        put_le(out_, std::bit_cast<std::uint32_t>(x));
    }
    void boolean(std::string_view, bool& x, const char*) { out_.push_back(x ? 1 : 0); }
    template <class E, std::size_t N>
    void enumeration(std::string_view f, E& x, const std::array<std::string_view, N>& names,
                     const char*) {
        const auto raw = static_cast<std::uint8_t>(x);
        if (raw >= names.size()) rules_.fail(f, "not one of its values");
        out_.push_back(raw);
    }
    void string(std::string_view f, std::string& s, const char*) {
        rules_.text(f, s);
        put_le(out_, static_cast<std::uint16_t>(std::min(s.size(), max_text_bytes)));
        out_.insert(out_.end(), s.begin(),
                    s.begin() + static_cast<std::ptrdiff_t>(std::min(s.size(), max_text_bytes)));
    }
    void strings(std::string_view f, std::vector<std::string>& list, const char* d) {
        if (list.size() > max_list_items) rules_.fail(f, "too many items");
        const auto n = std::min(list.size(), max_list_items);
        out_.push_back(static_cast<std::uint8_t>(n));
        for (std::size_t i = 0; i < n; ++i) string(f, list[i], d);
    }
    void bytes(std::string_view f, std::span<const std::uint8_t>& b, std::size_t max, const char*) {
        if (b.size() > max) {
            rules_.fail(f, "too long");
            return;
        }
        put_le(out_, static_cast<std::uint32_t>(b.size()));
        out_.insert(out_.end(), b.begin(), b.end());
    }
    void invalid(std::string_view what) { rules_.fail("", what); }

  private:
    std::vector<std::uint8_t>& out_;
    Rules& rules_;
};

// Reads the fields; the first problem stops the reading (later reads do nothing).
class Reader {
  public:
    static constexpr bool checking = true;
    Reader(std::span<const std::uint8_t> in, Rules& rules) : in_(in), rules_(rules) {}

    bool ok() const { return rules_.error.empty(); }
    std::size_t left() const { return in_.size() - at_; }

    void u16(std::string_view f, std::uint16_t& x, const char*) { x = take<std::uint16_t>(f); }
    void u16(std::string_view f, std::uint16_t& x, int min, int max, const char*) {
        x = take<std::uint16_t>(f);
        if (ok()) rules_.number(f, x, min, max);
    }
    void u32(std::string_view f, std::uint32_t& x, const char*) { x = take<std::uint32_t>(f); }
    void u32(std::string_view f, std::uint32_t& x, double min, double max, const char*) {
        x = take<std::uint32_t>(f);
        if (ok()) rules_.number(f, x, min, max);
    }
    void i64(std::string_view f, std::int64_t& x, const char*) { x = take<std::int64_t>(f); }
    void f32(std::string_view f, float& x, double min, double max, const char*) {
        x = std::bit_cast<float>(take<std::uint32_t>(f));
        if (ok()) rules_.number(f, x, min, max);
    }
    void boolean(std::string_view f, bool& x, const char*) {
        const auto raw = take<std::uint8_t>(f);
        if (ok() && raw > 1) rules_.fail(f, "not 0 or 1");
        x = raw == 1;
    }
    template <class E, std::size_t N>
    void enumeration(std::string_view f, E& x, const std::array<std::string_view, N>& names,
                     const char*) {
        const auto raw = take<std::uint8_t>(f);
        if (ok() && raw >= names.size()) rules_.fail(f, "not one of its values");
        if (ok()) x = static_cast<E>(raw);
    }
    void string(std::string_view f, std::string& s, const char*) {
        const auto n = take<std::uint16_t>(f);
        if (!ok()) return;
        if (n > max_text_bytes) {
            rules_.fail(f, "too long");
            return;
        }
        if (n > left()) {
            rules_.fail(f, "cut short");
            return;
        }
        s.assign(reinterpret_cast<const char*>(in_.data() + at_), n);
        at_ += n;
    }
    void strings(std::string_view f, std::vector<std::string>& list, const char* d) {
        const auto n = take<std::uint8_t>(f);
        if (ok() && n > max_list_items) rules_.fail(f, "too many items");
        list.clear();
        for (std::size_t i = 0; ok() && i < n; ++i) string(f, list.emplace_back(), d);
    }
    void bytes(std::string_view f, std::span<const std::uint8_t>& b, std::size_t max, const char*) {
        const auto n = take<std::uint32_t>(f);
        if (!ok()) return;
        if (n > max) {
            rules_.fail(f, "too long");
            return;
        }
        if (n > left()) {
            rules_.fail(f, "cut short");
            return;
        }
        b = in_.subspan(at_, n);
        at_ += n;
    }
    void invalid(std::string_view what) {
        if (ok()) rules_.fail("", what);
    }

  private:
    template <class T>
    T take(std::string_view f) {
        if (!ok()) return T{};
        if (left() < sizeof(T)) {
            rules_.fail(f, "cut short");
            return T{};
        }
        const T value = get_le<T>(in_.data() + at_);
        at_ += sizeof(T);
        return value;
    }

    std::span<const std::uint8_t> in_;
    std::size_t at_ = 0;
    Rules& rules_;
};

template <class M>
Decoded decode_as(std::span<const std::uint8_t> body) {
    M m{};
    Rules rules{.error = {}, .message = to_string(M::type)};
    Reader r(body, rules);
    m.fields(r);
    if (r.ok() && r.left() != 0) rules.fail("", "bytes after the message");
    if (!rules.error.empty()) return {std::nullopt, rules.error};
    return {Message{std::move(m)}, {}};
}

}  // namespace

std::optional<MessageType> peek_type(std::span<const std::uint8_t> datagram) {
    if (datagram.size() < header_bytes) return std::nullopt;
    const auto type = datagram[1];
    if (type < static_cast<std::uint8_t>(MessageType::hello) ||
        type > static_cast<std::uint8_t>(MessageType::error))
        return std::nullopt;
    return static_cast<MessageType>(type);
}

Decoded decode(std::span<const std::uint8_t> datagram) {
    if (datagram.size() < header_bytes) return {std::nullopt, "shorter than the header"};
    if (datagram.size() > max_datagram_bytes)
        return {std::nullopt, "larger than a datagram may be"};
    if (datagram[0] != protocol_version)
        return {std::nullopt, "protocol version " + std::to_string(datagram[0]) + ", expected " +
                                  std::to_string(protocol_version)};
    const auto type = peek_type(datagram);
    if (!type) return {std::nullopt, "unknown message type " + std::to_string(datagram[1])};
    const auto body = datagram.subspan(header_bytes);
    switch (*type) {
        case MessageType::hello:
            return decode_as<Hello>(body);
        case MessageType::start:
            return decode_as<Start>(body);
        case MessageType::au:
            return decode_as<AccessUnit>(body);
        case MessageType::stop:
            return decode_as<Stop>(body);
        case MessageType::box:
            return decode_as<Box>(body);
        case MessageType::ended:
            return decode_as<Ended>(body);
        case MessageType::error:
            return decode_as<Error>(body);
    }
    return {std::nullopt, "unknown message type"};
}

bool encode(const Message& message, std::vector<std::uint8_t>& out, std::string* error) {
    out.clear();
    Rules rules;
    std::visit(
        [&](const auto& m) {
            using M = std::decay_t<decltype(m)>;
            rules.message = to_string(M::type);
            out.push_back(protocol_version);
            out.push_back(static_cast<std::uint8_t>(M::type));
            M copy = m;  // fields() takes references; the message itself stays const
            Writer w(out, rules);
            copy.fields(w);
        },
        message);
    if (rules.error.empty()) return true;
    out.clear();
    if (error) *error = rules.error;
    return false;
}

}  // namespace gimbal::track::wire
