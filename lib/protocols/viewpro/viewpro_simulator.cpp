#include "protocols/viewpro/viewpro_entry.hpp"

#include "protocols/viewpro/codec/input_framer.hpp"
#include "protocols/viewpro/codec/json.hpp"
#include "protocols/viewpro/sim/viewpro_fault_frames.hpp"
#include "protocols/viewpro/sim/viewpro_sim.hpp"

namespace gimbal::protocols {

using nlohmann::json;

namespace {

using Flag = SimFlag;

constexpr std::string_view manual =
    R"(       --protocol viewpro: a simulated Viewpro gimbal speaking the target
       GPS-coordinates protocol (usually over --pty, as its serial port; TCP works
       the same way; no discovery). It is silent until a mode command
       (AA 55 0F MM FF) enables serial output, then sends the selected OUT1..OUT4
       frame at 10 Hz. IN1/IN2/IN3 frames set the vehicle position and attitude,
       AA 55 06/36 XX FF shift the calculated point; the target is where the line
       of sight meets flat terrain at --terrain-alt, or the IN3 laser distance along
       it. --alt and --terrain-alt are heights above mean sea level. Until the first
       IN frame the vehicle is level at 6.9428789 N, 79.8812446 E, 300 m (the ICD's
       OUT1 example), unless --lat, --lon and --alt say otherwise.
)";

constexpr std::string_view rx_log_manual =
    R"(       With --protocol viewpro, one line per valid IN frame or AA 55 command:
           {"t": 1.234, "src": "pty", "kind": "in2", "len": 40, "hex": "f9fc...",
            "frame": {...}}
       kind is mode, yaw_shift, pitch_shift, in1, in2 or in3; frame the decoded
       content in JSON units (degrees, metres).
)";

constexpr Flag flags[] = {
    {"--heading", "heading_deg", Flag::Type::number,
     "Vehicle heading before any IN frame, degrees"},
    {"--gimbal-pitch", "gimbal_pitch_deg", Flag::Type::number,
     "Gimbal pitch relative to the vehicle, degrees, up positive", Flag::Check::range, -180.0,
     180.0},
    {"--gimbal-yaw", "gimbal_yaw_deg", Flag::Type::number,
     "Gimbal yaw relative to the heading, degrees, right positive", Flag::Check::range, -180.0,
     180.0},
    {"--gimbal-yaw-rate", "gimbal_yaw_rate_dps", Flag::Type::number,
     "Gimbal yaw sweep rate, deg/s"},
    {"--angle-noise", "angle_noise_deg", Flag::Type::number,
     "Noise (1 sigma) on the reported gimbal angles, degrees", Flag::Check::non_negative},
    {"--zoom", "zoom_position", Flag::Type::integer, "Zoom position value reported",
     Flag::Check::range, 0, 65535},
    {"--no-laser", "no_laser", Flag::Type::flag, "No laser range finder: the LRF field stays 0"},
};

json defaults() {
    const sim::ViewproSimOptions o;
    return {{"heading_deg", o.yaw_deg},
            {"gimbal_pitch_deg", o.gimbal_pitch_deg},
            {"gimbal_yaw_deg", o.gimbal_yaw_deg},
            {"gimbal_yaw_rate_dps", o.gimbal_yaw_rate_dps},
            {"angle_noise_deg", o.angle_noise_deg},
            {"zoom_position", o.zoom_position},
            {"no_laser", !o.has_laser}};
}

std::unique_ptr<sim::Device> make(const SimScenario& s) {
    sim::ViewproSimOptions o;
    o.unix_time_at_start_s = s.unix_time_s;
    o.seed = s.seed;
    // The vehicle hovers at lat/lon at alt (MSL); the terrain height is MSL too.
    if (s.lat_deg) o.lat_deg = *s.lat_deg;
    if (s.lon_deg) o.lon_deg = *s.lon_deg;
    if (s.alt_m) o.alt_msl_m = *s.alt_m;
    if (s.terrain_alt_m) o.terrain_alt_msl_m = *s.terrain_alt_m;
    if (s.geoid_undulation_m) o.geoid_undulation_m = *s.geoid_undulation_m;
    const json& x = s.options;
    o.yaw_deg = x.value("heading_deg", o.yaw_deg);
    o.gimbal_pitch_deg = x.value("gimbal_pitch_deg", o.gimbal_pitch_deg);
    o.gimbal_yaw_deg = x.value("gimbal_yaw_deg", o.gimbal_yaw_deg);
    o.gimbal_yaw_rate_dps = x.value("gimbal_yaw_rate_dps", o.gimbal_yaw_rate_dps);
    o.angle_noise_deg = x.value("angle_noise_deg", o.angle_noise_deg);
    o.zoom_position = x.value("zoom_position", o.zoom_position);
    o.has_laser = !x.value("no_laser", !o.has_laser);
    return sim::make_viewpro_sim(o);
}

// --rx-log: {"kind", "len", "hex", "frame" (decoded, when it decodes)} per IN frame or
// AA 55 command.
class ViewproRxDecoder final : public RxDecoder {
  public:
    void push(std::span<const std::uint8_t> bytes, std::vector<json>& lines) override {
        framer_.push(bytes, [&](const viewpro::InputFrame& frame) {
            json line;
            line["kind"] = std::string(viewpro::to_string(frame.kind));
            line["len"] = frame.size;
            line["hex"] = hex_text(frame.view());
            json decoded = viewpro::to_json(frame);
            if (!decoded.is_null()) line["frame"] = std::move(decoded);
            lines.push_back(std::move(line));
        });
    }
    void reset() override { framer_.reset(); }

  private:
    viewpro::InputFramer framer_;
};

}  // namespace

Simulator viewpro_simulator() {
    Simulator s;
    s.manual = manual;
    s.rx_log_manual = rx_log_manual;
    s.make = make;
    s.flags = flags;
    s.defaults = defaults;
    s.fault_frames = sim::viewpro_output_frames;
    s.make_rx_decoder = [] {
        return std::unique_ptr<RxDecoder>(std::make_unique<ViewproRxDecoder>());
    };
    return s;
}

}  // namespace gimbal::protocols
