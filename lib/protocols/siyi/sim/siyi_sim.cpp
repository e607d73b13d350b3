#include "protocols/siyi/sim/siyi_sim.hpp"

#include <algorithm>
#include <cmath>

#include "protocols/siyi/codec/codec.hpp"

namespace gimbal::protocols {

namespace {

using namespace gimbal::siyi;

constexpr double max_step_s = 0.005;
constexpr double deg2rad = pi / 180.0;
constexpr double earth_radius_m = 6371000.0;           // a flat-earth step of at most 1.2 km
constexpr double laser_min_m = 5, laser_max_m = 1200;  // SDK 0x15: "5m to 1200m", else 0

template <class... F>
struct Overloaded : F... {
    using F::operator()...;
};
template <class... F>
Overloaded(F...) -> Overloaded<F...>;

}  // namespace

SiyiSim::SiyiSim(const SiyiSimOptions& options)
    : options_(options),
      model_(model_info(options.model)),
      motion_(model_, options.yaw_deg, options.pitch_deg, options.zoom),
      rng_(options.seed) {
    // A 10-digit id whose first two characters name the model, zero-padded to 12 bytes on
    // the wire (HardwareId).
    std::mt19937 serial(options.seed);
    hardware_id_ = std::string(model_.id_prefix);
    while (hardware_id_.size() < 10) hardware_id_.push_back(static_cast<char>('0' + serial() % 10));
}

void SiyiSim::receive(std::span<const std::uint8_t> bytes, double now_s) {
    run_until(now_s);
    framer_.push(bytes, [&](const Frame& frame) { on_frame(frame); });
}

void SiyiSim::advance(double now_s, std::vector<std::uint8_t>& out) {
    run_until(now_s);
    out.insert(out.end(), outbox_.begin(), outbox_.end());
    outbox_.clear();
}

void SiyiSim::run_until(double now_s) {
    if (!started_) {
        started_ = true;
        start_s_ = time_ = now_s;
    }
    while (time_ < now_s) {
        double dt = max_step_s;
        if (now_s - time_ <= max_step_s) {
            dt = now_s - time_;
            time_ = now_s;
        } else {
            time_ += dt;
        }
        motion_.step(dt);
        emit_streams();
    }
}

void SiyiSim::emit_streams() {
    const auto due = [&](Stream& s) {
        if (s.period_s <= 0 || time_ < s.next_s) return false;
        s.next_s += s.period_s;
        if (s.next_s <= time_) s.next_s = time_ + s.period_s;
        return true;
    };
    if (due(attitude_stream_)) send(attitude());
    if (due(laser_stream_)) send(LaserDistance{laser_range_m().value_or(0)});
    if (due(encoder_stream_)) send(MagneticEncoder{motion_.yaw(), motion_.pitch(), 0});
}

void SiyiSim::on_frame(const Frame& frame) {
    const Decoded<ToGimbal> d = decode_to_gimbal(frame);
    switch (d.error) {
        case DecodeError::none:
            if (handle(d.value))
                ++stats_.handled;
            else
                ++stats_.unsupported;
            return;
        case DecodeError::too_short:
            ++stats_.too_short;
            return;
        case DecodeError::unknown_command:
            ++stats_.unknown;
            return;
    }
}

// Returns false for a command this model does not answer.
bool SiyiSim::handle(const ToGimbal& message) {
    const bool optical = model_.optical_zoom_max > 1;
    return std::visit(
        Overloaded{
            [&](const TcpHeartbeat&) { return true; },
            [&](const FirmwareVersionRequest&) {
                send_firmware_version();
                return true;
            },
            [&](const HardwareIdRequest&) {
                send(HardwareId{hardware_id_});
                return true;
            },
            [&](const AutoFocus&) {
                send(AutoFocusReply{{optical}});  // "only supported by optical zoom cameras"
                return true;
            },
            [&](const ManualZoom& m) {
                motion_.zoom_step(m.zoom);
                send(ManualZoomReply{motion_.zoom()});
                return true;
            },
            [&](const ManualFocus&) {
                send(ManualFocusReply{{optical}});
                return true;
            },
            [&](const GimbalRotation& m) {
                motion_.turn(m.turn_yaw, m.turn_pitch);
                send(GimbalRotationReply{{true}});
                return true;
            },
            [&](const Center& m) {
                bool ok = true;
                switch (m.position) {
                    case CenterPosition::one_key_center:
                    case CenterPosition::center:
                        motion_.go_to(0, 0);
                        break;
                    case CenterPosition::center_down:
                        motion_.go_to(0, -90);
                        break;
                    case CenterPosition::down:
                        motion_.go_to(motion_.yaw(), -90);
                        break;
                    default:
                        ok = false;
                }
                send(CenterReply{{ok}});
                return true;
            },
            [&](const CameraSystemInfoRequest&) {
                send(system_info());
                return true;
            },
            [&](const Capture& m) {
                capture(m.function);
                return true;
            },
            [&](const GimbalAttitudeRequest&) {
                send(attitude());
                return true;
            },
            [&](const SetGimbalAttitude& m) {
                // The reply carries the angles the command found.
                send(SetGimbalAttitudeReply{motion_.yaw(), motion_.pitch(), 0});
                motion_.go_to(m.yaw, m.pitch);
                return true;
            },
            [&](const AbsoluteZoom& m) {
                motion_.zoom_to(m.zoom);
                send(AbsoluteZoomReply{{true}});
                return true;
            },
            [&](const LaserDistanceRequest&) {
                if (!model_.has_laser) return false;
                send(LaserDistance{laser_range_m().value_or(0)});
                return true;
            },
            [&](const ZoomRangeRequest&) {
                send(ZoomRange{model_.zoom_max});
                return true;
            },
            [&](const LaserTargetRequest&) {
                if (!model_.has_laser) return false;
                send(laser_target());
                return true;
            },
            [&](const CurrentZoomRequest&) {
                send(CurrentZoom{motion_.zoom()});
                return true;
            },
            [&](const GimbalModeRequest&) {
                send(GimbalMode{motion_mode_});
                return true;
            },
            [&](const AircraftAttitude& m) {
                if (std::isfinite(m.roll) && std::isfinite(m.pitch) && std::isfinite(m.yaw))
                    aircraft_attitude_ = m;
                return true;
            },
            [&](const DataStreamRequest& m) {
                const bool supported = m.type == StreamType::attitude ||
                                       m.type == StreamType::magnetic_encoder ||
                                       (m.type == StreamType::laser_range && model_.has_laser);
                if (!supported) return false;
                set_stream(m.type, m.rate);
                send(DataStreamReply{m.type});
                return true;
            },
            [&](const SetUtcTime&) {
                send(SetUtcTimeReply{true});
                return true;
            },
            [&](const RawGps& m) {
                aircraft_position_ = m;
                return true;
            },
        },
        message);
}

template <class M>
void SiyiSim::send(const M& message) {
    append(outbox_, message, Header{ctrl_ack_pack, seq_++});
}

void SiyiSim::send_firmware_version() {
    const bool booted = time_ - start_s_ >= options_.boot_time_s;
    const FirmwareVersion fw{booted ? model_.camera_firmware : 0,
                             booted ? model_.gimbal_firmware : 0,
                             booted ? model_.zoom_firmware : 0};
    // A camera without a zoom module answers camera and gimbal only (8 bytes).
    const Payload p = encode_payload(fw);
    const std::size_t n = model_.has_zoom_module ? p.size : min_length<FirmwareVersion>();
    append_frame(outbox_, Header{ctrl_ack_pack, seq_++}, FirmwareVersion::cmd, p.view().first(n));
}

GimbalAttitude SiyiSim::attitude() {
    GimbalAttitude a;
    a.yaw = motion_.yaw() + noise();
    a.pitch = motion_.pitch() + noise();
    a.roll = 0;
    a.yaw_rate = motion_.yaw_rate();
    a.pitch_rate = motion_.pitch_rate();
    a.roll_rate = 0;
    return a;
}

CameraSystemInfo SiyiSim::system_info() const {
    CameraSystemInfo info;
    info.record = !options_.sd_card ? RecordStatus::no_card
                  : recording_      ? RecordStatus::recording
                                    : RecordStatus::off;
    info.motion_mode = motion_mode_;
    return info;
}

void SiyiSim::capture(CaptureFunction f) {
    switch (f) {
        case CaptureFunction::take_photo:
            send(FunctionFeedback{options_.sd_card ? FeedbackInfo::photo_ok
                                                   : FeedbackInfo::photo_failed});
            break;
        case CaptureFunction::record_toggle:
            if (!options_.sd_card) {
                send(FunctionFeedback{FeedbackInfo::record_failed});
                break;
            }
            recording_ = !recording_;
            send(FunctionFeedback{recording_ ? FeedbackInfo::record_started
                                             : FeedbackInfo::record_stopped});
            break;
        case CaptureFunction::lock_mode:
            motion_mode_ = MotionMode::lock;
            break;
        case CaptureFunction::follow_mode:
            motion_mode_ = MotionMode::follow;
            break;
        case CaptureFunction::fpv_mode:
            motion_mode_ = MotionMode::fpv;
            break;
        default:
            break;  // HDR, video outputs, zoom linkage: nothing the simulation shows
    }
}

void SiyiSim::set_stream(StreamType type, StreamRate rate) {
    double hz = stream_rate_hz(rate);
    Stream* s = &attitude_stream_;
    if (type == StreamType::laser_range) {
        s = &laser_stream_;
        // "Laser Range Data frequency cannot be set; any non-zero value will start sending."
        hz = rate == StreamRate::off ? 0 : options_.laser_rate_hz;
    } else if (type == StreamType::magnetic_encoder) {
        s = &encoder_stream_;
    }
    s->period_s = hz > 0 ? 1.0 / hz : 0;
    s->next_s = time_;
}

std::optional<double> SiyiSim::laser_range_m() const {
    if (!model_.has_laser) return std::nullopt;
    const double down = -motion_.pitch() * deg2rad;
    if (down <= 0) return std::nullopt;  // level or up: flat ground is never hit
    const double range = options_.height_above_ground_m / std::sin(down);
    if (!(range >= laser_min_m && range <= laser_max_m)) return std::nullopt;
    return range;
}

// Where the beam meets the ground, from the aircraft's last position (0x3E) and heading
// (0x22); zeros while either or the range is missing.
LaserTarget SiyiSim::laser_target() const {
    const auto range = laser_range_m();
    if (!range || !aircraft_position_) return {};
    const double heading = aircraft_attitude_ ? aircraft_attitude_->yaw * rad2deg : 0.0;
    const double azimuth = (heading - motion_.yaw()) * deg2rad;  // SIYI yaw is left-positive
    const double horizontal = *range * std::cos(motion_.pitch() * deg2rad);
    const double lat0 = aircraft_position_->lat;
    LaserTarget t;
    t.lat = lat0 + horizontal * std::cos(azimuth) / earth_radius_m * rad2deg;
    t.lon = aircraft_position_->lon +
            horizontal * std::sin(azimuth) / (earth_radius_m * std::cos(lat0 * deg2rad)) * rad2deg;
    return t;
}

SiyiSimAircraft SiyiSim::aircraft() const {
    SiyiSimAircraft a;
    if (aircraft_position_) {
        a.lat_deg = aircraft_position_->lat;
        a.lon_deg = aircraft_position_->lon;
        a.alt_msl_m = aircraft_position_->alt_msl;
        a.alt_ellipsoid_m = aircraft_position_->alt_ellipsoid;
    } else {
        a.lat_deg = options_.lat_deg;
        a.lon_deg = options_.lon_deg;
        a.alt_msl_m = options_.alt_msl_m;
        a.alt_ellipsoid_m = options_.alt_msl_m + options_.geoid_undulation_m;
    }
    if (aircraft_attitude_) {
        a.roll_deg = aircraft_attitude_->roll * rad2deg;
        a.pitch_deg = aircraft_attitude_->pitch * rad2deg;
        a.yaw_deg = aircraft_attitude_->yaw * rad2deg;
    }
    return a;
}

double SiyiSim::noise() {
    if (options_.angle_noise_deg <= 0) return 0;
    return std::normal_distribution<double>(0.0, options_.angle_noise_deg)(rng_);
}

std::unique_ptr<sim::Device> make_siyi_sim(const SiyiSimOptions& options) {
    return std::make_unique<SiyiSim>(options);
}

}  // namespace gimbal::protocols
