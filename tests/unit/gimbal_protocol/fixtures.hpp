// Shared by the gimbal-protocol tests: two gimbals (an Orion and a Viewpro), STATE objects
// shaped like gimbald's (and a MAVLink gimbal device's), and command builders.
#pragma once

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include "gimbal_protocol/commands.hpp"
#include "gimbal_protocol/status.hpp"

namespace gptest {

using namespace gimbal::gimbal_protocol;
namespace mav = gimbal::mavlink;
using mav::MavResult;

inline const float NaN = std::numeric_limits<float>::quiet_NaN();
inline const float Inf = std::numeric_limits<float>::infinity();
inline const MavId gcs{255, 190};
inline const MavId other_gcs{254, 190};

inline std::vector<ExposedGimbal> two_gimbals() {
    return expose({{"main", "orion"}, {"nose", "viewpro"}});
}

inline nlohmann::json orion_state() {
    return {{"protocol", "orion"},
            {"link", {{"connected", true}}},
            {"stale", false},
            {"telemetry",
             {{"lat", 45.0},
              {"lon", -121.0},
              {"alt", 1500.0},
              {"alt_msl", 1521.0},
              {"geoid_undulation", -21.0},
              {"quat", {1.0, 0.0, 0.0, 0.0}},
              {"pan", 30.0},
              {"tilt", -20.0},
              {"hfov", 40.0},
              {"vfov", 30.0},
              {"target", {{"lat", 45.01}, {"lon", -121.0}, {"alt", 79.0}}}}},
            {"limits", {{"min_pos", {-180.0, -120.0}}, {"max_pos", {180.0, 30.0}}}},
            {"cameras",
             {{"cameras", nlohmann::json::array({{{"min_focal_length_mm", 4.3},
                                                  {"max_focal_length_mm", 129.0},
                                                  {"array_width", 1920},
                                                  {"array_height", 1080},
                                                  {"pixel_pitch_mm", 0.0029}}})}}}};
}

inline nlohmann::json viewpro_state() {
    return {{"protocol", "viewpro"},
            {"link", {{"connected", true}}},
            {"stale", false},
            {"output",
             {{"gimbal", {{"roll", 0.0}, {"pitch", -45.0}, {"yaw", 10.0}}},
              {"uav",
               {{"roll", 0.0},
                {"pitch", 0.0},
                {"yaw", 90.0},
                {"lat", 6.94},
                {"lon", 79.88},
                {"alt_msl", 300.0}}},
              {"target", {{"lat", 6.945}, {"lon", 79.88}}}}}};
}

// A MAVLink gimbal device's STATE as its session reports it: attitude from
// GIMBAL_DEVICE_ATTITUDE_STATUS (yaw in the vehicle frame), the vehicle's fix, its limits.
inline nlohmann::json device_state() {
    return {
        {"protocol", "mavlink"},
        {"link", {{"connected", true}}},
        {"stale", false},
        {"telemetry",
         {{"pan", 15.0},
          {"tilt", -30.0},
          {"hfov", 60.0},
          {"vfov", 34.0},
          {"lat", 45.7},
          {"lon", -121.5},
          {"alt", 1079.0},
          {"alt_msl", 1100.0},
          {"geoid_undulation", -21.0},
          {"roll", 0.0},
          {"pitch", 0.0},
          {"yaw", 90.0},
          {"target", {{"lat", 45.69}, {"lon", -121.49}, {"alt", 79.0}}}}},
        {"device",
         {{"vendor", "Gremsy"},
          {"model", "T3V3"},
          {"limits",
           {{"pitch_min", -120.0}, {"pitch_max", 45.0}, {"yaw_min", -170.0}, {"yaw_max", 170.0}}},
          {"attitude", {{"roll", 0.0}, {"pitch", -30.0}, {"yaw", 15.0}, {"frame", "vehicle"}}}}}};
}

inline StateLookup states(nlohmann::json orion = orion_state(),
                          nlohmann::json viewpro = viewpro_state()) {
    return [orion, viewpro](const std::string& name) { return name == "main" ? orion : viewpro; };
}

inline VehicleView vehicle(std::optional<double> heading = 90.0,
                           std::optional<double> home = 100.0) {
    return {heading, home};
}

// Commands go to component 0 (every gimbal manager) unless the test names one.
inline CommandView long_cmd(std::uint16_t command, std::array<float, 7> p,
                            std::uint8_t component = 0) {
    mav::CommandLong c;
    c.command = command;
    c.param = p;
    c.target_system = 1;
    c.target_component = component;
    return view(c);
}

inline CommandView int_cmd(std::uint16_t command, std::array<float, 4> p, std::int32_t x,
                           std::int32_t y, float z, std::uint8_t frame,
                           std::uint8_t component = 0) {
    mav::CommandInt c;
    c.command = command;
    c.param1 = p[0];
    c.param2 = p[1];
    c.param3 = p[2];
    c.param4 = p[3];
    c.x = x;
    c.y = y;
    c.z = z;
    c.frame = frame;
    c.target_system = 1;
    c.target_component = component;
    return view(c);
}

// No request ever asks for the laser.
inline bool no_laser(const Mapped& m) {
    for (const auto& r : m.requests)
        if (r.request.value("cmd", "") == "laser") return false;
    return true;
}

}  // namespace gptest
