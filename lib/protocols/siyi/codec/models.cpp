#include "protocols/siyi/codec/models.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

namespace gimbal::siyi {

namespace {

constexpr double pi = 3.14159265358979323846;
constexpr double deg = pi / 180.0;

// Firmware version word: byte 2 major, 1 minor, 0 patch.
constexpr std::uint32_t version(std::uint32_t major, std::uint32_t minor, std::uint32_t patch) {
    return (major << 16) | (minor << 8) | patch;
}

// A8 mini and ZT6: ArduPilot reports a 21 mm (35 mm-equivalent) focal length; over the 36 mm
// width of that format it is 2 atan(18 / 21) = 81.2 degrees.
// ZR10, ZR30, ZT30: ArduPilot's 5.15 mm wide end over an assumed 1/2.7-inch 16:9 active width
// of 5.63 mm: 2 atan(2.815 / 5.15) = 57.3 degrees (docs/siyi.md: to confirm on a camera).
constexpr double hfov_wide_21mm_equiv = 81.2;
constexpr double hfov_wide_5_15mm = 57.3;

constexpr std::array<ModelInfo, all_models.size()> table = {{
    {Model::a8_mini,
     "a8mini",
     "A8 mini",
     "73",
     false,
     -135,
     135,
     -90,
     25,
     90,
     6,
     1,
     hfov_wide_21mm_equiv,
     16.0 / 9.0,
     false,
     false,
     version(0, 2, 8),
     version(0, 3, 9),
     0,
     1.0},
    {Model::zr10,
     "zr10",
     "ZR10",
     "6B",
     false,
     -135,
     135,
     -90,
     25,
     90,
     30,
     10,
     hfov_wide_5_15mm,
     16.0 / 9.0,
     false,
     true,
     version(0, 3, 5),
     version(0, 4, 0),
     version(0, 2, 3),
     3.0},
    {Model::zr30,
     "zr30",
     "ZR30",
     "78",
     false,
     -270,
     270,
     -90,
     25,
     90,
     30,
     30,
     hfov_wide_5_15mm,
     16.0 / 9.0,
     false,
     true,
     version(0, 1, 6),
     version(0, 2, 2),
     version(0, 1, 6),
     4.0},
    {Model::zt30,
     "zt30",
     "ZT30",
     "7A",
     true,
     -180,
     180,
     -90,
     25,
     90,
     30,
     30,
     hfov_wide_5_15mm,
     16.0 / 9.0,
     true,
     true,
     version(0, 2, 7),
     version(0, 2, 8),
     version(0, 1, 6),
     4.0},
    {Model::zt6,
     "zt6",
     "ZT6",
     "82",
     false,
     -270,
     270,
     -90,
     25,
     90,
     6,
     1,
     hfov_wide_21mm_equiv,
     16.0 / 9.0,
     false,
     false,
     version(0, 1, 9),
     version(0, 2, 3),
     0,
     1.0},
}};

bool same_ignoring_case(std::string_view a, std::string_view b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
               return std::tolower(static_cast<unsigned char>(x)) ==
                      std::tolower(static_cast<unsigned char>(y));
           });
}

}  // namespace

const ModelInfo& model_info(Model model) {
    for (const ModelInfo& info : table)
        if (info.model == model) return info;
    return table[0];
}

std::optional<Model> model_from_key(std::string_view key) {
    for (const ModelInfo& info : table)
        if (same_ignoring_case(info.key, key)) return info.model;
    return std::nullopt;
}

std::optional<Model> model_from_hardware_id(std::string_view hardware_id) {
    if (hardware_id.size() < 2) return std::nullopt;
    for (const ModelInfo& info : table)
        if (same_ignoring_case(info.id_prefix, hardware_id.substr(0, 2))) return info.model;
    return std::nullopt;
}

FieldOfView field_of_view(Model model, double zoom) {
    const ModelInfo& m = model_info(model);
    const double z = std::isfinite(zoom) ? std::clamp(zoom, 1.0, m.zoom_max) : 1.0;
    const double half_h = std::tan(m.hfov_deg * deg / 2) / z;
    const double half_v = half_h / m.aspect;
    return {2 * std::atan(half_h) / deg, 2 * std::atan(half_v) / deg};
}

double wrap180(double d) {
    return d - 360.0 * std::floor((d + 180.0) / 360.0);
}

}  // namespace gimbal::siyi
