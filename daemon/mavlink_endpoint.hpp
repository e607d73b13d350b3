// The MAVLink gimbal manager (contract sections 8 and 14): on the vehicle's MAVLink endpoint,
// every gimbal is a gimbal manager component of its own (154, then 171..175) that answers
// COMMAND_LONG/COMMAND_INT and the gimbal set-point messages addressed to it and streams
// HEARTBEAT, GIMBAL_MANAGER_STATUS, GIMBAL_DEVICE_ATTITUDE_STATUS and CAMERA_FOV_STATUS. Each
// gimbal is also a camera component (100..105, contract section 16): HEARTBEAT, the camera
// protocol's information and status messages, click-to-track (CAMERA_TRACK_POINT -> `point`
// with stare) and CAMERA_TRACKING_GEO_STATUS while a point is held. What a
// message means is decided by lib/gimbal_protocol (pure); every gimbal request goes through
// RequestPath::execute (validation, laser rules, `command` log line with src "mavlink:SYS/COMP").
// MAVLink 2 signing when a key is configured.
#pragma once

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>
#include <chrono>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "config.hpp"
#include "gimbal_protocol/camera.hpp"
#include "gimbal_protocol/commands.hpp"
#include "gimbal_session.hpp"
#include "logging.hpp"
#include "mavlink/messages.hpp"
#include "mavlink/signing.hpp"
#include "request_path.hpp"
#include "vehicle_feed.hpp"
#include "video/video_config.hpp"

namespace gimbald {

struct MavlinkCounters {
    std::uint64_t commands = 0;          // commands and set-points addressed to us, handled
    std::uint64_t denied = 0;            // answered DENIED (control or parameters)
    std::uint64_t unsigned_ignored = 0;  // signing on: unsigned, badly signed or replayed
    std::uint64_t sent = 0;              // frames sent
};

class MavlinkEndpoint {
  public:
    // Reads nothing from disk: the signing key comes loaded. Resolves `targets` (throws on a
    // name that does not resolve). `feed` must have a vehicle source. `videos`: the `video`
    // section of each gimbal that has one (the streams its camera component announces).
    MavlinkEndpoint(boost::asio::io_context& io, const gimbal::daemon::MavlinkConfig& config,
                    std::optional<gimbal::mavlink::SigningKey> key, VehicleFeed& feed,
                    RequestPath& path, const std::vector<GimbalSession*>& sessions,
                    const std::map<std::string, video::VideoConfig>& videos = {});
    ~MavlinkEndpoint();

    void start();
    void stop();

    // The STATE `mavlink` object for one gimbal.
    nlohmann::json snapshot(const std::string& gimbal) const;
    const MavlinkCounters& counters() const { return counters_; }

  private:
    void on_message(const gimbal::mavlink::Message& m);
    // Signing off: true. On: a verified signature that is not a replay (the stream's timestamp
    // is recorded, so call it once per message).
    bool authentic(const gimbal::mavlink::Message& m);
    // A command or set-point addressed to us is obeyed only when authentic; counted if not.
    bool obeyed(bool authentic);
    // Executes or answers one command (ack_command set) or set-point message (msgid), as
    // `component`; a refusal is logged (mavlink_refused).
    // Returns the answer, and the first request's results when it succeeded.
    struct Ran {
        gimbal::mavlink::MavResult result = gimbal::mavlink::MavResult::accepted;
        nlohmann::json results;
    };
    Ran run(gimbal::gimbal_protocol::Mapped mapped, const gimbal::gimbal_protocol::MavId& from,
            std::optional<std::uint16_t> ack_command, std::uint8_t component,
            std::uint32_t msgid = 0);
    // A COMMAND_LONG/COMMAND_INT addressed to camera component `camera` (signature checked).
    void on_camera_command(const gimbal::gimbal_protocol::CommandView& command,
                           const gimbal::gimbal_protocol::ExposedCamera& camera,
                           const gimbal::gimbal_protocol::MavId& from);
    // Click-to-track: the point a camera holds, per gimbal device id.
    void hold(const gimbal::gimbal_protocol::ExposedCamera& camera, const nlohmann::json& located,
              float radius);
    void release(std::uint8_t device_id, const char* why);
    // Another MAVLink steering of a gimbal ends its click-to-track (the requests' gimbals).
    static std::vector<std::string> steered_gimbals(const gimbal::gimbal_protocol::Mapped& mapped);
    void release_steered(const std::vector<std::string>& gimbals);
    // Releases a held point whose gimbal went to steering other than geopoint (an operator's
    // command on another transport).
    void check_held();
    std::optional<gimbal::gimbal_protocol::ImageAt> image_at(
        const std::string& gimbal, const gimbal::gimbal_protocol::HeldPoint& held) const;
    static gimbal::gimbal_protocol::Mapped refused(gimbal::mavlink::MavResult result,
                                                   std::string reason);
    std::uint8_t first_component() const;
    void send(const gimbal::mavlink::Payload& payload, std::uint8_t component);
    void schedule_tick();
    void on_tick();
    std::optional<std::uint8_t> system_id() const;
    gimbal::gimbal_protocol::VehicleView vehicle_view() const;
    std::uint32_t time_boot_ms() const;
    // The local signing timestamp: the system clock, never behind clock_.
    std::uint64_t signing_now() const;
    void restore_signing_state();
    void save_signing_state_now();
    // The gimbal's typed state (capabilities, telemetry, health, video); an empty view for a
    // name no session has.
    gimbal::session::GimbalView state_of(const std::string& gimbal) const;

    gimbal::daemon::MavlinkConfig config_;
    std::optional<gimbal::mavlink::SigningKey> key_;
    gimbal::mavlink::SigningStreams streams_;
    gimbal::mavlink::SigningClock clock_;
    VehicleFeed& feed_;
    RequestPath& path_;
    std::vector<GimbalSession*> sessions_;
    gimbal::gimbal_protocol::GimbalManager manager_;
    gimbal::gimbal_protocol::CameraComponents cameras_;
    struct Held {
        gimbal::gimbal_protocol::HeldPoint point;
        std::uint64_t since_tick = 0;
        std::uint64_t next_geo_tick = 0, next_image_tick = 0;
    };
    std::map<std::uint8_t, Held> held_;  // by gimbal device id
    // A camera's visual track (STATE `track`, whoever started it): when its status messages
    // are next due, and whether one ran at the last tick (its end sends IDLE once).
    struct VisualStatus {
        bool running = false;
        std::uint64_t next_geo_tick = 0, next_image_tick = 0;
    };
    std::map<std::uint8_t, VisualStatus> visual_;  // by camera component id
    void send_visual_status(const gimbal::gimbal_protocol::ExposedCamera& camera,
                            const gimbal::session::GimbalView& state);
    boost::asio::steady_timer timer_;
    std::chrono::steady_clock::time_point epoch_;
    std::chrono::steady_clock::time_point next_tick_;
    std::uint64_t ticks_ = 0;
    std::map<std::uint8_t, std::uint8_t> seq_;  // per component: each is a sender of its own
    MavlinkCounters counters_;
    bool signing_dirty_ = false;  // a stream advanced since the last save
    gimbal::log::RateLimitedLog save_errors_{gimbal::log::Level::error, "mavlink_signing_state",
                                             "failed saves"};
    bool stopped_ = true;
};

// A MAVLink signing key file: 32 raw bytes, or 64 hex digits (surrounding white space
// ignored). Throws gimbal::daemon::ConfigError naming the problem.
gimbal::mavlink::SigningKey load_signing_key(const std::string& path);

}  // namespace gimbald
