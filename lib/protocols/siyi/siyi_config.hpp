// A SIYI gimbal's own configuration keys (docs/siyi.md "Connecting one"): `siyi`, what the
// camera does not report - its model until its hardware id arrives, the geoid and flat-ground
// heights. Declared once here; daemon/config.cpp reads and writes it through the registry
// (siyi_entry.cpp), and SiyiOptions is this struct plus what the daemon adds at run time.
#pragma once

#include <array>
#include <optional>

#include "config/fields.hpp"

namespace gimbal::protocols {

// `detect`: the model its hardware id (0x02) names; a key: that model whatever the id says.
enum class SiyiModelSetting { detect, a8mini, zr10, zr30, zt30, zt6 };

inline constexpr std::array<config::Named<SiyiModelSetting>, 6> siyi_model_names{
    {{"detect", SiyiModelSetting::detect},
     {"a8mini", SiyiModelSetting::a8mini},
     {"zr10", SiyiModelSetting::zr10},
     {"zr30", SiyiModelSetting::zr30},
     {"zt30", SiyiModelSetting::zt30},
     {"zt6", SiyiModelSetting::zt6}}};

struct SiyiConfig {
    SiyiModelSetting model = SiyiModelSetting::detect;
    // As the MAVLink device's: a fixed geoid undulation (metres), else the EGM96 geoid at the
    // aircraft's position, else 0; and the flat world's altitude above the ellipsoid.
    std::optional<double> geoid_undulation_m;
    double ground_alt_m = 0;
    bool operator==(const SiyiConfig&) const = default;
};

template <class V>
void fields(V& v, SiyiConfig& c) {
    v.section("siyi", [&](auto& s) {
        s.choice("model", c.model, siyi_model_names);
        s.optional_number("geoid_undulation_m", c.geoid_undulation_m, {-200, 200});
        s.number("ground_alt_m", c.ground_alt_m, {-2000, 10000});
    });
}

}  // namespace gimbal::protocols
