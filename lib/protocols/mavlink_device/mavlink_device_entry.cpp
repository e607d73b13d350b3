#include "protocols/mavlink_device/mavlink_device_entry.hpp"

#include <stdexcept>

#include "protocols/mavlink_device/mavlink_device_capabilities.hpp"
#include "protocols/mavlink_device/mavlink_device_feed.hpp"
#include "protocols/mavlink_device/mavlink_device_protocol.hpp"
#include "protocols/mavlink_device/mavlink_device_track.hpp"
#include "protocols/mavlink_device/mavlink_frame_scanner.hpp"

namespace gimbal::protocols {

namespace {

// The catalogue commands a MAVLink gimbal device plans (mavlink_device_commands.cpp).
constexpr PlannedCommand commands[] = {
    {"geopoint",
     "GIMBAL_DEVICE_SET_ATTITUDE (284), recomputed at 20 Hz; `stare`: a `stare_start` event "
     "once on the point; `joystick_range_m` must be 0"},
    {"path",
     "GIMBAL_DEVICE_SET_ATTITUDE (284) along the path, at 20 Hz; step-stare: a `stare_start` "
     "event at each stare"},
    {"stare_ack", "nothing on the wire: ends the current stare of a path's step-stare"},
    {"position",
     "GIMBAL_DEVICE_SET_ATTITUDE (284), yaw in the vehicle frame; `stabilized`: held from "
     "north (heading + pan)"},
    {"center", "GIMBAL_DEVICE_SET_ATTITUDE (284) at yaw 0, pitch 0 in the vehicle frame"},
    {"rate",
     "GIMBAL_DEVICE_SET_ATTITUDE (284) with angular velocities, from north when `stabilized`"},
};

std::unique_ptr<session::Protocol> make_session(const SessionSettings& s,
                                                const nlohmann::json& gimbal) {
    MavlinkDeviceOptions options = read_mavlink_device_options(gimbal);
    options.stale_after_s = s.stale_after_s;
    options.auto_ack_stare = s.auto_ack_stare;
    options.terrain = s.terrain;
    options.unix_clock = s.unix_clock;
    options.geoid = s.geoid_undulation;
    if (options.signing_key_file) {
        // config.cpp has checked the file; it may have changed since.
        auto key = load_signing_key(*options.signing_key_file, s.read_secret);
        if (!key) throw std::runtime_error(key.error().message);
        options.signing_key = *key;
    }
    return std::make_unique<MavlinkDeviceProtocol>(options);
}

// gimbals[].mavlink, with its signing key file read as the session will read it.
nlohmann::json read_config(config::Fields& gimbal, const ConfigContext& context) {
    MavlinkDeviceConfig read;
    fields(gimbal, read);
    if (read.signing_key_file) {
        if (auto key = load_signing_key(*read.signing_key_file, context.read_secret); !key)
            gimbal.problems().add(gimbal.path("mavlink.signing_key_file"), key.error().message);
    }
    return config::write(read);
}

// A configured geoid_undulation_m is a fixed override; without it the session asks the
// geoid at the aircraft's position.
bool needs_geoid(const nlohmann::json& gimbal) {
    return !read_mavlink_device_options(gimbal).geoid_undulation_m.has_value();
}

// STATE `device`: the gimbal device's own report (contract section 19).
constexpr std::string_view state_keys[] = {"device"};

std::size_t frame_size(const ScannedFrame& f) {
    return f.bytes.size();
}

Entry make_entry() {
    Entry e;
    e.id = ProtocolId::mavlink;
    e.name = "mavlink";
    e.display_name = "MAVLink";
    e.dissector = "mavlink";
    e.commands = commands;
    e.state_keys = state_keys;
    e.features = mavlink_device_features();
    e.config_section = "mavlink";
    e.read_config = read_config;
    e.make_session = make_session;
    e.make_feeder = make_mavlink_device_feeder;
    e.needs_geoid = needs_geoid;
    e.make_splitter = [] {
        return std::unique_ptr<framing::StreamSplitter>(
            std::make_unique<framing::FramerSplitter<MavlinkFrameScanner, frame_size>>());
    };
    e.make_track_decoder = make_mavlink_device_track_decoder;
    e.simulator = mavlink_device_simulator();
    return e;
}

}  // namespace

const Entry& mavlink_device_entry() {
    static const Entry entry = make_entry();
    return entry;
}

}  // namespace gimbal::protocols
