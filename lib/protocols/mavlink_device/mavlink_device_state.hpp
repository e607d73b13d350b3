// The live state of one MAVLink gimbal device (contract section 19): what it reported
// (GIMBAL_DEVICE_INFORMATION, GIMBAL_DEVICE_ATTITUDE_STATUS: STATE `device`) and, with the
// vehicle's fix, the Orion-style derived `telemetry` (position, pan/tilt, line of sight on the
// ground). Pure: every call takes now_s (monotonic seconds).
#pragma once

#include <array>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "geo/attitude.hpp"
#include "mavlink/messages.hpp"
#include "protocols/mavlink_device/mavlink_device_options.hpp"
#include "protocols/mavlink_device/mavlink_device_wire.hpp"
#include "state/event.hpp"

namespace gimbal::protocols {

// The device's latest attitude, as reported.
struct DeviceAttitude {
    double roll_deg = 0, pitch_deg = 0, yaw_deg = 0;
    bool earth_frame = false;  // yaw from north, else from the vehicle's heading
    std::array<double, 3> angular_velocity_dps{};
    std::uint32_t failure_flags = 0;
    double received_s = 0;
};

class MavlinkDeviceState {
  public:
    explicit MavlinkDeviceState(const MavlinkDeviceOptions& options) : options_(options) {}

    // One decoded message from the device link; false when it is not the device's.
    bool apply(const mavlink::Message& message, double now_s);
    // The vehicle's latest fix (nullopt: lost); telemetry follows at the next attitude.
    void set_vehicle(const std::optional<VehicleFix>& fix) { vehicle_ = fix; }
    const std::optional<VehicleFix>& vehicle() const { return vehicle_; }
    // Appends a `lost` event when the attitude goes stale (once per loss).
    void tick(double now_s, std::vector<state::Event>& events);

    bool stale(double now_s) const;
    std::uint64_t telemetry_count() const { return attitudes_; }
    nlohmann::json snapshot(double now_s) const;

    const std::optional<DeviceAttitude>& attitude() const { return attitude_; }
    bool has_information() const { return information_.has_value(); }
    // GIMBAL_DEVICE_CAP_FLAGS_SUPPORTS_YAW_IN_EARTH_FRAME, from the information.
    bool earth_frame_supported() const;
    // The device's MAVLink address (from its messages), once heard.
    std::optional<std::uint8_t> device_system() const { return device_system_; }
    std::uint8_t device_component() const { return device_component_; }

    // The device's yaw from the vehicle's heading and from north, when both are known.
    std::optional<double> pan_deg() const;
    // The camera's attitude (camera x along the line of sight) relative to NED.
    std::optional<geo::Quat> line_of_sight() const;

  private:
    void on_attitude(const mavlink::GimbalDeviceAttitudeStatus& m, double now_s);
    void on_information(const mavlink::GimbalDeviceInformation& m, double now_s);
    nlohmann::json telemetry_json() const;
    nlohmann::json device_json(double now_s) const;

    MavlinkDeviceOptions options_;
    std::optional<VehicleFix> vehicle_;
    std::optional<DeviceAttitude> attitude_;
    std::optional<mavlink::GimbalDeviceInformation> information_;
    std::optional<std::uint8_t> device_system_;
    std::uint8_t device_component_ = 154;
    nlohmann::json telemetry_ = nullptr;
    std::uint64_t attitudes_ = 0;
    bool lost_reported_ = false;
};

// Degrees in a quaternion's aerospace Euler angles (geo::quat_to_euler) of a wire q[4];
// nullopt when a component is not finite or the quaternion is zero.
std::optional<geo::EulerDeg> euler_of(const std::array<float, 4>& q);

}  // namespace gimbal::protocols
