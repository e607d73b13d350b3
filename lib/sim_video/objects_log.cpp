#include "sim_video/objects_log.hpp"

#include <nlohmann/json.hpp>

namespace gimbal::sim_video {

namespace {

const char* hidden_name(ObjectTruth::Hidden h) {
    switch (h) {
        case ObjectTruth::Hidden::deck:
            return "deck";
        case ObjectTruth::Hidden::terrain:
            return "terrain";
        case ObjectTruth::Hidden::no:
            break;
    }
    return nullptr;
}

}  // namespace

std::string objects_log_lines(const FrameStamp& stamp, std::span<const ObjectTruth> objects) {
    std::string out;
    for (const ObjectTruth& t : objects) {
        const sim::ObjectState& o = t.state;
        nlohmann::ordered_json j;
        j["frame"] = stamp.frame;
        j["unix_us"] = stamp.unix_us;
        j["pts_90k"] = stamp.pts_90k;
        j["t"] = stamp.model_time_s;
        j["name"] = o.spec().name;
        j["kind"] = std::string(sim::to_string(o.spec().kind));
        j["lat"] = o.position.lat_deg;
        j["lon"] = o.position.lon_deg;
        j["alt"] = o.position.alt_m;
        j["heading"] = o.heading_deg;
        j["speed"] = o.speed_mps;
        j["north"] = o.north_mps;
        j["east"] = o.east_mps;
        j["length_m"] = o.spec().length_m;
        j["slant_range_m"] = t.slant_range_m;
        j["x"] = t.at ? nlohmann::ordered_json(t.at->x) : nullptr;
        j["y"] = t.at ? nlohmann::ordered_json(t.at->y) : nullptr;
        if (t.box)
            j["box"] = {{"x0", t.box->x0}, {"y0", t.box->y0}, {"x1", t.box->x1}, {"y1", t.box->y1}};
        else
            j["box"] = nullptr;
        j["in_picture"] = t.in_picture;
        j["visible"] = t.visible_fraction;
        const char* hidden = hidden_name(t.hidden);
        j["hidden"] = hidden ? nlohmann::ordered_json(hidden) : nullptr;
        out += j.dump();
        out += '\n';
    }
    return out;
}

}  // namespace gimbal::sim_video
