// The one request path (ARCHITECTURE "Round two"): every transport - the UDP socket, MQTT,
// HTTP, MAVLink - hands its requests here and only moves bytes. This is where a request is
// size-checked, rate-limited, authenticated (token or signature, roles), parsed, checked
// against the laser rules, routed to its gimbal, logged (`command`) and audited (`audit`).
#pragma once

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/udp.hpp>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "auth/rate_limiter.hpp"
#include "auth/verifier.hpp"
#include "command/result.hpp"
#include "gimbal_session.hpp"
#include "ground_commands.hpp"
#include "subscriptions.hpp"

namespace gimbald {

struct RequestSource {
    std::string transport;  // "udp", "mqtt", "http", "mavlink"
    // The log's `src` and (unless signed, on MQTT) the rate-limit key: "127.0.0.1:40000"
    // (udp), "mqtt:<client>",
    // "http:127.0.0.1:5555", "mavlink:255/190".
    std::string address;
    std::optional<boost::asio::ip::udp::endpoint> udp;  // UDP only: subscriptions need it
    // The largest reply the transport can carry (UDP: one datagram). A reply that would be
    // larger becomes a too_large error reply naming its size (contract section 14, v4).
    std::optional<std::size_t> max_reply_bytes = std::nullopt;
};

// Handed to observers after every request (metrics).
struct CompletedRequest {
    std::string transport;
    std::optional<std::string> cmd;  // null when the request could not be parsed
    std::string result;              // "ok" or the error code
    double seconds = 0;              // received -> reply built
};

struct RequestPathOptions {
    std::optional<std::string> token;     // command.token (auth "none")
    bool signed_only = false;             // command.auth "signed"
    std::vector<gimbal::auth::Key> keys;  // command.keys, secrets loaded
    double max_skew_s = 30;
    double rate_per_source_hz = 200;  // command.rate_limit
    double rate_burst = 400;
    // Unix time in milliseconds (signed requests' `ts`); tests may pin it.
    std::function<std::int64_t()> unix_ms;
    // The daemon's elevation model (contract section 15), nullptr when none is configured.
    gimbal::terrain::ElevationModel* terrain = nullptr;
};

// STATE `command` (contract section 10): what the request path has seen since start.
struct RequestCounters {
    std::uint64_t requests = 0;      // every request that reached the path
    std::uint64_t rejected = 0;      // answered with ok:false (rate limits not included)
    std::uint64_t rate_limited = 0;  // refused by command.rate_limit, answered or not
};

class RequestPath {
  public:
    using Observer = std::function<void(const CompletedRequest&)>;
    using Tap =
        std::function<void(const RequestSource&, std::string_view request, std::string_view reply)>;
    // Called after a subscription was added or renewed (the UDP server reschedules its timer).
    using SubscriptionsChanged = std::function<void()>;

    RequestPath(boost::asio::io_context& io, RequestPathOptions options,
                std::vector<GimbalSession*> sessions);

    // One request exactly as received (a JSON object, plain or signed envelope). Returns the
    // reply text to send back, or nullopt when nothing must be sent. The bytes are parsed
    // once (command::parse_object), a signed request's payload once more, and the request
    // is read from that parse.
    std::optional<std::string> handle(std::string_view bytes, const RequestSource& from);
    // The same for a transport that had to look inside first (the WebSocket stream routes
    // subscribe itself): `request` is its parse of `bytes`, which were within the request
    // limits; the path does not parse them again.
    std::optional<std::string> handle_parsed(nlohmann::json request, std::string_view bytes,
                                             const RequestSource& from);

    // A request a transport refused for its size before it had read all of it (an HTTP body
    // or a WebSocket message over the limit; `size` when known): answered too_large, as
    // handle() answers an oversize request, counted, rate-limited and logged, never parsed.
    std::optional<std::string> refuse_too_large(std::optional<std::size_t> size,
                                                const RequestSource& from);

    // A request object built by an adapter that authenticates by its own means (MAVLink
    // signing): no token or signature check; the same validation, laser rules, logging and
    // audit. Read as the object it is: no JSON text, no parse. The adapter needs only the
    // outcome (MAVLink answers with a MAV_RESULT).
    struct Executed {
        std::optional<gimbal::command::Error> error;
        nlohmann::json results;  // the reply's results on success (e.g. `point`'s located point)
    };
    Executed execute_request(const nlohmann::json& request, const RequestSource& from);

    void add_observer(Observer observer) { observers_.push_back(std::move(observer)); }
    void add_tap(Tap tap) { taps_.push_back(std::move(tap)); }
    // Told of every gimbal command executed successfully, whatever the transport (the visual
    // tracker ends its track when a client steers the gimbal itself).
    using ExecutedListener = std::function<void(const std::string& gimbal, std::string_view cmd)>;
    void add_executed_listener(ExecutedListener listener) {
        executed_listeners_.push_back(std::move(listener));
    }
    // The UDP socket's subscriber table; subscribe/unsubscribe from other transports are
    // `unsupported` (they stream on their own: MQTT topics, WebSocket).
    void set_subscriptions(Subscriptions* table, SubscriptionsChanged changed);

    // A message for a signed subscriber: signed with `key_id`, with a fresh ts and nonce.
    std::string sign_message(const std::string& key_id, const nlohmann::json& message);

    const RequestCounters& counters() const { return counters_; }
    const std::vector<GimbalSession*>& sessions() const { return sessions_; }
    GimbalSession* find(const std::string& name) const;

  private:
    struct Outcome;
    std::optional<std::string> handle(std::string_view bytes, std::optional<nlohmann::json> parsed,
                                      const RequestSource& from);
    void run(Outcome& o, const RequestSource& from);
    nlohmann::json dispatch(Outcome& o, const RequestSource& from);
    nlohmann::json subscription(Outcome& o, const RequestSource& from);
    std::string finish(Outcome& o, const RequestSource& from, std::string_view request_bytes);
    // The reply's text: signed with the request's key when it was signed.
    std::string render(Outcome& o);
    // Size and nesting limits and the one parse (unless `parsed` holds the transport's), and
    // for a signed request its MAC (no state changes).
    void read(Outcome& o, std::string_view bytes, std::optional<nlohmann::json>& parsed);
    // A signed request's payload (its one parse), ts and nonce (the nonce is spent here).
    void accept(Outcome& o);
    // The request object itself: what the reply echoes and the envelope.
    void take(Outcome& o, nlohmann::json request);
    void authorize(Outcome& o);
    void audit(const Outcome& o, const RequestSource& from) const;
    std::string random_nonce();

    boost::asio::io_context& io_;
    RequestPathOptions options_;
    std::vector<GimbalSession*> sessions_;
    std::vector<Observer> observers_;
    std::vector<Tap> taps_;
    std::vector<ExecutedListener> executed_listeners_;
    Subscriptions* subscriptions_ = nullptr;
    SubscriptionsChanged subscriptions_changed_;
    gimbal::auth::Verifier verifier_;
    gimbal::auth::RateLimiter limiter_;
    RequestCounters counters_;
    GroundCommands ground_;
};

}  // namespace gimbald
