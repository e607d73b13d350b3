// encode(): one LocalSet to the bytes of a UAS Datalink LS, every value by its row's kind.
#include <algorithm>
#include <cmath>
#include <limits>

#include "klv/checksum.hpp"
#include "klv/local_set.hpp"
#include "klv/mapping.hpp"

namespace gimbal::klv {

namespace {

std::optional<double> as_number(const Value& v) {
    if (const auto* d = std::get_if<double>(&v)) return *d;
    if (const auto* i = std::get_if<std::int64_t>(&v)) return static_cast<double>(*i);
    if (const auto* u = std::get_if<std::uint64_t>(&v)) return static_cast<double>(*u);
    return std::nullopt;
}

// Integers keep all 64 bits; doubles are rounded half away from zero and saturated.
std::optional<std::uint64_t> as_unsigned(const Value& v) {
    if (const auto* u = std::get_if<std::uint64_t>(&v)) return *u;
    if (const auto* i = std::get_if<std::int64_t>(&v))
        return *i < 0 ? 0 : static_cast<std::uint64_t>(*i);
    if (const auto* d = std::get_if<double>(&v)) {
        if (std::isnan(*d)) return std::nullopt;
        const double r = std::round(*d);
        if (r <= 0) return 0;
        if (r >= 18446744073709551615.0) return std::numeric_limits<std::uint64_t>::max();
        return static_cast<std::uint64_t>(r);
    }
    return std::nullopt;
}

std::optional<std::int64_t> as_signed(const Value& v) {
    if (const auto* i = std::get_if<std::int64_t>(&v)) return *i;
    if (const auto* u = std::get_if<std::uint64_t>(&v))
        return static_cast<std::int64_t>(std::min<std::uint64_t>(
            *u, static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())));
    if (const auto* d = std::get_if<double>(&v)) {
        if (std::isnan(*d)) return std::nullopt;
        const double r = std::round(*d);
        if (r <= -9223372036854775808.0) return std::numeric_limits<std::int64_t>::min();
        if (r >= 9223372036854775807.0) return std::numeric_limits<std::int64_t>::max();
        return static_cast<std::int64_t>(r);
    }
    return std::nullopt;
}

void put_big_endian(Bytes& out, std::uint64_t v, std::size_t n) {
    for (std::size_t i = n; i-- > 0;) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}

std::size_t unsigned_size(std::uint64_t v) {
    std::size_t n = 1;
    while (n < 8 && (v >> (8 * n)) != 0) ++n;
    return n;
}

std::size_t signed_size(std::int64_t v) {
    std::size_t n = 1;
    while (n < 8) {
        const std::int64_t lo = -(std::int64_t{1} << (8 * n - 1));
        const std::int64_t hi = (std::int64_t{1} << (8 * n - 1)) - 1;
        if (v >= lo && v <= hi) break;
        ++n;
    }
    return n;
}

// Width of a variable-length integer: the caller's `length`, or the fewest bytes.
bool variable_width(const TagSpec& row, const Item& item, std::size_t needed, std::size_t& n,
                    std::string& error) {
    const std::size_t limit = row.max_length;
    n = item.length != 0 ? item.length : needed;
    if (n < needed || n > limit) {
        error = "needs " + std::to_string(needed) + " bytes, allowed 1.." + std::to_string(limit);
        if (item.length != 0) error += " (length " + std::to_string(item.length) + " asked)";
        return false;
    }
    return true;
}

bool encode_list(const TagSpec& row, const Item& item, Bytes& out, std::string& error) {
    const auto* list = std::get_if<std::vector<std::uint64_t>>(&item.value);
    if (list == nullptr) {
        error = "takes a list of integers";
        return false;
    }
    if (row.kind == Kind::oid_list) {
        for (const std::uint64_t id : *list) append_ber_oid(out, id);
        return true;
    }
    if (row.kind == Kind::frame_rate) {
        if (list->empty() || list->size() > 2) {
            error = "takes {numerator} or {numerator, denominator}";
            return false;
        }
        append_ber_oid(out, (*list)[0]);
        if (list->size() == 2) append_ber_oid(out, (*list)[1]);
        return true;
    }
    // bit_list: bit i of the value (least significant bit of the last byte = 0).
    std::uint64_t highest = 0;
    for (const std::uint64_t id : *list) {
        if (id > 8 * 127 - 1) {
            error = "payload id " + std::to_string(id) + " is past 1015";
            return false;
        }
        highest = std::max(highest, id);
    }
    const std::size_t n = static_cast<std::size_t>(highest / 8 + 1);
    const std::size_t start = out.size();
    out.resize(start + n, 0);
    for (const std::uint64_t id : *list)
        out[start + n - 1 - static_cast<std::size_t>(id / 8)] |=
            static_cast<std::uint8_t>(1u << (id % 8));
    return true;
}

bool encode_named(const TagSpec& row, const Item& item, Bytes& out, std::string& error) {
    std::optional<std::uint64_t> wire;
    if (const auto* name = std::get_if<std::string>(&item.value)) {
        if (row.kind != Kind::enumeration) {
            error = "takes the wire integer";
            return false;
        }
        for (std::size_t i = 0; i < row.names.size(); ++i)
            if (row.names[i] == *name) wire = i;
        if (!wire) {
            error = "has no value named \"" + *name + "\"";
            return false;
        }
    } else if (const auto* i = std::get_if<std::int64_t>(&item.value); i != nullptr && *i < 0) {
        error = std::to_string(*i) + " is negative";
        return false;
    } else {
        wire = as_unsigned(item.value);
    }
    if (!wire) {
        error = "takes an integer";
        return false;
    }
    const std::uint64_t limit = row.kind == Kind::enumeration
                                    ? row.names.size() - 1
                                    : (std::uint64_t{1} << (8 * row.length)) - 1;
    if (*wire > limit) {
        error = std::to_string(*wire) + " is past " + std::to_string(limit);
        return false;
    }
    put_big_endian(out, *wire, row.length);
    return true;
}

bool encode_number(const TagSpec& row, const Item& item, Bytes& out, std::string& error) {
    const bool reserved = std::holds_alternative<Reserved>(item.value);
    const std::optional<double> x = as_number(item.value);
    if (!reserved && !x) {
        error = "takes a number";
        return false;
    }
    const bool nan = x && std::isnan(*x);
    if ((reserved || nan) && !(row.kind == Kind::linear && row.reserved)) {
        error = reserved ? "has no reserved value" : "NaN and no reserved value to send";
        return false;
    }
    if (row.kind == Kind::linear) {
        const double value = reserved ? std::numeric_limits<double>::quiet_NaN() : *x / row.to_json;
        const std::int64_t wire = linear_to_wire(row, value);
        put_big_endian(out, static_cast<std::uint64_t>(wire), row.length);
        return true;
    }
    // IMAPB
    const int length = item.length != 0 ? item.length : row.length;
    if (length < 1 || length > 8) {
        error = "IMAPB length must be 1..8";
        return false;
    }
    put_big_endian(out, imapb_of(row, length).encode(*x / row.to_json),
                   static_cast<std::size_t>(length));
    return true;
}

bool encode_integer(const TagSpec& row, const Item& item, Bytes& out, std::string& error) {
    if (row.kind == Kind::sint) {
        std::optional<std::int64_t> v;
        if (row.to_json < 1.0) {  // JSON seconds, wire microseconds (correction_offset)
            if (const auto x = as_number(item.value); x && !std::isnan(*x))
                v = as_signed(Value{*x * std::round(1.0 / row.to_json)});
        } else {
            v = as_signed(item.value);
        }
        if (!v) {
            error = "takes an integer";
            return false;
        }
        std::size_t n = row.length;
        if (row.max_length != 0) {
            if (!variable_width(row, item, signed_size(*v), n, error)) return false;
        } else {
            const std::int64_t lo = -(std::int64_t{1} << (8 * n - 1));
            const std::int64_t hi = (std::int64_t{1} << (8 * n - 1)) - 1;
            v = std::clamp(*v, lo, hi);
        }
        put_big_endian(out, static_cast<std::uint64_t>(*v), n);
        return true;
    }
    const std::optional<std::uint64_t> v = as_unsigned(item.value);
    if (!v) {
        error = row.kind == Kind::time_us ? "takes microseconds since 1970" : "takes an integer";
        return false;
    }
    std::size_t n = row.length;
    std::uint64_t wire = *v;
    if (row.max_length != 0) {
        if (!variable_width(row, item, unsigned_size(wire), n, error)) return false;
    } else if (n < 8) {
        wire = std::min(wire, (std::uint64_t{1} << (8 * n)) - 1);
    }
    put_big_endian(out, wire, n);
    return true;
}

}  // namespace

namespace {

// encode_value()'s work: false with `error` when the item cannot be encoded.
bool encode_item(const Item& item, Bytes& out, std::string& error) {
    const TagSpec* row = find_tag(item.tag);
    // Raw bytes go out as they are for any tag but the checksum: nested sets and packs,
    // unknown tags, an item relayed from a decoded set, or a zero-length item ("unknown").
    if (std::holds_alternative<Bytes>(item.value) &&
        (row == nullptr || row->kind != Kind::checksum)) {
        const Bytes& bytes = std::get<Bytes>(item.value);
        out.insert(out.end(), bytes.begin(), bytes.end());
        return true;
    }
    if (row == nullptr || row->kind == Kind::raw) {
        const auto* bytes = std::get_if<Bytes>(&item.value);
        if (bytes == nullptr) {
            error = row == nullptr ? "is not an ST 0601 tag: only raw bytes can be sent"
                                   : "takes raw bytes (a nested set or pack)";
            return false;
        }
        out.insert(out.end(), bytes->begin(), bytes->end());
        return true;
    }
    switch (row->kind) {
        case Kind::checksum:
            error = "is written by the encoder";
            return false;
        case Kind::string: {
            const auto* text = std::get_if<std::string>(&item.value);
            if (text == nullptr) {
                error = "takes a string";
                return false;
            }
            if (text->size() > row->max_length) {
                error = "is " + std::to_string(text->size()) + " bytes, at most 127";
                return false;
            }
            out.insert(out.end(), text->begin(), text->end());
            return true;
        }
        case Kind::linear:
        case Kind::imapb:
            return encode_number(*row, item, out, error);
        case Kind::time_us:
        case Kind::uint:
        case Kind::sint:
            return encode_integer(*row, item, out, error);
        case Kind::enumeration:
        case Kind::flags:
        case Kind::nibbles:
            return encode_named(*row, item, out, error);
        case Kind::oid_list:
        case Kind::frame_rate:
        case Kind::bit_list:
            return encode_list(*row, item, out, error);
        case Kind::raw:
            break;
    }
    error = "cannot be encoded";
    return false;
}

}  // namespace

Status encode_value(const Item& item, Bytes& out) {
    std::string why;
    if (!encode_item(item, out, why)) return Error{code::bad_request, std::move(why)};
    return {};
}

std::uint32_t add_corners(LocalSet& set, LatLon frame_center,
                          const std::array<LatLon, 4>& corners) {
    const bool offsets = std::all_of(corners.begin(), corners.end(), [&](const LatLon& c) {
        return corner_offset_fits(c.lat, frame_center.lat) &&
               corner_offset_fits(c.lon, frame_center.lon);
    });
    const std::uint32_t first = offsets ? 26 : 82;
    for (std::uint32_t i = 0; i < 4; ++i) {
        const LatLon& c = corners[i];
        set.add(first + 2 * i, offsets ? c.lat - frame_center.lat : c.lat);
        set.add(first + 2 * i + 1, offsets ? c.lon - frame_center.lon : c.lon);
    }
    return first;
}

Encoded encode(const LocalSet& set) {
    Bytes body;
    body.reserve(16 * set.items.size() + 8);
    Bytes value;
    for (const Item& item : set.items) {
        if (item.tag == 1) continue;
        value.clear();
        std::string why;
        if (!encode_item(item, value, why)) {
            const TagSpec* row = find_tag(item.tag);
            std::string message = "tag " + std::to_string(item.tag);
            if (row != nullptr) message += " (" + std::string(row->name) + ")";
            message += " " + why;
            return Error{code::bad_request, std::move(message)};
        }
        append_ber_oid(body, item.tag);
        append_ber_length(body, value.size());
        body.insert(body.end(), value.begin(), value.end());
    }
    body.push_back(0x01);  // checksum tag and length; its value follows the sum
    body.push_back(0x02);
    // Built from the key rather than inserted into an empty reserved vector: GCC 12 at -O2
    // warns falsely about that insert's memmove (-Wstringop-overflow).
    Bytes out(uas_datalink_key.begin(), uas_datalink_key.end());
    out.reserve(uas_datalink_key.size() + 9 + body.size() + 2);
    append_ber_length(out, body.size() + 2);
    out.insert(out.end(), body.begin(), body.end());
    const std::uint16_t sum = checksum16(out);
    out.push_back(static_cast<std::uint8_t>(sum >> 8));
    out.push_back(static_cast<std::uint8_t>(sum));
    return out;
}

}  // namespace gimbal::klv
