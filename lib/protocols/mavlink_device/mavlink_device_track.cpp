#include "protocols/mavlink_device/mavlink_device_track.hpp"

#include "protocols/mavlink_device/mavlink_device_flags.hpp"
#include "protocols/mavlink_device/mavlink_device_json.hpp"
#include "protocols/mavlink_device/mavlink_frame_scanner.hpp"

namespace gimbal::protocols {

namespace {

class MavlinkDeviceTrackDecoder final : public TrackDecoder {
  public:
    void push(std::span<const std::uint8_t> bytes, std::int64_t time_us,
              std::vector<TrackPoint>& out) override {
        scanner_.push(bytes, [&](const ScannedFrame& f) {
            ++frames_;
            const auto* a = std::get_if<mavlink::GimbalDeviceAttitudeStatus>(&f.message.payload);
            if (!a) return;
            const auto j = mavlink_message_json(f.message.payload);
            TrackPoint p;
            p.time_us = time_us;
            p.values["gimbal_time"] = a->time_boot_ms;
            const bool earth = yaw_in_earth_frame(a->flags);
            p.values["tilt"] = j["pitch"];
            p.values[earth ? "gimbal_yaw" : "pan"] = j["yaw"];
            p.values["gimbal_roll"] = j["roll"];
            out.push_back(std::move(p));
        });
    }
    std::uint64_t frames() const override { return frames_; }
    std::uint64_t decode_errors() const override { return 0; }

  private:
    MavlinkFrameScanner scanner_;
    std::uint64_t frames_ = 0;
};

}  // namespace

std::unique_ptr<TrackDecoder> make_mavlink_device_track_decoder() {
    return std::make_unique<MavlinkDeviceTrackDecoder>();
}

}  // namespace gimbal::protocols
