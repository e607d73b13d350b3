#include "mqtt_run.hpp"

#include <mosquitto.h>
#include <mqtt_protocol.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <fstream>
#include <random>

#include "datagram.hpp"
#include "exit_status.hpp"
#include "output.hpp"
#include "signing.hpp"
#include "state/messages.hpp"
#include "state_merger.hpp"

namespace gimbalctl {
namespace {

std::atomic<bool> interrupted{false};

std::string random_hex(int n) {
    std::random_device rd;
    std::string out;
    for (int i = 0; i < n; ++i) out += "0123456789abcdef"[rd() % 16];
    return out;
}

struct Endpoint {
    std::string host;
    int port = 1883;
    bool tls = false;
};

std::optional<Endpoint> parse_url(const std::string& url, std::string& problem) {
    Endpoint e;
    std::string rest;
    if (url.rfind("mqtts://", 0) == 0) {
        e.tls = true;
        e.port = 8883;
        rest = url.substr(8);
    } else {
        rest = url.substr(7);
    }
    if (!rest.empty() && rest.back() == '/') rest.pop_back();
    std::string port;
    if (!rest.empty() && rest.front() == '[') {
        const auto close = rest.find(']');
        if (close == std::string::npos) {
            problem = "--mqtt: unclosed '['";
            return std::nullopt;
        }
        e.host = rest.substr(1, close - 1);
        if (close + 1 < rest.size() && rest[close + 1] == ':') port = rest.substr(close + 2);
    } else if (const auto colon = rest.rfind(':'); colon != std::string::npos) {
        e.host = rest.substr(0, colon);
        port = rest.substr(colon + 1);
    } else {
        e.host = rest;
    }
    if (!port.empty()) {
        try {
            e.port = std::stoi(port);
        } catch (...) {
            e.port = 0;
        }
    }
    if (e.host.empty() || e.port < 1 || e.port > 65535) {
        problem = "--mqtt: must be mqtt://HOST[:PORT] or mqtts://HOST[:PORT]";
        return std::nullopt;
    }
    return e;
}

// One broker connection driven by mosquitto_loop (gimbalctl is a short-lived client).
class Session {
  public:
    using OnMessage = std::function<void(const mosquitto_message&, const mosquitto_property*)>;

    Session(const MqttTarget& target, OnMessage on_message)
        : target_(target), on_message_(std::move(on_message)) {
        mosquitto_lib_init();
        client_id_ = "gimbalctl-" + random_hex(8);
        mosq_ = mosquitto_new(client_id_.c_str(), true, this);
    }
    ~Session() {
        if (mosq_ != nullptr) {
            mosquitto_disconnect(mosq_);
            mosquitto_loop(mosq_, 50, 1);
            mosquitto_destroy(mosq_);
        }
        mosquitto_lib_cleanup();
    }

    const std::string& client_id() const { return client_id_; }
    mosquitto* handle() { return mosq_; }

    // Connects and subscribes to `topics` (QoS 1); false with `problem` set on failure.
    bool open(const std::vector<std::string>& topics, double timeout_s, std::string& problem) {
        const auto endpoint = parse_url(target_.url, problem);
        if (!endpoint || mosq_ == nullptr) return false;
        topics_ = topics;
        mosquitto_int_option(mosq_, MOSQ_OPT_PROTOCOL_VERSION, MQTT_PROTOCOL_V5);
        mosquitto_connect_v5_callback_set(
            mosq_, [](mosquitto* m, void* self, int rc, int, const mosquitto_property*) {
                auto* s = static_cast<Session*>(self);
                s->connack_ = rc;
                if (rc != 0) return;
                for (const auto& t : s->topics_) {
                    int mid = 0;
                    mosquitto_subscribe_v5(m, &mid, t.c_str(), 1, 0, nullptr);
                    s->pending_subs_.push_back(mid);
                }
                s->subscribed_ = true;
            });
        mosquitto_subscribe_v5_callback_set(
            mosq_, [](mosquitto*, void* self, int mid, int, const int*, const mosquitto_property*) {
                auto* s = static_cast<Session*>(self);
                std::erase(s->pending_subs_, mid);
            });
        mosquitto_message_v5_callback_set(mosq_,
                                          [](mosquitto*, void* self, const mosquitto_message* msg,
                                             const mosquitto_property* props) {
                                              static_cast<Session*>(self)->on_message_(*msg, props);
                                          });
        if (target_.username) {
            std::string password;
            if (target_.password_file) {
                std::ifstream in(*target_.password_file);
                if (!in) {
                    problem = "cannot read " + *target_.password_file;
                    return false;
                }
                std::getline(in, password);
            }
            mosquitto_username_pw_set(mosq_, target_.username->c_str(),
                                      target_.password_file ? password.c_str() : nullptr);
        }
        if (endpoint->tls) {
            const int rc = mosquitto_tls_set(
                mosq_, target_.ca_file ? target_.ca_file->c_str() : nullptr,
                target_.ca_file ? nullptr : "/etc/ssl/certs", nullptr, nullptr, nullptr);
            if (rc != MOSQ_ERR_SUCCESS) {
                problem = std::string("TLS: ") + mosquitto_strerror(rc);
                return false;
            }
        }
        const int rc = mosquitto_connect(mosq_, endpoint->host.c_str(), endpoint->port, 10);
        if (rc != MOSQ_ERR_SUCCESS) {
            problem = "cannot connect to " + target_.url + ": " +
                      (rc == MOSQ_ERR_ERRNO ? std::strerror(errno) : mosquitto_strerror(rc));
            return false;
        }
        const auto deadline = std::chrono::steady_clock::now() + seconds_of(timeout_s);
        while (!(connack_ == 0 && subscribed_ && pending_subs_.empty())) {
            if (connack_ > 0) {
                problem = std::string("the broker refused the connection: ") +
                          mosquitto_reason_string(connack_);
                return false;
            }
            if (std::chrono::steady_clock::now() > deadline || interrupted) {
                problem = "no answer from the broker " + target_.url;
                return false;
            }
            if (mosquitto_loop(mosq_, 50, 1) != MOSQ_ERR_SUCCESS) {
                problem = "lost the broker " + target_.url;
                return false;
            }
        }
        return true;
    }

    // Runs until `done()` or the deadline; false when the connection broke.
    bool run_until(const std::function<bool()>& done,
                   std::optional<std::chrono::steady_clock::time_point> deadline) {
        while (!done() && !interrupted) {
            if (deadline && std::chrono::steady_clock::now() > *deadline) return true;
            const int rc = mosquitto_loop(mosq_, 50, 1);
            if (rc != MOSQ_ERR_SUCCESS) {
                // Watch outlives a broker restart: reconnect and resubscribe.
                if (mosquitto_reconnect(mosq_) != MOSQ_ERR_SUCCESS) return false;
            }
        }
        return true;
    }

  private:
    static std::chrono::steady_clock::duration seconds_of(double s) {
        return std::chrono::duration_cast<std::chrono::steady_clock::duration>(
            std::chrono::duration<double>(s));
    }

    MqttTarget target_;
    OnMessage on_message_;
    std::string client_id_;
    mosquitto* mosq_ = nullptr;
    std::vector<std::string> topics_;
    std::vector<int> pending_subs_;
    int connack_ = -1;  // -1: none yet
    bool subscribed_ = false;
};

std::string base_topic(const MqttTarget& t) {
    return t.prefix + "/" + t.station;
}

}  // namespace

int run_mqtt_exchange(const GlobalOptions& globals, const Json& request) {
    const MqttTarget& target = *globals.mqtt;
    if (target.station.find_first_of("+#") != std::string::npos) {
        print_diagnostic("--station: a command goes to one station, not '" + target.station + "'");
        return exit_usage;
    }
    int status = exit_ok;
    auto key = signing_key_for(globals, status);
    if (status != exit_ok) return status;
    Sealer sealer(std::move(key));
    std::optional<Json> reply;
    bool unauthenticated = false;
    const std::string correlation = random_hex(16);

    Session session(target, [&](const mosquitto_message& msg, const mosquitto_property* props) {
        void* data = nullptr;
        std::uint16_t length = 0;
        if (mosquitto_property_read_binary(props, MQTT_PROP_CORRELATION_DATA, &data, &length,
                                           false) == nullptr)
            return;
        const std::string got(static_cast<const char*>(data), length);
        std::free(data);
        if (got != correlation) return;
        auto value = parse_datagram(std::string_view(static_cast<const char*>(msg.payload),
                                                     static_cast<std::size_t>(msg.payloadlen)));
        if (!value) return;
        const auto opened = sealer.open(*value);
        if (opened == Sealer::Opened::forged ||
            (sealer.signing() && value->value("ok", false) &&
             (opened != Sealer::Opened::authentic ||
              value->value("nonce", std::string()) != sealer.last_nonce()))) {
            unauthenticated = true;
            return;
        }
        if (is_reply_to(*value, request)) reply = std::move(value);
    });
    const std::string response_topic = base_topic(target) + "/reply/" + session.client_id();
    std::string problem;
    const auto deadline = std::chrono::steady_clock::now() +
                          std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                              std::chrono::duration<double>(globals.timeout_s));
    if (!session.open({response_topic}, globals.timeout_s, problem)) {
        print_diagnostic(problem);
        return exit_no_reply;
    }
    const std::string payload = sealer.seal(request);
    mosquitto_property* props = nullptr;
    mosquitto_property_add_string(&props, MQTT_PROP_RESPONSE_TOPIC, response_topic.c_str());
    mosquitto_property_add_binary(&props, MQTT_PROP_CORRELATION_DATA, correlation.data(),
                                  static_cast<std::uint16_t>(correlation.size()));
    mosquitto_property_add_string_pair(&props, MQTT_PROP_USER_PROPERTY, "client_id",
                                       session.client_id().c_str());
    const std::string cmd_topic = base_topic(target) + "/cmd";
    mosquitto_publish_v5(session.handle(), nullptr, cmd_topic.c_str(),
                         static_cast<int>(payload.size()), payload.data(), 1, false, props);
    mosquitto_property_free_all(&props);
    session.run_until([&] { return reply.has_value() || unauthenticated; }, deadline);

    if (unauthenticated) {
        print_diagnostic("unauthenticated reply on " + response_topic +
                         ": its signature does not verify with key '" +
                         globals.key_id.value_or("") + "'");
        return exit_no_reply;
    }
    if (!reply) {
        print_diagnostic("no reply from station '" + target.station + "' via " + target.url +
                         " within " + format_seconds(globals.timeout_s) +
                         " (is gimbald connected with mqtt.commands true?)");
        return exit_no_reply;
    }
    if (sealer.signing()) {
        reply->erase("nonce");
        reply->erase("ts");
    }
    return report_reply(*reply, globals.pretty);
}

int run_mqtt_watch(const GlobalOptions& globals, const Json& subscribe, std::int64_t count) {
    const MqttTarget& target = *globals.mqtt;
    const std::string gimbal =
        subscribe.contains("gimbal") ? subscribe["gimbal"].get<std::string>() : "+";
    const bool events = subscribe.value("events", true);
    std::vector<std::string> keys;
    if (subscribe.contains("keys"))
        for (const auto& k : subscribe["keys"]) keys.push_back(k.get<std::string>());
    std::int64_t printed = 0;
    StateMerger merger;
    const std::size_t prefix_levels =
        static_cast<std::size_t>(std::count(target.prefix.begin(), target.prefix.end(), '/')) + 1;

    Session session(target, [&](const mosquitto_message& msg, const mosquitto_property*) {
        // {prefix}/{station}/{gimbal}/{state|event}
        std::vector<std::string> levels;
        std::string topic = msg.topic;
        for (std::size_t start = 0;;) {
            const auto slash = topic.find('/', start);
            levels.push_back(topic.substr(start, slash - start));
            if (slash == std::string::npos) break;
            start = slash + 1;
        }
        if (levels.size() != prefix_levels + 3) return;
        const std::string& station = levels[prefix_levels];
        const std::string& name = levels[prefix_levels + 1];
        const std::string& kind = levels[prefix_levels + 2];
        Json payload =
            Json::parse(static_cast<const char*>(msg.payload),
                        static_cast<const char*>(msg.payload) + msg.payloadlen, nullptr, false);
        if (payload.is_discarded() || !payload.is_object()) return;
        Json line;
        if (kind == "state") {
            // mqtt.state_changes: the payload is a delta-stream message; print it merged.
            if (payload.contains("full")) {
                auto merged = merger.merge(station + "/" + name, std::move(payload));
                if (!merged) return;
                payload = std::move((*merged)["state"]);
            }
            nlohmann::json state = nlohmann::json::parse(payload.dump());
            if (!keys.empty()) state = gimbal::state::select_keys(state, keys);
            line = {{"type", "state"},
                    {"station", station},
                    {"gimbal", name},
                    {"state", Json::parse(state.dump())}};
        } else if (kind == "event") {
            line = {{"type", "event"}, {"station", station}};
            for (auto& [k, v] : payload.items())
                if (k != "type") line[k] = v;
        } else {
            return;
        }
        print_json(line, globals.pretty);
        ++printed;
    });
    std::vector<std::string> topics = {base_topic(target) + "/" + gimbal + "/state"};
    if (events) topics.push_back(base_topic(target) + "/" + gimbal + "/event");
    std::string problem;
    if (!session.open(topics, globals.timeout_s, problem)) {
        print_diagnostic(problem);
        return exit_no_reply;
    }
    std::signal(SIGINT, [](int) { interrupted = true; });
    std::signal(SIGTERM, [](int) { interrupted = true; });
    if (!session.run_until([&] { return count > 0 && printed >= count; }, std::nullopt)) {
        print_diagnostic("lost the broker " + target.url);
        return exit_no_reply;
    }
    return exit_ok;
}

}  // namespace gimbalctl
