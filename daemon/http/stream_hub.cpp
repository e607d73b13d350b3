#include "stream_hub.hpp"

#include <algorithm>
#include <cmath>

#include "command/catalogue.hpp"
#include "command/envelope.hpp"
#include "command/params.hpp"
#include "command/request.hpp"
#include "command/request_limits.hpp"
#include "logging.hpp"
#include "state/messages.hpp"
#include "state/state_push.hpp"
#include "stream_params.hpp"
#include "subscriptions.hpp"
#include "ws_client.hpp"

namespace gimbald::http {

namespace log = gimbal::log;
namespace cmdns = gimbal::command;
namespace code = gimbal::command::code;
using nlohmann::json;

namespace {

// Clients due within this of a tick share its snapshot (as the UDP socket does).
constexpr double batch_s = 0.010;

std::string dump(const json& j) {
    return j.dump(-1, ' ', false, json::error_handler_t::replace);
}

bool covers(const StreamSubscription& s, const std::string& gimbal) {
    return !s.gimbal || *s.gimbal == gimbal;
}

}  // namespace

StreamHub::StreamHub(boost::asio::io_context& io, RequestPath& path, HttpStats& stats,
                     std::size_t queue_max, double idle_timeout_s)
    : path_(path),
      stats_(stats),
      queue_max_(queue_max),
      idle_timeout_s_(idle_timeout_s),
      timer_(io),
      send_failed_(log::Level::info, "websocket_send_failed",
                   "WebSocket messages that could not be sent") {}

void StreamHub::track(WsClient& client) {
    clients_.push_back(&client);
}

void StreamHub::add(WsClient& client) {
    auto& s = client.subscription();
    s.open = true;
    s.next_state_s = steady_seconds();  // the first STATE at once
    count_open();
    log::info("subscriber", "WebSocket client connected",
              {{"src", client.address()}, {"transport", "websocket"}});
    schedule();
}

void StreamHub::remove(WsClient& client) {
    const auto it = std::find(clients_.begin(), clients_.end(), &client);
    if (it == clients_.end()) return;
    clients_.erase(it);
    if (!client.subscription().open) return;
    count_open();
    log::info("subscriber", "WebSocket client disconnected",
              {{"src", client.address()}, {"transport", "websocket"}});
}

void StreamHub::count_open() {
    stats_.websocket_clients = static_cast<std::size_t>(std::count_if(
        clients_.begin(), clients_.end(), [](WsClient* c) { return c->subscription().open; }));
}

void StreamHub::dropped(WsClient& client, std::size_t queued) {
    ++stats_.websocket_dropped_total;
    log::warn("websocket_dropped",
              "WebSocket client dropped: it does not read and its send queue is full",
              {{"src", client.address()}, {"queued", queued}, {"queue_max", queue_max_}});
}

void StreamHub::send_failed(WsClient& client, std::size_t bytes,
                            const boost::system::error_code& ec) {
    ++stats_.websocket_send_failed_total;
    send_failed_.hit("a WebSocket message could not be sent: " + ec.message(),
                     {{"src", client.address()}, {"bytes", bytes}, {"error", ec.message()}});
}

void StreamHub::stop() {
    stopped_ = true;
    timer_.cancel();
    // close() only cancels the socket's operations: the clients leave from their handlers.
    for (auto* client : std::vector<WsClient*>(clients_)) client->close();
}

void StreamHub::publish_event(const std::string& gimbal, const gimbal::state::Event& event) {
    std::shared_ptr<const std::string> text;
    for (auto* client : std::vector<WsClient*>(clients_)) {
        const auto& s = client->subscription();
        if (!s.open || !s.events || !covers(s, gimbal)) continue;
        if (!text)
            text = std::make_shared<const std::string>(
                dump(gimbal::state::event_message(gimbal, event)));
        client->send(text);
    }
}

void StreamHub::schedule() {
    if (stopped_) return;
    double next = steady_seconds() + 1.0;
    for (auto* client : clients_) {
        const auto& s = client->subscription();
        if (s.open && s.state) next = std::min(next, s.next_state_s);
    }
    const double wait_s = std::max(0.0, next - steady_seconds());
    timer_.expires_after(std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(wait_s)));
    timer_.async_wait([this](const boost::system::error_code& ec) {
        if (ec || stopped_) return;  // aborted: a newer schedule() replaced this wait
        tick();
        schedule();
    });
}

void StreamHub::tick() {
    send_failed_.poll();  // a burst that stopped still gets its summary
    const double now = steady_seconds();
    const double horizon = now + batch_s;
    const auto clients = clients_;  // a send may drop a client
    for (auto* session : path_.sessions()) {
        // One snapshot, and one message per key list, kind and previous push (state_push.hpp).
        std::optional<gimbal::state::PushBatch> batch;
        for (auto* client : clients) {
            auto& s = client->subscription();
            if (!s.open || !s.state || s.next_state_s > horizon || !covers(s, session->name()))
                continue;
            if (!batch) batch.emplace(session->name(), session->snapshot());
            client->send(batch->next(s.stream, s.cursors[session->name()], horizon).text());
        }
    }
    for (auto* client : clients) {
        auto& s = client->subscription();
        if (!s.open || !s.state || s.next_state_s > horizon) continue;
        // The next multiple of the period on the daemon's clock: clients at the same rate
        // share one snapshot and one JSON text per tick, however their connections were
        // spread in time (50 browsers at 2 Hz: 2 snapshots a second, not 100). No bursts to
        // catch up after a stall.
        const double period = 1.0 / s.rate_hz;
        s.next_state_s = (std::floor(horizon / period) + 1.0) * period;
    }
}

StreamHub::Answer StreamHub::on_message(WsClient& client, std::string_view text) {
    const RequestSource source{"http", client.address(), std::nullopt};
    // Over the request limits: the request path answers (too_large, bad_json) unparsed.
    if (cmdns::check_request_limits(text)) return {path_.handle(text, source), std::nullopt, {}};
    // The message's one parse: subscribe is routed here, anything else goes to the request
    // path with it.
    auto request = cmdns::parse_object(text);
    if (!request)
        return {std::nullopt, boost::beast::websocket::close_code::policy_error,
                "not a JSON object"};
    const auto cmd = request->find("cmd");
    if (cmd != request->end() && cmd->is_string() &&
        (*cmd == "subscribe" || *cmd == "unsubscribe") && !request->contains("signed"))
        return {subscribe(client, *request, *cmd == "unsubscribe"), std::nullopt, {}};
    return {path_.handle_parsed(std::move(*request), text, source), std::nullopt, {}};
}

std::optional<std::string> StreamHub::too_large(WsClient& client) {
    return path_.refuse_too_large(std::nullopt, {"http", client.address(), std::nullopt});
}

// The UDP `subscribe` parameters with the UDP validation; ttl_s is accepted and ignored (the
// stream lasts as long as the connection).
std::string StreamHub::subscribe(WsClient& client, const json& request, bool unsubscribe) {
    const auto read = cmdns::read_envelope(request);
    if (!read) {
        const auto echo = cmdns::echo_of(request);
        return dump(cmdns::error_reply(echo.id, echo.cmd, read.error()));
    }
    const cmdns::Envelope& env = *read;
    const std::optional<std::string> cmd(std::string(env.cmd()));
    auto fail = [&](const cmdns::Error& error) {
        return dump(cmdns::error_reply(env.id, cmd, error));
    };
    if (env.gimbal && !path_.find(*env.gimbal))
        return fail({code::unknown_gimbal, "no gimbal named '" + *env.gimbal + "'"});
    cmdns::JsonParams params(request, env.cmd());
    json results = json::object();
    auto& s = client.subscription();
    if (unsubscribe) {
        params.reject_unknown();
        if (!params.ok()) return fail(params.error());
        s.state = false;
        s.events = false;
        results["subscribed"] = false;
        return dump(cmdns::ok_reply(env.id, env.cmd(), env.gimbal, std::move(results)));
    }
    StreamSubscription next;
    next.gimbal = env.gimbal;
    next.rate_hz = params.number_or("rate_hz", 2.0);
    params.number_or("ttl_s", 60.0);
    next.events = params.boolean_or("events", true);
    read_stream_options(params, next.stream);
    params.reject_unknown();
    if (!params.ok()) return fail(params.error());
    next.next_state_s = steady_seconds();
    next.open = true;
    s = next;
    results["rate_hz"] = s.rate_hz;
    results["events"] = s.events;
    describe_stream_options(s.stream, results);
    schedule();
    return dump(cmdns::ok_reply(env.id, env.cmd(), env.gimbal, std::move(results)));
}

}  // namespace gimbald::http
