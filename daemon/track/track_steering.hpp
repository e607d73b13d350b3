// Keeping the gimbal on a tracked object (contract section 20, `steer`). With a ground
// solution the gimbal is pointed at the object's filtered position through its geopoint
// capability: a gimbal that holds a location itself and reports doing so (an Orion) gets
// the object's velocity too (`vel_ned`, so it leads the object) at 10 Hz; a gimbal that
// gimbald aims (a MAVLink device, SIYI) gets the position at 20 Hz. Without one, rate
// commands turn the camera towards the box: each axis at `rate_gain` degrees per second for
// every degree the box centre lies off the optical axis. The commands go straight to the
// session, not through the request path, so they never count as a client overriding the
// track. No protocol is named: the gimbal's capabilities decide.
#pragma once

#include <cstdint>
#include <optional>

#include "gimbal_session.hpp"
#include "logging.hpp"
#include "track/ground/ground_filter.hpp"

namespace gimbald::track {

struct TrackSteeringOptions {
    double rate_gain = 1.0;    // deg/s of rate per degree of image error
    double max_rate_dps = 30;  // the rate commands' bound
    double leading_hz = 10;    // a gimbal that holds the location itself
    double aimed_hz = 20;      // a gimbal gimbald aims
    double rate_hz = 10;       // rate commands
};

class TrackSteering {
  public:
    explicit TrackSteering(GimbalSession& session, TrackSteeringOptions options = {});

    // Called often (at least 20 Hz); sends what is due at `now`. `estimate`: the object on
    // the ground now (null: none); `x`, `y`: the box centre in image coordinates.
    void steer(double now, const std::optional<gimbal::track::GroundEstimate>& estimate, double x,
               double y);
    void reset() {
        next_s_ = 0;
        turning_ = false;
    }
    // The track ended: a camera left turning at a rate is stopped.
    void halt();

    std::uint64_t sent() const { return sent_; }
    std::uint64_t failed() const { return failed_; }

  private:
    bool point_at(const gimbal::track::GroundEstimate& estimate, double& period_s);
    bool turn_towards(double x, double y);
    bool run(const gimbal::command::Result<nlohmann::json>& request);

    GimbalSession& session_;
    TrackSteeringOptions options_;
    double next_s_ = 0;
    bool turning_ = false;  // the latest command was a rate
    std::uint64_t sent_ = 0;
    std::uint64_t failed_ = 0;
    gimbal::log::RateLimitedLog failed_log_;
};

}  // namespace gimbald::track
