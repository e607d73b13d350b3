// The MQTT bridge's pure parts: mqtt.url parsing, the bounded outgoing queue's drop order,
// the request source of an MQTT request, and the `mqtt` configuration section.
#include <catch2/catch.hpp>

#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "config.hpp"
#include "mqtt/mqtt_bridge.hpp"
#include "mqtt/mqtt_url.hpp"
#include "mqtt/outgoing_queue.hpp"

using namespace gimbal::daemon;
using gimbald::mqtt::Kind;
using gimbald::mqtt::Message;
using gimbald::mqtt::OutgoingQueue;

namespace {

std::string url_problem(std::string_view text) {
    auto r = parse_mqtt_url(text);
    return r ? std::string() : r.error().message;
}

Message msg(Kind kind, std::string topic, std::string payload = "x") {
    return Message{kind, std::move(topic), std::move(payload), 0, false, {}};
}

std::vector<std::string> payloads(OutgoingQueue& q) {
    std::vector<std::string> out;
    while (auto m = q.pop()) out.push_back(m->payload);
    return out;
}

std::vector<std::string> problems_of(const std::string& mqtt_section) {
    const auto r = parse_config(
        R"({"gimbals":[{"name":"a","protocol":"orion","link":{"type":"sim"}}],"mqtt":)" +
        mqtt_section + "}");
    std::vector<std::string> out;
    for (const auto& p : r.problems) out.push_back(p.text());
    return out;
}

std::string temp_file(const std::string& text, mode_t mode) {
    char name[] = "/tmp/gimbald-mqtt-unit-XXXXXX";
    const int fd = ::mkstemp(name);
    REQUIRE(fd >= 0);
    REQUIRE(::write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size()));
    ::close(fd);
    ::chmod(name, mode);
    return name;
}

}  // namespace

TEST_CASE("mqtt.url: schemes, default ports, IPv6, and what is refused", "[mqtt]") {
    auto ok = [](std::string_view text) { return parse_mqtt_url(text).value(); };
    CHECK(ok("mqtt://broker.lan").port == 1883);
    CHECK_FALSE(ok("mqtt://broker.lan").tls);
    CHECK(ok("mqtts://broker.lan").port == 8883);
    CHECK(ok("mqtts://broker.lan").tls);
    CHECK(ok("mqtt://10.0.0.5:11883").host == "10.0.0.5");
    CHECK(ok("mqtt://10.0.0.5:11883").port == 11883);
    CHECK(ok("mqtt://[::1]:1884").host == "::1");
    CHECK(ok("mqtt://[::1]:1884").port == 1884);
    CHECK(ok("mqtt://host/").host == "host");
    for (const char* bad : {"http://h:1", "mqtt://", "mqtt://:1883", "mqtt://h:0", "mqtt://h:65536",
                            "mqtt://h:x", "mqtt://h:", "mqtt://user:pw@h", "mqtt://h/path",
                            "mqtt://::1:1883", "mqtt://[::1", "tcp://h"}) {
        INFO(bad);
        CHECK_FALSE(url_problem(bad).empty());
    }
}

TEST_CASE("outgoing queue: STATE dropped first, then retained, events last", "[mqtt]") {
    OutgoingQueue q(3);
    q.push(msg(Kind::event, "e", "e1"));
    q.push(msg(Kind::state, "s/a", "s1"));
    q.push(msg(Kind::retained, "l", "l1"));
    CHECK(q.push(msg(Kind::event, "e", "e2")) == 1);  // s1 goes
    CHECK(q.push(msg(Kind::event, "e", "e3")) == 1);  // l1 goes
    CHECK(q.push(msg(Kind::event, "e", "e4")) == 1);  // only events: the oldest goes
    CHECK(q.dropped() == 3);
    CHECK(payloads(q) == std::vector<std::string>{"e2", "e3", "e4"});
}

TEST_CASE("outgoing queue: a newer STATE of the same topic replaces the waiting one", "[mqtt]") {
    OutgoingQueue q(10);
    q.push(msg(Kind::state, "s/a", "a1"));
    q.push(msg(Kind::state, "s/b", "b1"));
    q.push(msg(Kind::event, "e", "e1"));
    for (int i = 2; i <= 100; ++i) q.push(msg(Kind::state, "s/a", "a" + std::to_string(i)));
    CHECK(q.size() == 3);
    CHECK(q.dropped() == 99);
    CHECK(payloads(q) == std::vector<std::string>{"a100", "b1", "e1"});
}

TEST_CASE("outgoing queue: put back in front, bounded", "[mqtt]") {
    OutgoingQueue q(2);
    q.push(msg(Kind::event, "e", "e2"));
    q.push_front(msg(Kind::event, "e", "e1"));
    CHECK(q.push_front(msg(Kind::event, "e", "e0")) == 1);
    CHECK(q.size() == 2);
}

TEST_CASE("the rate-limit key of an MQTT request", "[mqtt]") {
    gimbald::mqtt::Incoming in;
    CHECK(gimbald::mqtt::request_source(in) == "mqtt");
    in.response_topic = "replies/op1";
    CHECK(gimbald::mqtt::request_source(in) == "mqtt:replies/op1");
    in.client_id = "op-7";
    CHECK(gimbald::mqtt::request_source(in) == "mqtt:op-7");
}

TEST_CASE("config mqtt: defaults", "[mqtt][config]") {
    const auto r = parse_config(
        R"({"gimbals":[{"name":"a","protocol":"orion","link":{"type":"sim"}}],"mqtt":{}})");
    REQUIRE(r.ok());
    REQUIRE(r.config.mqtt.has_value());
    const auto& m = *r.config.mqtt;
    CHECK(m.host == "127.0.0.1");
    CHECK(m.port == 1883);
    CHECK_FALSE(m.tls);
    CHECK(!m.station.empty());
    CHECK(m.client_id == "gimbald-" + m.station);
    CHECK(m.prefix == "gimbald");
    CHECK(m.keepalive_s == 10);
    CHECK(m.state_rate_hz == 2);
    CHECK(m.queue_max == 1000);
    CHECK_FALSE(m.commands);
    CHECK_FALSE(m.state_keys.has_value());
    const auto none =
        parse_config(R"({"gimbals":[{"name":"a","protocol":"orion","link":{"type":"sim"}}]})");
    CHECK_FALSE(none.config.mqtt.has_value());
}

TEST_CASE("config mqtt: every problem with its path", "[mqtt][config]") {
    CHECK(problems_of(R"({"url":"http://x"})") ==
          std::vector<std::string>{"mqtt.url: must be mqtt://HOST[:PORT] or mqtts://HOST[:PORT]"});
    CHECK(problems_of(R"({"station":"A B"})") ==
          std::vector<std::string>{"mqtt.station: must match [a-z0-9_-]{1,32}"});
    CHECK(problems_of(R"({"state_rate_hz":0.05})") ==
          std::vector<std::string>{"mqtt.state_rate_hz: must be between 0.1 and 50"});
    CHECK(problems_of(R"({"prefix":"a/+/b"})").size() == 1);
    CHECK(problems_of(R"({"state_keys":["telemetry","nope"]})").size() == 1);
    CHECK(problems_of(R"({"qos":1})") == std::vector<std::string>{"mqtt.qos: unknown key"});
    CHECK(problems_of(R"({"url":"mqtt://h","ca_file":"/etc/hostname"})") ==
          std::vector<std::string>{"mqtt.url: ca_file/cert_file are set: use mqtts:// for TLS"});
    CHECK(problems_of(R"({"url":"mqtts://h","ca_file":"/nonexistent/ca"})") ==
          std::vector<std::string>{"mqtt.ca_file: /nonexistent/ca: No such file or directory"});
    CHECK(problems_of(R"({"url":"mqtts://h","cert_file":"/etc/hostname"})").size() == 1);
}

TEST_CASE("config mqtt: the password file must be private", "[mqtt][config]") {
    const std::string loose = temp_file("pw\n", 0644);
    const std::string tight = temp_file("s3cret\n", 0600);
    auto p = problems_of(R"({"username":"op","password_file":")" + loose + "\"}");
    REQUIRE(p.size() == 1);
    CHECK(p[0].find("mqtt.password_file: ") == 0);
    CHECK(p[0].find("0644") != std::string::npos);
    CHECK(problems_of(R"({"password_file":")" + tight + "\"}") ==
          std::vector<std::string>{"mqtt.password_file: needs \"username\""});
    const auto r = parse_config(
        R"({"gimbals":[{"name":"a","protocol":"orion","link":{"type":"sim"}}],"mqtt":{"username":"op","password_file":")" +
        tight + "\"}}");
    REQUIRE(r.ok());
    CHECK(r.config.mqtt->password == "s3cret");
    // The password never appears in the printed configuration.
    CHECK(to_json(r.config).dump().find("s3cret") == std::string::npos);
    std::remove(loose.c_str());
    std::remove(tight.c_str());
}
