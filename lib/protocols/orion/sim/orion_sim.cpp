#include "protocols/orion/sim/orion_sim.hpp"

#include <algorithm>
#include <cmath>

#include "protocols/orion/codec/codec.hpp"
#include "protocols/orion/codec/framing.hpp"
#include "protocols/orion/sim/orion_sim_info.hpp"
#include "protocols/orion/sim/orion_sim_model.hpp"
#include "sim/terrain.hpp"

namespace gimbal::sim {

namespace {

constexpr double max_step_s = 0.01;     // physics step
constexpr double max_backlog_s = 60.0;  // older periodic output is skipped, not replayed
// k * 0.1 is not exact in binary: a tick this close to the time asked for is due.
constexpr double tick_tolerance_s = 1e-9;
constexpr double gps_fix_valid_s = 2.0;  // an external GPS fix overrides the circle this long

CircleOptions circle_options(const OrionSimOptions& o) {
    CircleOptions c;
    c.centre = {o.lat_deg * deg, o.lon_deg * deg, o.alt_m};
    c.radius_m = o.radius_m;
    c.speed_mps = o.speed_mps;
    c.clockwise = o.clockwise;
    return c;
}

AxisLimits axis_limits(const OrionSimOptions& o) {
    AxisLimits a;
    a.pan_rate_max = std::abs(o.pan_rate_max_dps) * deg;
    a.tilt_rate_max = std::abs(o.tilt_rate_max_dps) * deg;
    a.tilt_min = std::min(o.tilt_min_deg, o.tilt_max_deg) * deg;
    a.tilt_max = std::max(o.tilt_min_deg, o.tilt_max_deg) * deg;
    return a;
}

PathOptions path_options(const OrionSimOptions& o) {
    PathOptions p;
    p.scan_speed_mps = o.path_scan_speed_mps;
    p.stare_time_s = o.stare_time_s;
    p.step_timeout_s = o.step_timeout_s;
    p.on_target_rad = o.on_target_deg * deg;
    return p;
}

// Where the gimbal looks when it starts: ahead and 30 degrees down, so the line of sight
// meets the terrain from the first telemetry on.
constexpr PanTilt start_angles{0, -30 * deg};

template <class P>
orion::Payload encoded(const P& packet) {
    orion::Payload payload;
    orion::encode(packet, payload);
    return payload;
}

bool is_version_id(std::uint8_t id) {
    namespace pkt = orion::pkt;
    return id == pkt::clevis_version || id == pkt::crown_version || id == pkt::payload_version ||
           id == pkt::tracker_version || id == pkt::retract_version || id == pkt::lensctl_version;
}

}  // namespace

OrionSim::OrionSim(const OrionSimOptions& options)
    : options_(options),
      terrain_(options.terrain_alt_m ? nullptr : terrain_surface()),
      circle_(circle_options(options)),
      path_options_(path_options(options)),
      on_target_rad_(options.on_target_deg * deg),
      axes_(axis_limits(options), start_angles),
      cameras_(info::cameras()),
      lasers_(options.lasers, options.laser_password),
      rng_(options.seed) {
    last_cmd_.mode = orion::Mode::position;
    last_cmd_.target = {start_angles.pan, start_angles.tilt};
    target_angles_ = start_angles;
    zoom_.assign(cameras_.cameras.size(), 1.0);

    namespace pkt = orion::pkt;
    schedule_ = {{pkt::geolocate_telemetry, 0.1},  {pkt::performance, 0.25},
                 {pkt::ins_quality, 1.0},          {pkt::gps_data, 1.0},
                 {pkt::software_diagnostics, 1.0}, {pkt::laser_states, 1.0},
                 {pkt::diagnostics, 3.0},          {pkt::vibration, 5.0}};
    if (options_.retract_installed) schedule_.push_back({pkt::retract_status, 1.0});

    orion::StartupCmd startup;
    startup.cmd = last_cmd_;
    settings_[pkt::startup_cmd] = encoded(startup);
    settings_[pkt::limits] = encoded(info::limits(axes_.limits()));
    settings_[pkt::network_settings] = encoded(info::network_settings());
    settings_[pkt::network_video] = encoded(info::network_video());
    settings_[pkt::ins_options] = encoded(info::ins_options());
    for (auto port : {orion::UserDataPort::ethernet, orion::UserDataPort::primary})
        uart_configs_[static_cast<std::uint8_t>(port)] = encoded(info::uart_config(port));

    update_platform(0);
}

// --- time --------------------------------------------------------------------------------------

void OrionSim::receive(std::span<const std::uint8_t> bytes, double now_s) {
    run_until(now_s);  // commands act on the state at the time they arrive
    framer_.push(bytes, [this](const orion::Frame& frame) { handle(frame); });
}

void OrionSim::advance(double now_s, std::vector<std::uint8_t>& out) {
    run_until(now_s);
    out.insert(out.end(), pending_.begin(), pending_.end());
    pending_.clear();
}

void OrionSim::run_until(double now_s) {
    if (!started_) {
        started_ = true;
        t0_ = now_s;
        orion::ResetSource reset;  // each processor reports its reset when it boots
        reset.source_board = orion::Board::crown;
        send(reset);
    }
    const double target = now_s - t0_;
    if (!(target >= t_)) return;  // time never runs backwards (NaN included)

    if (target - t_ > max_backlog_s) {
        // A caller that stopped calling for minutes gets the state of now, not minutes of
        // stale output: move on in coarse steps and skip the periodic packets of the gap.
        while (target - t_ > max_backlog_s) step(std::min(1.0, target - max_backlog_s - t_));
        for (auto& p : schedule_)
            p.next = std::max(p.next, static_cast<std::uint64_t>(std::ceil(t_ / p.period_s)));
    }
    while (true) {
        double due = target + 1;
        for (const auto& p : schedule_) due = std::min(due, p.due());
        if (due > target + tick_tolerance_s) break;
        step_to(due);
        for (auto& p : schedule_)
            if (p.due() <= t_ + tick_tolerance_s) {
                emit_periodic(p.id);
                ++p.next;
            }
    }
    step_to(target);
}

void OrionSim::step_to(double t) {
    while (t_ < t) step(std::min(max_step_s, t - t_));
}

void OrionSim::update_platform(double t) {
    if (gps_fix_ && t - gps_fix_t_ <= gps_fix_valid_s) {
        const auto& g = *gps_fix_;
        const Vec3 vel{g.vel_ned[0], g.vel_ned[1], g.vel_ned[2]};
        const Vec3 moved =
            to_ecef({g.lat, g.lon, g.alt}) + (t - gps_fix_t_) * (ned_to_ecef(g.lat, g.lon) * vel);
        platform_ = platform_from_fix(to_lla(moved), vel, platform_.yaw);
    } else {
        gps_fix_.reset();
        platform_ = circle_.at(t);
    }
    mount_to_ecef_ = mount_to_ecef(platform_.attitude, platform_.lla.lat, platform_.lla.lon);
}

// Runs the model from t_ to t_ + dt.
void OrionSim::step(double dt) {
    const double t = t_ + dt;
    update_platform(t);
    const Mat3 ecef_to_mount = transpose(mount_to_ecef_);
    const Mat3 ned_to_ecef_here = ned_to_ecef(platform_.lla.lat, platform_.lla.lon);

    // The direction (ECEF) the demand wants the line of sight along; zero for pure axis moves.
    Vec3 wanted;
    switch (demand_) {
        case Demand::hold:
            axes_.hold();
            break;
        case Demand::mount_angles:
            axes_.slew_toward(target_angles_, dt, within_limits_);
            break;
        case Demand::mount_rates:
            axes_.move_at(rates_.pan, rates_.tilt, dt, within_limits_);
            break;
        case Demand::inertial_rates:
            inertial_.pan = wrap_pi(inertial_.pan + rates_.pan * dt);
            inertial_.tilt = std::clamp(inertial_.tilt + rates_.tilt * dt, -pi / 2, pi / 2);
            [[fallthrough]];
        case Demand::inertial_angles:
            wanted = ned_to_ecef_here * los_in_mount(inertial_);  // NED uses the same axes
            break;
        case Demand::look_at_point:
            geo_point_ = geo_point_ + dt * (ned_to_ecef_here * geo_vel_ned_);
            wanted = geo_point_ - platform_.ecef;
            break;
        case Demand::look_down:
            wanted = ned_to_ecef_here * Vec3{0, 0, 1};
            break;
        case Demand::follow_path:
            wanted = path_->look_point() - platform_.ecef;
            break;
    }
    if (norm(wanted) > 0) axes_.slew_toward(pan_tilt_for(ecef_to_mount * wanted), dt);
    t_ = t;

    pointing_error_ = norm(wanted) > 0 ? angle_between(line_of_sight_dir(), wanted) : 0.0;
    if (demand_ == Demand::follow_path) {
        if (auto begin = path_->step(dt, platform_.ecef, pointing_error_)) send_stare_start(*begin);
    }
    if (demand_ == Demand::look_at_point && geo_stare_pending_ &&
        pointing_error_ <= on_target_rad_) {
        geo_stare_pending_ = false;
        StareBegin begin;
        begin.point_ecef = geo_point_;
        begin.max_stare_time_s = std::clamp(options_.stare_time_s, 0.0, 2.55);
        begin.slant_range_m = norm(wanted);
        send_stare_start(begin);
    }
    if (impulse_left_s_ > 0) {
        impulse_left_s_ -= dt;
        if (impulse_left_s_ <= 0) rates_ = {};  // the impulse is over: stop turning
    }
    retract_.step(dt);
}

std::uint32_t OrionSim::system_time_ms() const {
    return options_.uptime_at_start_ms + static_cast<std::uint32_t>(std::llround(t_ * 1000.0));
}

// A start time before the GPS epoch (1980) is clamped to it: week and time of week stay in range.
double OrionSim::gps_seconds() const {
    return std::max(0.0, options_.gps_time_at_start_s + t_);
}

// --- input -------------------------------------------------------------------------------------

void OrionSim::handle(const orion::Frame& frame) {
    namespace pkt = orion::pkt;
    const auto data = frame.data();
    if (data.empty()) {
        answer_request(frame.id);
        return;
    }
    switch (frame.id) {
        case pkt::cmd:
            if (auto c = orion::decode<orion::Cmd>(data)) {
                send_frame(frame.id, data);  // the gimbal echoes OrionCmd as received
                on_cmd(c.value.cmd);
            }
            break;
        case pkt::geopoint_cmd:
            if (auto g = orion::decode<orion::GeopointCmd>(data)) on_geopoint(g.value);
            break;
        case pkt::path:
            if (auto p = orion::decode<orion::Path>(data)) on_path(p.value);
            break;
        case pkt::laser_cmd:
            if (auto l = orion::decode<orion::LaserCmd>(data)) on_laser(l.value);
            break;
        case pkt::stare_ack:
            if (auto a = orion::decode<orion::StareAck>(data)) on_stare_ack(a.value);
            break;
        case pkt::camera_switch:
            if (auto s = orion::decode<orion::CameraSwitch>(data);
                s && s.value.index < cameras_.cameras.size())
                active_camera_ = s.value.index;
            break;
        case pkt::camera_state:
            if (auto s = orion::decode<orion::CameraState>(data);
                s && s.value.index < zoom_.size() && s.value.zoom > 0)
                zoom_[s.value.index] = std::max(1.0, s.value.zoom);
            break;
        case pkt::retract_cmd:
            if (auto r = orion::decode<orion::RetractCommand>(data);
                r && options_.retract_installed) {
                retract_.command(r.value.cmd);
                send(retract_status());
            }
            break;
        case pkt::range_data:
            if (auto r = orion::decode<orion::RangeData>(data)) {
                range_m_ = r.value.range_m;
                range_until_t_ = t_ + r.value.max_age_ms / 1000.0;
                range_source_ = r.value.source;
            }
            break;
        case pkt::gps_data:
            if (auto g = orion::decode<orion::GpsData>(data)) on_gps(g.value);
            break;
        case pkt::autopilot_data:
            if (auto ap = orion::decode<orion::AutopilotData>(data)) on_autopilot(ap.value);
            break;
        case pkt::uart_config:
            if (data.size() == 1) {  // the one-byte form asks for one port's configuration
                answer_uart_config(data[0]);
                break;
            }
            store_setting(frame.id, data);
            break;
        default:
            store_setting(frame.id, data);
            break;
    }
}

void OrionSim::on_cmd(const orion::PanTiltCmd& c) {
    using M = orion::Mode;
    const PanTilt target{wrap_pi(c.target[0]), c.target[1]};
    switch (c.mode) {
        case M::disabled:
        case M::calibration:
            demand_ = Demand::hold;
            break;
        case M::rate:
        case M::geo_rate:
        case M::scene:
        case M::track:
            rates_ = {c.target[0], c.target[1]};
            impulse_left_s_ = c.impulse_time_s > 0 ? c.impulse_time_s : -1;
            within_limits_ = true;
            if (c.stabilized) {
                inertial_ =
                    pan_tilt_for(dcm_from_quat(platform_.attitude) * los_in_mount(axes_.angles()));
                demand_ = Demand::inertial_rates;
            } else {
                demand_ = Demand::mount_rates;
            }
            break;
        case M::position:
        case M::position_no_limits:
        case M::ffc_manual:
            if (c.stabilized && c.mode == M::position) {
                inertial_ = target;  // azimuth from north, elevation above the horizon
                demand_ = Demand::inertial_angles;
            } else {
                target_angles_ = target;
                within_limits_ = c.mode != M::position_no_limits;
                demand_ = Demand::mount_angles;
            }
            break;
        case M::ffc_auto:  // look up at the black body
            target_angles_ = {0, axes_.limits().tilt_max};
            within_limits_ = true;
            demand_ = Demand::mount_angles;
            break;
        default:  // fault, geopoint, path, down and unknown cannot be commanded
            return;
    }
    mode_ = c.mode;
    last_cmd_ = c;
    path_.reset();
    geo_stare_pending_ = false;
}

void OrionSim::on_geopoint(const orion::GeopointCmd& g) {
    // A joystick geopoint (non-zero range while already in geopoint) keeps the point and only
    // takes the new velocity.
    const bool joystick = g.joystick_range_m != 0 && mode_ == orion::Mode::geopoint;
    if (!joystick) geo_point_ = to_ecef({g.target_lat, g.target_lon, g.target_alt});
    geo_vel_ned_ = {g.target_vel_ned[0], g.target_vel_ned[1], g.target_vel_ned[2]};
    const auto options = static_cast<unsigned>(g.options);
    geo_stare_pending_ = (options & 1u) != 0 && g.joystick_range_m == 0;
    mode_ = orion::Mode::geopoint;
    demand_ = Demand::look_at_point;
    path_.reset();
}

void OrionSim::on_path(const orion::Path& p) {
    if (p.points.empty()) {
        if (!p.point_down) return;  // nothing to follow and not asked to look down
        mode_ = orion::Mode::down;
        demand_ = Demand::look_down;
        path_.reset();
        return;
    }
    std::vector<Vec3> points;
    for (const auto& point : p.points)
        points.push_back({point.pos_ecef[0], point.pos_ecef[1], point.pos_ecef[2]});
    StepStare step_stare{p.along_track_step_angle, p.num_cross_track_steps,
                         p.cross_track_step_ratio};
    path_.emplace(std::move(points), step_stare, path_options_);
    mode_ = orion::Mode::path;
    demand_ = Demand::follow_path;
    geo_stare_pending_ = false;
}

void OrionSim::on_laser(const orion::LaserCmd& c) {
    LaserRequest r;
    r.index = c.index;
    r.password = c.password;
    r.enable = c.enable;
    r.arm = c.arm;
    r.fire = c.fire;
    r.on_time_ms = c.on_time_ms;
    r.off_time_ms = c.off_time_ms;
    r.prf_code = c.prf_code;
    r.safety_bypass = c.safety_bypass;
    lasers_.command(r);
    send(laser_states());  // the states packet is the gimbal's answer
}

void OrionSim::on_autopilot(const orion::AutopilotData& ap) {
    LaserInterlocks locks;
    locks.altitude = ap.agl < 0 || ap.agl < options_.laser_min_agl_m;
    locks.ap_comm = !ap.comm_good;
    locks.ap_flying = !ap.is_flying;
    lasers_.set_interlocks(locks);
}

void OrionSim::on_stare_ack(const orion::StareAck& ack) {
    if (path_ && ack.echo_system_time_ms == stare_system_time_ms_) path_->acknowledge();
}

void OrionSim::on_gps(const orion::GpsData& gps) {
    gps_fix_ = gps;
    gps_fix_t_ = t_;
    update_platform(t_);
}

// Zero-length packets ask for that packet (a version id asks for every version packet).
void OrionSim::answer_request(std::uint8_t id) {
    namespace pkt = orion::pkt;
    if (is_version_id(id)) {
        send(info::clevis_version());
        send(info::crown_version());
        send(info::payload_version());
        send(info::tracker_version());
        send(info::retract_version());
        send(info::lensctl_version());
        return;
    }
    switch (id) {
        case pkt::cmd:
            send(orion::Cmd{last_cmd_});
            return;
        case pkt::geolocate_telemetry:
        case pkt::performance:
        case pkt::diagnostics:
        case pkt::ins_quality:
        case pkt::gps_data:
        case pkt::software_diagnostics:
        case pkt::vibration:
        case pkt::laser_states:
            emit_periodic(id);
            return;
        case pkt::retract_status:
            if (options_.retract_installed) send(retract_status());
            return;
        case pkt::network_diagnostics:
            send(network_diagnostics());
            return;
        case pkt::cameras:
            send(cameras_);
            return;
        case pkt::board:
            for (const auto& b : info::boards()) send(b);
            return;
        case pkt::reset_source: {
            orion::ResetSource reset;
            reset.source_board = orion::Board::crown;
            send(reset);
            return;
        }
        case pkt::uart_config:
            answer_uart_config(static_cast<std::uint8_t>(orion::UserDataPort::current));
            return;
        default: {
            const auto it = settings_.find(id);
            if (it != settings_.end()) send_frame(id, it->second.view());
            return;
        }
    }
}

void OrionSim::answer_uart_config(std::uint8_t port) {
    if (port == static_cast<std::uint8_t>(orion::UserDataPort::current))
        port = static_cast<std::uint8_t>(orion::UserDataPort::ethernet);  // we talk over ethernet
    const auto it = uart_configs_.find(port);
    if (it != uart_configs_.end())
        send_frame(orion::pkt::uart_config, it->second.view());
    else
        send(info::uart_config(static_cast<orion::UserDataPort>(port)));  // an unused port
}

// A configuration packet with data sets that configuration; the gimbal answers with the
// configuration now in force. Packets the model does not keep are ignored.
void OrionSim::store_setting(std::uint8_t id, std::span<const std::uint8_t> data) {
    namespace pkt = orion::pkt;
    bool ok = false;
    switch (id) {
        case pkt::limits:
            if (auto l = orion::decode<orion::Limits>(data)) {
                axes_.set_limits(info::axis_limits(l.value));
                ok = true;
            }
            break;
        case pkt::uart_config:
            if (auto u = orion::decode<orion::UartConfig>(data)) {
                auto config = u.value;
                if (config.port == orion::UserDataPort::current)
                    config.port = orion::UserDataPort::ethernet;
                const auto key = static_cast<std::uint8_t>(config.port);
                uart_configs_[key] = encoded(config);
                send_frame(id, uart_configs_[key].view());
            }
            return;
        case pkt::cameras:  // fixed by the hardware: answer what is installed
            send(cameras_);
            return;
        case pkt::startup_cmd:
            ok = static_cast<bool>(orion::decode<orion::StartupCmd>(data));
            break;
        case pkt::network_settings:
            ok = static_cast<bool>(orion::decode<orion::NetworkSettings>(data));
            break;
        case pkt::network_video:
            ok = static_cast<bool>(orion::decode<orion::NetworkVideo>(data));
            break;
        case pkt::ins_options:
            ok = static_cast<bool>(orion::decode<orion::InsOptions>(data));
            break;
        case pkt::flir_settings:
            ok = static_cast<bool>(orion::decode<orion::FlirSettings>(data));
            break;
        case pkt::sony_settings:
            ok = static_cast<bool>(orion::decode<orion::SonySettings>(data));
            break;
        default:
            return;
    }
    if (!ok) return;
    orion::Payload stored;
    stored.size = std::min(data.size(), orion::max_data_length);
    std::copy_n(data.begin(), stored.size, stored.bytes.begin());
    settings_[id] = stored;
    send_frame(id, stored.view());
}

// --- factory -----------------------------------------------------------------------------------

std::vector<orion::LaserType> default_lasers() {
    return {orion::LaserType::pointer, orion::LaserType::lightware};
}

std::unique_ptr<Device> make_orion_sim(const OrionSimOptions& options) {
    return std::make_unique<OrionSim>(options);
}

std::vector<std::uint8_t> orion_sim_crown_version_frame() {
    return orion::to_wire(info::crown_version());
}

}  // namespace gimbal::sim
