#include "protocols/siyi/siyi_state.hpp"

#include <variant>

#include "geo/ground.hpp"
#include "protocols/siyi/codec/json.hpp"
#include "session/aimed_telemetry.hpp"
#include "session/capabilities.hpp"
#include "state/precision.hpp"

namespace gimbal::protocols {

using state::angle_deg;
using state::latlon_deg;
using state::metres;

namespace {

template <class... F>
struct Overloaded : F... {
    using F::operator()...;
};
template <class... F>
Overloaded(F...) -> Overloaded<F...>;

// The id's text up to its zero padding.
std::string id_text(const std::string& raw) {
    return siyi::printable(raw.substr(0, raw.find('\0')));
}

}  // namespace

SiyiState::SiyiState(const SiyiOptions& options) : options_(options) {
    data_.model = configured_model(options.model);
    if (options.geoid_undulation_m) geoid_undulation_m_ = *options.geoid_undulation_m;
}

const siyi::ModelInfo& SiyiState::model() const {
    return siyi::model_info(data_.model.value_or(siyi::Model::zt30));
}

void SiyiState::apply(const siyi::FromGimbal& message, double now_s) {
    using namespace siyi;
    std::visit(
        Overloaded{
            [&](const FirmwareVersion& m) {
                SiyiFirmware f{version_string(m.camera), version_string(m.gimbal), std::nullopt};
                if (m.zoom != 0) f.zoom = version_string(m.zoom);
                data_.firmware = f;
            },
            [&](const HardwareId& m) {
                data_.hardware_id = id_text(m.id);
                // A configured model wins: the id only names one where none is set.
                if (!configured_model(options_.model))
                    if (const auto model = model_from_hardware_id(*data_.hardware_id))
                        data_.model = model;
            },
            [&](const GimbalAttitude& m) { on_attitude(m, now_s); },
            [&](const CurrentZoom& m) { data_.zoom = m.zoom; },
            [&](const ManualZoomReply& m) { data_.zoom = m.zoom; },
            [&](const ZoomRange& m) { data_.zoom_max = m.zoom_max; },
            [&](const CameraSystemInfo& m) {
                data_.record = m.record;
                data_.motion_mode = m.motion_mode;
            },
            [&](const FunctionFeedback& m) {
                if (m.info == FeedbackInfo::record_started) data_.record = RecordStatus::recording;
                if (m.info == FeedbackInfo::record_stopped) data_.record = RecordStatus::off;
            },
            [&](const GimbalMode& m) { data_.motion_mode = m.mode; },
            // 0 is "out of range" (SDK 0x15): no reading, not a range of 0 m.
            [&](const LaserDistance& m) {
                data_.laser_range_m = m.distance > 0 ? std::optional(m.distance) : std::nullopt;
            },
            [&](const LaserTarget& m) {
                if (m.lat == 0 && m.lon == 0)
                    data_.laser_target.reset();
                else
                    data_.laser_target = SiyiLaserPoint{m.lat, m.lon};
            },
            [](const auto&) {},
        },
        message);
    if (data_.attitude) data_.telemetry = derive_telemetry();
}

void SiyiState::on_attitude(const siyi::GimbalAttitude& m, double now_s) {
    SiyiAttitude a;
    // + 0.0: a yaw of 0 negates to -0, which JSON would show as -0.0.
    a.pan_deg = session::wrap180(-m.yaw) + 0.0;
    a.tilt_deg = m.pitch;
    a.roll_deg = m.roll;
    a.pan_rate_dps = -m.yaw_rate + 0.0;
    a.tilt_rate_dps = m.pitch_rate;
    a.roll_rate_dps = m.roll_rate;
    a.received_s = now_s;
    data_.attitude = a;
    ++attitudes_;
    lost_reported_ = false;
}

void SiyiState::set_vehicle(const std::optional<vehicle::AircraftFix>& fix) {
    vehicle_ = fix;
    if (options_.geoid_undulation_m)
        geoid_undulation_m_ = *options_.geoid_undulation_m;
    else if (fix && options_.geoid)
        geoid_undulation_m_ = options_.geoid(fix->lat_deg, fix->lon_deg).value_or(0.0);
}

std::optional<geo::Lla> SiyiState::camera() const {
    if (!vehicle_) return std::nullopt;
    return geo::Lla{vehicle_->lat_deg, vehicle_->lon_deg,
                    geo::ellipsoid_from_msl(vehicle_->alt_msl_m, geoid_undulation_m_)};
}

siyi::FieldOfView SiyiState::field_of_view() const {
    return siyi::field_of_view(model().model, data_.zoom.value_or(1.0));
}

// SIYI's pitch and roll are stabilized (earth frame), its yaw from the aircraft's nose.
std::optional<geo::Quat> SiyiState::line_of_sight() const {
    if (!data_.attitude || !vehicle_) return std::nullopt;
    const SiyiAttitude& a = *data_.attitude;
    return geo::normalized(geo::euler_to_quat(
        geo::EulerDeg{0, a.tilt_deg, session::wrap180(vehicle_->yaw_deg + a.pan_deg)}));
}

state::Telemetry SiyiState::derive_telemetry() const {
    state::Telemetry t;
    const auto fov = field_of_view();
    t.pan = angle_deg(data_.attitude->pan_deg);
    t.tilt = angle_deg(data_.attitude->tilt_deg);
    t.hfov = angle_deg(fov.hfov_deg);
    t.vfov = angle_deg(fov.vfov_deg);
    const auto los = line_of_sight();
    if (!vehicle_ || !los) return t;
    const geo::CameraPose pose{*camera(), *los, fov.hfov_deg, fov.vfov_deg};
    const geo::Ground ground{options_.terrain, options_.ground_alt_m};
    const auto centre =
        session::fill_from_aircraft(t, *vehicle_, geoid_undulation_m_, pose, ground);
    // The ZT30's laser says where it hits (at the ground's height under the line of sight).
    if (data_.laser_target)
        t.target = state::GeoPoint{latlon_deg(data_.laser_target->lat),
                                   latlon_deg(data_.laser_target->lon),
                                   metres(centre ? centre->point.alt_m : options_.ground_alt_m)};
    return t;
}

bool SiyiState::stale(double now_s) const {
    return !data_.attitude || now_s - data_.attitude->received_s > options_.stale_after_s;
}

void SiyiState::tick(double now_s, std::vector<state::Event>& events) {
    if (data_.attitude && !lost_reported_ && stale(now_s)) {
        lost_reported_ = true;
        events.push_back(
            state::Event{"lost", {{"age_s", state::seconds(now_s - data_.attitude->received_s)}}});
    }
}

void SiyiState::write(state::JsonWriter& w, double now_s) const {
    w.object("siyi", [&](state::JsonWriter& s) {
        fields(s, data_);
        if (data_.attitude)
            s.seconds("age_s", std::max(0.0, now_s - data_.attitude->received_s));
        else
            s.null("age_s");
    });
    w.object("telemetry", data_.telemetry);
}

}  // namespace gimbal::protocols
