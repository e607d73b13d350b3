#include "protocols/viewpro/codec/json.hpp"

namespace gimbal::viewpro {

namespace {

using nlohmann::json;

void put_if(json& j, const char* key, const std::optional<double>& v) {
    if (v) j[key] = *v;
}

// An object of the present keys only, or nothing at all when none is present.
void put_group(json& parent, const char* key, json group) {
    if (!group.empty()) parent[key] = std::move(group);
}

json vel_json(const std::array<double, 3>& v) {
    return json::array({v[0], v[1], v[2]});
}

}  // namespace

json to_json(const Output& o) {
    json j = json::object();
    j["format"] = to_string(o.format);
    if (o.time) j["time"] = to_iso8601(*o.time);
    if (o.zoom) j["zoom"] = *o.zoom;

    json gimbal = json::object();
    put_if(gimbal, "roll", o.gimbal_roll_deg);
    put_if(gimbal, "pitch", o.gimbal_pitch_deg);
    put_if(gimbal, "yaw", o.gimbal_yaw_deg);
    put_group(j, "gimbal", std::move(gimbal));

    put_if(j, "lrf_m", o.lrf_m);

    json uav = json::object();
    put_if(uav, "roll", o.uav_roll_deg);
    put_if(uav, "pitch", o.uav_pitch_deg);
    put_if(uav, "yaw", o.uav_yaw_deg);
    put_if(uav, "lat", o.uav_lat_deg);
    put_if(uav, "lon", o.uav_lon_deg);
    put_if(uav, "alt_msl", o.uav_alt_msl_m);
    put_group(j, "uav", std::move(uav));

    json target = json::object();
    put_if(target, "lat", o.target_lat_deg);
    put_if(target, "lon", o.target_lon_deg);
    put_if(target, "alt_msl", o.target_alt_msl_m);
    put_group(j, "target", std::move(target));
    return j;
}

json to_json(const Mode& m) {
    return {{"osd", to_string(m.osd)},
            {"network", m.network},
            {"serial", m.serial},
            {"format", to_string(m.format)}};
}

json to_json(const VehicleInput& v) {
    json j = {{"time", to_iso8601(v.time)}, {"roll", v.roll_deg}, {"pitch", v.pitch_deg},
              {"yaw", v.yaw_deg},           {"lat", v.lat_deg},   {"lon", v.lon_deg},
              {"alt_msl", v.alt_msl_m}};
    if (v.vel_ned_mps) j["vel_ned"] = vel_json(*v.vel_ned_mps);
    return j;
}

json to_json(const In3& v) {
    return {{"time", to_iso8601(v.time)}, {"lrf_m", v.lrf_m},
            {"pitch", v.pitch_deg},       {"yaw", v.yaw_deg},
            {"lat", v.lat_deg},           {"lon", v.lon_deg},
            {"alt_msl", v.alt_msl_m},     {"vel_ned", vel_json(v.vel_ned_mps)}};
}

json to_json(const InputFrame& f) {
    switch (f.kind) {
        case InputFrame::Kind::mode:
            if (const auto m = decode_mode(f)) return to_json(*m);
            break;
        case InputFrame::Kind::yaw_shift:
        case InputFrame::Kind::pitch_shift:
            if (const auto s = decode_shift(f))
                return {{"hundredths_deg", *s}, {"deg", *s / 100.0}};
            break;
        case InputFrame::Kind::in1:
        case InputFrame::Kind::in2:
            if (const auto v = decode_vehicle(f)) return to_json(*v);
            break;
        case InputFrame::Kind::in3:
            if (const auto v = decode_in3(f)) return to_json(*v);
            break;
    }
    return nullptr;
}

}  // namespace gimbal::viewpro
