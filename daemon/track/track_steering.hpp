// Keeping the gimbal on a tracked object (contract section 20, `steer`). With a ground
// solution the gimbal is pointed at the object's filtered position through its geopoint
// capability: a gimbal that holds a location itself and reports doing so (an Orion) gets
// the object's velocity too (`vel_ned`, so it leads the object) at 10 Hz; a gimbal that
// gimbald aims (a MAVLink device, SIYI) gets the position at 20 Hz. The aim moves onto the
// object at a bounded speed across the picture (`max_slew_widths_s`): a gimbal that jumped
// onto it at once - from where the operator had it when the track started - would move the
// picture further in one frame than a tracker follows. Steering takes the gimbal over once the
// filter knows the object's velocity (`velocity_sigma_mps`, two or three seconds after the
// start), or at once when the object nears the picture's edge (`edge`): until then the gimbal
// keeps doing what the operator had it do - a gimbal pointed at a fixed spot before the
// velocity is known would let a vehicle drive off it. Without a ground solution, rate
// commands turn the camera towards the box: each axis at `rate_gain` degrees per second for
// every degree the box centre lies off the optical axis. The commands go straight to the
// session, not through the request path, so they never count as a client overriding the
// track. No protocol is named: the gimbal's capabilities decide.
#pragma once

#include <cstdint>
#include <optional>

#include "gimbal_session.hpp"
#include "logging.hpp"
#include "terrain/elevation_model.hpp"
#include "track/ground/ground_filter.hpp"

namespace gimbald::track {

struct TrackSteeringOptions {
    double rate_gain = 1.0;    // deg/s of rate per degree of image error
    double max_rate_dps = 30;  // the rate commands' bound
    double leading_hz = 10;    // a gimbal that holds the location itself
    double aimed_hz = 20;      // a gimbal gimbald aims
    double rate_hz = 10;       // rate commands
    // The aim moves towards the object at most this many image widths per second (0.25: 10 px
    // a frame at 640 px and 15 fps, a quarter of a small object's box).
    double max_slew_widths_s = 0.25;
    // The object's velocity is known (steering takes over, vel_ned is sent) once its one-sigma
    // spread is below this.
    double velocity_sigma_mps = 4;
    // A box centre this far off the axis (image coordinates, either axis) is steered at once.
    double edge = 0.5;
};

class TrackSteering {
  public:
    // `terrain` (nullptr: none) must outlive this object.
    TrackSteering(GimbalSession& session, gimbal::terrain::ElevationModel* terrain,
                  TrackSteeringOptions options = {});

    // Called often (at least 20 Hz); sends what is due at `now`. `estimate`: the object on
    // the ground now (null: none); `x`, `y`: the box centre in image coordinates; `seen`: the
    // box is the tracker's, not a lost track's guess. Rates follow only a seen box: turning
    // after a guess that may run off the picture would sweep the camera away from the object.
    void steer(double now, const std::optional<gimbal::track::GroundEstimate>& estimate, double x,
               double y, bool seen);
    void reset() {
        next_s_ = 0;
        turning_ = false;
        engaged_ = false;
    }
    // The track ended: a camera left turning at a rate is stopped.
    void halt();

    std::uint64_t sent() const { return sent_; }
    std::uint64_t failed() const { return failed_; }

  private:
    bool point_at(const gimbal::track::GroundEstimate& estimate, double& period_s);
    bool turn_towards(double x, double y);
    bool velocity_known(const gimbal::track::GroundEstimate& estimate) const;
    bool run(const gimbal::command::Result<nlohmann::json>& request);

    GimbalSession& session_;
    gimbal::terrain::ElevationModel* terrain_;
    TrackSteeringOptions options_;
    double next_s_ = 0;
    bool turning_ = false;  // the latest command was a rate
    bool engaged_ = false;  // steering has taken the gimbal over
    std::uint64_t sent_ = 0;
    std::uint64_t failed_ = 0;
    gimbal::log::RateLimitedLog failed_log_;
};

}  // namespace gimbald::track
