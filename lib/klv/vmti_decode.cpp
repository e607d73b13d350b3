// decode_vmti(): untrusted bytes of a VMTI local set to a typed set (vmti.hpp). Every length
// is checked against what is left before anything is read, and the number of items and
// targets is bounded, so work is linear in the input and a bad set is refused whole.
#include <set>
#include <string>
#include <type_traits>

#include "klv/vmti.hpp"
#include "klv/vmti_wire.hpp"

namespace gimbal::klv {

namespace w = vmti_wire;

namespace {

using Span = std::span<const std::uint8_t>;

Error refuse(std::string why) {
    return {code::bad_request, "VMTI: " + std::move(why)};
}

struct ItemView {
    std::uint32_t tag = 0;
    Span value;
};

// The items of a local set filling `bytes` exactly; `where` names the set in errors.
Result<std::vector<ItemView>> read_items(Span bytes, const std::string& where,
                                         std::size_t& item_budget) {
    std::vector<ItemView> items;
    std::size_t at = 0;
    while (at < bytes.size()) {
        if (item_budget == 0)
            return refuse("more than " + std::to_string(max_vmti_items) + " items");
        --item_budget;
        const BerRead tag = read_ber_oid(bytes.subspan(at));
        if (tag.status == BerStatus::truncated) return refuse(where + ": truncated tag");
        if (tag.status != BerStatus::ok || tag.value > UINT32_MAX)
            return refuse(where + ": invalid tag at byte " + std::to_string(at));
        at += tag.size;
        const std::string item = where + " tag " + std::to_string(tag.value);
        const BerRead length = read_ber_length(bytes.subspan(at));
        if (length.status == BerStatus::truncated) return refuse(item + ": truncated length");
        if (length.status != BerStatus::ok) return refuse(item + ": invalid BER length");
        at += length.size;
        if (length.value > bytes.size() - at)
            return refuse(item + ": truncated, needs " + std::to_string(length.value) + " bytes, " +
                          std::to_string(bytes.size() - at) + " left");
        items.push_back({static_cast<std::uint32_t>(tag.value),
                         bytes.subspan(at, static_cast<std::size_t>(length.value))});
        at += static_cast<std::size_t>(length.value);
    }
    return items;
}

// An unsigned integer of 1..max_bytes bytes.
Result<std::uint64_t> read_unsigned(const ItemView& item, std::size_t max_bytes,
                                    const std::string& where) {
    if (item.value.empty() || item.value.size() > max_bytes)
        return refuse(where + " tag " + std::to_string(item.tag) + ": " +
                      std::to_string(item.value.size()) + " bytes, needs 1.." +
                      std::to_string(max_bytes));
    std::uint64_t x = 0;
    for (const std::uint8_t b : item.value) x = (x << 8) | b;
    return x;
}

std::uint64_t big_endian(Span v) {
    std::uint64_t x = 0;
    for (const std::uint8_t b : v) x = (x << 8) | b;
    return x;
}

Result<VmtiLocation> read_location(const ItemView& item, const std::string& where) {
    const std::size_t n = item.value.size();
    if (n != w::location_bytes && n != w::location_with_sigmas_bytes &&
        n != w::location_with_rhos_bytes)
        return refuse(where + " tag 17: " + std::to_string(n) + " bytes, needs 10, 16 or 22");
    const auto lat = w::location_lat.decode(big_endian(item.value.subspan(0, 4)));
    const auto lon = w::location_lon.decode(big_endian(item.value.subspan(4, 4)));
    const auto hae = w::location_hae.decode(big_endian(item.value.subspan(8, 2)));
    if (!lat || !lon || !hae)
        return refuse(where + " tag 17: an IMAPB special value (not a location)");
    // Integers past the map's top end (b) are not values of it (ST 1201).
    if (*lat > w::location_lat.b || *lon > w::location_lon.b || *hae > w::location_hae.b)
        return refuse(where + " tag 17: a location out of range");
    return VmtiLocation{*lat, *lon, *hae};
}

// Each typed tag once per set or pack.
Status once(std::set<std::uint32_t>& seen, std::uint32_t tag, const std::string& where) {
    if (!seen.insert(tag).second)
        return refuse(where + " tag " + std::to_string(tag) + " appears twice");
    return {};
}

Result<VmtiTarget> read_pack(Span pack, std::size_t& item_budget) {
    const BerRead id = read_ber_oid(pack);
    if (id.status == BerStatus::truncated) return refuse("VTarget pack: truncated target id");
    if (id.status != BerStatus::ok) return refuse("VTarget pack: invalid target id");
    VmtiTarget t;
    t.id = id.value;
    const std::string where = "target " + std::to_string(t.id);
    auto items = read_items(pack.subspan(id.size), where, item_budget);
    if (!items.ok()) return items.error();
    std::set<std::uint32_t> seen;
    for (const ItemView& item : *items) {
        const auto pixel = [&](std::optional<std::uint64_t>& into) -> Status {
            auto v = read_unsigned(item, w::pixel_number_bytes, where);
            if (!v.ok()) return v.error();
            if (*v == 0) return refuse(where + " tag " + std::to_string(item.tag) + ": pixel 0");
            into = *v;
            return {};
        };
        const auto index = [&](std::optional<std::uint32_t>& into) -> Status {
            auto v = read_unsigned(item, w::pixel_index_bytes, where);
            if (!v.ok()) return v.error();
            if (*v == 0) return refuse(where + " tag " + std::to_string(item.tag) + ": index 0");
            into = static_cast<std::uint32_t>(*v);
            return {};
        };
        Status s;
        switch (item.tag) {
            case w::centroid:
                s = pixel(t.centroid);
                break;
            case w::top_left:
                s = pixel(t.top_left);
                break;
            case w::bottom_right:
                s = pixel(t.bottom_right);
                break;
            case w::centroid_row:
                s = index(t.centroid_row);
                break;
            case w::centroid_column:
                s = index(t.centroid_column);
                break;
            case w::confidence: {
                auto v = read_unsigned(item, w::confidence_bytes, where);
                if (!v.ok()) return v.error();
                if (*v > w::max_confidence_pct)
                    return refuse(where + " confidence " + std::to_string(*v) + " is over 100 %");
                t.confidence_pct = static_cast<std::uint8_t>(*v);
                break;
            }
            case w::location: {
                auto v = read_location(item, where);
                if (!v.ok()) return v.error();
                t.location = *v;
                break;
            }
            default:
                t.other.push_back({item.tag, Bytes(item.value.begin(), item.value.end())});
                continue;
        }
        if (!s.ok()) return s.error();
        if (Status dup = once(seen, item.tag, where); !dup.ok()) return dup.error();
    }
    return t;
}

Result<std::vector<VmtiTarget>> read_series(Span series, std::size_t& item_budget) {
    std::vector<VmtiTarget> targets;
    std::size_t at = 0;
    while (at < series.size()) {
        if (targets.size() == max_vmti_targets)
            return refuse("more than " + std::to_string(max_vmti_targets) + " targets");
        const std::string which = "VTarget pack " + std::to_string(targets.size() + 1);
        const BerRead length = read_ber_length(series.subspan(at));
        if (length.status == BerStatus::truncated) return refuse(which + ": truncated length");
        if (length.status != BerStatus::ok) return refuse(which + ": invalid BER length");
        at += length.size;
        if (length.value > series.size() - at)
            return refuse(which + ": truncated, needs " + std::to_string(length.value) +
                          " bytes, " + std::to_string(series.size() - at) + " left");
        auto t = read_pack(series.subspan(at, static_cast<std::size_t>(length.value)), item_budget);
        if (!t.ok()) return t.error();
        targets.push_back(std::move(t).value());
        at += static_cast<std::size_t>(length.value);
    }
    return targets;
}

}  // namespace

Result<VmtiSet> decode_vmti(Span bytes) {
    std::size_t item_budget = max_vmti_items;
    auto items = read_items(bytes, "set", item_budget);
    if (!items.ok()) return items.error();
    VmtiSet set;
    set.version.reset();  // only what the set says
    std::set<std::uint32_t> seen;
    for (const ItemView& item : *items) {
        const auto number = [&](auto& into, std::size_t max_bytes, bool nonzero) -> Status {
            auto v = read_unsigned(item, max_bytes, "set");
            if (!v.ok()) return v.error();
            if (nonzero && *v == 0) return refuse("tag " + std::to_string(item.tag) + " is 0");
            into = static_cast<typename std::decay_t<decltype(into)>::value_type>(*v);
            return {};
        };
        Status s;
        switch (item.tag) {
            case w::time_stamp:
                if (item.value.size() != w::time_stamp_bytes)
                    return refuse("tag 2: " + std::to_string(item.value.size()) +
                                  " bytes, needs 8");
                set.time_us = big_endian(item.value);
                break;
            case w::version:
                s = number(set.version, w::version_bytes, false);
                break;
            case w::total_targets:
                s = number(set.total_targets, w::target_count_bytes, false);
                break;
            case w::reported_targets:
                s = number(set.reported_targets, w::target_count_bytes, false);
                break;
            case w::frame_number:
                s = number(set.frame_number, w::frame_number_bytes, false);
                break;
            case w::frame_width:
                s = number(set.frame_width, w::frame_size_bytes, true);
                break;
            case w::frame_height:
                s = number(set.frame_height, w::frame_size_bytes, true);
                break;
            case w::vtarget_series: {
                auto targets = read_series(item.value, item_budget);
                if (!targets.ok()) return targets.error();
                set.targets = std::move(targets).value();
                break;
            }
            default:
                set.other.push_back({item.tag, Bytes(item.value.begin(), item.value.end())});
                continue;
        }
        if (!s.ok()) return s.error();
        if (Status dup = once(seen, item.tag, "set"); !dup.ok()) return dup.error();
    }
    return set;
}

}  // namespace gimbal::klv
