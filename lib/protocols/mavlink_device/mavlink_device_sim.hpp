// A simulated MAVLink gimbal device (gimbal-sim --protocol mavlink, gimbald --sim mavlink):
// two motor axes (pitch from the horizon, yaw from the vehicle's nose) that slew at a
// limited rate within angle limits, steered by GIMBAL_DEVICE_SET_ATTITUDE (angles with
// feed-forward rates, or rates alone; yaw from the vehicle or from north), told the
// vehicle's yaw by AUTOPILOT_STATE_FOR_GIMBAL_DEVICE. It sends HEARTBEAT at 1 Hz,
// GIMBAL_DEVICE_ATTITUDE_STATUS at a configurable rate, and GIMBAL_DEVICE_INFORMATION when
// asked (REQUEST_MESSAGE). Pure: time is passed in.
#pragma once

#include <cstdint>
#include <memory>
#include <random>

#include "mavlink/framer.hpp"
#include "protocols/mavlink_device/mavlink_device_wire.hpp"
#include "sim/device.hpp"

namespace gimbal::protocols {

struct MavlinkDeviceSimOptions {
    std::uint32_t seed = 1;
    double attitude_rate_hz = 20;
    double slew_rate_dps = 120;
    double pitch_min_deg = -120, pitch_max_deg = 30;
    // A yaw range of 360 degrees or more turns without end stops.
    double yaw_min_deg = -180, yaw_max_deg = 180;
    double angle_noise_deg = 0;         // 1 sigma on the reported angles
    double pitch_deg = 0, yaw_deg = 0;  // where the axes start
    std::uint8_t system_id = 1;
    std::uint8_t component_id = 154;  // MAV_COMP_ID_GIMBAL
    // MAVLink 2 signing (--signing-key): frames are signed, and only frames signed with the
    // key are heard. The device has no clock: it starts at unix_time_s and keeps ahead of
    // the timestamps it accepts.
    std::optional<mavlink::SigningKey> signing_key;
    double unix_time_s = 0;
};

class MavlinkDeviceSim final : public sim::Device {
  public:
    // GIMBAL_DEVICE_INFORMATION.firmware_version as common.xml encodes it (Major in the low
    // byte, then Minor, Patch, Dev): 2.4.1, a release (Dev 0). STATE shows "2.4.1".
    static constexpr std::uint32_t firmware_version = 2 | (4 << 8) | (1 << 16);

    explicit MavlinkDeviceSim(const MavlinkDeviceSimOptions& options);

    void receive(std::span<const std::uint8_t> bytes, double now_s) override;
    void advance(double now_s, std::vector<std::uint8_t>& out) override;

    double pitch_deg() const { return pitch_; }
    double yaw_deg() const { return yaw_; }  // from the vehicle's nose
    // The vehicle's yaw as the device estimates it at now_s (AUTOPILOT_STATE...).
    double vehicle_yaw_deg(double now_s) const;

  private:
    struct Target {
        bool angles = false;                  // else rates alone
        bool earth = false;                   // yaw from north
        double pitch = 0, yaw = 0;            // degrees (angles)
        double pitch_rate = 0, yaw_rate = 0;  // deg/s (feed-forward, or the rates)
        double since_s = 0;
    };

    void on_message(const mavlink::Message& m, double now_s);
    void step(double dt, double now_s);
    void send_status(double now_s, std::vector<std::uint8_t>& out);
    void send_information(std::vector<std::uint8_t>& out);
    bool yaw_continuous() const;
    // The vehicle's turn rate while its yaw is fresh enough to extrapolate, else 0.
    double vehicle_yaw_rate_at(double now_s) const;
    double clamp_yaw(double yaw, bool& at_limit) const;

    std::vector<std::uint8_t> make_frame(const mavlink::Payload& payload) {
        return sender_.frame(payload, options_.unix_time_s + time_);
    }

    MavlinkDeviceSimOptions options_;
    SignatureCheck signatures_;  // before framer_: it configures it
    mavlink::Framer framer_;
    MavlinkSender sender_;
    std::mt19937 rng_;
    double pitch_ = 0, yaw_ = 0;  // the axes
    double pitch_rate_ = 0, yaw_rate_ = 0;
    std::uint32_t failure_flags_ = 0;
    std::optional<Target> target_;
    bool report_earth_ = false;
    double vehicle_yaw_ = 0, vehicle_yaw_rate_ = 0, vehicle_yaw_s_ = 0;
    std::optional<double> manager_heard_s_;
    double time_ = 0;
    bool started_ = false;
    double next_status_s_ = 0, next_heartbeat_s_ = 0;
    int information_requests_ = 0;
    std::vector<std::pair<std::uint16_t, std::uint8_t>> acks_;  // command, result
};

std::unique_ptr<sim::Device> make_mavlink_device_sim(const MavlinkDeviceSimOptions& options);

}  // namespace gimbal::protocols
