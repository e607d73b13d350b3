#include "protocols/orion/orion_entry.hpp"

#include "protocols/orion/orion_capabilities.hpp"
#include "protocols/orion/orion_config.hpp"
#include "protocols/orion/orion_feed.hpp"
#include "protocols/orion/orion_protocol.hpp"
#include "protocols/orion/orion_track.hpp"

namespace gimbal::protocols {

namespace {

// The catalogue commands an Orion plans (orion_commands.cpp), with their packets.
constexpr PlannedCommand commands[] = {
    {"geopoint", "GeopointCmd, id 213, 21 bytes"},
    {"path", "OrionPath, id 215, 5 + 9 x points bytes"},
    {"laser", "OrionLaserCommand, id 3, 14 + len(password) bytes"},
    {"position", "OrionCmd, id 1, mode position"},
    {"rate", "OrionCmd, id 1, mode rate"},
    {"center", "OrionCmd, id 1, mode position at 0, 0, not stabilized"},
    {"mode", "OrionCmd with zero targets"},
    {"stare_ack", "StareAck, id 218"},
    {"retract", "OrionRetractCommand, id 160"},
    {"camera_switch", "OrionCameraSwitch, id 96"},
    {"camera_zoom", "OrionCameraState, id 97"},
    {"range", "OrionRangeData, id 214"},
    {"request", "zero-length packet(s) of that id"},
};

// STATE keys of an Orion's own packets (contract section 5), besides the shared ones.
constexpr std::string_view state_keys[] = {"ins",
                                           "gps",
                                           "diagnostics",
                                           "performance",
                                           "software",
                                           "network_diagnostics",
                                           "vibration",
                                           "retract",
                                           "cameras",
                                           "limits",
                                           "network_settings",
                                           "network_video",
                                           "uart_config",
                                           "ins_options",
                                           "versions",
                                           "reset_source",
                                           "boards"};

std::size_t frame_size(const orion::Frame& f) {
    return orion::header_size + f.payload.size + orion::checksum_size;
}

std::unique_ptr<session::Protocol> make_session(const SessionSettings& s, const nlohmann::json&) {
    OrionOptions options;
    options.stale_after_s = s.stale_after_s;
    options.auto_ack_stare = s.auto_ack_stare;
    options.allow_fire = s.allow_fire;
    options.allow_safety_bypass = s.allow_safety_bypass;
    options.terrain = s.terrain;
    return std::make_unique<OrionProtocol>(options);
}

Entry make_entry() {
    Entry e;
    e.id = ProtocolId::orion;
    e.name = "orion";
    e.display_name = "Orion";
    e.dissector = "orion";
    e.commands = commands;
    e.state_keys = state_keys;
    e.features = orion_features();
    e.read_config = [](config::Fields& gimbal, const ConfigContext&) {
        return config::read_and_write<OrionConfig>(gimbal);
    };
    e.make_session = make_session;
    e.make_feeder = make_orion_feeder;
    e.make_splitter = [] {
        return std::unique_ptr<framing::StreamSplitter>(
            std::make_unique<framing::FramerSplitter<orion::Framer, frame_size>>());
    };
    e.make_track_decoder = make_orion_track_decoder;
    e.discovery = orion_discovery();
    e.simulator = orion_simulator();
    return e;
}

}  // namespace

const Entry& orion_entry() {
    static const Entry entry = make_entry();
    return entry;
}

}  // namespace gimbal::protocols
