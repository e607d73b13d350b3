#include "command_server.hpp"

#include <boost/asio/ip/address.hpp>
#include <boost/asio/post.hpp>

#include "state/messages.hpp"
#include "state/state_push.hpp"

namespace gimbald {

namespace log = gimbal::log;
using nlohmann::json;

namespace {

// How early a STATE datagram may go out to share a snapshot: half the period of the highest
// rate_hz (50), so each subscriber still gets exactly one datagram per period.
constexpr double publish_batch_s = 0.010;

std::string dump(const json& j) {
    return j.dump(-1, ' ', false, json::error_handler_t::replace);
}

}  // namespace

std::string to_string(const boost::asio::ip::udp::endpoint& e) {
    const auto a = e.address();
    return (a.is_v6() ? "[" + a.to_string() + "]" : a.to_string()) + ":" + std::to_string(e.port());
}

CommandServer::CommandServer(boost::asio::io_context& io, CommandServerOptions options,
                             RequestPath& path)
    : io_(io),
      options_(std::move(options)),
      path_(path),
      socket_(io),
      publish_timer_(io),
      subscriptions_(options_.max_subscribers, options_.max_subscribers_per_host),
      dropped_(log::Level::warn, "dropped_source", "datagrams from sources not in command.allow") {
    const Endpoint local(boost::asio::ip::make_address(options_.bind), options_.port);
    socket_.open(local.protocol());
    // No SO_REUSEADDR: on UDP it would let a second daemon bind the same port and steal
    // datagrams instead of failing with exit code 2.
    socket_.bind(local);
    path_.set_subscriptions(&subscriptions_, [this] { schedule_publish(); });
}

void CommandServer::start() {
    stopped_ = false;
    do_receive();
    schedule_publish();
}

void CommandServer::stop() {
    stopped_ = true;
    publish_timer_.cancel();
    boost::system::error_code ignored;
    socket_.close(ignored);
}

void CommandServer::do_receive() {
    socket_.async_receive_from(
        boost::asio::buffer(buffer_), sender_,
        [this](const boost::system::error_code& ec, std::size_t n) { on_receive(ec, n); });
}

void CommandServer::on_receive(const boost::system::error_code& ec, std::size_t n) {
    if (stopped_ || ec == boost::asio::error::operation_aborted) return;
    if (!ec) {
        const Endpoint from = sender_;
        if (options_.allowed && !options_.allowed(from.address())) {
            ++dropped_sources_;
            dropped_.hit("datagram from a source not in command.allow dropped",
                         {{"src", to_string(from)}});
        } else {
            const RequestSource source{"udp", to_string(from), from};
            auto reply = path_.handle(std::string_view(buffer_.data(), n), source);
            // Posted after the link's write of whatever the request queued for the gimbal (the
            // link posts its writes too), so the packet goes out first: the reply is not part
            // of the command's latency, and `ok: true` then follows the write.
            if (reply)
                boost::asio::post(io_, [this, from, reply = std::move(*reply)]() mutable {
                    send(from, std::move(reply));
                });
        }
    } else {
        // ICMP port unreachable from an earlier reply surfaces here on Linux; keep serving.
        log::debug("command_socket", "receive error: " + ec.message());
    }
    do_receive();
}

void CommandServer::send(const Endpoint& to, std::string payload) {
    send(to, std::make_shared<const std::string>(std::move(payload)));
}

void CommandServer::send(const Endpoint& to, std::shared_ptr<const std::string> payload) {
    const auto& bytes = *payload;
    socket_.async_send_to(
        boost::asio::buffer(bytes), to,
        [payload = std::move(payload)](const boost::system::error_code&, std::size_t) {});
}

std::string CommandServer::payload_for(const Endpoint& to, const json& message) const {
    const Subscription* s = subscriptions_.find(to);
    if (s && s->key_id && options_.sign) return options_.sign(*s->key_id, message);
    return dump(message);
}

void CommandServer::publish_event(const std::string& gimbal, const gimbal::state::Event& event) {
    const auto targets = subscriptions_.event_targets(gimbal);
    if (targets.empty()) return;
    const json msg = gimbal::state::event_message(gimbal, event);
    std::optional<std::string> plain;
    for (const auto& to : targets) {
        const Subscription* s = subscriptions_.find(to);
        if (s && s->key_id) {
            send(to, payload_for(to, msg));
            continue;
        }
        if (!plain) plain = dump(msg);
        send(to, *plain);
    }
}

void CommandServer::publish_states() {
    const double now = steady_seconds();
    dropped_.poll();  // a burst of dropped datagrams that stopped still gets its summary
    for (const auto& gone : subscriptions_.expire(now))
        log::info("subscriber", "subscriber expired (no renewal within ttl_s)",
                  {{"src", to_string(gone)}});
    // Subscribers due a little later go out now too, sharing this tick's snapshot: without
    // it, subscribers that subscribed a few ms apart each cost a snapshot, a dump and a
    // timer wake-up per period (16 at 10 Hz: 160 snapshots/s instead of 10).
    const double horizon = now + publish_batch_s;
    for (auto* session : path_.sessions()) {
        const auto due = subscriptions_.due_state(session->name(), horizon);
        if (due.empty()) continue;
        // One snapshot per gimbal per tick; one message (and one dump) per distinct key
        // selection and kind, and per previous push for delta streams, shared by every plain
        // subscriber due now (state_push.hpp); signed subscribers get their own signature.
        gimbal::state::PushBatch batch(session->name(), session->snapshot());
        for (const auto& to : due) {
            Subscription* s = subscriptions_.find(to);
            if (!s) continue;
            const auto& message = batch.next(s->stream, s->cursors[session->name()], horizon);
            if (s->key_id && options_.sign) {
                send(to, options_.sign(*s->key_id, message.json()));
                continue;
            }
            send(to, message.text());
        }
    }
    subscriptions_.mark_sent(horizon);
}

void CommandServer::schedule_publish() {
    if (stopped_) return;
    const auto next = subscriptions_.next_due();
    const double wait_s = next ? std::max(0.0, *next - steady_seconds()) : 1.0;
    publish_timer_.expires_after(std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(std::min(wait_s, 1.0))));
    publish_timer_.async_wait([this](const boost::system::error_code& ec) {
        if (ec || stopped_) return;
        publish_states();
        schedule_publish();
    });
}

}  // namespace gimbald
