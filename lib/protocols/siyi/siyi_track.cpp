#include "protocols/siyi/siyi_track.hpp"

#include <variant>

#include "protocols/siyi/codec/framer.hpp"
#include "protocols/siyi/codec/messages.hpp"
#include "session/capabilities.hpp"
#include "state/precision.hpp"

namespace gimbal::protocols {

namespace {

class SiyiTrackDecoder final : public TrackDecoder {
  public:
    void push(std::span<const std::uint8_t> bytes, std::int64_t time_us,
              std::vector<TrackPoint>& out) override {
        framer_.push(bytes, [&](const siyi::Frame& f) {
            const auto d = siyi::decode_from_gimbal(f);
            if (!d) {
                ++decode_errors_;
                return;
            }
            const auto* a = std::get_if<siyi::GimbalAttitude>(&d.value);
            if (!a) return;
            TrackPoint p;
            p.time_us = time_us;
            p.values["pan"] = state::angle_deg(session::wrap180(-a->yaw));
            p.values["tilt"] = state::angle_deg(a->pitch);
            p.values["gimbal_roll"] = state::angle_deg(a->roll);
            out.push_back(std::move(p));
        });
    }
    std::uint64_t frames() const override { return framer_.stats().frames; }
    std::uint64_t decode_errors() const override { return decode_errors_; }

  private:
    siyi::Framer framer_;
    std::uint64_t decode_errors_ = 0;
};

}  // namespace

std::unique_ptr<TrackDecoder> make_siyi_track_decoder() {
    return std::make_unique<SiyiTrackDecoder>();
}

}  // namespace gimbal::protocols
