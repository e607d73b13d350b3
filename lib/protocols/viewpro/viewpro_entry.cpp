#include "protocols/viewpro/viewpro_entry.hpp"

#include "protocols/viewpro/viewpro_capabilities.hpp"
#include "protocols/viewpro/viewpro_config.hpp"
#include "protocols/viewpro/viewpro_feed.hpp"
#include "protocols/viewpro/viewpro_protocol.hpp"
#include "protocols/viewpro/viewpro_track.hpp"

namespace gimbal::protocols {

namespace {

// The catalogue commands a Viewpro plans (viewpro_commands.cpp), with their frames.
constexpr PlannedCommand commands[] = {
    {"viewpro_output", "`AA 55 0F MM FF`, `sent: [{\"frame\":\"mode\",\"len\":5}]`"},
    {"viewpro_adjust",
     "`AA 55 06 XX FF` / `AA 55 36 XX FF`, steps of at most 1.00 degree, yaw first; the reply "
     "adds `steps`"},
    {"vehicle", "IN2 (40 bytes) with `vel_ned`, else IN1 (34 bytes)"},
};

// STATE `output`: the Viewpro's latest OUTx frame (contract section 8).
constexpr std::string_view state_keys[] = {"output"};

std::size_t frame_size(const viewpro::OutputFrame& f) {
    return f.size;
}

std::unique_ptr<session::Protocol> make_session(const SessionSettings& s,
                                                const nlohmann::json& gimbal) {
    ViewproOptions options;
    options.stale_after_s = s.stale_after_s;
    options.output = config::read_checked<ViewproConfig>(gimbal).output;
    return std::make_unique<ViewproProtocol>(options);
}

Entry make_entry() {
    Entry e;
    e.id = ProtocolId::viewpro;
    e.name = "viewpro";
    e.display_name = "Viewpro";
    e.dissector = "viewpro";
    e.commands = commands;
    e.state_keys = state_keys;
    e.features = viewpro_features();
    e.config_section = "viewpro";
    e.read_config = [](config::Fields& gimbal, const ConfigContext&) {
        return config::read_and_write<ViewproConfig>(gimbal);
    };
    e.make_session = make_session;
    e.make_feeder = make_viewpro_feeder;
    e.make_splitter = [] {
        return std::unique_ptr<framing::StreamSplitter>(
            std::make_unique<framing::FramerSplitter<viewpro::OutputFramer, frame_size>>());
    };
    e.make_track_decoder = make_viewpro_track_decoder;
    e.simulator = viewpro_simulator();
    return e;
}

}  // namespace

const Entry& viewpro_entry() {
    static const Entry entry = make_entry();
    return entry;
}

}  // namespace gimbal::protocols
