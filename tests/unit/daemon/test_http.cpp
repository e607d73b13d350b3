// The HTTP server's pure parts: the `http` configuration section, and which static file a
// request target names (never one outside the web root).
#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "config.hpp"
#include "http/client_slots.hpp"
#include "http/command_metrics.hpp"
#include "http/frame_policy.hpp"
#include "http/static_files.hpp"

using namespace gimbal::daemon;
namespace fs = std::filesystem;
using gimbald::http::content_type;
using gimbald::http::percent_decode;
using gimbald::http::resolve_static;
using gimbald::http::target_path;

namespace {

const std::string one_gimbal =
    R"("gimbals":[{"name":"a","protocol":"orion","link":{"type":"sim"}}])";

ConfigResult with_http(const std::string& http, const std::string& extra = "") {
    return parse_config("{" + one_gimbal + R"(,"http":)" + http + extra + "}");
}

std::vector<std::string> problems_of(const ConfigResult& r) {
    std::vector<std::string> out;
    for (const auto& p : r.problems) out.push_back(p.text());
    return out;
}

void write(const fs::path& path, const std::string& text) {
    std::ofstream(path) << text;
}

}  // namespace

TEST_CASE("http is off unless the section is set; its defaults", "[http][config]") {
    const auto off = parse_config("{" + one_gimbal + "}");
    REQUIRE(off.ok());
    CHECK_FALSE(off.config.http.has_value());

    const auto on = with_http("{}");
    REQUIRE(on.ok());
    REQUIRE(on.config.http.has_value());
    const auto& h = *on.config.http;
    CHECK(h.bind.to_string() == "127.0.0.1");
    CHECK(h.port == 8761);
    CHECK(h.console);
    CHECK_FALSE(h.tiles_url.has_value());
    CHECK_FALSE(h.web_root.has_value());
    CHECK(h.max_connections == 64);
    CHECK(h.max_connections_per_client == 16);
    CHECK(h.idle_timeout_s == 30);
    CHECK(h.ws_queue_max == 64);
    CHECK(to_json(on.config)["http"]["port"] == 8761);
    CHECK(to_json(on.config)["http"]["max_connections_per_client"] == 16);
}

TEST_CASE("http values are read", "[http][config]") {
    const auto r = with_http(
        R"({"bind":"::1","port":0,"console":false,"tiles_url":"https://t/{z}/{x}/{y}.png",)"
        R"("web_root":"/srv/web","max_connections":5,"idle_timeout_s":2.5,"ws_queue_max":8,)"
        R"("max_connections_per_client":3})");
    INFO(problems_of(r).size());
    REQUIRE(r.ok());
    const auto& h = *r.config.http;
    CHECK(h.bind.to_string() == "::1");
    CHECK(h.port == 0);
    CHECK_FALSE(h.console);
    CHECK(*h.tiles_url == "https://t/{z}/{x}/{y}.png");
    CHECK(*h.web_root == "/srv/web");
    CHECK(h.max_connections == 5);
    CHECK(h.max_connections_per_client == 3);
    CHECK(h.idle_timeout_s == 2.5);
    CHECK(h.ws_queue_max == 8);
}

TEST_CASE("bad http values are reported with their paths", "[http][config]") {
    auto only = [](const ConfigResult& r) {
        const auto p = problems_of(r);
        REQUIRE(p.size() == 1);
        return p[0];
    };
    CHECK(only(with_http(R"({"bind":"localhost"})")) ==
          "http.bind: must be an IPv4 or IPv6 address");
    CHECK(only(with_http(R"({"port":70000})")) == "http.port: must be between 0 and 65535");
    CHECK(only(with_http(R"({"console":"yes"})")) == "http.console: must be true or false");
    CHECK(only(with_http(R"({"tiles_url":"https://t/tiles.png"})")) ==
          "http.tiles_url: must be an XYZ template with {z}, {x} and {y}");
    CHECK(only(with_http(R"({"web_root":"web"})")) == "http.web_root: must be an absolute path");
    CHECK(only(with_http(R"({"max_connections":0})")) ==
          "http.max_connections: must be between 1 and 10000");
    CHECK(only(with_http(R"({"max_connections_per_client":0})")) ==
          "http.max_connections_per_client: must be between 1 and 10000");
    CHECK(only(with_http(R"({"idle_timeout_s":0})")) ==
          "http.idle_timeout_s: must be between 1 and 3600");
    CHECK(only(with_http(R"({"ws_queue_max":1})")) ==
          "http.ws_queue_max: must be between 2 and 100000");
    CHECK(only(with_http(R"({"prot":8761})")) == "http.prot: unknown key (did you mean \"port\"?)");
    CHECK(only(with_http("[]")) == "http: must be an object");
}

TEST_CASE("laser fire over a non-loopback HTTP port needs signed commands", "[http][config]") {
    const auto open = with_http(R"({"bind":"0.0.0.0"})", R"(,"laser":{"allow_fire":true})");
    REQUIRE(problems_of(open).size() == 1);
    CHECK(open.problems[0].path == "http.bind");
    CHECK(with_http(R"({"bind":"0.0.0.0"})").ok());
    CHECK(with_http(R"({"bind":"127.0.0.1"})", R"(,"laser":{"allow_fire":true})").ok());
}

TEST_CASE("request targets: path, percent-decoding", "[http]") {
    CHECK(target_path("/a/b?x=1#f") == "/a/b");
    CHECK(target_path("/a#f?x") == "/a");
    CHECK(*percent_decode("/a%20b%2Fc") == "/a b/c");
    CHECK_FALSE(percent_decode("/a%2").has_value());
    CHECK_FALSE(percent_decode("/a%zz").has_value());
    CHECK_FALSE(percent_decode("/a%00b").has_value());
}

TEST_CASE("static files stay inside the web root", "[http]") {
    const fs::path base =
        fs::temp_directory_path() / ("gimbald-http-unit-" + std::to_string(::getpid()));
    fs::remove_all(base);
    const fs::path root = base / "web";
    fs::create_directories(root / "js");
    write(root / "index.html", "index");
    write(root / "js" / "app.js", "app");
    write(root / "js" / "index.html", "js index");
    write(root / ".secret", "secret");
    write(base / "outside.txt", "outside");
    fs::create_symlink(base / "outside.txt", root / "link.txt");
    fs::create_symlink(root / "js" / "app.js", root / "inside-link.js");
    const fs::path real_root = fs::canonical(root);

    CHECK(*resolve_static(root, "/") == real_root / "index.html");
    CHECK(*resolve_static(root, "/index.html?v=2") == real_root / "index.html");
    CHECK(*resolve_static(root, "/js/app.js") == real_root / "js" / "app.js");
    CHECK(*resolve_static(root, "//js//app.js") == real_root / "js" / "app.js");
    CHECK(*resolve_static(root, "/js/") == real_root / "js" / "index.html");
    CHECK(*resolve_static(root, "/js") == real_root / "js" / "index.html");
    CHECK(*resolve_static(root, "/inside-link.js") == real_root / "js" / "app.js");
    for (const char* bad : {"/../outside.txt", "/js/../../outside.txt", "/%2e%2e/outside.txt",
                            "/js/%2e%2e/index.html", "/.secret", "/link.txt", "/missing.html",
                            "relative.html", "", "/%00", "/js\\..\\index.html", "/%5c.."}) {
        INFO(bad);
        CHECK_FALSE(resolve_static(root, bad).has_value());
    }
    fs::remove_all(base);
}

TEST_CASE("content types by extension", "[http]") {
    CHECK(content_type("a/index.html") == "text/html; charset=utf-8");
    CHECK(content_type("app.js") == "text/javascript; charset=utf-8");
    CHECK(content_type("s.css") == "text/css; charset=utf-8");
    CHECK(content_type("i.svg") == "image/svg+xml");
    CHECK(content_type("i.png") == "image/png");
    CHECK(content_type("d.json") == "application/json");
    CHECK(content_type("x.bin") == "application/octet-stream");
    CHECK(content_type("noext") == "application/octet-stream");
}

TEST_CASE("command metrics: counts by cmd and result, unknown names folded", "[http]") {
    gimbald::http::CommandMetrics m;
    m.observe({"udp", std::string("ping"), "ok", 0.0001});
    m.observe({"http", std::string("ping"), "ok", 0.0002});
    m.observe({"udp", std::string("geopoint"), "out_of_range", 0.003});
    m.observe({"udp", std::nullopt, "bad_json", 0.00001});
    m.observe({"udp", std::string("made-up-1"), "unknown_cmd", 0.00001});
    m.observe({"udp", std::string("made-up-2"), "unknown_cmd", 0.00001});
    const auto& t = m.totals();
    CHECK(t.at({"ping", "ok"}) == 2);
    CHECK(t.at({"geopoint", "out_of_range"}) == 1);
    CHECK(t.at({"none", "bad_json"}) == 1);
    CHECK(t.at({"unknown", "unknown_cmd"}) == 2);
    CHECK(t.size() == 4);
    CHECK(m.durations().count() == 6);
    CHECK(m.durations().sum() == Approx(0.00333));
}

TEST_CASE("frame policy: frame-ancestors 'none' merged into any policy", "[http]") {
    using gimbald::http::deny_framing;
    CHECK(deny_framing("") == "frame-ancestors 'none'");
    CHECK(deny_framing("default-src 'self'") == "default-src 'self'; frame-ancestors 'none'");
    CHECK(deny_framing(" default-src 'self' ; img-src * ;") ==
          "default-src 'self'; img-src *; frame-ancestors 'none'");
    // A page's own frame-ancestors gives way, whatever its case.
    CHECK(deny_framing("Frame-Ancestors https://a.example; script-src 'self'") ==
          "script-src 'self'; frame-ancestors 'none'");
    CHECK(deny_framing("frame-ancestors-x 1") == "frame-ancestors-x 1; frame-ancestors 'none'");

    boost::beast::http::fields fields;
    gimbald::http::add_frame_policy(fields);
    CHECK(fields["X-Frame-Options"] == "DENY");
    CHECK(fields["Content-Security-Policy"] == "frame-ancestors 'none'");
    fields.set("Content-Security-Policy", "default-src 'self'");
    gimbald::http::add_frame_policy(fields);
    CHECK(fields["Content-Security-Policy"] == "default-src 'self'; frame-ancestors 'none'");
    CHECK(fields.count("X-Frame-Options") == 1);
}

TEST_CASE("client slots: per address, given back when the holder goes", "[http]") {
    using gimbald::http::ClientSlots;
    const auto a = boost::asio::ip::make_address("127.0.0.1");
    const auto b = boost::asio::ip::make_address("127.0.0.2");
    ClientSlots slots(2);
    auto first = slots.take(a);
    auto second = slots.take(a);
    REQUIRE(first);
    REQUIRE(second);
    CHECK_FALSE(slots.take(a));  // the third from a
    CHECK(slots.take(b));        // taken and given back at once
    CHECK(slots.open(b) == 0);
    CHECK(slots.open(a) == 2);
    {
        // Moved from the connection to its WebSocket client: still one slot.
        ClientSlots::Slot moved = std::move(*first);
        CHECK(slots.open(a) == 2);
        CHECK_FALSE(slots.take(a));
    }
    CHECK(slots.open(a) == 1);
    auto again = slots.take(a);
    CHECK(again);
    CHECK(slots.open(a) == 2);
}
