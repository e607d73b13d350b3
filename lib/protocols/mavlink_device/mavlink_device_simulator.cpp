#include "protocols/mavlink_device/mavlink_device_entry.hpp"

#include <stdexcept>
#include "protocols/mavlink_device/mavlink_device_json.hpp"
#include "protocols/mavlink_device/mavlink_device_sim.hpp"
#include "protocols/mavlink_device/mavlink_frame_scanner.hpp"

namespace gimbal::protocols {

using nlohmann::json;

namespace {

using Flag = SimFlag;

constexpr std::string_view manual =
    R"(       --protocol mavlink: a simulated MAVLink gimbal device (Gimbal Protocol v2,
       component 154), usually over --udp or --pty. It sends HEARTBEAT at 1 Hz and
       GIMBAL_DEVICE_ATTITUDE_STATUS at --attitude-rate, answers REQUEST_MESSAGE for
       GIMBAL_DEVICE_INFORMATION (vendor "gimbald", its angle limits and capability
       flags, SUPPORTS_YAW_IN_EARTH_FRAME among them), and follows
       GIMBAL_DEVICE_SET_ATTITUDE: angles (with their angular velocities as
       feed-forward) or rates alone, yaw from the vehicle's nose or from north. Its
       pitch and yaw slew at no more than --slew-rate within --pitch-min/--pitch-max
       and --yaw-min/--yaw-max (a yaw range of 360 degrees turns without end stops);
       failure flags say AT_PITCH_LIMIT / AT_YAW_LIMIT, and NO_MANAGER until a manager
       is heard. AUTOPILOT_STATE_FOR_GIMBAL_DEVICE tells it the vehicle's yaw, for
       yaw from north. It knows no position: gimbald aims it from the vehicle's.
       With --signing-key it signs every frame (MAVLink 2 message signing) and hears
       only frames signed with that key whose timestamps move forward, as a device
       configured for signing does; having no clock, it keeps its timestamps ahead of
       the ones it accepts.
)";

constexpr std::string_view rx_log_manual =
    R"(       With --protocol mavlink, one line per valid MAVLink frame:
           {"t": 1.234, "src": "udp", "kind": "gimbal_device_set_attitude",
            "msgid": 284, "sysid": 1, "compid": 1, "len": 44, "hex": "fd20...",
            "message": {...}}
       kind is the message's name in lower case; message its fields, quaternions
       also as roll/pitch/yaw degrees and rates in deg/s.
)";

constexpr Flag flags[] = {
    {"--attitude-rate", "attitude_rate_hz", Flag::Type::number,
     "GIMBAL_DEVICE_ATTITUDE_STATUS rate, Hz", Flag::Check::range, 0.5, 200.0},
    {"--slew-rate", "slew_rate_dps", Flag::Type::number, "Largest axis rate, deg/s",
     Flag::Check::positive},
    {"--pitch-min", "pitch_min_deg", Flag::Type::number, "Lowest pitch, degrees",
     Flag::Check::range, -180.0, 180.0},
    {"--pitch-max", "pitch_max_deg", Flag::Type::number, "Highest pitch, degrees",
     Flag::Check::range, -180.0, 180.0},
    {"--yaw-min", "yaw_min_deg", Flag::Type::number, "Yaw end stop left of the nose, degrees",
     Flag::Check::range, -360.0, 360.0},
    {"--yaw-max", "yaw_max_deg", Flag::Type::number, "Yaw end stop right of the nose, degrees",
     Flag::Check::range, -360.0, 360.0},
    {"--angle-noise", "angle_noise_deg", Flag::Type::number,
     "Noise (1 sigma) on the reported angles, degrees", Flag::Check::non_negative},
    {"--signing-key", "signing_key", Flag::Type::text,
     "MAVLink 2 signing key, 64 hex digits (a test key: it shows in ps)"},
};

json defaults() {
    const MavlinkDeviceSimOptions o;
    return {{"attitude_rate_hz", o.attitude_rate_hz}, {"slew_rate_dps", o.slew_rate_dps},
            {"pitch_min_deg", o.pitch_min_deg},       {"pitch_max_deg", o.pitch_max_deg},
            {"yaw_min_deg", o.yaw_min_deg},           {"yaw_max_deg", o.yaw_max_deg},
            {"angle_noise_deg", o.angle_noise_deg},   {"signing_key", "none: unsigned"}};
}

std::unique_ptr<sim::Device> make(const SimScenario& s) {
    MavlinkDeviceSimOptions o;
    o.seed = s.seed;
    const json& x = s.options;
    o.attitude_rate_hz = x.value("attitude_rate_hz", o.attitude_rate_hz);
    o.slew_rate_dps = x.value("slew_rate_dps", o.slew_rate_dps);
    o.pitch_min_deg = x.value("pitch_min_deg", o.pitch_min_deg);
    o.pitch_max_deg = x.value("pitch_max_deg", o.pitch_max_deg);
    o.yaw_min_deg = x.value("yaw_min_deg", o.yaw_min_deg);
    o.yaw_max_deg = x.value("yaw_max_deg", o.yaw_max_deg);
    o.angle_noise_deg = x.value("angle_noise_deg", o.angle_noise_deg);
    o.unix_time_s = s.unix_time_s;
    if (const auto key = x.find("signing_key"); key != x.end() && key->is_string()) {
        o.signing_key = mavlink::parse_signing_key(key->get<std::string>());
        if (!o.signing_key || key->get<std::string>().size() != 64)
            throw std::invalid_argument("--signing-key: must be 64 hex digits");
    }
    return make_mavlink_device_sim(o);
}

// MAVLink v1/v2 frames for the fault injector: the length byte says the size; the CRC's
// high byte is last.
std::size_t frame_size_at(std::span<const std::uint8_t> in) {
    if (in.size() < 3) return 0;
    if (in[0] == mavlink::magic_v2) {
        const bool signed_frame = (in[2] & mavlink::incompat_signed) != 0;
        return mavlink::header_size_v2 + in[1] + mavlink::checksum_size +
               (signed_frame ? mavlink::signature_size : 0);
    }
    if (in[0] == mavlink::magic_v1) return mavlink::header_size_v1 + in[1] + mavlink::checksum_size;
    return 0;
}

sim::FrameShape fault_frames() {
    // A stray 0xFD, sometimes followed by a plausible length: a false header.
    return sim::FrameShape{frame_size_at, mavlink::magic_v2, 0x20};
}

class MavlinkRxDecoder final : public RxDecoder {
  public:
    void push(std::span<const std::uint8_t> bytes, std::vector<json>& lines) override {
        scanner_.push(bytes, [&](const ScannedFrame& f) {
            json line;
            line["kind"] = mavlink_message_name(f.message.payload);
            line["msgid"] = f.message.msgid;
            line["sysid"] = f.message.sysid;
            line["compid"] = f.message.compid;
            line["len"] = f.bytes.size();
            line["hex"] = hex_text(f.bytes);
            line["message"] = mavlink_message_json(f.message.payload);
            lines.push_back(std::move(line));
        });
    }
    void reset() override { scanner_.reset(); }

  private:
    MavlinkFrameScanner scanner_;
};

}  // namespace

Simulator mavlink_device_simulator() {
    Simulator s;
    s.manual = manual;
    s.rx_log_manual = rx_log_manual;
    s.make = make;
    s.flags = flags;
    s.defaults = defaults;
    s.fault_frames = fault_frames;
    s.make_rx_decoder = [] {
        return std::unique_ptr<RxDecoder>(std::make_unique<MavlinkRxDecoder>());
    };
    return s;
}

}  // namespace gimbal::protocols
