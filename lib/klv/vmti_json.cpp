// vmti_json(): a typed VMTI set as the JSON of STATE `video.klv.vmti` (docs/video.md "VMTI").
#include <cmath>
#include <string>

#include "framing/hex.hpp"
#include "klv/mapping.hpp"
#include "klv/vmti.hpp"
#include "klv/vmti_wire.hpp"

namespace gimbal::klv {

namespace w = vmti_wire;

namespace {

using nlohmann::json;

// The fewest decimals that map to the same IMAPB integer (contract section 1), as ST 0601's
// JSON does.
double shortest(double x, const Imapb& map) {
    const std::uint64_t wire = map.encode(x);
    double scale = 1.0;
    for (int decimals = 0; decimals <= 12; ++decimals, scale *= 10.0) {
        const double candidate = std::round(x * scale) / scale;
        if (map.encode(candidate) == wire) return candidate;
    }
    return x;
}

json pixel(std::uint64_t number, const std::optional<std::uint32_t>& width) {
    json p = {{"pixel", number}};
    if (width) {
        const VmtiRowColumn rc = vmti_row_column(number, *width);
        p["row"] = rc.row;
        p["column"] = rc.column;
    }
    return p;
}

json raw_items(const std::vector<VmtiRawItem>& items) {
    json out = json::array();
    for (const VmtiRawItem& item : items)
        out.push_back(
            {{"tag", item.tag}, {"value", framing::to_hex(item.value, framing::HexCase::upper)}});
    return out;
}

json target_json(const VmtiTarget& t, const std::optional<std::uint32_t>& width) {
    json j = {{"id", t.id}};
    if (t.centroid) j["centroid"] = pixel(*t.centroid, width);
    if (t.top_left) j["top_left"] = pixel(*t.top_left, width);
    if (t.bottom_right) j["bottom_right"] = pixel(*t.bottom_right, width);
    if (t.centroid_row) j["centroid_row"] = *t.centroid_row;
    if (t.centroid_column) j["centroid_column"] = *t.centroid_column;
    if (t.confidence_pct) j["confidence_level"] = *t.confidence_pct;
    if (t.location)
        j["location"] = {{"lat", shortest(t.location->lat_deg, w::location_lat)},
                         {"lon", shortest(t.location->lon_deg, w::location_lon)},
                         {"hae", shortest(t.location->hae_m, w::location_hae)}};
    if (!t.other.empty()) j["other_items"] = raw_items(t.other);
    return j;
}

}  // namespace

json vmti_json(const VmtiSet& set) {
    json j = json::object();
    if (set.time_us) j["precision_time_stamp"] = iso8601_utc(*set.time_us);
    if (set.version) j["version"] = *set.version;
    if (set.total_targets) j["total_targets"] = *set.total_targets;
    if (set.reported_targets) j["reported_targets"] = *set.reported_targets;
    if (set.frame_number) j["frame_number"] = *set.frame_number;
    if (set.frame_width) j["frame_width"] = *set.frame_width;
    if (set.frame_height) j["frame_height"] = *set.frame_height;
    j["targets"] = json::array();
    for (const VmtiTarget& t : set.targets) j["targets"].push_back(target_json(t, set.frame_width));
    if (!set.other.empty()) j["other_items"] = raw_items(set.other);
    return j;
}

}  // namespace gimbal::klv
