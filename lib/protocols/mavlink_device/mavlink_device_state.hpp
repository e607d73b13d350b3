// The live state of one MAVLink gimbal device (contract section 19): what it reported
// (GIMBAL_DEVICE_INFORMATION, GIMBAL_DEVICE_ATTITUDE_STATUS: STATE `device`) and, with the
// vehicle's fix, the Orion-style derived `telemetry` (position, pan/tilt, line of sight on the
// ground). Pure: every call takes now_s (monotonic seconds).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "geo/attitude.hpp"
#include "geo/wgs84.hpp"
#include "mavlink/messages.hpp"
#include "protocols/mavlink_device/mavlink_device_options.hpp"
#include "protocols/mavlink_device/mavlink_device_wire.hpp"
#include "state/event.hpp"
#include "state/telemetry.hpp"

namespace gimbal::protocols {

// The device's latest attitude, as reported.
struct DeviceAttitude {
    double roll_deg = 0, pitch_deg = 0, yaw_deg = 0;
    bool earth_frame = false;  // yaw from north, else from the vehicle's heading
    std::array<double, 3> angular_velocity_dps{};
    std::uint32_t failure_flags = 0;
    std::uint32_t time_boot_ms = 0;  // the device's clock at the report
    double received_s = 0;
};

// What the device reported, typed: what its capabilities read (mavlink_device_capabilities.hpp).
struct MavlinkDeviceData {
    std::optional<DeviceAttitude> attitude;
    std::optional<mavlink::GimbalDeviceInformation> information;
    // STATE `telemetry`: the shared keys, from the latest attitude and the vehicle's fix then.
    std::optional<state::Telemetry> telemetry;
};

// The information's texts as STATE shows them: a char[32] of the wire (printable ASCII, '?'
// for anything else), and the firmware version "Major.Minor.Patch[.Dev]".
std::string device_text(const std::array<std::uint8_t, 32>& chars);
std::string firmware_text(std::uint32_t version);
// One axis's reported limits (min, max) in degrees, as STATE shows them before rounding: a
// limit outside -360..360 degrees, or a pair whose min exceeds its max, is unknown.
std::pair<std::optional<double>, std::optional<double>> device_limits(float min_rad, float max_rad);

class MavlinkDeviceState {
  public:
    explicit MavlinkDeviceState(const MavlinkDeviceOptions& options) : options_(options) {}

    // One decoded message from the device link; false when it is not the device's.
    bool apply(const mavlink::Message& message, double now_s);
    // The vehicle's latest fix (nullopt: lost); telemetry follows at the next attitude. The
    // geoid undulation follows the fix: the configured override, else the geoid model at
    // the aircraft's position, else 0 (kept while the fix is lost).
    void set_vehicle(const std::optional<vehicle::AircraftFix>& fix);
    const std::optional<vehicle::AircraftFix>& vehicle() const { return vehicle_; }
    double geoid_undulation() const { return geoid_undulation_m_; }
    // The camera's position above the ellipsoid, from the fix.
    std::optional<geo::Lla> camera() const;
    // The latest stare_start's fields: STATE `stare`, as an Orion's latest StareStart.
    void set_stare(nlohmann::json fields) { stare_ = std::move(fields); }
    // Appends a `lost` event when the attitude goes stale (once per loss).
    void tick(double now_s, std::vector<state::Event>& events);

    bool stale(double now_s) const;
    // Seconds since the latest attitude report; nullopt before the first.
    std::optional<double> telemetry_age_s(double now_s) const {
        if (!data_.attitude) return std::nullopt;
        return std::max(0.0, now_s - data_.attitude->received_s);
    }
    std::uint64_t telemetry_count() const { return attitudes_; }
    // STATE `device`, `telemetry` and `stare`.
    void write(state::JsonWriter& w, double now_s) const;
    nlohmann::json snapshot(double now_s) const;  // write() as a JSON object

    const std::optional<DeviceAttitude>& attitude() const { return data_.attitude; }
    // STATE `telemetry`: the shared keys, from the latest attitude and the vehicle's fix then.
    const std::optional<state::Telemetry>& telemetry() const { return data_.telemetry; }
    const MavlinkDeviceData& data() const { return data_; }
    bool has_information() const { return data_.information.has_value(); }
    // GIMBAL_DEVICE_CAP_FLAGS_SUPPORTS_YAW_IN_EARTH_FRAME, from the information.
    bool earth_frame_supported() const;
    // GIMBAL_DEVICE_CAP_FLAGS, from the information (0 before it).
    std::uint32_t cap_flags() const { return data_.information ? data_.information->cap_flags : 0; }
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
    state::Telemetry derive_telemetry() const;
    void write_device(state::JsonWriter& d, double now_s) const;

    MavlinkDeviceOptions options_;
    std::optional<vehicle::AircraftFix> vehicle_;
    double geoid_undulation_m_ = 0;
    nlohmann::json stare_ = nullptr;
    MavlinkDeviceData data_;
    std::optional<std::uint8_t> device_system_;
    std::uint8_t device_component_ = 154;
    std::uint64_t attitudes_ = 0;
    bool lost_reported_ = false;
};

// Degrees in a quaternion's aerospace Euler angles (geo::quat_to_euler) of a wire q[4];
// nullopt when a component is not finite or the quaternion is zero.
std::optional<geo::EulerDeg> euler_of(const std::array<float, 4>& q);

}  // namespace gimbal::protocols
