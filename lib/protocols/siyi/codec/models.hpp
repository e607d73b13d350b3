// The SIYI gimbal cameras gimbald knows: how each identifies itself (hardware id), where its
// axes can go, how far it zooms and what its main camera sees. One table, used by the
// simulated gimbal and by the protocol's STATE (pan/tilt limits, hfov/vfov per zoom). The
// sources of each number, and which are assumptions, are in docs/siyi.md "Models".
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

namespace gimbal::siyi {

enum class Model : std::uint8_t { a8_mini, zr10, zr30, zt30, zt6 };

inline constexpr std::array all_models = {Model::a8_mini, Model::zr10, Model::zr30, Model::zt30,
                                          Model::zt6};

struct ModelInfo {
    Model model;
    std::string_view key;        // "zt30": configuration and command-line value
    std::string_view name;       // "ZT30": for people
    std::string_view id_prefix;  // first two characters of its hardware id (0x02)
    // Axis limits in SIYI's frame (yaw positive left, from the aircraft's nose; pitch positive
    // up), degrees, from the 0x0E table of the SDK. A continuous yaw has no stops.
    bool yaw_continuous;
    double yaw_min, yaw_max;
    double pitch_min, pitch_max;
    double max_rate_dps;      // the rate of speed 100 in 0x07 (and of an absolute move)
    double zoom_max;          // largest zoom of 0x0F / 0x16
    double optical_zoom_max;  // 1 for a camera that zooms only digitally
    double hfov_deg;          // main camera's horizontal field of view at zoom 1
    double aspect;            // main stream's width / height
    bool has_laser;           // 0x15 range, 0x17 target position
    bool has_zoom_module;     // 0x01 reply carries the zoom module's version (12 bytes)
    // The simulated gimbal's firmware (0x01 words) and zoom speed.
    std::uint32_t camera_firmware, gimbal_firmware, zoom_firmware;
    double zoom_traverse_s;  // time from zoom 1 to zoom_max
};

const ModelInfo& model_info(Model model);
// By key ("a8mini", "zr10", "zr30", "zt30", "zt6"; case-insensitive).
std::optional<Model> model_from_key(std::string_view key);
// By the first two characters of a hardware id (case-insensitive hex digits).
std::optional<Model> model_from_hardware_id(std::string_view hardware_id);

struct FieldOfView {
    double hfov_deg = 0, vfov_deg = 0;
};

// The main camera's field of view at `zoom` (clamped to [1, zoom_max]): optical and digital
// zoom both narrow the view as tan(fov/2) / zoom.
FieldOfView field_of_view(Model model, double zoom);

// Wraps an angle to [-180, 180).
double wrap180(double deg);

}  // namespace gimbal::siyi
