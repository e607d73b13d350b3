// The running daemon: one io_context, a session per configured gimbal, the command server,
// signals (SIGTERM/SIGINT stop, SIGHUP reopens the log) and systemd notification.
#pragma once

#include <boost/asio/io_context.hpp>
#include <boost/asio/signal_set.hpp>
#include <boost/asio/steady_timer.hpp>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "command_server.hpp"
#include "config.hpp"
#include "event_hub.hpp"
#include "gimbal_session.hpp"
#include "http/http_server.hpp"
#include "link/sim_link.hpp"
#include "mavlink_endpoint.hpp"
#include "mqtt/mqtt_bridge.hpp"
#include "protocols/registry.hpp"
#include "record/recorder.hpp"
#include "request_path.hpp"
#include "terrain/elevation_model.hpp"
#include "terrain_loader.hpp"
#include "track/track_controller.hpp"
#include "vehicle_feed.hpp"
#include "video/gimbal_video.hpp"
#include "video/sim_video_sender.hpp"

namespace gimbald {

class App {
  public:
    // Builds every session and binds the command socket; throws on a bind failure. `terrain`
    // is the elevation model opened from the configuration (null without a terrain section).
    explicit App(const gimbal::daemon::Config& config,
                 std::unique_ptr<gimbal::terrain::ElevationModel> terrain = nullptr);
    ~App();

    // Runs until SIGTERM/SIGINT; returns the process exit code.
    int run();
    // A terrain read was still running when run() returned (stop_terrain_reads): the process
    // must end with std::_Exit, so that nothing tears GDAL down under that read.
    static bool left_a_terrain_read_running();

  private:
    std::unique_ptr<gimbal::session::Protocol> make_protocol(
        const gimbal::protocols::Entry& protocol, const nlohmann::json& gimbal);
    std::unique_ptr<Link> make_link(const gimbal::daemon::GimbalConfig& g);
    void add_sim_video(SimLink& link, const gimbal::daemon::GimbalConfig& g);
    void start_recorder();
    void tap_recorder();
    void on_signal(const boost::system::error_code& ec, int signo);
    void shutdown();
    void stop_terrain_reads();
    void arm_watchdog();
    void poll_logs();  // once a second: the log roll-up's summaries of stopped bursts
    void start_http();
    void start_video();
    void start_tracking();
    void tap_track_recording();
    void update_status();
    void open_geoid_if_needed(const nlohmann::json& gimbal_objects);

    gimbal::daemon::Config config_;
    boost::asio::io_context io_;
    boost::asio::signal_set signals_;
    boost::asio::steady_timer watchdog_timer_;
    boost::asio::steady_timer log_timer_;  // the log roll-up's summaries (log::poll)
    // Contract section 15: one model shared by every gimbal; declared before them so it
    // outlives them. Its blocks are read on the loader's thread (section 14 v4), which stops
    // before the model goes and after the sessions that look blocks up.
    std::unique_ptr<gimbal::terrain::ElevationModel> terrain_;
    std::unique_ptr<TerrainLoader> terrain_loader_;
    // The EGM96 undulation for sessions that ask (open_geoid), after terrain_ it may use.
    std::function<std::optional<double>(double, double)> geoid_;
    // Declared before everything that records into it, so it outlives them.
    std::unique_ptr<record::Recorder> recorder_;  // contract section 12; null unless `record`
    std::vector<std::unique_ptr<GimbalSession>> sessions_;
    // Contract section 17: per gimbal, null unless it has a `video` section.
    std::vector<std::unique_ptr<video::GimbalVideo>> videos_;
    // A simulated gimbal with `video` sends its camera's picture to that video's input.
    std::vector<std::unique_ptr<video::SimVideoSender>> sim_videos_;
    // Contract section 20: per gimbal with video.tracking, its gimbal-track and tracks;
    // after videos_ and sessions_, which they use.
    std::vector<std::unique_ptr<track::TrackController>> trackers_;
    EventHub events_;
    std::unique_ptr<RequestPath> request_path_;
    std::unique_ptr<CommandServer> server_;
    std::unique_ptr<VehicleFeed> vehicle_;
    std::unique_ptr<MavlinkEndpoint> mavlink_;
    std::unique_ptr<mqtt::Bridge> mqtt_;      // contract section 9; null unless `mqtt` is set
    std::unique_ptr<http::HttpServer> http_;  // contract section 11; null unless `http` is set
    bool stopping_ = false;
    std::string stop_signal_;  // "SIGTERM" or "SIGINT", once one asked gimbald to stop
};

}  // namespace gimbald
