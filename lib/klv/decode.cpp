// decode() and find_sets(): bytes of UAS Datalink Local Sets to items and JSON, every value by
// its row's kind (st0601.hpp).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "framing/hex.hpp"
#include "klv/checksum.hpp"
#include "klv/local_set.hpp"
#include "klv/mapping.hpp"
#include "klv/vmti.hpp"

namespace gimbal::klv {

namespace {

using Span = std::span<const std::uint8_t>;
using nlohmann::json;

std::uint64_t read_unsigned(Span v) {
    std::uint64_t x = 0;
    for (const std::uint8_t b : v) x = (x << 8) | b;
    return x;
}

std::int64_t read_signed(Span v) {
    const std::uint64_t x = read_unsigned(v);
    const std::size_t bits = 8 * v.size();
    if (bits >= 64) return static_cast<std::int64_t>(x);
    const std::uint64_t sign = std::uint64_t{1} << (bits - 1);
    return static_cast<std::int64_t>((x ^ sign) - sign);
}

std::string hex(Span v) {
    return framing::to_hex(v, framing::HexCase::upper);
}

// UTF-8 text cut at the first zero byte; invalid sequences and control characters become
// '?' so the JSON can always be written.
std::string text(Span v) {
    std::string s;
    s.reserve(v.size());
    std::size_t i = 0;
    while (i < v.size() && v[i] != 0) {
        const std::uint8_t c = v[i];
        std::size_t n = c < 0x80         ? 1
                        : (c >> 5) == 6  ? 2
                        : (c >> 4) == 14 ? 3
                        : (c >> 3) == 30 ? 4
                                         : 0;
        bool ok = n != 0 && i + n <= v.size() && !(c >= 0x80 && c < 0xC2) && c <= 0xF4;
        for (std::size_t k = 1; ok && k < n; ++k) ok = (v[i + k] & 0xC0) == 0x80;
        if (ok && n == 3) {  // no overlong forms, no surrogates
            ok = !(c == 0xE0 && v[i + 1] < 0xA0) && !(c == 0xED && v[i + 1] >= 0xA0);
        } else if (ok && n == 4) {
            ok = !(c == 0xF0 && v[i + 1] < 0x90) && !(c == 0xF4 && v[i + 1] >= 0x90);
        }
        if (!ok || (n == 1 && (c < 0x20 || c == 0x7F))) {
            s.push_back('?');
            ++i;
            continue;
        }
        s.append(reinterpret_cast<const char*>(&v[i]), n);
        i += n;
    }
    return s;
}

// The fewest decimals that still map to the same wire integer (contract section 1).
template <class SameWire>
json shortest(double exact, SameWire same_wire) {
    double scale = 1.0;
    for (int decimals = 0; decimals <= 15; ++decimals, scale *= 10.0) {
        const double candidate = std::round(exact * scale) / scale;
        if (same_wire(candidate)) {
            if (decimals == 0 && std::abs(candidate) < 1e15)
                return static_cast<std::int64_t>(candidate);
            return candidate;
        }
    }
    return exact;
}

json number(const TagSpec& row, Span v, Digits digits, bool& valid) {
    if (row.kind == Kind::linear) {
        if (v.size() != row.length) return valid = false, json();
        const std::int64_t wire =
            row.is_signed ? read_signed(v) : static_cast<std::int64_t>(read_unsigned(v));
        const std::optional<double> x = linear_from_wire(row, wire);
        if (!x) return nullptr;
        const double exact = *x * row.to_json;
        if (digits == Digits::exact) return exact;
        return shortest(exact, [&](double c) {
            const double w = c / row.to_json;
            return w >= row.min && w <= row.max && linear_to_wire(row, w) == wire;
        });
    }
    // IMAPB
    if (v.size() > 8) return valid = false, json();
    const Imapb map = imapb_of(row, static_cast<int>(v.size()));
    const std::uint64_t wire = read_unsigned(v);
    const std::optional<double> x = map.decode(wire);
    if (!x) return nullptr;
    const double exact = *x * row.to_json;
    if (digits == Digits::exact) return exact;
    return shortest(exact, [&](double c) {
        const double w = c / row.to_json;
        return w >= row.min && w <= row.max && map.encode(w) == wire;
    });
}

json integer(const TagSpec& row, Span v, bool& valid) {
    const bool fits = row.max_length != 0 ? v.size() <= row.max_length : v.size() == row.length;
    if (!fits) return valid = false, json();
    if (row.kind == Kind::time_us) return iso8601_utc(read_unsigned(v));
    if (row.kind == Kind::uint) return read_unsigned(v);
    const std::int64_t x = read_signed(v);
    if (row.to_json < 1.0) return static_cast<double>(x) / std::round(1.0 / row.to_json);
    return x;
}

json named(const TagSpec& row, Span v, bool& valid) {
    if (v.size() != row.length) return valid = false, json();
    const std::uint64_t x = read_unsigned(v);
    if (row.kind == Kind::enumeration) {
        if (x < row.names.size()) return std::string(row.names[x]);
        return x;  // contract section 1: an unknown value as its number
    }
    json obj = json::object();
    if (row.kind == Kind::flags) {
        for (std::size_t bit = 0; bit < 8 * row.length; ++bit) {
            const bool set = (x >> bit) & 1u;
            if (bit < row.names.size())
                obj[std::string(row.names[bit])] = set;
            else if (set)
                obj["bit_" + std::to_string(bit)] = true;  // reserved bits, shown when set
        }
        return obj;
    }
    for (std::size_t i = 0; i < row.names.size(); ++i) {  // nibbles, most significant first
        const std::size_t shift = 4 * (row.names.size() - 1 - i);
        obj[std::string(row.names[i])] = (x >> shift) & 0xFu;
    }
    return obj;
}

json list(const TagSpec& row, Span v, bool& valid) {
    if (row.kind == Kind::bit_list) {
        json ids = json::array();
        for (std::size_t i = 0; i < 8 * v.size(); ++i)
            if ((v[v.size() - 1 - i / 8] >> (i % 8)) & 1u) ids.push_back(i);
        return ids;
    }
    std::vector<std::uint64_t> values;
    for (std::size_t at = 0; at < v.size();) {
        const BerRead r = read_ber_oid(v.subspan(at));
        if (r.status != BerStatus::ok) return valid = false, json();
        values.push_back(r.value);
        at += r.size;
    }
    if (row.kind == Kind::oid_list) return values;
    if (values.empty() || values.size() > 2 || (values.size() == 2 && values[1] == 0))
        return valid = false, json();
    return json{{"numerator", values[0]}, {"denominator", values.size() == 2 ? values[1] : 1}};
}

// Tag 74 (contract section 20): the VMTI set decoded under "vmti" (null when zero-length,
// ST 0601's "unknown"); one that does not decode keeps its hex under the row's name,
// "vmti_local_set", and says why under "vmti_error".
constexpr std::uint32_t vmti_tag = 74;

void add_vmti(json& out, Span value) {
    if (value.empty()) {
        out["vmti"] = nullptr;
        return;
    }
    const Result<VmtiSet> vmti = decode_vmti(value);
    if (vmti.ok()) {
        out["vmti"] = vmti_json(*vmti);
        return;
    }
    out["vmti_local_set"] = hex(value);
    out["vmti_error"] = vmti.error().message;
}

}  // namespace

json value_json(const TagSpec& row, Span value, Digits digits, bool& valid) {
    valid = true;
    if (row.kind == Kind::checksum) {
        if (value.size() != 2) return valid = false, json();
        return read_unsigned(value);
    }
    if (value.empty()) return nullptr;  // ST 0601: a zero-length item means "unknown"
    switch (row.kind) {
        case Kind::checksum:
            break;
        case Kind::string:
            return text(value);
        case Kind::linear:
        case Kind::imapb:
            return number(row, value, digits, valid);
        case Kind::time_us:
        case Kind::uint:
        case Kind::sint:
            return integer(row, value, valid);
        case Kind::enumeration:
        case Kind::flags:
        case Kind::nibbles:
            return named(row, value, valid);
        case Kind::oid_list:
        case Kind::frame_rate:
        case Kind::bit_list:
            return list(row, value, valid);
        case Kind::raw:
            break;
    }
    return hex(value);
}

std::string_view to_string(DecodeStatus status) {
    switch (status) {
        case DecodeStatus::ok:
            return "ok";
        case DecodeStatus::bad_checksum:
            return "bad_checksum";
        case DecodeStatus::malformed:
            return "malformed";
        case DecodeStatus::too_large:
            return "too_large";
    }
    return "malformed";
}

DecodeResult decode(Span bytes, Digits digits) {
    DecodeResult r;
    auto refuse = [&r](DecodeStatus status, std::string why) {
        r.status = status;
        r.reason = std::move(why);
        r.items.clear();
        return std::move(r);
    };
    auto malformed = [&refuse](std::string why) {
        return refuse(DecodeStatus::malformed, std::move(why));
    };
    const std::size_t key_size = uas_datalink_key.size();
    if (bytes.size() < key_size) return malformed("shorter than the 16-byte key");
    if (!std::equal(uas_datalink_key.begin(), uas_datalink_key.end(), bytes.begin()))
        return malformed("not the UAS Datalink LS key");
    const BerRead length = read_ber_length(bytes.subspan(key_size));
    if (length.status == BerStatus::truncated) return malformed("truncated BER length");
    if (length.status != BerStatus::ok) return malformed("invalid BER length");
    const std::size_t head = key_size + length.size;
    // The size limit comes before anything else: a set's length says how much would be read.
    if (length.value > max_set_bytes - head) {
        if (length.value <= bytes.size() - head)
            r.consumed = head + static_cast<std::size_t>(length.value);
        return refuse(DecodeStatus::too_large, "the set is " + std::to_string(length.value + head) +
                                                   " bytes, over the limit of " +
                                                   std::to_string(max_set_bytes));
    }
    if (length.value > bytes.size() - head)
        return malformed("truncated: the set needs " + std::to_string(length.value) +
                         " value bytes, " + std::to_string(bytes.size() - head) + " present");
    const std::size_t end = head + static_cast<std::size_t>(length.value);
    r.consumed = end;

    // The checksum before any item is read: it is the last item, tag 1 with 2 bytes (ST 0601
    // 6.6), summed from the key through its length byte.
    if (end - head < 4 || bytes[end - 4] != 0x01 || bytes[end - 3] != 0x02)
        return malformed("no checksum (tag 1, 2 bytes) as the last item");
    r.checksum_stored = static_cast<std::uint16_t>((bytes[end - 2] << 8) | bytes[end - 1]);
    r.checksum_computed = checksum16(bytes.first(end - 2));
    if (r.checksum_stored != r.checksum_computed) {
        char why[64];
        std::snprintf(why, sizeof why, "checksum 0x%04X, computed 0x%04X", r.checksum_stored,
                      r.checksum_computed);
        return refuse(DecodeStatus::bad_checksum, why);
    }

    std::size_t at = head;
    std::size_t checksum_at = 0;  // offset of the last item's tag when it is tag 1
    while (at < end) {
        if (r.items.size() == max_set_items)
            return refuse(DecodeStatus::too_large,
                          "more than " + std::to_string(max_set_items) + " items");
        const std::size_t item_at = at;
        const BerRead tag = read_ber_oid(bytes.subspan(at, end - at));
        if (tag.status != BerStatus::ok)
            return malformed("invalid tag at byte " + std::to_string(at));
        at += tag.size;
        const BerRead len = read_ber_length(bytes.subspan(at, end - at));
        if (len.status != BerStatus::ok)
            return malformed("invalid length of tag " + std::to_string(tag.value));
        at += len.size;
        if (len.value > end - at)
            return malformed("tag " + std::to_string(tag.value) + " runs past the set");
        const Span value = bytes.subspan(at, static_cast<std::size_t>(len.value));
        r.items.push_back(
            {static_cast<std::uint32_t>(std::min<std::uint64_t>(tag.value, UINT32_MAX)), at,
             Bytes(value.begin(), value.end())});
        checksum_at = (tag.value == 1 && value.size() == 2) ? item_at : 0;
        at += value.size();
    }
    if (checksum_at != end - 4) return malformed("no checksum (tag 1, 2 bytes) as the last item");

    for (const RawItem& item : r.items) {
        const TagSpec* row = find_tag(item.tag);
        const std::string number = std::to_string(item.tag);
        if (row == nullptr) {
            r.json["unknown"][number] = hex(item.value);
            continue;
        }
        if (item.tag == vmti_tag) {
            add_vmti(r.json, item.value);
            continue;
        }
        bool valid = true;
        json value = value_json(*row, item.value, digits, valid);
        if (!valid) {
            r.json["invalid"][number] = hex(item.value);
        } else if (row->multiple) {
            r.json[std::string(row->name)].push_back(std::move(value));
        } else {
            r.json[std::string(row->name)] = std::move(value);
        }
    }
    r.status = DecodeStatus::ok;
    return r;
}

FoundSets find_sets(Span bytes) {
    FoundSets found;
    found.keep_from = bytes.size();
    const std::size_t key_size = uas_datalink_key.size();
    std::size_t at = 0;
    while (at < bytes.size()) {
        const auto hit = std::search(bytes.begin() + static_cast<std::ptrdiff_t>(at), bytes.end(),
                                     uas_datalink_key.begin(), uas_datalink_key.end());
        if (hit == bytes.end()) {
            // A key cut off by the end of the input: keep its start.
            for (std::size_t tail = std::min(key_size - 1, bytes.size() - at); tail > 0; --tail) {
                const std::size_t from = bytes.size() - tail;
                if (std::equal(bytes.begin() + static_cast<std::ptrdiff_t>(from), bytes.end(),
                               uas_datalink_key.begin())) {
                    found.keep_from = from;
                    break;
                }
            }
            break;
        }
        const auto start = static_cast<std::size_t>(hit - bytes.begin());
        const BerRead length = read_ber_length(bytes.subspan(start + key_size));
        if (length.status == BerStatus::truncated) {
            found.keep_from = start;
            break;
        }
        if (length.status != BerStatus::ok) {
            at = start + 1;
            continue;
        }
        const std::size_t head = start + key_size + length.size;
        if (length.value > bytes.size() - head) {
            found.keep_from = start;
            break;
        }
        const std::size_t size = key_size + length.size + static_cast<std::size_t>(length.value);
        found.sets.push_back({start, size});
        at = start + size;
    }
    return found;
}

}  // namespace gimbal::klv
