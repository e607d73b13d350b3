// The live state of one SIYI gimbal camera: what it reported (firmware 0x01, hardware id 0x02,
// attitude 0x0D, zoom 0x18/0x16, recording 0x0A/0x0B, laser 0x15/0x17: STATE `siyi`) and,
// with the vehicle's fix, the shared `telemetry` (pan/tilt, fields of view per model and zoom,
// position, target, footprint, ground), as the MAVLink device's. Angles in gimbald's frame:
// pan is the negated SIYI yaw (docs/siyi.md "Angles and signs"). Pure: every call takes now_s.
#pragma once

#include <algorithm>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "geo/attitude.hpp"
#include "geo/wgs84.hpp"
#include "protocols/siyi/codec/messages.hpp"
#include "protocols/siyi/codec/models.hpp"
#include "protocols/siyi/siyi_options.hpp"
#include "state/event.hpp"
#include "state/telemetry.hpp"
#include "state/writer.hpp"
#include "vehicle/aircraft_fix.hpp"

namespace gimbal::protocols {

// The camera's latest attitude (0x0D), in gimbald's frame.
struct SiyiAttitude {
    double pan_deg = 0;   // from the aircraft's nose, right positive (-SIYI yaw)
    double tilt_deg = 0;  // up positive
    double roll_deg = 0;
    double pan_rate_dps = 0, tilt_rate_dps = 0, roll_rate_dps = 0;
    double received_s = 0;
};

struct SiyiFirmware {
    std::string camera, gimbal;
    std::optional<std::string> zoom;  // the A8 mini has no zoom module
};

struct SiyiLaserPoint {
    double lat = 0, lon = 0;
};

// What the camera reported, typed: what its capabilities read (siyi_capabilities.hpp).
struct SiyiData {
    std::optional<std::string> hardware_id;
    std::optional<siyi::Model> model;  // configured, else named by the hardware id
    std::optional<SiyiFirmware> firmware;
    std::optional<SiyiAttitude> attitude;
    std::optional<double> zoom, zoom_max;
    std::optional<siyi::RecordStatus> record;
    std::optional<siyi::MotionMode> motion_mode;
    std::optional<double> laser_range_m;  // nullopt: no laser, or nothing in range (0)
    std::optional<SiyiLaserPoint> laser_target;
    // STATE `telemetry`: the shared keys, from the latest attitude and the vehicle's fix.
    std::optional<state::Telemetry> telemetry;
};

// STATE siyi.attitude and attitude_rate: as the camera reports them (0x0D), in SIYI's frame -
// yaw from the nose, positive LEFT (telemetry.pan is its negation), pitch up positive.
struct SiyiReportedAngles {
    double yaw = 0, pitch = 0, roll = 0;
};

template <class V>
void fields(V& v, const SiyiReportedAngles& a) {
    v.angle("yaw", a.yaw);
    v.angle("pitch", a.pitch);
    v.angle("roll", a.roll);
}

// SIYI's yaw from gimbald's pan (0 stays 0: a negated 0 would be written as -0.0).
inline double siyi_yaw_of_pan(double pan_deg) {
    return pan_deg == 0 ? 0.0 : -pan_deg;
}

template <class V>
void fields(V& v, const SiyiFirmware& f) {
    v.string("camera", f.camera);
    v.string("gimbal", f.gimbal);
    v.string("zoom", f.zoom);
}

template <class V>
void fields(V& v, const SiyiLaserPoint& p) {
    v.latlon("lat", p.lat);
    v.latlon("lon", p.lon);
}

// STATE `siyi`.
template <class V>
void fields(V& v, const SiyiData& d) {
    v.string("hardware_id", d.hardware_id);
    v.string("model",
             d.model ? std::optional(std::string(siyi::model_info(*d.model).name)) : std::nullopt);
    v.object("firmware", d.firmware);
    std::optional<SiyiReportedAngles> attitude, rate;
    if (const auto& a = d.attitude) {
        attitude = SiyiReportedAngles{siyi_yaw_of_pan(a->pan_deg), a->tilt_deg, a->roll_deg};
        rate = SiyiReportedAngles{siyi_yaw_of_pan(a->pan_rate_dps), a->tilt_rate_dps,
                                  a->roll_rate_dps};
    }
    v.object("attitude", attitude);
    v.object("attitude_rate", rate);
    v.decimals("zoom", d.zoom, 1);
    v.decimals("zoom_max", d.zoom_max, 1);
    v.boolean("recording",
              d.record ? std::optional(*d.record == siyi::RecordStatus::recording) : std::nullopt);
    // Why it is not recording: off, no_card, data_loss (0x0A record_sta).
    v.string("record_status",
             d.record ? std::optional(std::string(siyi::enum_name(*d.record))) : std::nullopt);
    v.string("motion_mode", d.motion_mode
                                ? std::optional(std::string(siyi::enum_name(*d.motion_mode)))
                                : std::nullopt);
    v.metres("laser_range_m", d.laser_range_m);
    v.object("laser_target", d.laser_target);
}

class SiyiState {
  public:
    explicit SiyiState(const SiyiOptions& options);

    // One decoded message from the camera.
    void apply(const siyi::FromGimbal& message, double now_s);
    // The vehicle's latest fix (nullopt: lost); telemetry follows at the next attitude.
    void set_vehicle(const std::optional<vehicle::AircraftFix>& fix);
    const std::optional<vehicle::AircraftFix>& vehicle() const { return vehicle_; }
    double geoid_undulation() const { return geoid_undulation_m_; }
    // The camera's position above the ellipsoid, from the fix.
    std::optional<geo::Lla> camera() const;
    // Appends a `lost` event when the attitude goes stale (once per loss).
    void tick(double now_s, std::vector<state::Event>& events);

    bool stale(double now_s) const;
    std::optional<double> telemetry_age_s(double now_s) const {
        if (!data_.attitude) return std::nullopt;
        return std::max(0.0, now_s - data_.attitude->received_s);
    }
    std::uint64_t telemetry_count() const { return attitudes_; }
    // STATE `siyi` and `telemetry`.
    void write(state::JsonWriter& w, double now_s) const;

    const SiyiData& data() const { return data_; }
    const std::optional<state::Telemetry>& telemetry() const { return data_.telemetry; }
    // The model's table: the configured or reported one, else the ZT30 (the largest limits
    // and zoom: nothing is refused before the camera has said what it is).
    const siyi::ModelInfo& model() const;
    // The camera's line of sight relative to NED (needs the vehicle's heading).
    std::optional<geo::Quat> line_of_sight() const;
    siyi::FieldOfView field_of_view() const;

  private:
    void on_attitude(const siyi::GimbalAttitude& m, double now_s);
    state::Telemetry derive_telemetry() const;

    SiyiOptions options_;
    std::optional<vehicle::AircraftFix> vehicle_;
    double geoid_undulation_m_ = 0;
    SiyiData data_;
    std::uint64_t attitudes_ = 0;
    bool lost_reported_ = false;
};

}  // namespace gimbal::protocols
