#include "protocols/mavlink_device/mavlink_device_steering.hpp"

#include <cmath>

#include "protocols/mavlink_device/mavlink_device_flags.hpp"
#include "session/capabilities.hpp"

namespace gimbal::protocols {

namespace {

constexpr double deg_to_rad = 3.14159265358979323846 / 180.0;
// The look-ahead of the line of sight's rate (feed-forward for the device between updates).
constexpr double rate_dt_s = 0.05;
constexpr std::uint16_t locks = device_flags::roll_lock | device_flags::pitch_lock;
// GIMBAL_DEVICE_CAP_FLAGS.
constexpr std::uint32_t cap_has_yaw_lock = 1024;
constexpr std::uint32_t cap_yaw_in_earth_frame = 4096;

mavlink::GimbalDeviceSetAttitude attitude(double roll_deg, double pitch_deg, double yaw_deg,
                                          std::uint16_t frame_flag) {
    mavlink::GimbalDeviceSetAttitude m;
    const auto q = geo::normalized(geo::euler_to_quat(geo::EulerDeg{roll_deg, pitch_deg, yaw_deg}));
    m.q = {static_cast<float>(q.w), static_cast<float>(q.x), static_cast<float>(q.y),
           static_cast<float>(q.z)};
    m.flags = static_cast<std::uint16_t>(locks | frame_flag);
    return m;
}

geo::Lla moved(const geo::Lla& p, const std::array<double, 3>& v_ned, double dt) {
    if (dt == 0 || (v_ned[0] == 0 && v_ned[1] == 0 && v_ned[2] == 0)) return p;
    const geo::Vec3 d = geo::ned_to_ecef(geo::Vec3{v_ned[0] * dt, v_ned[1] * dt, v_ned[2] * dt}, p);
    return geo::ecef_to_lla(geo::lla_to_ecef(p) + d);
}

// The frame flags of a stabilized (earth-frame) set-point: YAW_LOCK asks the device to keep
// the heading between set-points, the frame flag says how the yaw is given.
std::uint16_t north_flags(NorthYaw how) {
    switch (how) {
        case NorthYaw::earth_frame:
            return device_flags::yaw_lock | device_flags::yaw_in_earth_frame;
        case NorthYaw::yaw_lock:
            return device_flags::yaw_lock;
        case NorthYaw::from_heading:
            break;
    }
    return device_flags::yaw_in_vehicle_frame;
}

}  // namespace

NorthYaw north_yaw_of(std::uint32_t cap_flags) {
    if ((cap_flags & cap_yaw_in_earth_frame) != 0) return NorthYaw::earth_frame;
    if ((cap_flags & cap_has_yaw_lock) != 0) return NorthYaw::yaw_lock;
    return NorthYaw::from_heading;
}

geo::Lla geopoint_at(const HoldGeopoint& g, double now_s) {
    return moved(g.point, g.vel_ned, now_s - g.since_s);
}

mavlink::GimbalDeviceSetAttitude vehicle_frame_attitude(double pan_deg, double tilt_deg) {
    return attitude(0, tilt_deg, pan_deg, device_flags::yaw_in_vehicle_frame);
}

std::optional<mavlink::GimbalDeviceSetAttitude> MavlinkDeviceSteering::command(
    const std::optional<vehicle::AircraftFix>& fix, const std::optional<geo::Lla>& camera,
    const std::optional<Aim>& aim, double now_s) {
    if (const auto* a = std::get_if<HoldAngles>(&hold_))
        return vehicle_frame_attitude(a->pan_deg, a->tilt_deg);
    if (const auto* h = std::get_if<HoldHeading>(&hold_)) return heading(*h, fix);
    if (const auto* r = std::get_if<HoldRates>(&hold_)) return rates(*r, fix, now_s);
    if (!fix || !camera) return std::nullopt;

    geo::Lla target;
    std::array<double, 3> target_vel{};
    if (auto* g = std::get_if<HoldGeopoint>(&hold_)) {
        target = geopoint_at(*g, now_s);
        target_vel = g->vel_ned;
    } else if (auto* p = std::get_if<HoldPath>(&hold_)) {
        const geo::Vec3 at = geo::lla_to_ecef(*camera);
        double error = 3.14159265358979323846;
        if (aim) {
            const geo::Vec3 los =
                geo::ned_to_ecef(geo::rotate(aim->camera_to_ned, geo::Vec3{1, 0, 0}), *camera);
            error = sim::angle_between(los, p->follower->look_point() - at);
        }
        if (auto begun = p->follower->step(std::max(0.0, now_s - p->last_s), at, error))
            stare_began_ = begun;
        p->last_s = now_s;
        target = geo::ecef_to_lla(p->follower->look_point());
    } else {
        return std::nullopt;
    }

    const auto look = geo::look_angles(*camera, target);
    if (!(look.range_m > 0)) return std::nullopt;
    // The line of sight's rate over the next tick, from both velocities: sent with the
    // attitude so the device moves between updates.
    const std::array<double, 3> own{fix->vn_mps, fix->ve_mps, fix->vd_mps};
    const auto ahead =
        geo::look_angles(moved(*camera, own, rate_dt_s), moved(target, target_vel, rate_dt_s));
    const double yaw_rate = session::wrap180(ahead.azimuth_deg - look.azimuth_deg) / rate_dt_s;
    const double pitch_rate = (ahead.elevation_deg - look.elevation_deg) / rate_dt_s;

    mavlink::GimbalDeviceSetAttitude m;
    if (north_yaw_ == NorthYaw::earth_frame) {
        m = attitude(0, look.elevation_deg, look.azimuth_deg, device_flags::yaw_in_earth_frame);
        m.angular_velocity_z = static_cast<float>(yaw_rate * deg_to_rad);
    } else {
        m = attitude(0, look.elevation_deg, session::wrap180(look.azimuth_deg - fix->yaw_deg),
                     device_flags::yaw_in_vehicle_frame);
        m.angular_velocity_z = static_cast<float>((yaw_rate - fix->yaw_rate_dps) * deg_to_rad);
    }
    m.angular_velocity_y = static_cast<float>(pitch_rate * deg_to_rad);
    return m;
}

std::optional<mavlink::GimbalDeviceSetAttitude> MavlinkDeviceSteering::heading(
    const HoldHeading& h, const std::optional<vehicle::AircraftFix>& fix) const {
    if (north_yaw_ != NorthYaw::from_heading)
        return attitude(0, h.tilt_deg, h.yaw_deg, north_flags(north_yaw_));
    // The device takes only yaw from the nose: the heading's, now, and the aircraft's turn
    // against it as feed-forward so the device holds between set-points.
    if (!fix) return std::nullopt;
    auto m = attitude(0, h.tilt_deg, session::wrap180(h.yaw_deg - fix->yaw_deg),
                      device_flags::yaw_in_vehicle_frame);
    m.angular_velocity_z = static_cast<float>(-fix->yaw_rate_dps * deg_to_rad);
    return m;
}

mavlink::GimbalDeviceSetAttitude MavlinkDeviceSteering::rates(
    const HoldRates& r, const std::optional<vehicle::AircraftFix>& fix, double now_s) const {
    mavlink::GimbalDeviceSetAttitude m;
    m.q = {mavlink::nan_f, mavlink::nan_f, mavlink::nan_f, mavlink::nan_f};
    const bool running = !r.until_s || now_s < *r.until_s;
    double pan_dps = running ? r.pan_dps : 0.0;
    m.angular_velocity_y = static_cast<float>(running ? r.tilt_dps * deg_to_rad : 0.0);
    std::uint16_t frame = device_flags::yaw_in_vehicle_frame;
    if (r.earth) {
        frame = north_flags(north_yaw_);
        // A device that integrates only from the nose is given the aircraft's turn against
        // the rate (without a fix it integrates from the nose).
        if (north_yaw_ == NorthYaw::from_heading && fix) pan_dps -= fix->yaw_rate_dps;
    }
    m.angular_velocity_z = static_cast<float>(pan_dps * deg_to_rad);
    m.flags = static_cast<std::uint16_t>(locks | frame);
    return m;
}

}  // namespace gimbal::protocols
