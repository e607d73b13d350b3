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
      dropped_(log::Level::warn, "dropped_source", "datagrams from sources not in command.allow"),
      send_failed_(log::Level::warn, "send_failed",
                   "replies and pushes the command socket could not send"),
      too_large_(log::Level::warn, "push_too_large",
                 "pushes too large for one datagram, replaced by a too_large event") {
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
            const RequestSource source{"udp", to_string(from), from, max_datagram_bytes};
            auto reply = path_.handle(std::string_view(buffer_.data(), n), source);
            // Posted after the link's write of whatever the request queued for the gimbal (the
            // link posts its writes too), so the packet goes out first: the reply is not part
            // of the command's latency, and `ok: true` then follows the write.
            if (reply)
                boost::asio::post(io_, [this, from, reply = std::move(*reply)]() mutable {
                    send(from, std::make_shared<const std::string>(std::move(reply)), Kind::reply);
                });
        }
    } else {
        // ICMP port unreachable from an earlier reply surfaces here on Linux; keep serving.
        log::debug("command_socket", "receive error: " + ec.message());
    }
    do_receive();
}

void CommandServer::send(const Endpoint& to, std::shared_ptr<const std::string> payload,
                         Kind kind) {
    const auto& bytes = *payload;
    socket_.async_send_to(boost::asio::buffer(bytes), to,
                          [this, to, kind, payload = std::move(payload)](
                              const boost::system::error_code& ec, std::size_t) {
                              if (ec) send_failed(to, kind, payload->size(), ec);
                          });
}

void CommandServer::send_failed(const Endpoint& to, Kind kind, std::size_t bytes,
                                const boost::system::error_code& ec) {
    if (ec == boost::asio::error::operation_aborted || stopped_) return;
    ++sent_.failed;
    const std::string what = kind == Kind::reply ? "reply" : "push";
    send_failed_.hit(
        "a " + what + " could not be sent: " + ec.message(),
        {{"src", to_string(to)}, {"what", what}, {"bytes", bytes}, {"error", ec.message()}});
}

bool CommandServer::push(const Endpoint& to, std::shared_ptr<const std::string> payload,
                         const std::string& gimbal, const std::function<json()>& carried,
                         Notices& notices) {
    if (payload->size() <= max_datagram_bytes) {
        send(to, std::move(payload), Kind::push);
        return true;
    }
    ++sent_.pushes_too_large;
    too_large_.hit("a push of " + std::to_string(payload->size()) +
                       " bytes is over one datagram; the subscriber got a too_large event",
                   {{"src", to_string(to)}, {"gimbal", gimbal}, {"bytes", payload->size()}});
    const auto event = [&] {
        return gimbal::state::too_large_event(gimbal, payload->size(), max_datagram_bytes,
                                              carried());
    };
    const Subscription* s = subscriptions_.find(to);
    if (s && s->key_id && options_.sign) {
        send(to, std::make_shared<const std::string>(options_.sign(*s->key_id, event())),
             Kind::push);
        return false;
    }
    auto& shared = notices[payload.get()];
    if (!shared) shared = std::make_shared<const std::string>(dump(event()));
    send(to, shared, Kind::push);
    return false;
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
    const auto carried = [&msg] { return msg; };
    std::shared_ptr<const std::string> plain;
    Notices notices;
    for (const auto& to : targets) {
        const Subscription* s = subscriptions_.find(to);
        if (s && s->key_id) {
            push(to, std::make_shared<const std::string>(payload_for(to, msg)), gimbal, carried,
                 notices);
            continue;
        }
        if (!plain) plain = std::make_shared<const std::string>(dump(msg));
        push(to, plain, gimbal, carried, notices);
    }
}

void CommandServer::publish_states() {
    const double now = steady_seconds();
    // A burst that stopped still gets its summary.
    dropped_.poll();
    send_failed_.poll();
    too_large_.poll();
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
        Notices notices;
        for (const auto& to : due) {
            Subscription* s = subscriptions_.find(to);
            if (!s) continue;
            auto& cursor = s->cursors[session->name()];
            // A patch over one Ethernet payload goes as several that fit, back to back.
            const auto& parts = batch.split(batch.next(s->stream, cursor, horizon),
                                            gimbal::state::patch_budget_bytes);
            // Every part ready before the first goes, so the parts leave back to back.
            std::vector<std::shared_ptr<const std::string>> payloads;
            for (const auto& message : parts)
                payloads.push_back(s->key_id && options_.sign
                                       ? std::make_shared<const std::string>(
                                             options_.sign(*s->key_id, message.json()))
                                       : message.text());
            for (std::size_t i = 0; i < parts.size(); ++i) {
                // Only a push too large needs its content as JSON (to name its largest keys).
                const auto carried = [&parts, i] { return *parts[i].body(); };
                // A patch that did not go out breaks the chain: the next push is full.
                if (!push(to, std::move(payloads[i]), session->name(), carried, notices))
                    cursor.restart();
            }
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
