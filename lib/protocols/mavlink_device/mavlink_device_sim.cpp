#include "protocols/mavlink_device/mavlink_device_sim.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "protocols/mavlink_device/mavlink_device_flags.hpp"
#include "protocols/mavlink_device/mavlink_device_state.hpp"
#include "session/capabilities.hpp"

namespace gimbal::protocols {

namespace {

constexpr double rad_to_deg = 180.0 / 3.14159265358979323846;
constexpr double deg_to_rad = 1.0 / rad_to_deg;
constexpr double max_step_s = 0.005;
// Feed-forward rates carry an angle target this long at most (the manager updates at 20 Hz).
constexpr double max_extrapolation_s = 0.5;
// Without a manager's heartbeat or command for this long: GIMBAL_DEVICE_ERROR_FLAGS_NO_MANAGER.
constexpr double manager_timeout_s = 3.0;
constexpr std::uint32_t at_pitch_limit = 2, at_yaw_limit = 4, no_manager = 512;
// HAS_NEUTRAL, HAS_PITCH_AXIS, HAS_PITCH_LOCK, HAS_YAW_AXIS, HAS_YAW_FOLLOW, HAS_YAW_LOCK,
// SUPPORTS_YAW_IN_EARTH_FRAME.
constexpr std::uint16_t cap_flags = 2 | 32 | 128 | 256 | 512 | 1024 | 4096;
constexpr std::uint16_t infinite_yaw = 2048;

void put_text(std::array<std::uint8_t, 32>& to, const char* text) {
    std::memcpy(to.data(), text, std::min<std::size_t>(std::strlen(text), to.size()));
}

double toward(double from, double to, double max_step) {
    return from + std::clamp(to - from, -max_step, max_step);
}

}  // namespace

MavlinkDeviceSim::MavlinkDeviceSim(const MavlinkDeviceSimOptions& options)
    : options_(options),
      signatures_(options.signing_key),
      framer_(signatures_.framer_options()),
      sender_(options.system_id, options.component_id, options.signing_key),
      rng_(options.seed),
      pitch_(options.pitch_deg),
      yaw_(options.yaw_deg) {}

bool MavlinkDeviceSim::yaw_continuous() const {
    return options_.yaw_max_deg - options_.yaw_min_deg >= 360;
}

double MavlinkDeviceSim::clamp_yaw(double yaw, bool& at_limit) const {
    if (yaw_continuous()) return session::wrap180(yaw);
    const double c = std::clamp(yaw, options_.yaw_min_deg, options_.yaw_max_deg);
    at_limit = at_limit || c != yaw;
    return c;
}

double MavlinkDeviceSim::vehicle_yaw_deg(double now_s) const {
    const double dt = std::clamp(now_s - vehicle_yaw_s_, 0.0, max_extrapolation_s);
    return session::wrap180(vehicle_yaw_ + vehicle_yaw_rate_ * dt);
}

double MavlinkDeviceSim::vehicle_yaw_rate_at(double now_s) const {
    return now_s - vehicle_yaw_s_ <= max_extrapolation_s ? vehicle_yaw_rate_ : 0.0;
}

void MavlinkDeviceSim::receive(std::span<const std::uint8_t> bytes, double now_s) {
    framer_.push(bytes, [&](const mavlink::Message& m) {
        if (!signatures_.accept(m, options_.unix_time_s + now_s)) return;
        sender_.follow(signatures_.latest());
        on_message(m, now_s);
    });
}

void MavlinkDeviceSim::on_message(const mavlink::Message& m, double now_s) {
    using namespace mavlink;
    if (std::holds_alternative<Heartbeat>(m.payload)) {
        manager_heard_s_ = now_s;
    } else if (const auto* c = std::get_if<CommandLong>(&m.payload)) {
        if (c->target_component != 0 && c->target_component != options_.component_id) return;
        manager_heard_s_ = now_s;
        if (c->command == mav_cmd::request_message &&
            static_cast<std::uint32_t>(c->param[0]) == GimbalDeviceInformation::id) {
            ++information_requests_;
            acks_.emplace_back(c->command, static_cast<std::uint8_t>(MavResult::accepted));
        } else {
            acks_.emplace_back(c->command, static_cast<std::uint8_t>(MavResult::unsupported));
        }
    } else if (const auto* a = std::get_if<AutopilotStateForGimbalDevice>(&m.payload)) {
        if (const auto e = euler_of(a->q)) {
            vehicle_yaw_ = e->yaw_deg;
            vehicle_yaw_s_ = now_s;
            vehicle_yaw_rate_ = std::isfinite(a->feed_forward_angular_velocity_z)
                                    ? a->feed_forward_angular_velocity_z * rad_to_deg
                                    : 0.0;
        }
    } else if (const auto* s = std::get_if<GimbalDeviceSetAttitude>(&m.payload)) {
        if (s->target_component != 0 && s->target_component != options_.component_id) return;
        manager_heard_s_ = now_s;
        Target t;
        t.earth = yaw_in_earth_frame(s->flags);
        t.since_s = now_s;
        const auto rate = [](float v) { return std::isfinite(v) ? v * rad_to_deg : 0.0; };
        t.pitch_rate = rate(s->angular_velocity_y);
        t.yaw_rate = rate(s->angular_velocity_z);
        if (const auto e = euler_of(s->q)) {
            t.angles = true;
            t.pitch = e->pitch_deg;
            t.yaw = e->yaw_deg;
        } else if (!std::isfinite(s->angular_velocity_y) && !std::isfinite(s->angular_velocity_z)) {
            return;  // neither angles nor rates: nothing to do
        }
        target_ = t;
        report_earth_ = t.earth;
    }
}

void MavlinkDeviceSim::step(double dt, double now_s) {
    failure_flags_ = 0;
    const double vehicle_yaw = vehicle_yaw_deg(now_s);
    const double max_move = options_.slew_rate_dps * dt;
    const double pitch_before = pitch_, yaw_before = yaw_;
    bool pitch_limit = false, yaw_limit = false;
    if (target_ && target_->angles) {
        const double ahead = std::min(now_s - target_->since_s, max_extrapolation_s);
        double want_pitch = target_->pitch + target_->pitch_rate * ahead;
        double want_yaw = target_->yaw + target_->yaw_rate * ahead;
        if (target_->earth) want_yaw -= vehicle_yaw;
        const double clamped_pitch =
            std::clamp(want_pitch, options_.pitch_min_deg, options_.pitch_max_deg);
        pitch_limit = clamped_pitch != want_pitch;
        want_yaw = clamp_yaw(yaw_continuous() ? want_yaw : session::wrap180(want_yaw), yaw_limit);
        pitch_ = toward(pitch_, clamped_pitch, max_move);
        const double dyaw = yaw_continuous() ? session::wrap180(want_yaw - yaw_) : want_yaw - yaw_;
        yaw_ = yaw_ + std::clamp(dyaw, -max_move, max_move);
    } else if (target_) {
        const auto limit = [&](double rate) {
            return std::clamp(rate, -options_.slew_rate_dps, options_.slew_rate_dps);
        };
        const double p = pitch_ + limit(target_->pitch_rate) * dt;
        pitch_ = std::clamp(p, options_.pitch_min_deg, options_.pitch_max_deg);
        pitch_limit = pitch_ != p;
        // A yaw rate from north turns the axis against the aircraft's own turn.
        const double yaw_rate =
            target_->yaw_rate - (target_->earth ? vehicle_yaw_rate_at(now_s) : 0.0);
        yaw_ += limit(yaw_rate) * dt;
    }
    yaw_ = clamp_yaw(yaw_, yaw_limit);
    if (dt > 0) {
        pitch_rate_ = (pitch_ - pitch_before) / dt;
        yaw_rate_ = session::wrap180(yaw_ - yaw_before) / dt;
    }
    if (pitch_limit) failure_flags_ |= at_pitch_limit;
    if (yaw_limit) failure_flags_ |= at_yaw_limit;
    if (!manager_heard_s_ || now_s - *manager_heard_s_ > manager_timeout_s)
        failure_flags_ |= no_manager;
}

void MavlinkDeviceSim::send_status(double now_s, std::vector<std::uint8_t>& out) {
    std::normal_distribution<double> noise(0.0, options_.angle_noise_deg);
    const auto jitter = [&] { return options_.angle_noise_deg > 0 ? noise(rng_) : 0.0; };
    mavlink::GimbalDeviceAttitudeStatus s;
    s.time_boot_ms = static_cast<std::uint32_t>(now_s * 1000);
    const double yaw = report_earth_ ? yaw_ + vehicle_yaw_deg(now_s) : yaw_;
    const auto q = geo::normalized(
        geo::euler_to_quat(geo::EulerDeg{0, pitch_ + jitter(), session::wrap180(yaw + jitter())}));
    s.q = {static_cast<float>(q.w), static_cast<float>(q.x), static_cast<float>(q.y),
           static_cast<float>(q.z)};
    s.angular_velocity_x = 0;
    s.angular_velocity_y = static_cast<float>(pitch_rate_ * deg_to_rad);
    s.angular_velocity_z = static_cast<float>(yaw_rate_ * deg_to_rad);
    s.failure_flags = failure_flags_;
    s.flags = static_cast<std::uint16_t>(
        device_flags::roll_lock | device_flags::pitch_lock |
        (report_earth_ ? device_flags::yaw_in_earth_frame | device_flags::yaw_lock
                       : device_flags::yaw_in_vehicle_frame));
    s.gimbal_device_id = 0;
    const auto frame = make_frame(s);
    out.insert(out.end(), frame.begin(), frame.end());
}

void MavlinkDeviceSim::send_information(std::vector<std::uint8_t>& out) {
    mavlink::GimbalDeviceInformation i;
    i.uid = 0x6769'6D62'616C'6400ULL | options_.component_id;
    i.firmware_version = firmware_version;
    i.hardware_version = 1;
    i.roll_min = static_cast<float>(-45 * deg_to_rad);
    i.roll_max = static_cast<float>(45 * deg_to_rad);
    i.pitch_min = static_cast<float>(options_.pitch_min_deg * deg_to_rad);
    i.pitch_max = static_cast<float>(options_.pitch_max_deg * deg_to_rad);
    if (!yaw_continuous()) {
        i.yaw_min = static_cast<float>(options_.yaw_min_deg * deg_to_rad);
        i.yaw_max = static_cast<float>(options_.yaw_max_deg * deg_to_rad);
    }
    i.cap_flags = static_cast<std::uint16_t>(cap_flags | (yaw_continuous() ? infinite_yaw : 0));
    put_text(i.vendor_name, "gimbald");
    put_text(i.model_name, "simulated MAVLink gimbal");
    put_text(i.custom_name, "gimbal-sim");
    const auto frame = make_frame(i);
    out.insert(out.end(), frame.begin(), frame.end());
}

void MavlinkDeviceSim::advance(double now_s, std::vector<std::uint8_t>& out) {
    if (!started_) {
        started_ = true;
        time_ = now_s;
        next_status_s_ = now_s;
        next_heartbeat_s_ = now_s;
    }
    const double status_period = 1.0 / std::max(options_.attitude_rate_hz, 0.1);
    while (time_ < now_s) {
        const double dt = std::min(max_step_s, now_s - time_);
        time_ += dt;
        step(dt, time_);
        if (time_ >= next_heartbeat_s_) {
            mavlink::Heartbeat hb;
            hb.type = mavlink::mav_type_gimbal;
            hb.autopilot = mavlink::mav_autopilot_invalid;
            hb.system_status = 4;  // MAV_STATE_ACTIVE
            const auto frame = make_frame(hb);
            out.insert(out.end(), frame.begin(), frame.end());
            next_heartbeat_s_ += 1.0;
        }
        if (time_ >= next_status_s_) {
            send_status(time_, out);
            next_status_s_ += status_period;
            if (next_status_s_ < time_) next_status_s_ = time_ + status_period;
        }
    }
    for (const auto& [command, result] : acks_) {
        mavlink::CommandAck ack;
        ack.command = command;
        ack.result = result;
        const auto frame = make_frame(ack);
        out.insert(out.end(), frame.begin(), frame.end());
    }
    acks_.clear();
    for (; information_requests_ > 0; --information_requests_) send_information(out);
}

std::unique_ptr<sim::Device> make_mavlink_device_sim(const MavlinkDeviceSimOptions& options) {
    return std::make_unique<MavlinkDeviceSim>(options);
}

}  // namespace gimbal::protocols
