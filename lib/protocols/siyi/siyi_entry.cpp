#include "protocols/siyi/siyi_entry.hpp"

#include "protocols/siyi/codec/framer.hpp"
#include "protocols/siyi/siyi_capabilities.hpp"
#include "protocols/siyi/siyi_feed.hpp"
#include "protocols/siyi/siyi_protocol.hpp"
#include "protocols/siyi/siyi_track.hpp"

namespace gimbal::protocols {

namespace {

// The catalogue commands a SIYI camera plans (siyi_commands.cpp).
constexpr PlannedCommand commands[] = {
    {"position",
     "0x0E set gimbal attitude (yaw = -pan, pitch = tilt); `stabilized`: held from north, "
     "re-sent at 20 Hz"},
    {"center", "0x08 one-key centring (`center_pos` 1): nose-forward and level"},
    {"rate", "0x07 gimbal rotation, speeds -100..100 of the model's top rate"},
    {"camera_zoom", "0x0F absolute zoom, one decimal, within the model's range"},
    {"geopoint",
     "0x0E set gimbal attitude, recomputed at 20 Hz from the vehicle's position; `stare`: a "
     "`stare_start` event once on the point"},
    {"path", "0x0E set gimbal attitude along the path, at 20 Hz; `down`: pitch -90"},
};

// STATE `siyi`: the camera's own report (contract section 22).
constexpr std::string_view state_keys[] = {"siyi"};

std::unique_ptr<session::Protocol> make_session(const SessionSettings& s,
                                                const nlohmann::json& gimbal) {
    SiyiOptions options = read_siyi_options(gimbal);
    options.stale_after_s = s.stale_after_s;
    options.terrain = s.terrain;
    options.geoid = s.geoid_undulation;
    return std::make_unique<SiyiProtocol>(options);
}

nlohmann::json read_config(config::Fields& gimbal, const ConfigContext&) {
    SiyiConfig read;
    fields(gimbal, read);
    return config::write(read);
}

// A configured geoid_undulation_m is a fixed override; without it the session asks the
// geoid at the aircraft's position.
bool needs_geoid(const nlohmann::json& gimbal) {
    return !read_siyi_options(gimbal).geoid_undulation_m.has_value();
}

std::size_t frame_size(const siyi::Frame& f) {
    return f.wire_size();
}

Entry make_entry() {
    Entry e;
    e.id = ProtocolId::siyi;
    e.name = "siyi";
    e.display_name = "SIYI";
    e.dissector = "siyi";
    e.commands = commands;
    e.state_keys = state_keys;
    e.features = siyi_features();
    e.config_section = "siyi";
    e.read_config = read_config;
    e.make_session = make_session;
    e.make_feeder = make_siyi_feeder;
    e.needs_geoid = needs_geoid;
    e.make_splitter = [] {
        return std::unique_ptr<framing::StreamSplitter>(
            std::make_unique<framing::FramerSplitter<siyi::Framer, frame_size>>());
    };
    e.make_track_decoder = make_siyi_track_decoder;
    e.simulator = siyi_simulator();
    return e;
}

}  // namespace

const Entry& siyi_entry() {
    static const Entry entry = make_entry();
    return entry;
}

}  // namespace gimbal::protocols
