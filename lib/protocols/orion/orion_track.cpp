#include "protocols/orion/orion_track.hpp"

#include "protocols/orion/codec/framer.hpp"
#include "protocols/orion/orion_state.hpp"
#include "protocols/track_values.hpp"
#include "state/precision.hpp"

namespace gimbal::protocols {

using nlohmann::json;

namespace {

class OrionTrackDecoder final : public TrackDecoder {
  public:
    void push(std::span<const std::uint8_t> bytes, std::int64_t time_us,
              std::vector<TrackPoint>& out) override {
        framer_.push(bytes, [&](const orion::Frame& frame) {
            ++frames_;
            if (frame.id != orion::GeolocateTelemetry::id) return;
            const auto t = orion::decode<orion::GeolocateTelemetry>(frame.data());
            if (!t.ok) {
                ++decode_errors_;
                return;
            }
            out.push_back(orion_track_point(time_us, state::telemetry_json(t.value)));
        });
    }
    std::uint64_t frames() const override { return frames_; }
    std::uint64_t decode_errors() const override { return decode_errors_; }

  private:
    orion::Framer framer_;
    std::uint64_t frames_ = 0;
    std::uint64_t decode_errors_ = 0;
};

}  // namespace

std::unique_ptr<TrackDecoder> make_orion_track_decoder() {
    return std::make_unique<OrionTrackDecoder>();
}

TrackPoint orion_track_point(std::int64_t time_us, const json& t) {
    TrackPoint p;
    p.time_us = time_us;
    json& v = p.values;
    copy_value(v, "gimbal_time", t, "utc");
    for (const char* key : {"system_time_ms", "lat", "lon", "alt", "alt_msl", "roll", "pitch",
                            "yaw", "pan", "tilt", "hfov", "vfov", "mode", "range_source"})
        copy_value(v, key, t, key);
    const auto undulation = number_value(t, "geoid_undulation");
    const auto lat = number_value(t, "lat");
    const auto lon = number_value(t, "lon");
    if (lat && lon)
        p.aircraft = TrackPosition{*lat, *lon, number_value(t, "alt"), number_value(t, "alt_msl")};
    const json& target = t.contains("target") ? t["target"] : json();
    if (target.is_object()) {
        copy_value(v, "target_lat", target, "lat");
        copy_value(v, "target_lon", target, "lon");
        copy_value(v, "target_alt", target, "alt");
        const auto alt = number_value(target, "alt");
        std::optional<double> alt_msl;
        if (alt && undulation) alt_msl = state::metres(*alt - *undulation);
        if (alt_msl) v["target_alt_msl"] = *alt_msl;
        p.target =
            TrackPosition{*number_value(target, "lat"), *number_value(target, "lon"), alt, alt_msl};
        const json& corners = t.contains("footprint") ? t["footprint"] : json();
        if (corners.is_array() && corners.size() == 4) {
            std::array<TrackPosition, 4> f;
            for (std::size_t i = 0; i < 4; ++i)
                f[i] = TrackPosition{number_value(corners[i], "lat").value_or(0),
                                     number_value(corners[i], "lon").value_or(0), alt, alt_msl};
            p.footprint = f;
        }
    }
    return p;
}

}  // namespace gimbal::protocols
