#include "command_server.hpp"

#include <boost/asio/ip/address.hpp>
#include <boost/asio/post.hpp>

#include "command/envelope.hpp"
#include "command/orion_commands.hpp"
#include "command/params.hpp"
#include "command/viewpro_commands.hpp"

namespace gimbald {

namespace cmdns = gimbal::command;
namespace log = gimbal::log;
using cmdns::Error;
namespace code = gimbal::command::code;

namespace {

bool known_command(std::string_view cmd) {
    return cmdns::is_common_command(cmd) || cmdns::is_orion_command(cmd) ||
           cmdns::is_viewpro_command(cmd);
}

// How early a STATE datagram may go out to share a snapshot: half the period of the highest
// rate_hz (50), so each subscriber still gets exactly one datagram per period.
constexpr double publish_batch_s = 0.010;

std::string to_string(const boost::asio::ip::udp::endpoint& e) {
    const auto a = e.address();
    return (a.is_v6() ? "[" + a.to_string() + "]" : a.to_string()) + ":" + std::to_string(e.port());
}

}  // namespace

CommandServer::CommandServer(boost::asio::io_context& io, CommandServerOptions options,
                             std::vector<GimbalSession*> sessions)
    : io_(io),
      options_(std::move(options)),
      sessions_(std::move(sessions)),
      socket_(io),
      publish_timer_(io),
      subscriptions_(options_.max_subscribers),
      epoch_(std::chrono::steady_clock::now()),
      dropped_(log::Level::warn, "dropped_source", "datagrams from sources not in command.allow") {
    const Endpoint local(boost::asio::ip::make_address(options_.bind), options_.port);
    socket_.open(local.protocol());
    // No SO_REUSEADDR: on UDP it would let a second daemon bind the same port and steal
    // datagrams instead of failing with exit code 2.
    socket_.bind(local);
}

double CommandServer::now_s() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - epoch_).count();
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
            dropped_.hit("datagram from a source not in command.allow dropped",
                         {{"src", to_string(from)}});
        } else {
            nlohmann::json reply = handle(std::string_view(buffer_.data(), n), from);
            // Posted after the link's write of whatever handle() queued for the gimbal (the
            // link posts its writes too), so the packet goes out first: the reply is not part
            // of the command's latency, and `ok: true` then follows the write.
            boost::asio::post(io_, [this, from, reply = std::move(reply)] {
                send(from, reply.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
            });
        }
    } else {
        // ICMP port unreachable from an earlier reply surfaces here on Linux; keep serving.
        log::debug("command_socket", "receive error: " + ec.message());
    }
    do_receive();
}

void CommandServer::send(const Endpoint& to, std::string payload) {
    auto data = std::make_shared<std::string>(std::move(payload));
    socket_.async_send_to(boost::asio::buffer(*data), to,
                          [data](const boost::system::error_code&, std::size_t) {});
}

CommandServer::Routed CommandServer::route(const std::optional<std::string>& gimbal) const {
    Routed r;
    if (gimbal) {
        for (auto* s : sessions_)
            if (s->name() == *gimbal) {
                r.session = s;
                return r;
            }
        r.error = Error{code::unknown_gimbal, "no gimbal named '" + *gimbal + "'"};
        return r;
    }
    if (sessions_.size() == 1) {
        r.session = sessions_.front();
        return r;
    }
    r.error = Error{code::unknown_gimbal, std::to_string(sessions_.size()) +
                                              " gimbals are configured: name one with 'gimbal'"};
    return r;
}

nlohmann::json CommandServer::handle(std::string_view datagram, const Endpoint& from) {
    cmdns::Envelope env;
    nlohmann::json reply;
    std::optional<Error> error;
    std::optional<std::string> reply_gimbal;
    std::optional<std::string> cmd_name;
    if (auto bad = cmdns::parse_envelope(datagram, known_command, env)) {
        error = bad->error;
        cmd_name = bad->cmd;
        env.id = bad->id;
    } else {
        cmd_name = env.cmd;
        if (options_.token && !cmdns::is_open_command(env.cmd) && env.token != options_.token) {
            error =
                Error{code::forbidden, env.token ? "wrong token" : "this command needs 'token'"};
        } else {
            try {
                reply = dispatch(env.cmd, env.request, env.gimbal, from, error, reply_gimbal);
            } catch (const std::exception& e) {
                // A bug must not take the daemon (or the next client) down.
                log::error("internal_error", e.what(), {{"cmd", env.cmd}});
                error = Error{code::internal, "internal error, see the daemon log"};
            }
        }
    }
    if (error)
        reply = cmdns::error_reply(env.id, cmd_name, *error);
    else
        reply = cmdns::ok_reply(env.id, *cmd_name, reply_gimbal, std::move(reply));

    // Logged from a posted handler, after the link's write of the packets queued above: the
    // log line (formatted, then written and flushed to stdout) is not part of the latency.
    nlohmann::json fields = {
        {"src", to_string(from)},
        {"id", env.id ? *env.id : nlohmann::json(nullptr)},
        {"cmd", cmd_name ? nlohmann::json(*cmd_name) : nlohmann::json(nullptr)},
        {"gimbal", reply_gimbal ? nlohmann::json(*reply_gimbal) : nlohmann::json(nullptr)},
        {"ok", !error},
        {"error", error ? nlohmann::json(error->code) : nlohmann::json(nullptr)}};
    boost::asio::post(io_, [msg = error ? error->message : std::string("ok"),
                            fields = std::move(fields)] { log::info("command", msg, fields); });
    return reply;
}

nlohmann::json CommandServer::dispatch(const std::string& cmd, const nlohmann::json& request,
                                       const std::optional<std::string>& gimbal,
                                       const Endpoint& from, std::optional<Error>& error,
                                       std::optional<std::string>& reply_gimbal) {
    nlohmann::json results = nlohmann::json::object();
    cmdns::Params params(request);
    // Records the error and returns no results: the caller builds the error reply.
    auto fail = [&error](Error e) {
        error = std::move(e);
        return nlohmann::json::object();
    };

    if (cmd == "ping" || cmd == "version" || cmd == "list") {
        params.reject_unknown();
        if (!params.ok()) return fail(params.error());
        if (cmd == "ping") results["pong"] = true;
        if (cmd == "version") {
            results["version"] = GIMBALD_VERSION;
            results["protocols"] = {"orion", "viewpro"};
        }
        if (cmd == "list") {
            auto list = nlohmann::json::array();
            for (auto* s : sessions_)
                list.push_back(
                    {{"name", s->name()},
                     {"protocol", std::string(s->protocol())},
                     {"link", {{"type", s->link_type()}, {"connected", s->connected()}}}});
            results["gimbals"] = std::move(list);
        }
        return results;
    }

    if (cmd == "subscribe" || cmd == "unsubscribe") {
        if (gimbal) {
            const auto r = route(gimbal);
            if (r.error) return fail(*r.error);
            reply_gimbal = gimbal;
        }
        if (cmd == "unsubscribe") {
            params.reject_unknown();
            if (!params.ok()) return fail(params.error());
            const bool was = subscriptions_.unsubscribe(from);
            if (was)
                log::info("subscriber", "subscriber removed",
                          {{"src", to_string(from)}, {"reason", "unsubscribe"}});
            results["subscribed"] = false;
            return results;
        }
        Subscription s;
        s.gimbal = gimbal;
        s.rate_hz = params.number_or("rate_hz", 0.1, 50.0, 10.0);
        s.ttl_s = params.number_or("ttl_s", 1.0, 3600.0, 60.0);
        s.events = params.boolean_or("events", true);
        params.reject_unknown();
        if (!params.ok()) return fail(params.error());
        const auto outcome = subscriptions_.subscribe(from, s, now_s());
        if (outcome == Subscriptions::Result::full)
            return fail(Error{code::busy, "subscriber table full (command.max_subscribers = " +
                                              std::to_string(options_.max_subscribers) + ")"});
        if (outcome == Subscriptions::Result::added)
            log::info("subscriber", "subscriber added",
                      {{"src", to_string(from)},
                       {"rate_hz", s.rate_hz},
                       {"ttl_s", s.ttl_s},
                       {"gimbal", gimbal ? nlohmann::json(*gimbal) : nlohmann::json(nullptr)}});
        results["rate_hz"] = s.rate_hz;
        results["ttl_s"] = s.ttl_s;
        results["events"] = s.events;
        schedule_publish();
        return results;
    }

    const auto r = route(gimbal);
    if (r.error) return fail(*r.error);
    reply_gimbal = r.session->name();

    if (cmd == "state") {
        params.reject_unknown();
        if (!params.ok()) return fail(params.error());
        results["state"] = r.session->snapshot();
        return results;
    }
    if (!r.session->supports(cmd)) {
        return fail(Error{code::unsupported, "'" + cmd + "' is not a command of " +
                                                 std::string(r.session->protocol()) + " gimbals"});
    }
    auto outcome = r.session->execute(cmd, request);
    if (outcome.error) error = std::move(outcome.error);
    return std::move(outcome.results);
}

void CommandServer::publish_event(const std::string& gimbal, const gimbal::state::Event& event) {
    const auto targets = subscriptions_.event_targets(gimbal);
    if (targets.empty()) return;
    nlohmann::json msg = {{"type", "event"}, {"gimbal", gimbal}, {"event", event.kind}};
    for (const auto& [k, v] : event.fields.items()) msg[k] = v;
    const std::string payload = msg.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    for (const auto& to : targets) send(to, payload);
}

void CommandServer::publish_states() {
    const double now = now_s();
    dropped_.poll();  // a burst of dropped datagrams that stopped still gets its summary
    for (const auto& gone : subscriptions_.expire(now))
        log::info("subscriber", "subscriber expired (no renewal within ttl_s)",
                  {{"src", to_string(gone)}});
    // Subscribers due a little later go out now too, sharing this tick's snapshot: without
    // it, subscribers that subscribed a few ms apart each cost a snapshot, a dump and a
    // timer wake-up per period (16 at 10 Hz: 160 snapshots/s instead of 10).
    const double horizon = now + publish_batch_s;
    for (auto* s : sessions_) {
        const auto due = subscriptions_.due_state(s->name(), horizon);
        if (due.empty()) continue;
        // One snapshot per gimbal per tick, shared by every subscriber due now.
        const nlohmann::json msg = {
            {"type", "state"}, {"gimbal", s->name()}, {"state", s->snapshot()}};
        const std::string payload =
            msg.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
        for (const auto& to : due) send(to, payload);
    }
    subscriptions_.mark_sent(horizon);
}

void CommandServer::schedule_publish() {
    if (stopped_) return;
    const auto next = subscriptions_.next_due();
    const double wait_s = next ? std::max(0.0, *next - now_s()) : 1.0;
    publish_timer_.expires_after(std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(std::min(wait_s, 1.0))));
    publish_timer_.async_wait([this](const boost::system::error_code& ec) {
        if (ec || stopped_) return;
        publish_states();
        schedule_publish();
    });
}

}  // namespace gimbald
