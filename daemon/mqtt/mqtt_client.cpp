#include "mqtt_client.hpp"

#include <mosquitto.h>
#include <mqtt_protocol.h>

#include <boost/asio/post.hpp>
#include <cstdlib>
#include <mutex>

namespace gimbald::mqtt {

namespace log = gimbal::log;
namespace asio = boost::asio;

namespace {

// Messages handed to libmosquitto at a time; the rest wait in our bounded queue.
constexpr std::size_t window = 64;
// MQTT 5 Maximum Packet Size in CONNECT (contract section 14): the broker does not deliver
// a packet larger than this to us, so a huge P/cmd message is never buffered here
// (libmosquitto reads a whole packet into memory before handing it over). Room for a request
// a little over the 8192-byte limit, its topic and properties: that one is answered
// too_large; a larger one is dropped by the broker unanswered.
constexpr std::uint32_t max_packet_bytes = 65536;
constexpr auto tick = std::chrono::milliseconds(500);
constexpr auto stop_wait = std::chrono::seconds(1);

void init_library_once() {
    static std::once_flag once;
    std::call_once(once, [] {
        mosquitto_lib_init();
        std::atexit([] { mosquitto_lib_cleanup(); });
    });
}

Client* self_of(void* p) {
    return static_cast<Client*>(p);
}

std::string error_text(int rc) {
    if (rc == MOSQ_ERR_ERRNO)
        return std::string(mosquitto_strerror(rc)) + ": " + std::strerror(errno);
    return mosquitto_strerror(rc);
}

}  // namespace

Client::Client(asio::io_context& io, ClientOptions options, MessageHandler on_message,
               ConnectedHandler on_connected)
    : io_(io),
      options_(std::move(options)),
      on_message_(std::move(on_message)),
      on_connected_(std::move(on_connected)),
      socket_(io),
      tick_timer_(io),
      reconnect_timer_(io),
      stop_timer_(io),
      backoff_(options_.backoff),
      queue_(options_.queue_max),
      failures_(log::Level::warn, "mqtt_down", "failed broker connection attempts",
                std::chrono::seconds(60)),
      refused_log_(log::Level::warn, "mqtt_publish", "messages the MQTT library refused") {
    init_library_once();
}

Client::~Client() {
    lifetime_.reset();
    close_instance();
}

std::string Client::broker() const {
    return (options_.host.find(':') != std::string::npos ? "[" + options_.host + "]"
                                                         : options_.host) +
           ":" + std::to_string(options_.port);
}

const ClientCounters& Client::counters() const {
    counters_.dropped = queue_.dropped() + refused_;
    return counters_;
}

void Client::start() {
    connect();
    tick_timer_.expires_after(tick);
    tick_timer_.async_wait(lifetime_.wrap([this](const boost::system::error_code& ec) {
        if (!ec) on_tick();
    }));
}

void Client::configure(struct mosquitto* m) {
    mosquitto_int_option(m, MOSQ_OPT_PROTOCOL_VERSION,
                         v311_ ? MQTT_PROTOCOL_V311 : MQTT_PROTOCOL_V5);
    mosquitto_int_option(m, MOSQ_OPT_TCP_NODELAY, 1);
    mosquitto_connect_v5_callback_set(m, &Client::on_connect_cb);
    mosquitto_disconnect_v5_callback_set(m, &Client::on_disconnect_cb);
    mosquitto_publish_v5_callback_set(m, &Client::on_publish_cb);
    mosquitto_message_v5_callback_set(m, &Client::on_message_cb);
    if (options_.username)
        mosquitto_username_pw_set(m, options_.username->c_str(),
                                  options_.password.empty() ? nullptr : options_.password.c_str());
    if (!options_.will_topic.empty())
        mosquitto_will_set_v5(m, options_.will_topic.c_str(),
                              static_cast<int>(options_.will_payload.size()),
                              options_.will_payload.data(), 1, true, nullptr);
    if (options_.tls) {
        auto c = [](const std::optional<std::string>& s) { return s ? s->c_str() : nullptr; };
        const char* ca_dir = options_.ca_file ? nullptr : "/etc/ssl/certs";
        const int rc = mosquitto_tls_set(m, c(options_.ca_file), ca_dir, c(options_.cert_file),
                                         c(options_.key_file), nullptr);
        if (rc != MOSQ_ERR_SUCCESS) last_error_ = "TLS setup: " + error_text(rc);
    }
}

bool Client::set_connect_properties(struct mosquitto* m) {
    // libmosquitto 2.0 takes CONNECT properties only through the blocking
    // mosquitto_connect_bind_v5(), which keeps them on the instance for every later connect
    // (mosquitto_connect_bind_async() included) and checks its arguments before it
    // connects: called with an invalid port it stores the properties and returns
    // MOSQ_ERR_INVAL without touching the network. The integration test
    // (test_gimbald_mqtt_limits) checks on the wire that CONNECT carries them.
    mosquitto_property* props = nullptr;
    if (mosquitto_property_add_int32(&props, MQTT_PROP_MAXIMUM_PACKET_SIZE, max_packet_bytes) !=
        MOSQ_ERR_SUCCESS)
        return false;
    const int rc = mosquitto_connect_bind_v5(m, options_.host.c_str(), -1, options_.keepalive_s,
                                             nullptr, props);
    mosquitto_property_free_all(&props);
    return rc == MOSQ_ERR_INVAL;
}

void Client::connect() {
    if (stopping_) return;
    close_instance();
    attempt_started_ = std::chrono::steady_clock::now();
    last_error_.clear();
    mosq_ = mosquitto_new(options_.client_id.c_str(), true, this);
    if (mosq_ == nullptr) {
        lost("mosquitto_new failed");
        return;
    }
    configure(mosq_);
    if (!last_error_.empty()) {
        lost(last_error_);
        return;
    }
    if (!v311_ && !set_connect_properties(mosq_)) {
        lost("cannot set the MQTT 5 CONNECT properties");
        return;
    }
    // Non-blocking: the TCP connect completes later; CONNECT waits in libmosquitto's queue.
    // (A host name is resolved with getaddrinfo here; use an address to avoid any wait.)
    const int rc = mosquitto_connect_bind_async(mosq_, options_.host.c_str(), options_.port,
                                                options_.keepalive_s, nullptr);
    if (rc != MOSQ_ERR_SUCCESS) {
        lost(error_text(rc));
        return;
    }
    const int fd = mosquitto_socket(mosq_);
    if (fd < 0) {
        lost("no socket");
        return;
    }
    boost::system::error_code ec;
    socket_.assign(fd, ec);
    if (ec) {
        lost("cannot watch the socket: " + ec.message());
        return;
    }
    watch();
}

void Client::watch() {
    if (mosq_ == nullptr || !socket_.is_open()) return;
    if (!reading_) {
        reading_ = true;
        socket_.async_wait(asio::posix::stream_descriptor::wait_read,
                           connection_.wrap([this](const boost::system::error_code& ec) {
                               reading_ = false;
                               on_readable(ec);
                           }));
    }
    if (!writing_ && mosquitto_want_write(mosq_)) {
        writing_ = true;
        socket_.async_wait(asio::posix::stream_descriptor::wait_write,
                           connection_.wrap([this](const boost::system::error_code& ec) {
                               writing_ = false;
                               on_writable(ec);
                           }));
    }
}

void Client::on_readable(const boost::system::error_code& ec) {
    if (ec || mosq_ == nullptr) return;
    after_io(mosquitto_loop_read(mosq_, 1), "read");
}

void Client::on_writable(const boost::system::error_code& ec) {
    if (ec || mosq_ == nullptr) return;
    after_io(mosquitto_loop_write(mosq_, 1), "write");
}

void Client::after_io(int rc, const char* what) {
    if (rc != MOSQ_ERR_SUCCESS || mosquitto_socket(mosq_) < 0) {
        if (stopping_) {
            finish_stop();
            return;
        }
        lost(last_error_.empty() ? std::string(what) + ": " + error_text(rc) : last_error_);
        return;
    }
    pump();
    watch();
}

void Client::on_tick() {
    if (mosq_ != nullptr) {
        // Keep-alive pings and their timeout.
        const int rc = mosquitto_loop_misc(mosq_);
        if (rc != MOSQ_ERR_SUCCESS || mosquitto_socket(mosq_) < 0) {
            if (!stopping_)
                lost(last_error_.empty() ? "keep-alive: " + error_text(rc) : last_error_);
        } else if (!connected_ && std::chrono::steady_clock::now() - attempt_started_ >
                                      std::chrono::seconds(std::max(5, options_.keepalive_s))) {
            lost("no CONNACK from the broker in time");
        } else {
            watch();
        }
    }
    failures_.poll();
    refused_log_.poll();
    if (stopped_) return;
    tick_timer_.expires_after(tick);
    tick_timer_.async_wait(lifetime_.wrap([this](const boost::system::error_code& ec) {
        if (!ec) on_tick();
    }));
}

void Client::close_instance() {
    connection_.reset();
    reading_ = writing_ = false;
    if (socket_.is_open()) {
        boost::system::error_code ignored;
        socket_.cancel(ignored);
        (void)socket_.release();  // libmosquitto owns the descriptor and closes it
    }
    if (mosq_ != nullptr) {
        mosquitto_destroy(mosq_);
        mosq_ = nullptr;
    }
}

void Client::lost(const std::string& reason) {
    const bool was_connected = connected_;
    connected_ = false;
    close_instance();
    // Handed over but not confirmed: back to the front, oldest first.
    for (auto it = in_flight_.rbegin(); it != in_flight_.rend(); ++it)
        queue_.push_front(std::move(it->second));
    in_flight_.clear();
    confirmed_early_.clear();
    const nlohmann::json fields = {{"broker", broker()}, {"reason", reason}};
    if (was_connected)
        log::warn("mqtt_down", "lost the MQTT broker: " + reason, fields);
    else
        failures_.hit("cannot connect to the MQTT broker: " + reason, fields);
    schedule_reconnect();
}

void Client::schedule_reconnect() {
    if (stopping_) return;
    const double delay = backoff_.next();
    reconnect_timer_.expires_after(std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(delay)));
    reconnect_timer_.async_wait(lifetime_.wrap([this](const boost::system::error_code& ec) {
        if (!ec) connect();
    }));
}

void Client::publish(Message message) {
    if (stopping_) return;
    queue_.push(std::move(message));
    if (connected_) {
        pump();
        watch();
    }
}

bool Client::hand_over(Message& m) {
    mosquitto_property* props = nullptr;
    if (m.correlation && !v311_)
        mosquitto_property_add_binary(&props, MQTT_PROP_CORRELATION_DATA, m.correlation->data(),
                                      static_cast<std::uint16_t>(m.correlation->size()));
    int mid = 0;
    const int rc =
        mosquitto_publish_v5(mosq_, &mid, m.topic.c_str(), static_cast<int>(m.payload.size()),
                             m.payload.data(), m.qos, m.retain, props);
    mosquitto_property_free_all(&props);
    if (rc == MOSQ_ERR_SUCCESS) {
        // A QoS 0 message written at once is confirmed inside mosquitto_publish_v5.
        if (confirmed_early_.erase(mid) > 0)
            ++counters_.published;
        else
            in_flight_.emplace(mid, std::move(m));
        return true;
    }
    if (rc == MOSQ_ERR_NO_CONN || rc == MOSQ_ERR_CONN_LOST) {
        queue_.push_front(std::move(m));
        return false;
    }
    // Too large for the broker, bad topic: this message can never go.
    ++refused_;
    refused_log_.hit("message not published: " + error_text(rc),
                     {{"topic", m.topic}, {"bytes", m.payload.size()}});
    return true;
}

void Client::pump() {
    if (!connected_ || mosq_ == nullptr) return;
    while (in_flight_.size() < window && !queue_.empty()) {
        auto m = queue_.pop();
        if (!hand_over(*m)) break;
    }
}

void Client::stop(Message last) {
    if (stopping_) return;
    stopping_ = true;
    reconnect_timer_.cancel();
    if (!connected_ || mosq_ == nullptr) {
        finish_stop();
        return;
    }
    int mid = 0;
    if (mosquitto_publish_v5(mosq_, &mid, last.topic.c_str(), static_cast<int>(last.payload.size()),
                             last.payload.data(), 1, true, nullptr) != MOSQ_ERR_SUCCESS) {
        finish_stop();
        return;
    }
    stop_mid_ = mid;
    stop_timer_.expires_after(stop_wait);
    stop_timer_.async_wait(lifetime_.wrap([this](const boost::system::error_code& ec) {
        if (!ec) finish_stop();
    }));
    watch();
}

void Client::finish_stop() {
    if (stopped_) return;
    stopped_ = true;
    if (mosq_ != nullptr && mosquitto_socket(mosq_) >= 0) {
        // DISCONNECT with reason 0: the broker drops the last will.
        mosquitto_disconnect(mosq_);
        (void)mosquitto_loop_write(mosq_, 1);
    }
    if (connected_)
        log::info("mqtt_down", "disconnected from the MQTT broker (stop)",
                  {{"broker", broker()}, {"reason", "stop"}});
    connected_ = false;
    lifetime_.reset();
    close_instance();
    tick_timer_.cancel();
    stop_timer_.cancel();
    reconnect_timer_.cancel();
}

void Client::on_connect_cb(struct mosquitto*, void* p, int rc, int, const mosquitto_property*) {
    Client* self = self_of(p);
    if (rc == MQTT_RC_UNSUPPORTED_PROTOCOL_VERSION && !self->v311_) {
        // An MQTT 3.1.1 broker: the next attempt speaks 3.1.1 (replies then go to P/reply).
        self->v311_ = true;
        self->last_error_ = "the broker does not speak MQTT 5: retrying with MQTT 3.1.1";
        return;
    }
    if (rc != 0) {
        self->last_error_ =
            std::string("the broker refused the connection: ") + mosquitto_reason_string(rc);
        return;
    }
    self->connected_ = true;
    self->backoff_.reset();
    if (self->ever_connected_) ++self->counters_.reconnects;
    self->ever_connected_ = true;
    for (const auto& topic : self->options_.subscriptions)
        mosquitto_subscribe_v5(self->mosq_, nullptr, topic.c_str(), 1, 0, nullptr);
    log::info("mqtt_up", "connected to the MQTT broker",
              {{"broker", self->broker()},
               {"client_id", self->options_.client_id},
               {"protocol", self->v311_ ? "mqtt 3.1.1" : "mqtt 5"}});
    asio::post(self->io_, self->lifetime_.wrap([self] {
        if (!self->connected_) return;
        if (self->on_connected_) self->on_connected_();
        self->pump();
        self->watch();
    }));
}

void Client::on_disconnect_cb(struct mosquitto*, void* p, int rc, const mosquitto_property*) {
    Client* self = self_of(p);
    if (rc != 0 && self->last_error_.empty())
        self->last_error_ = std::string("disconnected: ") + mosquitto_reason_string(rc);
}

void Client::on_publish_cb(struct mosquitto*, void* p, int mid, int, const mosquitto_property*) {
    Client* self = self_of(p);
    if (self->stop_mid_ && *self->stop_mid_ == mid) {
        asio::post(self->io_, self->lifetime_.wrap([self] { self->finish_stop(); }));
        return;
    }
    if (self->in_flight_.erase(mid) > 0)
        ++self->counters_.published;
    else
        self->confirmed_early_.insert(mid);
    asio::post(self->io_, self->lifetime_.wrap([self] {
        self->pump();
        self->watch();
    }));
}

void Client::on_message_cb(struct mosquitto*, void* p, const struct mosquitto_message* msg,
                           const mosquitto_property* props) {
    Client* self = self_of(p);
    Incoming in;
    in.topic = msg->topic != nullptr ? msg->topic : "";
    in.retained = msg->retain;
    if (msg->payload != nullptr)
        in.payload.assign(static_cast<const char*>(msg->payload),
                          static_cast<std::size_t>(msg->payloadlen));
    char* text = nullptr;
    if (mosquitto_property_read_string(props, MQTT_PROP_RESPONSE_TOPIC, &text, false) != nullptr &&
        text != nullptr) {
        in.response_topic = text;
        std::free(text);
    }
    void* data = nullptr;
    std::uint16_t length = 0;
    if (mosquitto_property_read_binary(props, MQTT_PROP_CORRELATION_DATA, &data, &length, false) !=
        nullptr) {
        in.correlation = std::string(static_cast<const char*>(data), length);
        std::free(data);
    }
    bool skip = false;
    for (const mosquitto_property* prop = props;;) {
        char* name = nullptr;
        char* value = nullptr;
        prop =
            mosquitto_property_read_string_pair(prop, MQTT_PROP_USER_PROPERTY, &name, &value, skip);
        skip = true;
        if (prop == nullptr) break;
        if (name != nullptr && value != nullptr && std::string_view(name) == "client_id")
            in.client_id = value;
        std::free(name);
        std::free(value);
    }
    asio::post(self->io_, self->lifetime_.wrap([self, in = std::move(in)] {
        if (self->on_message_) self->on_message_(in);
    }));
}

}  // namespace gimbald::mqtt
