#include "protocols/orion/orion_entry.hpp"

#include "protocols/orion/codec/framer.hpp"
#include "protocols/orion/codec/json.hpp"
#include "protocols/orion/codec/packets.hpp"
#include "protocols/orion/sim/orion_fault_frames.hpp"
#include "protocols/orion/sim/orion_sim.hpp"
#include "protocols/orion/sim/sim_camera.hpp"

namespace gimbal::protocols {

using nlohmann::json;

namespace {

using Flag = SimFlag;

constexpr std::string_view manual =
    R"(       --protocol orion: a simulated Orion gimbal speaking the OrionPublic protocol.
       The gimbal rides on an aircraft flying a level circle, sends GeolocateTelemetry
       at 10 Hz, Performance at 4 Hz, InsQuality, GpsData, SoftwareDiagnostics,
       LaserStates and RetractStatus at 1 Hz, Diagnostics every 3 s and Vibration
       every 5 s, and obeys OrionCmd (echoed back), GeopointCmd, OrionPath with
       step-stare, laser, retract, camera and configuration packets. Zero-length
       packets are requests for that packet. Its line of sight (losECEF, the target)
       meets the simulator's terrain - hills and a river valley around 45.7 N
       121.5 W, the DEM --write-dem writes - or flat ground at --terrain-alt.
       --alt and --terrain-alt are heights above the WGS84 ellipsoid. The circle's
       centre is 45.7 N, 121.5 W, 1500 m, unless --lat, --lon and --alt say otherwise.
)";

constexpr std::string_view rx_log_manual =
    R"(       With --protocol orion, one line per checksum-valid packet:
           {"t": 1.234, "src": "tcp", "id": 213, "name": "geopoint_cmd", "len": 21,
            "hex": "d00dd515...", "packet": {...}}
       hex is the whole frame as received (sync bytes to checksum), packet the
       decoded packet (absent when it does not decode, e.g. a zero-length request).
)";

constexpr Flag flags[] = {
    {"--radius", "radius_m", Flag::Type::number, "Circle radius, metres; 0 hovers",
     Flag::Check::non_negative},
    {"--speed", "speed_mps", Flag::Type::number, "Ground speed, m/s", Flag::Check::non_negative},
    {"--counter-clockwise", "counter_clockwise", Flag::Type::flag, "Circle counter-clockwise"},
    {"--pan-rate", "pan_rate_dps", Flag::Type::number, "Pan slew rate limit, deg/s",
     Flag::Check::positive},
    {"--tilt-rate", "tilt_rate_dps", Flag::Type::number, "Tilt slew rate limit, deg/s",
     Flag::Check::positive},
    {"--stare-time", "stare_time_s", Flag::Type::number, "Step-stare stare time, seconds (<= 2.55)",
     Flag::Check::range, 0.0, 2.55},
    {"--path-speed", "path_speed_mps", Flag::Type::number,
     "Path sweep speed without step-stare, m/s", Flag::Check::positive},
    {"--laser-password", "laser_password", Flag::Type::text,
     "Password the lasers require (at most 15 characters)", Flag::Check::range, 0, 15},
    {"--no-retract", "no_retract", Flag::Type::flag, "No retract mechanism installed"},
};

json defaults() {
    const sim::OrionSimOptions o;
    return {{"radius_m", o.radius_m},
            {"speed_mps", o.speed_mps},
            {"counter_clockwise", !o.clockwise},
            {"pan_rate_dps", o.pan_rate_max_dps},
            {"tilt_rate_dps", o.tilt_rate_max_dps},
            {"stare_time_s", o.stare_time_s},
            {"path_speed_mps", o.path_scan_speed_mps},
            {"laser_password", o.laser_password},
            {"no_retract", !o.retract_installed}};
}

std::unique_ptr<sim::Device> make(const SimScenario& s) {
    sim::OrionSimOptions o;
    o.gps_time_at_start_s = sim::gps_time_from_unix_s(s.unix_time_s);
    o.seed = s.seed;
    // The aircraft flies around lat/lon at alt (WGS84); flat ground at terrain_alt (WGS84 too)
    // replaces the analytic terrain.
    if (s.lat_deg) o.lat_deg = *s.lat_deg;
    if (s.lon_deg) o.lon_deg = *s.lon_deg;
    if (s.alt_m) o.alt_m = *s.alt_m;
    if (s.terrain_alt_m) o.terrain_alt_m = *s.terrain_alt_m;
    if (s.geoid_undulation_m) o.geoid_undulation_m = *s.geoid_undulation_m;
    const json& x = s.options;
    o.radius_m = x.value("radius_m", o.radius_m);
    o.speed_mps = x.value("speed_mps", o.speed_mps);
    o.clockwise = !x.value("counter_clockwise", !o.clockwise);
    o.pan_rate_max_dps = x.value("pan_rate_dps", o.pan_rate_max_dps);
    o.tilt_rate_max_dps = x.value("tilt_rate_dps", o.tilt_rate_max_dps);
    o.stare_time_s = x.value("stare_time_s", o.stare_time_s);
    o.path_scan_speed_mps = x.value("path_speed_mps", o.path_scan_speed_mps);
    o.laser_password = x.value("laser_password", o.laser_password);
    o.retract_installed = !x.value("no_retract", !o.retract_installed);
    return sim::make_orion_sim(o);
}

// --rx-log: {"id", "name", "len", "hex" (the whole frame), "packet" (when it decodes)}.
class OrionRxDecoder final : public RxDecoder {
  public:
    void push(std::span<const std::uint8_t> bytes, std::vector<json>& lines) override {
        framer_.push(bytes, [&](const orion::Frame& frame) {
            json line;
            line["id"] = frame.id;
            line["name"] = std::string(orion::packet_name(frame.id));
            line["len"] = frame.payload.size;
            line["hex"] = hex_text(orion::frame_bytes(frame.id, frame.data()));
            if (frame.payload.size > 0) {
                orion::dispatch(frame.id, [&]<class P>() {
                    if (auto decoded = orion::decode<P>(frame.data()))
                        line["packet"] = orion::to_json(decoded.value);
                });
            }
            lines.push_back(std::move(line));
        });
    }
    void reset() override { framer_.reset(); }

  private:
    orion::Framer framer_;
};

// The Orion SDK's discovery: a zero-length CROWN_VERSION request. Each datagram stands
// alone: a fresh framer, so no partial frame carries over.
bool is_discovery_request(std::span<const std::uint8_t> datagram) {
    orion::Framer framer;
    bool asked = false;
    framer.push(datagram, [&](const orion::Frame& f) {
        asked |= f.id == orion::pkt::crown_version && f.payload.size == 0;
    });
    return asked;
}

// The active camera, as the rendered video and its KLV need it.
std::optional<sim::CameraView> camera(const sim::Device& device) {
    const auto v = sim::orion_sim_camera(device);
    if (!v) return std::nullopt;
    return sim::camera_view(*v);
}

}  // namespace

Simulator orion_simulator() {
    Simulator s;
    s.manual = manual;
    s.rx_log_manual = rx_log_manual;
    s.make = make;
    s.flags = flags;
    s.defaults = defaults;
    s.fault_frames = sim::orion_frames;
    s.make_rx_decoder = [] {
        return std::unique_ptr<RxDecoder>(std::make_unique<OrionRxDecoder>());
    };
    s.is_discovery_request = is_discovery_request;
    s.discovery_reply = sim::orion_sim_crown_version_frame;
    s.camera = camera;
    return s;
}

}  // namespace gimbal::protocols
