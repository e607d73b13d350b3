// The MQTT bridge (contract section 9): publishes P/status, P/{gimbal}/state, /event and
// /link, and - when mqtt.commands is true - takes requests from P/cmd through the one
// request path, exactly as the UDP socket does, replying to the MQTT 5 response topic with
// the request's correlation data (else to P/reply). P = {prefix}/{station}.
#pragma once

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>
#include <chrono>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "config.hpp"
#include "event_hub.hpp"
#include "mqtt_client.hpp"
#include "request_path.hpp"
#include "state/state_push.hpp"
#include "state_pacer.hpp"

namespace gimbald::mqtt {

// The rate-limit key and log `src` of a request from MQTT. PUBLISH does not carry the
// sender's client id, so: the user property "client_id" when the publisher sets one, else its
// response topic, else "mqtt" (all anonymous requesters share one bucket).
std::string request_source(const Incoming& in);

class Bridge {
  public:
    Bridge(boost::asio::io_context& io, const gimbal::daemon::MqttConfig& config, RequestPath& path,
           EventHub& events);

    void start();
    void stop();  // publishes {"online": false} and disconnects cleanly

    nlohmann::json state_key() const;  // STATE `mqtt`

  private:
    void on_connected();
    void on_message(const Incoming& in);
    void publish_state(GimbalSession& session);
    void publish_delta(GimbalSession& session);
    void publish_link(const std::string& gimbal, bool connected);
    std::string topic(const std::string& tail) const { return base_ + "/" + tail; }

    boost::asio::io_context& io_;
    gimbal::daemon::MqttConfig config_;
    RequestPath& path_;
    std::string base_;  // {prefix}/{station}
    std::unique_ptr<Client> client_;
    // Per gimbal: when its STATE goes out, and the telemetry count it last carried. With
    // mqtt.state_changes: what the broker last got, and the client's drop count then (a
    // dropped message breaks the chain of patches: the next one is full).
    struct Stream {
        std::unique_ptr<StatePacer> pacer;
        std::uint64_t telemetry_seen = 0;
        gimbal::state::DeltaCursor cursor;
        std::uint64_t dropped_seen = 0;
    };
    std::map<std::string, Stream> streams_;
    bool stopped_ = false;
};

}  // namespace gimbald::mqtt
