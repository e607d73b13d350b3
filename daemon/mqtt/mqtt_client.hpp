// An MQTT 5 client on the daemon's io_context: Debian's libmosquitto does the protocol (and
// TLS), Asio does the waiting. Its socket is watched with a posix::stream_descriptor and
// mosquitto_loop_read/loop_write/loop_misc are called from handlers; there is no second
// thread (no mosquitto_loop_start). Connecting is non-blocking (mosquitto_connect_async).
//
// Messages wait in a bounded OutgoingQueue and go to libmosquitto only while connected and
// only a small window at a time, so a lost or slow broker costs at most `queue_max` messages
// of memory and never blocks the caller. Messages handed over but not confirmed when the
// connection breaks go back to the front of the queue (at-least-once for QoS 1). Every
// connection attempt uses a fresh libmosquitto instance, so nothing is queued out of sight.
#pragma once

#include <boost/asio/io_context.hpp>
#include <boost/asio/posix/stream_descriptor.hpp>
#include <boost/asio/steady_timer.hpp>
#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "link/backoff.hpp"
#include "link/lifetime.hpp"
#include "logging.hpp"
#include "outgoing_queue.hpp"

struct mosquitto;
struct mosquitto_message;
typedef struct mqtt5__property mosquitto_property;

namespace gimbald::mqtt {

struct ClientOptions {
    std::string host;
    std::uint16_t port = 1883;
    bool tls = false;
    std::optional<std::string> ca_file;  // TLS without one: the system's CA directory
    std::optional<std::string> cert_file;
    std::optional<std::string> key_file;
    std::optional<std::string> username;
    std::string password;
    std::string client_id;
    int keepalive_s = 10;
    std::string will_topic;  // the last will (retained, QoS 1)
    std::string will_payload;
    std::vector<std::string> subscriptions;  // QoS 1, renewed on every connection
    std::size_t queue_max = 1000;
    BackoffOptions backoff{0.2, 5.0, 0.2};
};

struct Incoming {
    std::string topic;
    std::string payload;
    std::optional<std::string> response_topic;  // MQTT 5 properties
    std::optional<std::string> correlation;
    std::optional<std::string> client_id;  // user property "client_id"
    bool retained = false;                 // delivered from the broker's retained store
};

struct ClientCounters {
    std::uint64_t published = 0;   // confirmed: written (QoS 0) or acknowledged (QoS 1)
    std::uint64_t dropped = 0;     // dropped from the queue, or refused by libmosquitto
    std::uint64_t reconnects = 0;  // successful connections after the first
};

class Client {
  public:
    using MessageHandler = std::function<void(const Incoming&)>;
    using ConnectedHandler = std::function<void()>;

    Client(boost::asio::io_context& io, ClientOptions options, MessageHandler on_message,
           ConnectedHandler on_connected);
    ~Client();
    Client(const Client&) = delete;
    Client& operator=(const Client&) = delete;

    void start();
    // A clean stop: sends `last` (the offline status) when connected, waits up to 1 s for
    // the broker's acknowledgement, disconnects normally (no last will), then goes quiet.
    void stop(Message last);

    void publish(Message message);

    bool connected() const { return connected_; }
    const ClientCounters& counters() const;
    std::size_t queued() const { return queue_.size(); }
    std::string broker() const;

  private:
    void connect();
    void configure(struct mosquitto* m);
    bool set_connect_properties(struct mosquitto* m);
    void watch();
    void on_readable(const boost::system::error_code& ec);
    void on_writable(const boost::system::error_code& ec);
    void on_tick();
    void after_io(int rc, const char* what);
    void lost(const std::string& reason);
    void close_instance();
    void schedule_reconnect();
    void pump();
    bool hand_over(Message& message);
    void finish_stop();

    static void on_connect_cb(struct mosquitto*, void* self, int rc, int flags,
                              const mosquitto_property* props);
    static void on_disconnect_cb(struct mosquitto*, void* self, int rc,
                                 const mosquitto_property* props);
    static void on_publish_cb(struct mosquitto*, void* self, int mid, int reason,
                              const mosquitto_property* props);
    static void on_message_cb(struct mosquitto*, void* self, const struct mosquitto_message* msg,
                              const mosquitto_property* props);

    boost::asio::io_context& io_;
    ClientOptions options_;
    MessageHandler on_message_;
    ConnectedHandler on_connected_;
    struct mosquitto* mosq_ = nullptr;
    boost::asio::posix::stream_descriptor socket_;
    boost::asio::steady_timer tick_timer_;
    boost::asio::steady_timer reconnect_timer_;
    boost::asio::steady_timer stop_timer_;
    Lifetime lifetime_;    // every handler; reset on stop
    Lifetime connection_;  // socket waits; reset when an instance is closed
    Backoff backoff_;
    OutgoingQueue queue_;
    std::map<int, Message> in_flight_;  // mid -> message handed to libmosquitto
    std::set<int> confirmed_early_;     // confirmed before mosquitto_publish_v5 returned
    mutable ClientCounters counters_;
    std::uint64_t refused_ = 0;  // messages libmosquitto refused (too large, bad topic)
    bool reading_ = false;
    bool writing_ = false;
    bool connected_ = false;
    bool ever_connected_ = false;
    bool stopping_ = false;
    bool stopped_ = false;
    bool v311_ = false;  // the broker refused MQTT 5: speak 3.1.1 (no properties)
    std::optional<int> stop_mid_;
    std::chrono::steady_clock::time_point attempt_started_;
    std::string last_error_;
    gimbal::log::RateLimitedLog failures_;
    // Messages libmosquitto refused (too large for the broker, bad topic): counted in
    // `dropped`, logged rolled up.
    gimbal::log::RateLimitedLog refused_log_;
};

}  // namespace gimbald::mqtt
