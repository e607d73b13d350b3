// One configured gimbal at run time: link -> protocol (framer, state, commands) ->
// subscribers. Owns the timers of its protocol (staleness, laser dead-man) and the link's
// life cycle. The same class serves Orion and Viewpro: the protocol object holds the
// differences.
#pragma once

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>
#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "link/link.hpp"
#include "logging.hpp"
#include "session/gimbal_view.hpp"
#include "session/laser_guard.hpp"
#include "session/protocol.hpp"
#include "state/event.hpp"
#include "state/link_state.hpp"

namespace gimbald {

class GimbalSession {
  public:
    using EventSink = std::function<void(const std::string& gimbal, const gimbal::state::Event&)>;

    GimbalSession(boost::asio::io_context& io, std::string name,
                  std::unique_ptr<gimbal::session::Protocol> protocol, std::unique_ptr<Link> link,
                  double fire_timeout_s, EventSink on_event);
    ~GimbalSession();

    void start();
    // Sends cease-fire for any laser still firing (synchronously, ahead of everything queued),
    // then closes the link.
    void stop();

    const std::string& name() const { return name_; }
    std::string_view protocol() const { return protocol_->name(); }
    bool connected() const { return link_->connected(); }
    // Position telemetry received so far: a listener sees whether a chunk carried any.
    std::uint64_t telemetry_count() const { return protocol_->telemetry_count(); }
    std::string link_type() const { return link_->type(); }
    // The daemon's own record of a laser it commanded to fire (metrics).
    bool laser_firing(std::uint8_t index) const { return lasers_.firing(index); }

    bool supports(std::string_view cmd) const {
        return protocol_->supports(cmd) || commands_.count(std::string(cmd)) != 0;
    }
    // What the gimbal can do and how its camera sees (session/capabilities.hpp), bound to its
    // live state.
    const gimbal::session::Capabilities& capabilities() const { return protocol_->capabilities(); }
    // The gimbal as the daemon's consumers read it (typed STATE: capabilities, telemetry,
    // health, video), for the MAVLink endpoint, KLV and the image commands.
    gimbal::session::GimbalView view() const;
    // Runs a gimbal command: validate, refuse (nothing sent) or write its packets.
    // Returns the reply results (with "sent") or the error.
    struct Outcome {
        std::optional<gimbal::command::Error> error;
        nlohmann::json results = nlohmann::json::object();
    };
    Outcome execute(std::string_view cmd, const nlohmann::json& request);

    // STATE `link`: the link's and the framer's counters now.
    gimbal::state::LinkState link_state() const;
    // No telemetry within telemetry.stale_after_s (STATE `stale`).
    bool stale() const;
    // Seconds since the gimbal's latest position telemetry; nullopt before the first.
    std::optional<double> telemetry_age_s() const { return protocol_->telemetry_age_s(now_s()); }
    // STATE (contract section 5) as JSON: for the edges (replies, pushes, MQTT, HTTP,
    // recordings); consumers inside the daemon read the typed parts.
    nlohmann::json snapshot() const;
    // The vehicle feed: writes one feed packet when the link is up (false otherwise), beside
    // the commands on the same ordered queue.
    bool send_feed(std::vector<std::uint8_t> bytes);
    // The vehicle feed's tick: what the protocol sends from the vehicle's state itself
    // (session::Protocol::steer), written like the feed when the link is up.
    // Returns how many of the vehicle feed's own frames were sent (STATE vehicle.feed.sent).
    std::uint64_t steer(const gimbal::vehicle::VehicleState& vehicle, double vehicle_now_s);
    // Fills STATE's top-level `vehicle` key.
    void set_vehicle_snapshot(std::function<nlohmann::json()> vehicle_snapshot) {
        vehicle_snapshot_ = std::move(vehicle_snapshot);
    }
    // STATE `video` (null until set, and for a gimbal without a video section).
    void set_video(std::function<std::optional<gimbal::state::VideoState>()> video) {
        video_ = std::move(video);
    }
    // STATE `track` (null while no visual track runs, and for a gimbal without tracking).
    void set_track(std::function<std::optional<gimbal::state::TrackState>()> track) {
        track_ = std::move(track);
    }
    // A daemon-level top-level STATE key (`command`, `mavlink`, `mqtt`, `record`), filled at
    // every snapshot.
    void add_state_key(std::string key, std::function<nlohmann::json()> fill) {
        state_keys_.emplace_back(std::move(key), std::move(fill));
    }
    // Called after every chunk of bytes from the gimbal has updated the state (streams that
    // want to follow new telemetry at once, such as MQTT).
    void add_receive_listener(std::function<void()> listener) {
        receive_listeners_.push_back(std::move(listener));
    }
    // A command every gimbal answers from daemon-level data rather than its protocol (`klv`,
    // contract section 17): execute() runs it, with no link needed.
    using LocalCommand =
        std::function<gimbal::command::Result<nlohmann::json>(const nlohmann::json& request)>;
    void add_command(std::string cmd, LocalCommand handler) {
        commands_[std::move(cmd)] = std::move(handler);
    }
    // Short text for systemd's STATUS= line.
    std::string status() const;

  private:
    double now_s() const;
    void on_data(std::span<const std::uint8_t> bytes);
    void on_link_state(bool connected);
    void on_link_error(std::string_view what, std::string_view detail);
    void emit(std::vector<gimbal::state::Event>& events);
    void schedule_tick();
    void arm_deadman();
    void on_deadman();
    // Cease-fires go on the link's safety lane and count as sent when written.
    enum class CeaseCause { deadman, reconnect };
    bool queue_cease(const gimbal::session::LaserGuard::Cease& cease, CeaseCause cause);
    void on_cease_written(const gimbal::session::LaserGuard::Cease& cease, CeaseCause cause,
                          bool written);
    void report_waiting_ceases();
    void report_counters();

    std::string name_;
    std::unique_ptr<gimbal::session::Protocol> protocol_;
    std::unique_ptr<Link> link_;
    gimbal::session::LaserGuard lasers_;
    EventSink on_event_;
    boost::asio::steady_timer tick_timer_;
    boost::asio::steady_timer deadman_timer_;
    std::chrono::steady_clock::time_point epoch_;
    bool stopped_ = false;
    gimbal::log::RateLimitedLog bad_checksums_;
    gimbal::log::RateLimitedLog decode_errors_;
    std::uint64_t reported_bad_checksums_ = 0;
    std::uint64_t reported_decode_errors_ = 0;
    std::function<nlohmann::json()> vehicle_snapshot_;
    std::function<std::optional<gimbal::state::VideoState>()> video_;
    std::function<std::optional<gimbal::state::TrackState>()> track_;
    std::vector<std::pair<std::string, std::function<nlohmann::json()>>> state_keys_;
    std::vector<std::function<void()>> receive_listeners_;
    std::map<std::string, LocalCommand> commands_;
};

}  // namespace gimbald
