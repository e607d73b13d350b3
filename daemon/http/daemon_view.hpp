// What the HTTP side reads of the rest of the daemon, handed in by App so daemon/http depends
// on no other transport: the configuration, the one request path (with the sessions), and a
// few numbers from the UDP socket, the vehicle feed and MQTT.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <string>

#include "config.hpp"
#include "metrics/histogram.hpp"
#include "request_path.hpp"
#include "video/video_tap.hpp"

namespace gimbald::http {

struct DaemonView {
    const gimbal::daemon::Config* config = nullptr;
    RequestPath* path = nullptr;
    std::function<std::size_t()> udp_subscribers;
    std::function<std::uint64_t()> udp_dropped_sources;
    std::function<std::uint64_t()> udp_send_failed;       // replies and pushes not sent
    std::function<std::uint64_t()> udp_pushes_too_large;  // replaced by a too_large event
    std::function<bool()> vehicle_up;                     // false without a vehicle section
    std::function<bool()> mqtt_up;                        // false without an mqtt section
    // Contract section 18: a gimbal's video, null for no such gimbal or one without video.
    std::function<video::VideoTap*(const std::string& gimbal)> video;
    // Contract section 20: a gimbal's frame received -> steering command sent latencies,
    // null for a gimbal without visual tracking.
    std::function<const gimbal::metrics::Histogram*(const std::string& gimbal)> track_steer_latency;
};

// The HTTP server's own counters (metrics).
struct HttpStats {
    std::uint64_t connections_total = 0;    // accepted and served
    std::uint64_t refused_total = 0;        // source not in command.allow
    std::uint64_t over_capacity_total = 0;  // closed at once: a connection cap reached
    std::uint64_t cross_site_total = 0;     // refused by the Host/Origin checks (403)
    std::size_t open_connections = 0;       // HTTP (WebSocket clients not included)
    std::size_t websocket_clients = 0;
    std::uint64_t websocket_dropped_total = 0;          // send queue full
    std::uint64_t websocket_send_failed_total = 0;      // a write failed (peer gone)
    std::map<unsigned, std::uint64_t> responses_total;  // by HTTP status
    std::size_t video_viewers = 0;                      // GET /api/video/{gimbal} streams
    std::uint64_t video_dropped_total = 0;              // viewers that stopped reading
    std::uint64_t video_backlogs_dropped_total = 0;     // frames skipped to the next key frame
};

}  // namespace gimbald::http
