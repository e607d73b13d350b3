#include "mqtt_bridge.hpp"

#include <chrono>

#include "state/messages.hpp"
#include "subscriptions.hpp"

namespace gimbald::mqtt {

namespace asio = boost::asio;
using nlohmann::json;

std::string request_source(const Incoming& in) {
    if (in.client_id && !in.client_id->empty()) return "mqtt:" + *in.client_id;
    if (in.response_topic && !in.response_topic->empty()) return "mqtt:" + *in.response_topic;
    return "mqtt";
}

Bridge::Bridge(asio::io_context& io, const gimbal::daemon::MqttConfig& config, RequestPath& path,
               EventHub& events)
    : io_(io), config_(config), path_(path), base_(config.prefix + "/" + config.station) {
    ClientOptions o;
    o.host = config_.host;
    o.port = config_.port;
    o.tls = config_.tls;
    o.ca_file = config_.ca_file;
    o.cert_file = config_.cert_file;
    o.key_file = config_.key_file;
    o.username = config_.username;
    o.password = config_.password;
    o.client_id = config_.client_id;
    o.keepalive_s = static_cast<int>(config_.keepalive_s);
    o.will_topic = topic("status");
    o.will_payload = json{{"online", false}}.dump();
    if (config_.commands) o.subscriptions.push_back(topic("cmd"));
    o.queue_max = config_.queue_max;
    client_ = std::make_unique<Client>(
        io_, std::move(o), [this](const Incoming& in) { on_message(in); },
        [this] { on_connected(); });

    events.add([this](const std::string& gimbal, const gimbal::state::Event& e) {
        if (stopped_) return;
        client_->publish({Kind::event,
                          topic(gimbal + "/event"),
                          gimbal::state::event_message(gimbal, e).dump(),
                          1,
                          false,
                          {}});
        if (e.kind == "link") {
            if (const auto* session = path_.find(gimbal))
                publish_link(gimbal, session->connected());
        }
    });
    for (auto* session : path_.sessions()) {
        session->add_state_key("mqtt", [this] { return state_key(); });
        auto& stream = streams_[session->name()];
        stream.pacer = std::make_unique<StatePacer>(io_, config_.state_rate_hz,
                                                    [this, session] { publish_state(*session); });
        // STATE follows the gimbal's telemetry (state_pacer.hpp), not a fixed tick.
        session->add_receive_listener([this, session, &stream] {
            if (stopped_ || session->telemetry_count() == stream.telemetry_seen) return;
            stream.telemetry_seen = session->telemetry_count();
            stream.pacer->on_telemetry();
        });
    }
}

json Bridge::state_key() const {
    const auto& c = client_->counters();
    return {{"connected", client_->connected()},
            {"published", c.published},
            {"dropped", c.dropped},
            {"reconnects", c.reconnects}};
}

void Bridge::start() {
    client_->start();
    for (auto& [name, stream] : streams_) stream.pacer->publish_now();
}

void Bridge::stop() {
    if (stopped_) return;
    stopped_ = true;
    for (auto& [name, stream] : streams_) stream.pacer->stop();
    client_->stop({Kind::retained, topic("status"), json{{"online", false}}.dump(), 1, true, {}});
}

void Bridge::on_connected() {
    // Retained topics may be gone (a broker restarted without persistence): publish anew.
    json gimbals = json::array();
    for (const auto* s : path_.sessions()) gimbals.push_back(s->name());
    client_->publish(
        {Kind::retained,
         topic("status"),
         json{{"online", true}, {"version", GIMBALD_VERSION}, {"gimbals", gimbals}}.dump(),
         1,
         true,
         {}});
    for (auto* s : path_.sessions()) {
        publish_link(s->name(), s->connected());
        auto& stream = streams_.at(s->name());
        stream.cursor.restart();  // the broker may have lost what was in flight
        stream.pacer->publish_now();
    }
}

void Bridge::publish_link(const std::string& gimbal, bool connected) {
    client_->publish({Kind::retained,
                      topic(gimbal + "/link"),
                      json{{"connected", connected}}.dump(),
                      1,
                      true,
                      {}});
}

void Bridge::publish_state(GimbalSession& session) {
    if (config_.state_changes) {
        publish_delta(session);
        return;
    }
    json state = session.snapshot();
    if (config_.state_keys) state = gimbal::state::select_keys(state, *config_.state_keys);
    client_->publish({Kind::state,
                      topic(session.name() + "/state"),
                      state.dump(-1, ' ', false, json::error_handler_t::replace),
                      0,
                      true,
                      {}});
}

// mqtt.state_changes (contract section 14): the delta-stream message of section 4.1. Full
// STATEs are retained (what a newcomer gets first), patches are not.
void Bridge::publish_delta(GimbalSession& session) {
    auto& stream = streams_.at(session.name());
    const auto dropped = client_->counters().dropped;
    if (!client_->connected() || dropped != stream.dropped_seen) stream.cursor.restart();
    stream.dropped_seen = dropped;
    gimbal::state::StreamOptions options;
    if (config_.state_keys) options.keys = *config_.state_keys;
    options.changes = true;
    options.full_every_s = config_.state_full_every_s;
    gimbal::state::PushBatch batch(session.name(), session.snapshot());
    const auto& message = batch.next(options, stream.cursor, steady_seconds());
    const bool full = message.full().value_or(true);
    client_->publish({Kind::state, topic(session.name() + "/state"), *message.text(), 0, full, {}});
}

void Bridge::on_message(const Incoming& in) {
    if (stopped_ || !config_.commands || in.topic != topic("cmd")) return;
    if (in.retained) {
        // A retained request would run again at every reconnection: never execute one.
        gimbal::log::warn("mqtt_retained_cmd",
                          "ignored a retained request on " + in.topic +
                              " (publish requests without the retain flag; clear it with an "
                              "empty retained message)",
                          {{"src", request_source(in)}});
        return;
    }
    const RequestSource from{"mqtt", request_source(in), std::nullopt};
    const auto reply = path_.handle(in.payload, from);
    if (!reply) return;
    // Replies may not land on our own topics (status, state, ...) except below P/reply.
    const auto& rt = in.response_topic;
    const bool to_response_topic =
        rt && !rt->empty() && rt->find_first_of("+#") == std::string::npos &&
        (rt->rfind(base_ + "/", 0) != 0 || rt->rfind(topic("reply/"), 0) == 0);
    client_->publish({Kind::event, to_response_topic ? *in.response_topic : topic("reply"), *reply,
                      1, false, to_response_topic ? in.correlation : std::nullopt});
}

}  // namespace gimbald::mqtt
