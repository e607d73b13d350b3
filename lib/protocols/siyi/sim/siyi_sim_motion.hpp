// The simulated SIYI gimbal's moving parts: two axes that slew at the model's top rate within
// its limits, toward absolute angles (0x0E, 0x08) or at commanded speeds (0x07), and a zoom
// lens that travels at a fixed speed in log-zoom (0x0F, 0x05). Angles in SIYI's frame (yaw
// positive left, pitch positive up), degrees. Pure: time comes in as dt.
#pragma once

#include <cstdint>

#include "protocols/siyi/codec/commands.hpp"
#include "protocols/siyi/codec/models.hpp"

namespace gimbal::siyi {

class SimMotion {
  public:
    SimMotion(const ModelInfo& model, double yaw, double pitch, double zoom);

    // Go to absolute angles at the top rate (clamped into the limits; a continuous yaw takes
    // the short way round).
    void go_to(double yaw, double pitch);
    // Turn at speeds -100..100 of the top rate, as 0x07: positive turn_yaw turns right (SIYI
    // yaw decreases), positive turn_pitch up. An axis stops at its limit; 0 0 stops.
    void turn(std::int8_t turn_yaw, std::int8_t turn_pitch);
    void zoom_to(double zoom);   // clamped to [1, zoom_max]
    void zoom_step(ZoomStep s);  // in/out until the end of the range or stop

    void step(double dt);

    double yaw() const { return yaw_; }
    double pitch() const { return pitch_; }
    double yaw_rate() const { return yaw_rate_; }  // deg/s over the last step, SIYI frame
    double pitch_rate() const { return pitch_rate_; }
    double zoom() const { return zoom_; }

  private:
    enum class Drive : std::uint8_t { hold, angles, speeds };

    double clamp_yaw(double yaw) const;
    double clamp_pitch(double pitch) const;

    const ModelInfo& model_;
    double yaw_, pitch_, zoom_;
    double yaw_rate_ = 0, pitch_rate_ = 0;
    Drive drive_ = Drive::hold;
    double target_yaw_ = 0, target_pitch_ = 0;
    double speed_yaw_ = 0, speed_pitch_ = 0;  // deg/s, SIYI frame
    double target_zoom_;
};

}  // namespace gimbal::siyi
