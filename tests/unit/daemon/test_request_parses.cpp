// One JSON parse per request on every transport (issue 26, docs/architecture.md "A request
// parsed once"): command::parse_object() is the one place a request's bytes are parsed and
// it counts. Each transport's own entry point gets a request for a simulated Orion (and a
// ping), plain and signed: a plain request is parsed once, a signed one once for its
// envelope and once for its payload, which the request is then read from; MAVLink's
// requests are objects already and are never parsed.
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/udp.hpp>
#include <catch2/catch.hpp>
#include <chrono>
#include <memory>
#include <string>

#include "auth/signed_envelope.hpp"
#include "command/request.hpp"
#include "command_server.hpp"
#include "gimbal_session.hpp"
#include "http/http_api.hpp"
#include "http/stream_hub.hpp"
#include "http/ws_client.hpp"
#include "link/sim_link.hpp"
#include "protocols/registry.hpp"
#include "request_path.hpp"

namespace asio = boost::asio;
using gimbal::command::request_parses;
using nlohmann::json;

namespace {

constexpr std::int64_t now_ms = 1'790'000'000'000;

gimbal::auth::Key ops_key() {
    gimbal::auth::Key k{"ops", std::vector<std::uint8_t>(32, 7), {}};
    k.roles.add(gimbal::auth::Role::observe);
    k.roles.add(gimbal::auth::Role::control);
    return k;
}

// A daemon's request path with one simulated Orion, "main", connected.
struct Daemon {
    asio::io_context io;
    std::unique_ptr<gimbald::GimbalSession> session;
    std::unique_ptr<gimbald::RequestPath> path;
    int nonce = 0;

    Daemon() {
        const auto* orion = gimbal::protocols::find("orion");
        REQUIRE(orion);
        const json config = {{"name", "main"}, {"protocol", "orion"}, {"link", {{"type", "sim"}}}};
        gimbal::protocols::SimScenario scenario;
        scenario.unix_time_s = 1'790'000'000.0;
        session = std::make_unique<gimbald::GimbalSession>(
            io, "main", orion->make_session(gimbal::protocols::SessionSettings{}, config),
            std::make_unique<gimbald::SimLink>(io, orion->simulator.make(scenario)), 1.0,
            [](const std::string&, const gimbal::state::Event&) {});
        session->start();
        gimbald::RequestPathOptions options;
        options.keys = {ops_key()};
        options.unix_ms = [] { return now_ms; };
        path = std::make_unique<gimbald::RequestPath>(
            io, options, std::vector<gimbald::GimbalSession*>{session.get()});
        run_for(0.05);
        REQUIRE(session->connected());
    }
    ~Daemon() { session->stop(); }

    void run_for(double seconds) {
        io.restart();
        io.run_for(std::chrono::duration_cast<std::chrono::nanoseconds>(
            std::chrono::duration<double>(seconds)));
    }

    std::string signed_text(json request) {
        const auto key = ops_key();
        request["ts"] = now_ms;
        request["nonce"] = "nonce-" + std::to_string(++nonce) + "-abcdef";
        return gimbal::auth::sign(key.id, key.secret, request.dump());
    }
};

const json position = {{"cmd", "position"}, {"id", 1}, {"pan", 10}, {"tilt", -20}};
const json ping = {{"cmd", "ping"}, {"id", 2}};

// The reply text's ok, for a plain or a signed reply.
bool ok(const std::string& reply) {
    json j = json::parse(reply);
    if (j.contains("signed")) j = json::parse(j["signed"]["payload"].get<std::string>());
    INFO(j.dump());
    return j.value("ok", false);
}

// How many parses `send` cost.
template <class F>
std::uint64_t parses(F&& send) {
    const auto before = request_parses();
    send();
    return request_parses() - before;
}

}  // namespace

TEST_CASE("UDP: one parse per request, two for a signed one", "[daemon][parses]") {
    Daemon d;
    gimbald::CommandServerOptions options;
    options.port = 0;
    gimbald::CommandServer server(d.io, options, *d.path);
    server.start();
    asio::ip::udp::socket client(d.io, asio::ip::udp::endpoint(asio::ip::udp::v4(), 0));
    const auto exchange = [&](const std::string& text) {
        client.send_to(asio::buffer(text), server.local_endpoint());
        std::string reply;
        std::array<char, 65536> buffer{};
        asio::ip::udp::endpoint from;
        client.async_receive_from(asio::buffer(buffer), from,
                                  [&](const boost::system::error_code& ec, std::size_t n) {
                                      if (!ec) reply.assign(buffer.data(), n);
                                  });
        for (int i = 0; i < 100 && reply.empty(); ++i) d.run_for(0.01);
        REQUIRE_FALSE(reply.empty());
        return reply;
    };
    std::string reply;
    CHECK(parses([&] { reply = exchange(position.dump()); }) == 1);
    CHECK(ok(reply));
    CHECK(parses([&] { reply = exchange(ping.dump()); }) == 1);
    CHECK(ok(reply));
    CHECK(parses([&] { reply = exchange(d.signed_text(position)); }) == 2);
    CHECK(ok(reply));
    server.stop();
}

TEST_CASE("HTTP: POST /api/command parses its body once", "[daemon][parses]") {
    Daemon d;
    gimbald::http::HttpStats stats;
    gimbald::http::DaemonView view;
    view.path = d.path.get();
    gimbald::http::HttpApi api(view, {}, stats);
    const auto post = [&](const std::string& body) {
        gimbald::http::Request request{boost::beast::http::verb::post, "/api/command", 11};
        request.body() = body;
        request.prepare_payload();
        return api.handle(request, "http:127.0.0.1:5555").body();
    };
    std::string reply;
    CHECK(parses([&] { reply = post(position.dump()); }) == 1);
    CHECK(ok(reply));
    CHECK(parses([&] { reply = post(d.signed_text(position)); }) == 2);
    CHECK(ok(reply));
}

TEST_CASE("WebSocket: a message is parsed once, routed or not", "[daemon][parses]") {
    Daemon d;
    gimbald::http::HttpStats stats;
    gimbald::http::StreamHub hub(d.io, *d.path, stats, 16, 60);
    auto client = std::make_shared<gimbald::http::WsClient>(boost::beast::tcp_stream(d.io), hub,
                                                            "http:127.0.0.1:5556",
                                                            gimbald::http::ClientSlots::Slot{});
    std::optional<std::string> reply;
    // Through the request path with the hub's parse.
    CHECK(parses([&] { reply = hub.on_message(*client, position.dump()).reply; }) == 1);
    REQUIRE(reply);
    CHECK(ok(*reply));
    CHECK(parses([&] { reply = hub.on_message(*client, d.signed_text(position)).reply; }) == 2);
    REQUIRE(reply);
    CHECK(ok(*reply));
    // subscribe, which the hub answers itself.
    const json subscribe = {{"cmd", "subscribe"}, {"id", 3}, {"rate_hz", 5}};
    CHECK(parses([&] { reply = hub.on_message(*client, subscribe.dump()).reply; }) == 1);
    REQUIRE(reply);
    CHECK(ok(*reply));
    hub.stop();
}

TEST_CASE("MQTT: the payload is parsed once, signed ones read before the rate limit too",
          "[daemon][parses]") {
    // The bridge hands P/cmd's payload to the request path as it came (mqtt_bridge.cpp); an
    // MQTT request is read before the rate limit, to key a signed one by its key.
    Daemon d;
    const gimbald::RequestSource from{"mqtt", "mqtt:tester", std::nullopt};
    std::optional<std::string> reply;
    CHECK(parses([&] { reply = d.path->handle(position.dump(), from); }) == 1);
    REQUIRE(reply);
    CHECK(ok(*reply));
    CHECK(parses([&] { reply = d.path->handle(d.signed_text(position), from); }) == 2);
    REQUIRE(reply);
    CHECK(ok(*reply));
}

TEST_CASE("MAVLink: a request built as an object is never parsed", "[daemon][parses]") {
    Daemon d;
    const gimbald::RequestSource from{"mavlink", "mavlink:255/190", std::nullopt};
    json request = position;
    request["gimbal"] = "main";
    gimbald::RequestPath::Executed outcome;
    CHECK(parses([&] { outcome = d.path->execute_request(request, from); }) == 0);
    CHECK_FALSE(outcome.error);
    CHECK(outcome.results.contains("sent"));
}

TEST_CASE("refusals cost no more: limits unparsed, a bad MAC's payload once", "[daemon][parses]") {
    Daemon d;
    const gimbald::RequestSource from{"http", "http:127.0.0.1:5557", std::nullopt};
    std::optional<std::string> reply;
    const std::string big = R"({"cmd":"ping","pad":")" + std::string(9000, 'x') + "\"}";
    CHECK(parses([&] { reply = d.path->handle(big, from); }) == 0);
    CHECK(parses([&] { reply = d.path->handle("[1,2]", from); }) == 1);
    // Signed with another secret: the envelope, and the payload once for the id it echoes.
    const auto forged = gimbal::auth::sign("ops", std::vector<std::uint8_t>(32, 8),
                                           json{{"cmd", "ping"}, {"id", 9}}.dump());
    CHECK(parses([&] { reply = d.path->handle(forged, from); }) == 2);
    REQUIRE(reply);
    CHECK(json::parse(*reply)["id"] == 9);
    // A replayed nonce: refused after the payload's one parse, echoing from it.
    const auto once = d.signed_text(ping);
    CHECK(parses([&] { reply = d.path->handle(once, from); }) == 2);
    CHECK(parses([&] { reply = d.path->handle(once, from); }) == 2);
    REQUIRE(reply);
    CHECK_FALSE(json::parse(*reply)["ok"].get<bool>());
    CHECK(json::parse(*reply)["id"] == 2);
}
