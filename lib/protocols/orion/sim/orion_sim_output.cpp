// What the simulated Orion sends: periodic telemetry and health packets, and the packets built
// from its state on request. Health numbers are plausible constants with seeded noise.
#include <algorithm>
#include <cmath>

#include "protocols/orion/codec/codec.hpp"
#include "protocols/orion/codec/framing.hpp"
#include "protocols/orion/sim/camera.hpp"
#include "protocols/orion/sim/orion_sim_model.hpp"
#include "sim/terrain.hpp"

namespace gimbal::sim {

namespace {

constexpr double seconds_per_week = 604800.0;
constexpr double max_los_component_m = 32767.0;  // I16 losECEF

std::array<double, 4> quat_array(const Quat& q) {
    const double s = q.w < 0 ? -1.0 : 1.0;  // report the hemisphere with w >= 0
    return {s * q.w, s * q.x, s * q.y, s * q.z};
}

}  // namespace

void OrionSim::send_frame(std::uint8_t id, std::span<const std::uint8_t> data) {
    const std::size_t before = pending_.size();
    orion::append_frame(id, data, pending_);
    tx_bytes_ += pending_.size() - before;
    ++tx_packets_;
}

double OrionSim::noise(double sigma) {
    std::normal_distribution<double> n(0.0, sigma);
    return n(rng_);
}

void OrionSim::emit_periodic(std::uint8_t id) {
    namespace pkt = orion::pkt;
    switch (id) {
        case pkt::geolocate_telemetry:
            send(telemetry());
            break;
        case pkt::performance:
            send(performance());
            break;
        case pkt::diagnostics:
            send(diagnostics());
            break;
        case pkt::ins_quality:
            send(ins_quality());
            break;
        case pkt::gps_data:
            send(gps_data());
            break;
        case pkt::software_diagnostics:
            send(software_diagnostics());
            break;
        case pkt::vibration:
            send(vibration());
            break;
        case pkt::laser_states:
            if (!lasers_.units().empty()) send(laser_states());
            break;
        case pkt::retract_status:
            send(retract_status());
            break;
        default:
            break;
    }
}

Vec3 OrionSim::line_of_sight_dir() const {
    return mount_to_ecef_ * los_in_mount(axes_.angles());
}

std::optional<Vec3> OrionSim::ground_hit(Vec3 dir) const {
    if (options_.terrain_alt_m)
        return hit_flat_terrain(platform_.ecef, dir, *options_.terrain_alt_m);
    // Beyond the I16 field's reach the gimbal reports no location anyway.
    const geo::RayOptions reach{2 * max_los_component_m};
    const Lla& p = platform_.lla;
    const auto hit = terrain_->intersect({p.lat / deg, p.lon / deg, p.alt}, dir, reach);
    if (hit.status != geo::RayStatus::hit) return std::nullopt;
    return geo::lla_to_ecef(hit.point);
}

Vec3 OrionSim::line_of_sight_vector(orion::RangeSource& source) const {
    const Vec3 dir = line_of_sight_dir();
    Vec3 v;
    if (t_ <= range_until_t_ && range_m_ > 0) {  // a client's range, while it is fresh
        v = range_m_ * dir;
        source = range_source_;
    } else if (auto hit = ground_hit(dir)) {
        v = *hit - platform_.ecef;
        source = orion::RangeSource::internal;
    } else {
        source = orion::RangeSource::none;
        return {};
    }
    if (std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}) > max_los_component_m) {
        source = orion::RangeSource::none;  // too far for the field: report no location
        return {};
    }
    return v;
}

orion::GeolocateTelemetry OrionSim::telemetry() const {
    orion::GeolocateTelemetry t;
    const double gps_s = gps_seconds();
    const double week = std::floor(gps_s / seconds_per_week);
    t.system_time_ms = system_time_ms();
    t.gps_week = static_cast<std::uint16_t>(week);
    t.gps_itow_ms =
        static_cast<std::uint32_t>(std::llround((gps_s - week * seconds_per_week) * 1000));
    t.geoid_undulation = options_.geoid_undulation_m;
    t.lat = platform_.lla.lat;
    t.lon = platform_.lla.lon;
    t.alt = platform_.lla.alt;
    t.vel_ned = {platform_.vel_ned.x, platform_.vel_ned.y, platform_.vel_ned.z};
    t.quat = quat_array(platform_.attitude);
    t.pan = axes_.angles().pan;
    t.tilt = axes_.angles().tilt;
    const auto& camera = cameras_.cameras[active_camera_];
    const FieldOfView fov = field_of_view(camera, zoom_[active_camera_]);
    t.hfov = fov.horizontal;
    t.vfov = fov.vertical;
    const Vec3 los = line_of_sight_vector(t.range_source);
    t.los_ecef = {los.x, los.y, los.z};
    t.pixel_width = camera.array_width;
    t.pixel_height = camera.array_height;
    t.mode = mode_;
    if (path_) {
        t.path_progress = path_->progress();
        t.stare_time_s = path_->stare_remaining_s();
        t.path_from = path_->from_index();
        t.path_to = path_->to_index();
    }
    t.leap_seconds = options_.leap_seconds;
    return t;
}

void OrionSim::send_stare_start(const StareBegin& b) {
    orion::StareStart s;
    s.system_time_ms = system_time_ms();
    s.max_stare_time_s = b.max_stare_time_s;
    s.along_track_stare = b.along_track;
    s.prev_stare_terminated_by_time = b.prev_terminated_by_time;
    s.stare_started_by_time = b.started_by_time;
    s.gimbal_data_valid = true;
    s.prev_stare_time_s = b.prev_stare_time_s;
    s.stare_load = b.stare_load;
    const Lla point = to_lla(b.point_ecef);
    s.lat = point.lat;
    s.lon = point.lon;
    s.alt = point.alt;
    s.gimbal_lat = platform_.lla.lat;
    s.gimbal_lon = platform_.lla.lon;
    s.gimbal_alt = platform_.lla.alt;
    s.gimbal_quat = quat_array(platform_.attitude);
    s.pan = axes_.angles().pan;
    s.tilt = axes_.angles().tilt;
    s.range_source = orion::RangeSource::internal;
    s.slant_range = b.slant_range_m;
    s.cross_stare_angle = b.cross_angle;
    stare_system_time_ms_ = s.system_time_ms;
    send(s);
}

orion::Performance OrionSim::performance() {
    orion::Performance p;
    const PanTilt rate = axes_.rates();
    const double rate_fraction[2] = {std::abs(rate.pan) / axes_.limits().pan_rate_max,
                                     std::abs(rate.tilt) / axes_.limits().tilt_rate_max};
    for (std::size_t axis = 0; axis < 2; ++axis) {
        p.rms_quad[axis] = std::abs(4e-6 + noise(5e-7));
        p.rms_dir[axis] = std::abs(6e-6 + noise(5e-7));
        p.rms_vel[axis] = std::abs(0.002 + noise(2e-4));
        p.rms_pos[axis] = std::abs(1e-5 + noise(1e-6));
        p.iout[axis] = std::abs(0.15 + 1.2 * rate_fraction[axis] + noise(0.01));
    }
    return p;
}

orion::Diagnostics OrionSim::diagnostics() {
    orion::Diagnostics d;
    const PanTilt rate = axes_.rates();
    const double motor = std::abs(rate.pan) + std::abs(rate.tilt);
    d.voltage24 = 24.1 + noise(0.02);
    d.voltage12 = 12.02 + noise(0.01);
    d.voltage3v3 = 3.31 + noise(0.003);
    d.current24 = 0.9 + 0.8 * motor + noise(0.02);
    d.current12 = 0.62 + noise(0.01);
    d.current3v3 = 0.41 + noise(0.005);
    d.crown_temp = std::round(38 + noise(0.4));
    d.sla_temp = 0;  // no SLA-1500 board
    d.gyro_temp = std::round(41 + noise(0.4));
    d.voltage24_var = 0.0004;
    d.voltage12_var = 0.0001;
    d.voltage3v3_var = 0.00001;
    d.current24_var = 0.0009;
    d.current12_var = 0.0002;
    d.current3v3_var = 0.00002;
    return d;
}

orion::InsQuality OrionSim::ins_quality() {
    orion::InsQuality q;
    q.system_time_ms = system_time_ms();
    q.gps_source = gps_fix_ ? orion::GpsSource::external : orion::GpsSource::ublox;
    q.imu_type = orion::ImuType::internal;
    q.ins_mode = orion::InsMode::run;
    q.has_gyro_bias = true;
    q.gps_period_s = gps_fix_ ? 0.25 : 0.2;
    q.hdg_period_s = 0;
    q.pos_chi_square = std::abs(1.0 + noise(0.2));
    q.vel_chi_square = std::abs(1.0 + noise(0.2));
    q.hdg_chi_square = 0;
    q.att_confidence = {0.0015, 0.0015, 0.006};
    q.vel_confidence = {0.05, 0.05, 0.08};
    q.pos_confidence = {1.2, 1.2, 2.5};
    q.gyro_confidence = {0.00005, 0.00005, 0.00008};
    q.gyro_bias = {0.0001, -0.00005, 0.00002};
    return q;
}

orion::GpsData OrionSim::gps_data() const {
    orion::GpsData g;
    const double gps_s = gps_seconds();
    const double week = std::floor(gps_s / seconds_per_week);
    g.fix_type = orion::UbloxFixType::three_d_fix;
    g.fix_state = 0x03;  // gnssFixOK | diffSoln
    g.tracked_sats = 14;
    g.pdop = 1.3;
    g.lat = platform_.lla.lat;
    g.lon = platform_.lla.lon;
    g.alt = platform_.lla.alt;
    g.vel_ned = {platform_.vel_ned.x, platform_.vel_ned.y, platform_.vel_ned.z};
    g.hacc = 1.1;
    g.vacc = 1.9;
    g.speed_acc = 0.15;
    g.heading_acc = 0.5 * deg;
    g.itow_ms = static_cast<std::uint32_t>(std::llround((gps_s - week * seconds_per_week) * 1000));
    g.week = static_cast<std::uint16_t>(week);
    g.geoid_undulation = options_.geoid_undulation_m;
    g.source = gps_fix_ ? orion::GpsSource::external : orion::GpsSource::ublox;
    g.vertical_velocity_valid = true;
    g.leap_seconds = options_.leap_seconds;
    return g;
}

orion::LaserStates OrionSim::laser_states() const {
    orion::LaserStates states;
    for (const auto& unit : lasers_.units()) {
        if (states.states.size() == orion::max_lasers) break;
        orion::LaserState s;
        s.type = unit.type;
        s.enabled = unit.enabled;
        s.armed = unit.armed;
        s.active = unit.active;
        s.password_lock = unit.password_lock;
        s.bypass_enabled = unit.bypass;
        s.altitude_lock = unit.altitude_lock;
        s.ap_comm_lock = unit.ap_comm_lock;
        s.ap_flying_lock = unit.ap_flying_lock;
        states.states.push_back(s);
    }
    return states;
}

orion::RetractStatus OrionSim::retract_status() const {
    orion::RetractStatus r;
    r.cmd = retract_.last_command();
    r.state = retract_.state();
    r.pos = retract_.position();
    return r;
}

orion::SoftwareDiagnostics OrionSim::software_diagnostics() {
    orion::SoftwareDiagnostics s;
    s.source_board = orion::Board::crown;
    orion::CoreLoading core;
    core.cpu_load = std::clamp(42 + noise(2), 0.0, 100.0);
    core.heap_load = 37;
    core.stack_load = 21;
    const double thread_cpu[] = {18, 12, 7};
    for (double cpu : thread_cpu) {
        orion::ThreadLoading thread;
        thread.cpu_load = std::clamp(cpu + noise(0.5), 0.0, 100.0);
        thread.stack_load = 30;
        thread.watchdog_left = 90;
        thread.num_iterations = 1000;
        thread.worstcase = 1.4;
        core.threads.push_back(thread);
    }
    s.cores.push_back(core);
    return s;
}

orion::Vibration OrionSim::vibration() {
    orion::Vibration v;
    v.max_accel = {1.8 + noise(0.05), 1.6 + noise(0.05), 3.9 + noise(0.1)};
    v.max_gyro = {0.012, 0.010, 0.008};
    for (std::size_t i = 0; i < v.fft_data.size(); ++i) {
        auto& point = v.fft_data[i];
        point.frequency = 10.0 * static_cast<double>(i + 1);
        const double peak = i == 7 ? 0.9 : 0.1;  // the engine at 80 Hz
        point.accel = {peak, peak * 0.8, peak};
        point.gyro = {peak * 0.5, peak * 0.5, peak * 0.3};
    }
    return v;
}

orion::NetworkDiagnostics OrionSim::network_diagnostics() const {
    orion::NetworkDiagnostics n;
    const auto& rx = framer_.stats();
    n.flags = 0x0001;  // link up
    n.rx_bytes = static_cast<std::uint32_t>(rx.bytes);
    n.tx_bytes = static_cast<std::uint32_t>(tx_bytes_);
    n.rx_packets = static_cast<std::uint32_t>(rx.packets);
    n.tx_packets = static_cast<std::uint32_t>(tx_packets_);
    n.rx_errors = static_cast<std::uint16_t>(std::min<std::uint64_t>(rx.bad_checksums, 65535));
    return n;
}

}  // namespace gimbal::sim
