// A gimbal's typed state -> the MAVLink messages gimbald sends as a gimbal manager (contract
// section 8):
// the line-of-sight attitude, the camera's field of view, and the information messages.
// Pure; unknown values are NaN (floats) or INT32_MAX (positions), as common.xml says.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

#include "geo/attitude.hpp"
#include "gimbal_protocol/commands.hpp"
#include "gimbal_protocol/control.hpp"
#include "mavlink/messages.hpp"
#include "session/gimbal_view.hpp"

namespace gimbal::gimbal_protocol {

// HEARTBEAT of a gimbal component: MAV_TYPE_GIMBAL, MAV_AUTOPILOT_INVALID, MAV_STATE_ACTIVE.
mavlink::Heartbeat heartbeat();

// The camera's line of sight as a rotation from the camera frame (x along the view) to NED,
// as the gimbal's capabilities read it (nullopt: not reported yet).
std::optional<geo::Quat> line_of_sight(const session::GimbalView& state);

mavlink::GimbalDeviceAttitudeStatus attitude_status(const ExposedGimbal& g,
                                                    const session::GimbalView& state,
                                                    std::uint32_t time_boot_ms);
mavlink::CameraFovStatus fov_status(const ExposedGimbal& g, const session::GimbalView& state,
                                    std::uint32_t time_boot_ms);
mavlink::GimbalManagerStatus manager_status(const ExposedGimbal& g, const Control& control,
                                            std::uint32_t time_boot_ms);
mavlink::GimbalManagerInformation manager_information(const ExposedGimbal& g,
                                                      const session::GimbalView& state,
                                                      std::uint32_t time_boot_ms);
mavlink::GimbalDeviceInformation device_information(const ExposedGimbal& g,
                                                    const session::GimbalView& state,
                                                    std::uint32_t time_boot_ms);
mavlink::CameraInformation camera_information(const ExposedGimbal& g,
                                              const session::GimbalView& state,
                                              std::uint32_t time_boot_ms);

}  // namespace gimbal::gimbal_protocol
