#include "request_path.hpp"

#include <boost/asio/post.hpp>

#include "auth/hmac.hpp"
#include "auth/signed_envelope.hpp"
#include "auth/token.hpp"
#include "command/catalogue.hpp"
#include "command/envelope.hpp"
#include "command/params.hpp"
#include "command/request.hpp"
#include "command/request_limits.hpp"
#include "logging.hpp"
#include "protocols/registry.hpp"
#include "state/messages.hpp"
#include "stream_params.hpp"

namespace gimbald {

namespace cmdns = gimbal::command;
namespace log = gimbal::log;
using cmdns::Error;
namespace code = gimbal::command::code;
using nlohmann::json;

namespace {

json or_null(const std::optional<std::string>& s) {
    return s ? json(*s) : json(nullptr);
}

std::int64_t system_unix_ms() {
    return std::chrono::duration_cast<std::chrono::milliseconds>(
               std::chrono::system_clock::now().time_since_epoch())
        .count();
}

// The commands that move, configure or feed a gimbal (the audit trail's subject): those
// the catalogue gives the control or laser role (`point` among them, not `locate`).
bool reaches_gimbal(std::string_view cmd) {
    const auto* spec = cmdns::find_command(cmd);
    return !spec || (spec->access != cmdns::Access::open && spec->access != cmdns::Access::observe);
}

// The rate limit's key: a UDP client's address without its port (one host, one bucket),
// else the transport's own name for the client (MQTT: "mqtt:<client_id property>", which a
// publisher may claim at will; a signed MQTT request is keyed by its key instead, handle()).
// HTTP clients likewise by address: "http:IP:PORT" -> "http:IP" (a new connection per
// request must not get a new bucket).
std::string rate_key(const RequestSource& from) {
    if (from.udp) return from.udp->address().to_string();
    if (from.transport == "http") {
        const auto colon = from.address.rfind(':');
        if (colon != std::string::npos && colon > 5) return from.address.substr(0, colon);
    }
    return from.address;
}

}  // namespace

// One request on its way through the path: what was read of it, and what it came to.
struct RequestPath::Outcome {
    json doc;                // the request object, parsed once (a signed request's payload)
    cmdns::Envelope env;     // read from doc: the command, gimbal, token
    std::optional<json> id;  // what the reply echoes
    std::optional<std::string> cmd;
    std::optional<std::string> gimbal;  // the gimbal the reply names
    std::optional<Error> error;
    json results = json::object();
    std::chrono::steady_clock::time_point received = std::chrono::steady_clock::now();
    bool read = false;  // read() has run
    // A signed request whose MAC is right (read()), before accept() checks its ts and nonce.
    const gimbal::auth::Key* authentic = nullptr;
    std::optional<gimbal::auth::SignedEnvelope> envelope;
    // A signed request, accepted: its key (the reply is signed with it) and nonce.
    const gimbal::auth::Key* key = nullptr;
    std::string nonce;

    json fail(Error e) {
        error = std::move(e);
        return json::object();
    }

    void echo(const json& request) {
        auto e = cmdns::echo_of(request);
        id = std::move(e.id);
        cmd = std::move(e.cmd);
    }
    // For a refusal decided before the request is read (rate limit, bad signature): the id
    // and cmd of `text`, if it has them, so the client can still match the reply. Text over
    // the request limits is not parsed: nothing is echoed (a too_large reply's id is null).
    // This is the text's one parse: the request is not read further.
    void echo_text(std::string_view text) {
        if (auto refused = cmdns::check_request_limits(text)) {
            if (refused->code == code::too_large) id = json(nullptr);
            return;
        }
        if (auto parsed = cmdns::parse_object(text)) echo(*parsed);
    }
};

RequestPath::RequestPath(boost::asio::io_context& io, RequestPathOptions options,
                         std::vector<GimbalSession*> sessions)
    : io_(io),
      options_(std::move(options)),
      sessions_(std::move(sessions)),
      verifier_(options_.keys, options_.max_skew_s),
      limiter_(options_.rate_per_source_hz, options_.rate_burst),
      ground_(options_.terrain) {
    if (!options_.unix_ms) options_.unix_ms = system_unix_ms;
}

void RequestPath::set_subscriptions(Subscriptions* table, SubscriptionsChanged changed) {
    subscriptions_ = table;
    subscriptions_changed_ = std::move(changed);
}

GimbalSession* RequestPath::find(const std::string& name) const {
    for (auto* s : sessions_)
        if (s->name() == name) return s;
    return nullptr;
}

std::optional<std::string> RequestPath::handle(std::string_view bytes, const RequestSource& from) {
    return handle(bytes, std::nullopt, from);
}

std::optional<std::string> RequestPath::handle_parsed(json request, std::string_view bytes,
                                                      const RequestSource& from) {
    return handle(bytes, std::move(request), from);
}

std::optional<std::string> RequestPath::handle(std::string_view bytes, std::optional<json> parsed,
                                               const RequestSource& from) {
    ++counters_.requests;
    Outcome o;
    // MQTT has no trustworthy source address: a signed request's bucket is its key, once
    // the request is known to come from that key's holder - MAC right, ts in the window,
    // nonce fresh - so neither a forged MAC nor a replayed capture can drain the key's
    // bucket; those are charged to the claimed client_id. Reading first is bounded (8192
    // bytes, 32 levels). Other transports are limited by address before anything is read.
    const bool bucket_per_key = from.transport == "mqtt";
    if (bucket_per_key) {
        read(o, bytes, parsed);
        if (!o.error) accept(o);
    }
    const std::string bucket = bucket_per_key && o.key ? "key:" + o.key->id : rate_key(from);
    switch (limiter_.admit(bucket, steady_seconds())) {
        case gimbal::auth::RateLimiter::Decision::admit:
            break;
        case gimbal::auth::RateLimiter::Decision::limited_silent:
            ++counters_.rate_limited;
            return std::nullopt;
        case gimbal::auth::RateLimiter::Decision::limited_reply: {
            ++counters_.rate_limited;
            // Once a second per bucket: parsing the id is affordable at that rate.
            Outcome refused;
            if (o.read) {
                refused.id = o.id;
                refused.cmd = o.cmd;
            } else if (parsed) {
                refused.echo(*parsed);
            } else {
                refused.echo_text(bytes);
            }
            refused.error = Error{code::rate_limited,
                                  "more than command.rate_limit allows from " + bucket +
                                      "; this request and the others over the limit in the next "
                                      "second were not executed"};
            return finish(refused, from, bytes);
        }
    }

    if (!o.read) read(o, bytes, parsed);
    if (!o.error) accept(o);
    if (!o.error) authorize(o);
    if (!o.error) run(o, from);
    return finish(o, from, bytes);
}

std::optional<std::string> RequestPath::refuse_too_large(std::optional<std::size_t> size,
                                                         const RequestSource& from) {
    ++counters_.requests;
    switch (limiter_.admit(rate_key(from), steady_seconds())) {
        case gimbal::auth::RateLimiter::Decision::admit:
            break;
        case gimbal::auth::RateLimiter::Decision::limited_silent:
        case gimbal::auth::RateLimiter::Decision::limited_reply:
            // Nothing of it was read; the client learns nothing more from a rate_limited.
            ++counters_.rate_limited;
            return std::nullopt;
    }
    Outcome o;
    o.id = json(nullptr);
    const std::string limit = std::to_string(cmdns::max_request_bytes);
    o.error = Error{code::too_large, size ? "the request is " + std::to_string(*size) +
                                                " bytes, the limit is " + limit
                                          : "the request is over the limit of " + limit + " bytes"};
    return finish(o, from, {});
}

void RequestPath::read(Outcome& o, std::string_view bytes, std::optional<json>& parsed) {
    o.read = true;
    if (!parsed) {
        // Size and nesting first, on the raw bytes: an oversize request is never parsed.
        if (auto refused = cmdns::check_request_limits(bytes)) {
            if (refused->code == code::too_large) o.id = json(nullptr);
            o.error = std::move(refused);
            return;
        }
        parsed = cmdns::parse_object(bytes);  // the request's one parse
        if (!parsed) {
            o.error = Error{code::bad_json, "the datagram is not a JSON object"};
            return;
        }
    }
    json doc = std::move(*parsed);
    parsed.reset();
    auto signed_request = gimbal::auth::parse_signed(doc);
    if (!signed_request) {
        o.error = signed_request.error();
        return;
    }
    if (!signed_request->has_value()) return take(o, std::move(doc));
    auto& envelope = **signed_request;
    auto key = verifier_.authenticate(envelope);
    if (!key) {
        o.error = key.error();
        // The unsigned refusal still echoes id and cmd, so the client can match it;
        // nothing else of an unverified payload is used.
        o.echo_text(envelope.payload);
        return;
    }
    o.authentic = *key;
    o.envelope = std::move(envelope);
}

void RequestPath::accept(Outcome& o) {
    if (!o.authentic || o.key) return;  // not signed, or accepted already
    // The payload's one parse; the request is read from it.
    auto payload = gimbal::auth::read_signed_payload(o.envelope->payload);
    if (!payload) {
        o.error = payload.error();
        if (o.error->code == code::too_large) o.id = json(nullptr);
        return;
    }
    const auto echo = cmdns::echo_of(*payload);
    auto verified = verifier_.accept(*o.authentic, std::move(payload).value(), options_.unix_ms());
    if (!verified) {
        o.error = verified.error();
        o.id = echo.id;
        o.cmd = echo.cmd;
        return;
    }
    o.key = verified->key;
    o.nonce = std::move(verified->nonce);
    take(o, std::move(verified->request));
}

void RequestPath::take(Outcome& o, json request) {
    o.echo(request);
    auto env = cmdns::read_envelope(request);
    if (env)
        o.env = std::move(env).value();
    else
        o.error = env.error();
    o.doc = std::move(request);
}

void RequestPath::authorize(Outcome& o) {
    const auto role = gimbal::auth::required_role(o.env.cmd(), o.doc);
    if (!role) return;  // ping, version, list: open to every allowed source
    if (o.key) {
        if (!o.key->roles.has(*role))
            o.error =
                Error{code::forbidden, "key '" + o.key->id + "' lacks the '" +
                                           std::string(gimbal::auth::to_string(*role)) +
                                           "' role that '" + std::string(o.env.cmd()) + "' needs"};
        return;
    }
    if (options_.signed_only) {
        o.error =
            Error{code::forbidden, "command.auth is \"signed\": '" + std::string(o.env.cmd()) +
                                       "' must be signed by a key"};
        return;
    }
    if (options_.token && o.env.spec->needs_token &&
        !(o.env.token && gimbal::auth::token_matches(*o.env.token, *options_.token)))
        o.error =
            Error{code::forbidden, o.env.token ? "wrong token" : "this command needs 'token'"};
}

RequestPath::Executed RequestPath::execute_request(const json& request, const RequestSource& from) {
    ++counters_.requests;
    Outcome o;
    take(o, request);  // an object already: no text, no parse
    if (!o.error) run(o, from);
    Executed out{o.error, o.error ? json() : o.results};  // finish() may consume the results
    // A recording shows the request as the JSON text it would have been.
    finish(o, from,
           taps_.empty() ? std::string()
                         : request.dump(-1, ' ', false, json::error_handler_t::replace));
    return out;
}

void RequestPath::run(Outcome& o, const RequestSource& from) {
    try {
        o.results = dispatch(o, from);
        if (!o.error && o.gimbal)
            for (const auto& listener : executed_listeners_) listener(*o.gimbal, o.env.cmd());
    } catch (const std::exception& e) {
        // A bug must not take the daemon (or the next client) down.
        log::error("internal_error", e.what(), {{"cmd", o.env.cmd()}});
        o.error = Error{code::internal, "internal error, see the daemon log"};
    }
}

std::string RequestPath::render(Outcome& o) {
    json reply = o.error ? cmdns::error_reply(o.id, o.cmd, *o.error)
                         : cmdns::ok_reply(o.id, *o.cmd, o.gimbal, std::move(o.results));
    if (!o.key) return reply.dump(-1, ' ', false, json::error_handler_t::replace);
    // The reply to a signed request is signed with the same key and carries its nonce.
    reply["nonce"] = o.nonce;
    reply["ts"] = options_.unix_ms();
    return gimbal::auth::sign(o.key->id, o.key->secret,
                              reply.dump(-1, ' ', false, json::error_handler_t::replace));
}

std::string RequestPath::finish(Outcome& o, const RequestSource& from,
                                std::string_view request_bytes) {
    std::string text = render(o);
    if (from.max_reply_bytes && text.size() > *from.max_reply_bytes) {
        // Never silence (contract section 14, v4): the client learns why and what to ask for.
        std::string message = "the reply is " + std::to_string(text.size()) +
                              " bytes, over the limit of one datagram (" +
                              std::to_string(*from.max_reply_bytes) + " bytes)";
        if (o.cmd == "state")
            message += "; ask for fewer STATE keys with 'keys', e.g. [\"telemetry\"]";
        else if (!o.error && o.cmd && reaches_gimbal(*o.cmd))
            message += "; the command itself was carried out";
        o.error = Error{code::too_large, std::move(message)};
        o.results = json::object();
        text = render(o);
    }
    if (o.error && o.error->code != code::rate_limited) ++counters_.rejected;
    if (o.cmd && reaches_gimbal(*o.cmd)) audit(o, from);

    const CompletedRequest done{
        from.transport, o.cmd, o.error ? std::string(to_string(o.error->code)) : std::string("ok"),
        std::chrono::duration<double>(std::chrono::steady_clock::now() - o.received).count()};
    for (const auto& observe : observers_) observe(done);
    for (const auto& tap : taps_) tap(from, request_bytes, text);

    // Logged from a posted handler, after the link's write of the packets queued above: the
    // log line (formatted, then written and flushed) is not part of the command's latency.
    json fields = {
        {"src", from.address},   {"id", o.id ? *o.id : json(nullptr)},
        {"cmd", or_null(o.cmd)}, {"gimbal", or_null(o.gimbal)},
        {"ok", !o.error},        {"error", o.error ? json(o.error->code) : json(nullptr)}};
    if (from.transport != "udp") fields["transport"] = from.transport;
    boost::asio::post(io_, [msg = o.error ? o.error->message : std::string("ok"),
                            fields = std::move(fields)] { log::info("command", msg, fields); });
    return text;
}

namespace {

// The laser a `laser` request fired: its `index`, or the catalogue's default when it has none
// (the audit line keeps what the client sent; `laser_fire` says which laser fired).
json laser_index_used(const json& request) {
    if (const auto it = request.find("index"); it != request.end() && it->is_number_integer())
        return *it;
    const auto* spec = gimbal::command::find_command("laser");
    const auto* param = spec ? gimbal::command::find_param(*spec, "index") : nullptr;
    if (param && !param->default_text.empty()) return std::stoi(std::string(param->default_text));
    return nullptr;
}

}  // namespace

void RequestPath::audit(const Outcome& o, const RequestSource& from) const {
    json fields = {{"src", from.address},
                   {"transport", from.transport},
                   {"key", o.key ? json(o.key->id) : json(nullptr)},
                   {"cmd", or_null(o.cmd)},
                   {"gimbal", o.gimbal ? json(*o.gimbal) : or_null(o.env.gimbal)},
                   {"ok", !o.error},
                   {"error", o.error ? json(o.error->code) : json(nullptr)}};
    if (o.cmd == "laser" && o.doc.is_object()) {
        // Every laser flag as the client sent it (absent ones as null).
        for (const char* flag : {"index", "enable", "arm", "fire", "safety_bypass"}) {
            const auto it = o.doc.find(flag);
            fields[flag] = it == o.doc.end() ? json(nullptr) : *it;
        }
    }
    const bool fire = fields.contains("fire") && fields["fire"] == true;
    // A laser that fired has its own event besides the audit line, so the journal can be
    // asked for exactly those: journalctl -u gimbald EVENT=laser_fire.
    std::optional<json> fired;
    if (fire && !o.error)
        fired = json{{"src", from.address},
                     {"transport", from.transport},
                     {"key", fields["key"]},
                     {"gimbal", fields["gimbal"]},
                     {"index", laser_index_used(o.doc)}};
    boost::asio::post(
        io_, [fire, fired = std::move(fired), msg = o.error ? o.error->message : std::string("ok"),
              fields = std::move(fields)] {
            if (fire)
                log::warn("audit", msg, fields);
            else
                log::info("audit", msg, fields);
            if (fired) log::warn("laser_fire", "laser fire commanded", *fired);
        });
}

std::string RequestPath::random_nonce() {
    return gimbal::auth::to_hex(gimbal::auth::random_bytes(12));
}

std::string RequestPath::sign_message(const std::string& key_id, const json& message) {
    const auto* key = verifier_.find(key_id);
    if (key == nullptr) return message.dump(-1, ' ', false, json::error_handler_t::replace);
    json payload = message;
    payload["ts"] = options_.unix_ms();
    payload["nonce"] = random_nonce();
    return gimbal::auth::sign(key->id, key->secret,
                              payload.dump(-1, ' ', false, json::error_handler_t::replace));
}

json RequestPath::dispatch(Outcome& o, const RequestSource& from) {
    const std::string cmd(o.env.cmd());
    const json& request = o.doc;
    json results = json::object();
    cmdns::JsonParams params(request, cmd);

    if (cmd == "ping" || cmd == "version" || cmd == "list") {
        params.reject_unknown();
        if (!params.ok()) return o.fail(params.error());
        if (cmd == "ping") results["pong"] = true;
        if (cmd == "version") {
            results["version"] = GIMBALD_VERSION;
            results["protocols"] = gimbal::protocols::names();
        }
        if (cmd == "list") {
            auto list = json::array();
            for (auto* s : sessions_)
                list.push_back(
                    {{"name", s->name()},
                     {"protocol", std::string(s->protocol())},
                     {"link", {{"type", s->link_type()}, {"connected", s->connected()}}}});
            results["gimbals"] = std::move(list);
        }
        return results;
    }

    if (cmd == "subscribe" || cmd == "unsubscribe") return subscription(o, from);
    if (GroundCommands::answers_without_gimbal(cmd)) {
        auto answer = ground_.run(cmd, request);
        if (!answer) return o.fail(answer.error());
        return std::move(answer).value();
    }

    // Route to the gimbal.
    GimbalSession* session = nullptr;
    if (o.env.gimbal) {
        session = find(*o.env.gimbal);
        if (!session)
            return o.fail(Error{code::unknown_gimbal, "no gimbal named '" + *o.env.gimbal + "'"});
    } else if (sessions_.size() == 1) {
        session = sessions_.front();
    } else {
        return o.fail(Error{
            code::unknown_gimbal,
            std::to_string(sessions_.size()) + " gimbals are configured: name one with 'gimbal'"});
    }
    o.gimbal = session->name();

    if (cmd == "state") {
        std::vector<std::string> keys;
        if (const json* k = params.raw("keys")) {
            auto read = gimbal::state::read_state_keys(*k, gimbal::protocols::is_state_key);
            if (!read) return o.fail(read.error());
            keys = std::move(read).value();
        }
        params.reject_unknown();
        if (!params.ok()) return o.fail(params.error());
        results["state"] = gimbal::state::select_keys(session->snapshot(), keys);
        return results;
    }
    if (GroundCommands::answers_for_gimbal(cmd)) {
        auto outcome = ground_.run(cmd, *session, request);
        if (outcome.error) o.error = std::move(outcome.error);
        return std::move(outcome.results);
    }
    if (!session->supports(cmd)) {
        return o.fail(Error{code::unsupported, "'" + cmd + "' is not a command of " +
                                                   std::string(session->protocol()) + " gimbals"});
    }
    // Altitudes left to the terrain (geopoint, path) become plain ones before planning.
    const auto prepared = ground_.prepare(cmd, request);
    if (!prepared) return o.fail(prepared.error());
    auto outcome = session->execute(cmd, *prepared);
    if (outcome.error) o.error = std::move(outcome.error);
    return std::move(outcome.results);
}

json RequestPath::subscription(Outcome& o, const RequestSource& from) {
    const std::string cmd(o.env.cmd());
    cmdns::JsonParams params(o.doc, cmd);
    json results = json::object();
    if (!from.udp || !subscriptions_)
        return o.fail(Error{code::unsupported,
                            "'" + cmd + "' is for the UDP command socket; " + from.transport +
                                " clients get STATE and events from their own stream"});
    if (o.env.gimbal) {
        if (!find(*o.env.gimbal))
            return o.fail(Error{code::unknown_gimbal, "no gimbal named '" + *o.env.gimbal + "'"});
        o.gimbal = o.env.gimbal;
    }
    if (cmd == "unsubscribe") {
        params.reject_unknown();
        if (!params.ok()) return o.fail(params.error());
        if (subscriptions_->unsubscribe(*from.udp))
            log::info("subscriber", "subscriber removed",
                      {{"src", from.address}, {"reason", "unsubscribe"}});
        results["subscribed"] = false;
        return results;
    }
    Subscription s;
    s.gimbal = o.env.gimbal;
    if (o.key) s.key_id = o.key->id;
    s.rate_hz = params.number_or("rate_hz", 10.0);
    s.ttl_s = params.number_or("ttl_s", 60.0);
    s.events = params.boolean_or("events", true);
    read_stream_options(params, s.stream);
    params.reject_unknown();
    if (!params.ok()) return o.fail(params.error());
    const auto outcome = subscriptions_->subscribe(*from.udp, s, steady_seconds());
    if (outcome == Subscriptions::Result::full)
        return o.fail(Error{code::busy, "subscriber table full (command.max_subscribers = " +
                                            std::to_string(subscriptions_->capacity()) + ")"});
    if (outcome == Subscriptions::Result::host_full)
        return o.fail(
            Error{code::busy, "too many subscriptions from " + from.udp->address().to_string() +
                                  " (command.max_subscribers_per_host = " +
                                  std::to_string(subscriptions_->per_host_capacity()) + ")"});
    if (outcome == Subscriptions::Result::added)
        log::info("subscriber", "subscriber added",
                  {{"src", from.address},
                   {"rate_hz", s.rate_hz},
                   {"ttl_s", s.ttl_s},
                   {"gimbal", or_null(o.env.gimbal)}});
    results["rate_hz"] = s.rate_hz;
    results["ttl_s"] = s.ttl_s;
    results["events"] = s.events;
    describe_stream_options(s.stream, results);
    if (subscriptions_changed_) subscriptions_changed_();
    return results;
}

}  // namespace gimbald
