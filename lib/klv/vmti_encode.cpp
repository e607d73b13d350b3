// encode_vmti(): a typed VMTI set to the items of its local set (vmti.hpp).
#include <algorithm>
#include <cmath>
#include <string>

#include "klv/vmti.hpp"
#include "klv/vmti_wire.hpp"

namespace gimbal::klv {

namespace w = vmti_wire;

std::uint64_t vmti_pixel_number(std::uint32_t row, std::uint32_t column, std::uint32_t width) {
    return std::uint64_t{column} + (std::uint64_t{row} - 1) * width;
}

VmtiRowColumn vmti_row_column(std::uint64_t pixel_number, std::uint32_t width) {
    if (pixel_number == 0 || width == 0) return {};
    return {(pixel_number - 1) / width + 1, (pixel_number - 1) % width + 1};
}

namespace {

// Big-endian in the fewest bytes, at least one.
Bytes unsigned_bytes(std::uint64_t value, std::size_t at_least = 1) {
    std::size_t n = 1;
    while (n < 8 && (value >> (8 * n)) != 0) ++n;
    n = std::max(n, at_least);
    Bytes out(n);
    for (std::size_t i = 0; i < n; ++i)
        out[n - 1 - i] = static_cast<std::uint8_t>(value >> (8 * i));
    return out;
}

void append_item(Bytes& out, std::uint32_t tag, const Bytes& value) {
    append_ber_oid(out, tag);
    append_ber_length(out, value.size());
    out.insert(out.end(), value.begin(), value.end());
}

void append_fixed(Bytes& out, std::uint64_t value, std::size_t bytes) {
    for (std::size_t i = bytes; i-- > 0;)
        out.push_back(static_cast<std::uint8_t>(value >> (8 * i)));
}

Error refuse(std::string why) {
    return {code::bad_request, "VMTI: " + std::move(why)};
}

std::optional<Error> check_pixel(const std::optional<std::uint64_t>& pixel, const char* what) {
    if (pixel && (*pixel == 0 || *pixel >> (8 * w::pixel_number_bytes) != 0))
        return refuse(std::string(what) + " pixel number " + std::to_string(*pixel) +
                      " is not in 1..2^48-1");
    return std::nullopt;
}

Result<Bytes> vtarget_pack(const VmtiTarget& t) {
    for (const auto& [pixel, what] :
         {std::pair{&t.centroid, "centroid"}, std::pair{&t.top_left, "top left"},
          std::pair{&t.bottom_right, "bottom right"}})
        if (auto e = check_pixel(*pixel, what)) return *e;
    if (t.confidence_pct && *t.confidence_pct > w::max_confidence_pct)
        return refuse("confidence " + std::to_string(*t.confidence_pct) + " is over 100 %");
    if (t.location && !(std::isfinite(t.location->lat_deg) && std::isfinite(t.location->lon_deg) &&
                        std::isfinite(t.location->hae_m)))
        return refuse("target " + std::to_string(t.id) + " has a location that is not a number");
    Bytes out;
    append_ber_oid(out, t.id);
    if (t.centroid) append_item(out, w::centroid, unsigned_bytes(*t.centroid));
    if (t.top_left) append_item(out, w::top_left, unsigned_bytes(*t.top_left));
    if (t.bottom_right) append_item(out, w::bottom_right, unsigned_bytes(*t.bottom_right));
    if (t.confidence_pct) append_item(out, w::confidence, unsigned_bytes(*t.confidence_pct));
    if (t.location) {
        Bytes v;
        append_fixed(v, w::location_lat.encode(t.location->lat_deg), 4);
        append_fixed(v, w::location_lon.encode(t.location->lon_deg), 4);
        append_fixed(v, w::location_hae.encode(t.location->hae_m), 2);
        append_item(out, w::location, v);
    }
    if (t.centroid_row) append_item(out, w::centroid_row, unsigned_bytes(*t.centroid_row));
    if (t.centroid_column) append_item(out, w::centroid_column, unsigned_bytes(*t.centroid_column));
    for (const VmtiRawItem& item : t.other) append_item(out, item.tag, item.value);
    return out;
}

}  // namespace

Result<Bytes> encode_vmti(const VmtiSet& set) {
    for (const auto& [size, what] :
         {std::pair{&set.frame_width, "frame width"}, std::pair{&set.frame_height, "frame height"}})
        if (*size && (**size == 0 || **size >> (8 * w::frame_size_bytes) != 0))
            return refuse(std::string(what) + " " + std::to_string(**size) +
                          " is not in 1..16777215");
    for (const auto& [count, what] : {std::pair{&set.total_targets, "total targets"},
                                      std::pair{&set.reported_targets, "reported targets"}})
        if (*count && **count >> (8 * w::target_count_bytes) != 0)
            return refuse(std::string(what) + " " + std::to_string(**count) + " is over 16777215");
    if (set.targets.size() > max_vmti_targets)
        return refuse(std::to_string(set.targets.size()) + " targets, over the limit of " +
                      std::to_string(max_vmti_targets));
    Bytes out;
    if (set.time_us) append_item(out, w::time_stamp, unsigned_bytes(*set.time_us, 8));
    if (set.version) append_item(out, w::version, unsigned_bytes(*set.version));
    if (set.total_targets) append_item(out, w::total_targets, unsigned_bytes(*set.total_targets));
    if (set.reported_targets)
        append_item(out, w::reported_targets, unsigned_bytes(*set.reported_targets));
    if (set.frame_number) append_item(out, w::frame_number, unsigned_bytes(*set.frame_number));
    if (set.frame_width) append_item(out, w::frame_width, unsigned_bytes(*set.frame_width));
    if (set.frame_height) append_item(out, w::frame_height, unsigned_bytes(*set.frame_height));
    for (const VmtiRawItem& item : set.other) append_item(out, item.tag, item.value);
    if (!set.targets.empty()) {
        Bytes series;
        for (const VmtiTarget& target : set.targets) {
            Result<Bytes> pack = vtarget_pack(target);
            if (!pack.ok()) return pack.error();
            append_ber_length(series, pack->size());
            series.insert(series.end(), pack->begin(), pack->end());
        }
        append_item(out, w::vtarget_series, series);
    }
    return out;
}

}  // namespace gimbal::klv
