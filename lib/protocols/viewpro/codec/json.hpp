// JSON views of Viewpro frames in the units of the interface contract (section 5 `output`).
#pragma once

#include <nlohmann/json.hpp>

#include "protocols/viewpro/codec/input.hpp"
#include "protocols/viewpro/codec/mode.hpp"
#include "protocols/viewpro/codec/output.hpp"

namespace gimbal::viewpro {

// {"format":"out3","time":ISO,"zoom","gimbal":{"roll","pitch","yaw"},"lrf_m",
//  "uav":{"roll","pitch","yaw","lat","lon","alt_msl"},"target":{"lat","lon","alt_msl"?}}
// - only what the format carries.
nlohmann::json to_json(const Output&);
// {"osd":"target","network":false,"serial":true,"format":"out3"}
nlohmann::json to_json(const Mode&);
// {"time","roll","pitch","yaw","lat","lon","alt_msl","vel_ned"?}
nlohmann::json to_json(const VehicleInput&);
// {"time","lrf_m","pitch","yaw","lat","lon","alt_msl","vel_ned"}
nlohmann::json to_json(const In3&);
// Decoded content of any input frame: mode -> Mode, shifts -> {"hundredths_deg","deg"},
// IN1/IN2 -> VehicleInput, IN3 -> In3. null if the frame does not decode.
nlohmann::json to_json(const InputFrame&);

// ADL forms so `nlohmann::json j = output;` works.
inline void to_json(nlohmann::json& j, const Output& v) {
    j = to_json(v);
}
inline void to_json(nlohmann::json& j, const Mode& v) {
    j = to_json(v);
}
inline void to_json(nlohmann::json& j, const VehicleInput& v) {
    j = to_json(v);
}
inline void to_json(nlohmann::json& j, const In3& v) {
    j = to_json(v);
}

}  // namespace gimbal::viewpro
