#include "metrics_page.hpp"

#include <limits>

#include "metrics/exposition.hpp"
#include "state/precision.hpp"

namespace gimbald::http {

using gimbal::metrics::Exposition;
using gimbal::metrics::Labels;
using gimbal::metrics::Type;

namespace {

// The age of the gimbal's latest position telemetry, to the millisecond as STATE shows ages.
// +Inf until the first one arrives, so an alert on "age > N" fires for a gimbal that never
// sent any.
double telemetry_age_s(const GimbalSession& session) {
    const auto age = session.telemetry_age_s();
    return age ? gimbal::state::seconds(*age) : std::numeric_limits<double>::infinity();
}

}  // namespace

std::string render_metrics(const DaemonView& daemon, const CommandMetrics& commands,
                           const HttpStats& http) {
    Exposition e;
    e.family("gimbald_build_info", Type::gauge, "Always 1; the version is a label.");
    e.sample({{"version", GIMBALD_VERSION}}, 1);

    // The link read once per gimbal: every link metric comes from the same instant.
    struct Gimbal {
        GimbalSession* session;
        gimbal::state::LinkState link;
    };
    std::vector<Gimbal> gimbals;
    for (auto* session : daemon.path->sessions())
        gimbals.push_back({session, session->link_state()});
    auto per_gimbal = [&](const char* name, Type type, const char* help, auto value) {
        e.family(name, type, help);
        for (const auto& g : gimbals) e.sample({{"gimbal", g.session->name()}}, value(g));
    };
    using Counter = std::uint64_t gimbal::state::LinkState::*;
    auto link_counter = [&](const char* name, Counter counter, const char* help) {
        per_gimbal(name, Type::counter, help,
                   [counter](const Gimbal& g) { return static_cast<double>(g.link.*counter); });
    };
    using gimbal::state::LinkState;
    per_gimbal("gimbald_link_up", Type::gauge, "1 when the gimbal's link is connected.",
               [](const Gimbal& g) { return g.session->connected() ? 1.0 : 0.0; });
    link_counter("gimbald_link_rx_bytes_total", &LinkState::rx_bytes,
                 "Bytes received from the gimbal.");
    link_counter("gimbald_link_tx_bytes_total", &LinkState::tx_bytes,
                 "Bytes written to the gimbal.");
    link_counter("gimbald_link_rx_packets_total", &LinkState::rx_packets,
                 "Valid packets received from the gimbal.");
    link_counter("gimbald_link_tx_packets_total", &LinkState::tx_packets,
                 "Packets written to the gimbal.");
    link_counter("gimbald_link_bad_checksums_total", &LinkState::bad_checksums,
                 "Frames from the gimbal dropped for a bad checksum.");
    link_counter("gimbald_link_dropped_bytes_total", &LinkState::dropped_bytes,
                 "Bytes from the gimbal skipped while looking for a frame.");
    link_counter("gimbald_link_reconnects_total", &LinkState::reconnects, "Link reconnections.");
    per_gimbal("gimbald_telemetry_age_seconds", Type::gauge,
               "Age of the gimbal's latest position telemetry; +Inf before the first.",
               [](const Gimbal& g) { return telemetry_age_s(*g.session); });
    per_gimbal("gimbald_telemetry_stale", Type::gauge,
               "1 when no telemetry arrived within telemetry.stale_after_s.",
               [](const Gimbal& g) { return g.session->stale() ? 1.0 : 0.0; });

    e.family("gimbald_laser_firing", Type::gauge,
             "1 while the daemon last commanded this laser to fire (dead-man pending).");
    for (const auto& g : gimbals) {
        if (!g.session->supports("laser")) continue;  // a protocol without laser commands
        for (std::uint8_t index = 0; index < 2; ++index)
            e.sample({{"gimbal", g.session->name()}, {"index", std::to_string(index)}},
                     g.session->laser_firing(index) ? 1.0 : 0.0);
    }

    e.family("gimbald_track_steer_latency_seconds", Type::histogram,
             "Visual tracking: from a frame's arrival to the steering command its box made "
             "due, handed to the gimbal's link (commands of the 20 Hz tick not counted).");
    for (const auto& g : gimbals) {
        const auto* latency =
            daemon.track_steer_latency ? daemon.track_steer_latency(g.session->name()) : nullptr;
        if (latency != nullptr) e.histogram({{"gimbal", g.session->name()}}, *latency);
    }

    e.family("gimbald_commands_total", Type::counter,
             "Requests completed by the request path (every transport), by command and result "
             "(ok or the error code).");
    for (const auto& [key, count] : commands.totals())
        e.sample({{"cmd", key.first}, {"result", key.second}}, static_cast<double>(count));
    e.family("gimbald_command_duration_seconds", Type::histogram,
             "Time from a request's arrival to its reply, every transport.");
    e.histogram({}, commands.durations());

    const auto& counters = daemon.path->counters();
    e.family("gimbald_requests_rate_limited_total", Type::counter,
             "Requests refused by command.rate_limit.");
    e.sample({}, static_cast<double>(counters.rate_limited));
    e.family("gimbald_dropped_sources_total", Type::counter,
             "Datagrams and connections from sources outside command.allow.");
    e.sample({{"transport", "udp"}},
             static_cast<double>(daemon.udp_dropped_sources ? daemon.udp_dropped_sources() : 0));
    e.sample({{"transport", "http"}}, static_cast<double>(http.refused_total));

    const double udp = daemon.udp_subscribers ? static_cast<double>(daemon.udp_subscribers()) : 0;
    e.family("gimbald_subscribers", Type::gauge,
             "STATE subscribers: UDP subscriptions plus WebSocket clients.");
    e.sample({}, udp + static_cast<double>(http.websocket_clients));
    e.family("gimbald_vehicle_up", Type::gauge,
             "1 while the vehicle's MAVLink feed is fresh; 0 without a vehicle section.");
    e.sample({}, daemon.vehicle_up && daemon.vehicle_up() ? 1 : 0);
    e.family("gimbald_mqtt_up", Type::gauge,
             "1 while connected to the MQTT broker; 0 without an mqtt section.");
    e.sample({}, daemon.mqtt_up && daemon.mqtt_up() ? 1 : 0);

    e.family("gimbald_http_connections", Type::gauge, "Open HTTP and WebSocket connections.");
    e.sample({}, static_cast<double>(http.open_connections + http.websocket_clients +
                                     http.video_viewers));
    e.family("gimbald_http_connections_total", Type::counter, "HTTP connections accepted.");
    e.sample({}, static_cast<double>(http.connections_total));
    e.family("gimbald_http_connections_rejected_total", Type::counter,
             "HTTP connections closed at once because http.max_connections were open, or "
             "http.max_connections_per_client from that address.");
    e.sample({}, static_cast<double>(http.over_capacity_total));
    e.family("gimbald_http_cross_site_refused_total", Type::counter,
             "HTTP requests refused (403) because their Host or Origin names another site.");
    e.sample({}, static_cast<double>(http.cross_site_total));
    e.family("gimbald_http_responses_total", Type::counter, "HTTP responses by status code.");
    for (const auto& [status, count] : http.responses_total)
        e.sample({{"code", std::to_string(status)}}, static_cast<double>(count));
    e.family("gimbald_websocket_clients", Type::gauge, "Open WebSocket streams (/api/stream).");
    e.sample({}, static_cast<double>(http.websocket_clients));
    e.family("gimbald_websocket_dropped_total", Type::counter,
             "WebSocket clients dropped because their send queue was full.");
    e.sample({}, static_cast<double>(http.websocket_dropped_total));
    e.family("gimbald_send_failures_total", Type::counter,
             "Replies and pushes that could not be sent: the UDP command socket's (reply or "
             "push) and WebSocket messages.");
    const auto count = [](const std::function<std::uint64_t()>& f) {
        return static_cast<double>(f ? f() : 0);
    };
    e.sample({{"transport", "udp"}}, count(daemon.udp_send_failed));
    e.sample({{"transport", "websocket"}}, static_cast<double>(http.websocket_send_failed_total));
    e.family("gimbald_pushes_too_large_total", Type::counter,
             "UDP subscription pushes over one datagram, replaced by a too_large event.");
    e.sample({}, count(daemon.udp_pushes_too_large));
    e.family("gimbald_video_viewers", Type::gauge, "Open video WebSockets (/api/video/{gimbal}).");
    e.sample({}, static_cast<double>(http.video_viewers));
    e.family("gimbald_video_viewers_dropped_total", Type::counter,
             "Video viewers dropped because they stopped reading.");
    e.sample({}, static_cast<double>(http.video_dropped_total));
    e.family("gimbald_video_backlogs_dropped_total", Type::counter,
             "Times a video viewer fell behind and skipped to the next key frame.");
    e.sample({}, static_cast<double>(http.video_backlogs_dropped_total));
    return e.text();
}

}  // namespace gimbald::http
