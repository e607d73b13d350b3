// The whole request path (contract sections 4 and 10) under arbitrary datagrams: envelope,
// signature, roles, rate limit, parsing, laser rules and planning, against a configured Orion
// and Viewpro whose in-process simulated gimbals receive whatever is planned. Every input must
// get exactly one well-formed reply.
//
// The first byte chooses how the rest is sent: as a plain datagram, as the payload of a
// correctly signed envelope (the fuzzer cannot compute MACs; this reaches the parsing behind
// the signature check; a fresh ts and nonce are put in when the payload is an object), or
// signed with a wrong secret; and whether it comes over UDP or MQTT (whose rate limit reads
// signed requests first). A request over the limits of contract section 14 gets a short
// reply that echoes nothing of it.
#include <boost/asio/io_context.hpp>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "auth/signed_envelope.hpp"
#include "command/request_limits.hpp"
#include "gimbal_session.hpp"
#include "link/sim_link.hpp"
#include "logging.hpp"
#include "protocols/registry.hpp"
#include "request_path.hpp"

namespace {

using nlohmann::json;

constexpr std::int64_t base_ms = 1'790'000'000'000;
std::int64_t clock_ms = base_ms;

const std::vector<std::uint8_t> secret(32, 0x5a);
const std::vector<std::uint8_t> wrong_secret(32, 0xa5);

struct World {
    boost::asio::io_context io;
    std::vector<std::unique_ptr<gimbald::GimbalSession>> sessions;
    std::unique_ptr<gimbald::RequestPath> path;

    World() {
        gimbal::log::Settings quiet;
        quiet.level = gimbal::log::Level::error;
        gimbal::log::configure(quiet);

        // Every protocol of the registry, each with its in-process simulated gimbal.
        gimbal::protocols::SessionSettings settings;
        settings.allow_fire = true;
        settings.allow_safety_bypass = false;
        const char* names[] = {"main", "nose", "tail", "wing"};
        std::size_t n = 0;
        for (const auto* entry : gimbal::protocols::entries()) {
            const nlohmann::json config = {{"name", names[n % 4]}, {"protocol", entry->name}};
            sessions.push_back(std::make_unique<gimbald::GimbalSession>(
                io, names[n++ % 4], entry->make_session(settings, config),
                std::make_unique<gimbald::SimLink>(io, entry->simulator.make({})), 5.0,
                [](const std::string&, const gimbal::state::Event&) {}));
        }
        std::vector<gimbald::GimbalSession*> raw;
        for (auto& s : sessions) {
            s->start();
            raw.push_back(s.get());
        }
        gimbald::RequestPathOptions options;
        gimbal::auth::Key key{"ops", secret, {}};
        key.roles.add(gimbal::auth::Role::observe);
        key.roles.add(gimbal::auth::Role::control);
        key.roles.add(gimbal::auth::Role::laser);
        gimbal::auth::Key viewer{"viewer", std::vector<std::uint8_t>(32, 0x11), {}};
        viewer.roles.add(gimbal::auth::Role::observe);
        options.keys = {key, viewer};
        options.rate_per_source_hz = 1e9;  // the limiter is unit-tested; here it must not mute
        options.rate_burst = 1e9;
        options.unix_ms = [] { return clock_ms; };
        path = std::make_unique<gimbald::RequestPath>(io, std::move(options), std::move(raw));
        io.poll();
    }
};

World& world() {
    static World w;
    return w;
}

void check_reply(const std::optional<std::string>& reply, bool expect_signed) {
    if (!reply) std::abort();  // no rate limit here: every request is answered
    const json j = json::parse(*reply, nullptr, false);
    if (!j.is_object()) std::abort();
    if (const auto* signed_reply = j.contains("signed") ? &j : nullptr) {
        auto envelope = gimbal::auth::parse_signed(*signed_reply);
        if (!envelope || !envelope->has_value()) std::abort();
        const auto& e = **envelope;
        if (e.key == "ops" && !gimbal::auth::mac_matches(e, secret)) std::abort();
        const json inner = json::parse(e.payload, nullptr, false);
        if (!inner.is_object() || !inner.contains("ok") || !inner.contains("nonce")) std::abort();
        return;
    }
    if (!j.contains("ok") || !j["ok"].is_boolean()) std::abort();
    // A verified signed request is answered signed, whatever its outcome.
    (void)expect_signed;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    World& w = world();
    if (size == 0) return 0;
    clock_ms += 1;  // nonces expire after max_skew_s of fuzzing time
    const std::string body(reinterpret_cast<const char*>(data + 1), size - 1);
    const bool mqtt = (data[0] / 3) % 2 == 1;
    const gimbald::RequestSource from = mqtt ? gimbald::RequestSource{"mqtt", "mqtt:fuzz", {}}
                                             : gimbald::RequestSource{"udp", "127.0.0.1:5000", {}};
    std::string datagram = body;
    bool signed_request = false;
    switch (data[0] % 3) {
        case 0:
            break;
        case 1:
        case 2: {
            std::string payload = body;
            // Only within the limits: the harness's own dump() would recurse on deep input.
            json j = gimbal::command::check_request_limits(body)
                         ? json()
                         : json::parse(body, nullptr, false);
            if (j.is_object()) {
                j["ts"] = clock_ms;
                j["nonce"] = "fuzz-" + std::to_string(clock_ms);
                payload = j.dump(-1, ' ', false, json::error_handler_t::replace);
            }
            signed_request = data[0] % 3 == 1;
            datagram = gimbal::auth::sign("ops", signed_request ? secret : wrong_secret, payload);
            break;
        }
    }
    const auto reply = w.path->handle(datagram, from);
    check_reply(reply, signed_request);
    if (gimbal::command::check_request_limits(datagram) && reply->size() > 512) std::abort();
    w.io.poll();
    return 0;
}
