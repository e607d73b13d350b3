#include "protocols/viewpro/sim/viewpro_sim.hpp"

#include <algorithm>
#include <cmath>

#include "protocols/viewpro/codec/input.hpp"
#include "protocols/viewpro/codec/mode.hpp"
#include "protocols/viewpro/sim/viewpro_sim_model.hpp"

namespace gimbal::sim {

namespace {

constexpr double output_period_s = 0.1;  // 10 Hz
constexpr double max_backlog_s = 60.0;   // older output is skipped, not replayed
// k * 0.1 is not exact in binary: a tick this close to the time asked for is due.
constexpr double tick_tolerance_s = 1e-9;
// Shifts accumulate; beyond a half turn they would only wrap around.
constexpr int max_shift_hundredths = 18000;

double wrap_180(double deg) {
    double a = std::fmod(deg + 180.0, 360.0);
    if (a < 0) a += 360.0;
    return a - 180.0;
}

}  // namespace

ViewproSim::ViewproSim(const ViewproSimOptions& options)
    : options_(options),
      utc_at_t_base_s_(options.unix_time_at_start_s),
      mode_byte_(options.mode_byte),
      rng_(options.seed) {
    pose_.lat_deg = options.lat_deg;
    pose_.lon_deg = options.lon_deg;
    pose_.alt_msl_m = options.alt_msl_m;
    pose_.yaw_deg = options.yaw_deg;
}

void ViewproSim::receive(std::span<const std::uint8_t> bytes, double now_s) {
    run_until(now_s);  // frames act on the state at the time they arrive
    framer_.push(bytes, [this](const viewpro::InputFrame& frame) { handle(frame); });
}

void ViewproSim::advance(double now_s, std::vector<std::uint8_t>& out) {
    run_until(now_s);
    out.insert(out.end(), pending_.begin(), pending_.end());
    pending_.clear();
}

void ViewproSim::run_until(double now_s) {
    if (!started_) {
        started_ = true;
        t0_ = now_s;
    }
    const double target = now_s - t0_;
    if (!(target >= t_)) return;  // time never runs backwards (NaN included)
    if (target - t_ > max_backlog_s) {
        const auto first =
            static_cast<std::uint64_t>(std::ceil((target - max_backlog_s) / output_period_s));
        next_tick_ = std::max(next_tick_, first);
    }
    while (static_cast<double>(next_tick_) * output_period_s <= target + tick_tolerance_s) {
        t_ = std::max(t_, static_cast<double>(next_tick_) * output_period_s);
        ++next_tick_;
        const viewpro::Mode mode = viewpro::decode_mode_byte(mode_byte_);
        if (!mode.serial) continue;  // network-only output goes to a port this model lacks
        const auto frame = viewpro::encode_output(measure());
        pending_.insert(pending_.end(), frame.begin(), frame.end());
    }
    t_ = target;
}

void ViewproSim::set_clock(const viewpro::DateTime& utc) {
    utc_at_t_base_s_ = viewpro::to_unix_seconds(utc);
    t_base_s_ = t_;
}

void ViewproSim::handle(const viewpro::InputFrame& frame) {
    using Kind = viewpro::InputFrame::Kind;
    switch (frame.kind) {
        case Kind::mode:
            // An undefined OUT format (5..7) is not a setting the gimbal could take: ignored.
            if (viewpro::mode_byte_is_defined(frame.bytes[3])) mode_byte_ = frame.bytes[3];
            break;
        case Kind::yaw_shift:
        case Kind::pitch_shift: {
            int& shift =
                frame.kind == Kind::yaw_shift ? yaw_shift_hundredths_ : pitch_shift_hundredths_;
            if (const auto step = viewpro::decode_shift(frame))
                shift = std::clamp(shift + *step, -max_shift_hundredths, max_shift_hundredths);
            break;
        }
        case Kind::in1:
        case Kind::in2:
            if (const auto v = viewpro::decode_vehicle(frame)) {
                pose_ = {v->lat_deg,  v->lon_deg,   v->alt_msl_m,
                         v->roll_deg, v->pitch_deg, v->yaw_deg};
                laser_range_m_.reset();
                set_clock(v->time);
            }
            break;
        case Kind::in3:
            if (const auto v = viewpro::decode_in3(frame)) {
                // IN3 carries no roll: the vehicle is taken as level about its x axis.
                pose_ = {v->lat_deg, v->lon_deg, v->alt_msl_m, 0.0, v->pitch_deg, v->yaw_deg};
                laser_range_m_ = v->lrf_m > 0 ? std::optional<double>(v->lrf_m) : std::nullopt;
                set_clock(v->time);
            }
            break;
    }
}

double ViewproSim::gimbal_yaw_deg() const {
    return wrap_180(options_.gimbal_yaw_deg + options_.gimbal_yaw_rate_dps * t_);
}

double ViewproSim::noise() {
    if (!(options_.angle_noise_deg > 0)) return 0;
    return std::normal_distribution<double>(0.0, options_.angle_noise_deg)(rng_);
}

viewpro::Output ViewproSim::measure() {
    viewpro::Output o;
    o.format = viewpro::decode_mode_byte(mode_byte_).format;
    const double utc_s = utc_at_t_base_s_ + (t_ - t_base_s_);
    o.time = viewpro::from_unix_seconds(utc_s);
    o.zoom = options_.zoom_position;

    const double pitch = options_.gimbal_pitch_deg, yaw = gimbal_yaw_deg();
    o.gimbal_roll_deg = options_.gimbal_roll_deg + noise();
    o.gimbal_pitch_deg = pitch + noise();
    o.gimbal_yaw_deg = yaw + noise();

    o.uav_roll_deg = pose_.roll_deg;
    o.uav_pitch_deg = pose_.pitch_deg;
    o.uav_yaw_deg = pose_.yaw_deg;
    o.uav_lat_deg = pose_.lat_deg;
    o.uav_lon_deg = pose_.lon_deg;
    o.uav_alt_msl_m = pose_.alt_msl_m;

    // The calculation uses the encoder angles plus the operator's shift corrections.
    const ViewproLook look{pitch + pitch_shift_hundredths_ / 100.0,
                           yaw + yaw_shift_hundredths_ / 100.0};
    const auto target = locate_viewpro_target(pose_, look, options_.terrain_alt_msl_m,
                                              options_.geoid_undulation_m, laser_range_m_);
    if (target) {  // no target (looking at the sky): zeros, as missing fields encode
        o.target_lat_deg = target->lat_deg;
        o.target_lon_deg = target->lon_deg;
        o.target_alt_msl_m = target->alt_msl_m;
        if (options_.has_laser || laser_range_m_) o.lrf_m = target->range_m;
    }
    return o;
}

std::unique_ptr<Device> make_viewpro_sim(const ViewproSimOptions& options) {
    return std::make_unique<ViewproSim>(options);
}

}  // namespace gimbal::sim
