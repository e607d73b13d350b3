#include "protocols/viewpro/viewpro_track.hpp"

#include "protocols/track_values.hpp"
#include "protocols/viewpro/codec/json.hpp"
#include "protocols/viewpro/codec/output_framer.hpp"

namespace gimbal::protocols {

using nlohmann::json;

namespace {

class ViewproTrackDecoder final : public TrackDecoder {
  public:
    void push(std::span<const std::uint8_t> bytes, std::int64_t time_us,
              std::vector<TrackPoint>& out) override {
        framer_.push(bytes, [&](const viewpro::OutputFrame& frame) {
            ++frames_;
            const auto o = viewpro::decode_output(frame);
            if (!o) {
                ++decode_errors_;
                return;
            }
            out.push_back(viewpro_track_point(time_us, viewpro::to_json(*o)));
        });
    }
    std::uint64_t frames() const override { return frames_; }
    std::uint64_t decode_errors() const override { return decode_errors_; }

  private:
    viewpro::OutputFramer framer_;
    std::uint64_t frames_ = 0;
    std::uint64_t decode_errors_ = 0;
};

}  // namespace

std::unique_ptr<TrackDecoder> make_viewpro_track_decoder() {
    return std::make_unique<ViewproTrackDecoder>();
}

TrackPoint viewpro_track_point(std::int64_t time_us, const json& o) {
    TrackPoint p;
    p.time_us = time_us;
    json& v = p.values;
    copy_value(v, "gimbal_time", o, "time");
    const json& uav = o.contains("uav") ? o["uav"] : json();
    const json& gimbal = o.contains("gimbal") ? o["gimbal"] : json();
    const json& target = o.contains("target") ? o["target"] : json();
    copy_value(v, "lat", uav, "lat");
    copy_value(v, "lon", uav, "lon");
    copy_value(v, "alt_msl", uav, "alt_msl");
    for (const char* key : {"roll", "pitch", "yaw"}) copy_value(v, key, uav, key);
    copy_value(v, "pan", gimbal, "yaw");
    copy_value(v, "tilt", gimbal, "pitch");
    copy_value(v, "mode", o, "format");
    copy_value(v, "target_lat", target, "lat");
    copy_value(v, "target_lon", target, "lon");
    copy_value(v, "target_alt_msl", target, "alt_msl");
    copy_value(v, "zoom", o, "zoom");
    copy_value(v, "lrf_m", o, "lrf_m");
    const auto lat = number_value(uav, "lat");
    const auto lon = number_value(uav, "lon");
    if (lat && lon)
        p.aircraft = TrackPosition{*lat, *lon, std::nullopt, number_value(uav, "alt_msl")};
    const auto tlat = number_value(target, "lat");
    const auto tlon = number_value(target, "lon");
    // A target at exactly 0,0 is the frame's "no target" (nothing in the Gulf of Guinea).
    if (tlat && tlon && (*tlat != 0 || *tlon != 0))
        p.target = TrackPosition{*tlat, *tlon, std::nullopt, number_value(target, "alt_msl")};
    return p;
}

}  // namespace gimbal::protocols
