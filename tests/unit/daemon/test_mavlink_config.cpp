// The `mavlink` configuration section (contract section 8) and the signing key file.
#include <catch2/catch.hpp>

#include <sys/stat.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "config.hpp"
#include "mavlink_endpoint.hpp"
#include "signing_state.hpp"

using namespace gimbal::daemon;
using nlohmann::json;

namespace {

json base() {
    return {{"gimbals",
             {{{"name", "main"},
               {"protocol", "orion"},
               {"link", {{"type", "tcp"}, {"host", "127.0.0.1"}, {"port", 8747}}}}}},
            {"vehicle", json::object()}};
}

std::vector<std::string> problems(const json& config) {
    std::vector<std::string> out;
    for (const auto& p : parse_config(config.dump()).problems) out.push_back(p.text());
    return out;
}

}  // namespace

TEST_CASE("mavlink section: defaults and every key", "[config]") {
    auto r = parse_config(base().dump());
    REQUIRE(r.ok());
    CHECK_FALSE(r.config.mavlink.gimbal_manager);
    CHECK(r.config.mavlink.component_id == 154);
    CHECK_FALSE(r.config.mavlink.system_id);

    json c = base();
    CHECK(r.config.mavlink.commands);
    CHECK_FALSE(r.config.mavlink.home_alt_msl);
    CHECK_FALSE(r.config.mavlink.signing_state_file);
    // The key file is read by the check (contract section 14, v4): a real one.
    const auto key_file =
        std::filesystem::temp_directory_path() / ("gimbald-mavkey-" + std::to_string(::getpid()));
    std::ofstream(key_file) << std::string(64, 'b') << "\n";
    ::chmod(key_file.c_str(), 0600);
    c["mavlink"] = {{"gimbal_manager", true},
                    {"system_id", 7},
                    {"component_id", 171},
                    {"targets", {"127.0.0.1:14550", "gcs.local:14551"}},
                    {"signing_key_file", key_file.string()},
                    {"commands", false},
                    {"home_alt_msl", 412.5},
                    {"signing_state_file", "/var/lib/gimbald/signing.json"}};
    r = parse_config(c.dump());
    INFO(problems(c).size());
    REQUIRE(r.ok());
    CHECK(r.config.mavlink.gimbal_manager);
    CHECK(r.config.mavlink.system_id == 7);
    CHECK(r.config.mavlink.component_id == 171);
    CHECK(r.config.mavlink.targets.size() == 2);
    CHECK(r.config.mavlink.signing_key_file == key_file.string());
    CHECK_FALSE(r.config.mavlink.commands);
    CHECK(r.config.mavlink.home_alt_msl == 412.5);
    CHECK(r.config.mavlink.signing_state_file == "/var/lib/gimbald/signing.json");
    CHECK(to_json(r.config)["mavlink"] == c["mavlink"]);
    std::filesystem::remove(key_file);
}

TEST_CASE("mavlink.signing_key_file is checked with the configuration", "[config]") {
    // Issue 25: a malformed or 0644 key passed --check-config, then gimbald exited 2 at start.
    const auto dir = std::filesystem::temp_directory_path();
    const auto write = [&](const std::string& name, const std::string& text, mode_t mode) {
        const auto path = dir / ("gimbald-mavkey-" + std::to_string(::getpid()) + "-" + name);
        std::ofstream(path) << text;
        ::chmod(path.c_str(), mode);
        return path;
    };
    const auto good = write("good", std::string(64, 'c'), 0600);
    const auto shortkey = write("short", "abcd\n", 0600);
    const auto open = write("open", std::string(64, 'c'), 0644);
    const auto check = [&](const std::string& key_file) {
        json c = base();
        c["mavlink"] = {{"gimbal_manager", false}, {"signing_key_file", key_file}};
        return problems(c);
    };
    CHECK(check(good.string()).empty());
    const auto short_problems = check(shortkey.string());
    REQUIRE(short_problems.size() == 1);
    CHECK(short_problems[0] == "mavlink.signing_key_file: " + shortkey.string() +
                                   ": must hold 32 bytes, or 64 hex digits");
    const auto open_problems = check(open.string());
    REQUIRE(open_problems.size() == 1);
    CHECK(open_problems[0].find("readable by group or others (mode 0644)") != std::string::npos);
    const auto missing = check((dir / "gimbald-no-such.key").string());
    REQUIRE(missing.size() == 1);
    CHECK(missing[0].rfind("mavlink.signing_key_file: ", 0) == 0);
    for (const auto& p : {good, shortkey, open}) std::filesystem::remove(p);
}

TEST_CASE("mavlink section: problems with their paths", "[config]") {
    json c = base();
    c["mavlink"] = {{"targets", {"nohost", "h:0", "h:99999", 5, "127.0.0.1:14550"}},
                    {"component_id", 0},
                    {"system_id", 256},
                    {"signing_key_file", ""},
                    {"signing_state_file", 3},
                    {"commands", "yes"},
                    {"home_alt_msl", 20000},
                    {"bogus", 1}};
    const auto p = problems(c);
    const auto has = [&](const std::string& prefix) {
        return std::any_of(p.begin(), p.end(),
                           [&](const std::string& t) { return t.rfind(prefix, 0) == 0; });
    };
    CHECK(has("mavlink.targets[0]"));
    CHECK(has("mavlink.targets[1]"));
    CHECK(has("mavlink.targets[2]"));
    CHECK(has("mavlink.targets[3]"));
    CHECK_FALSE(has("mavlink.targets[4]"));
    CHECK(has("mavlink.component_id"));
    CHECK(has("mavlink.system_id"));
    CHECK(has("mavlink.signing_key_file"));
    CHECK(has("mavlink.signing_state_file"));
    CHECK(has("mavlink.commands"));
    CHECK(has("mavlink.home_alt_msl"));
    CHECK(has("mavlink.bogus"));

    json no_vehicle = base();
    no_vehicle.erase("vehicle");
    no_vehicle["mavlink"] = {{"gimbal_manager", true}};
    CHECK(problems(no_vehicle) ==
          std::vector<std::string>{"mavlink.gimbal_manager: needs a vehicle section: the gimbal "
                                   "manager talks on vehicle.source"});
}

TEST_CASE("command.auth signed covers MAVLink: a signing key, or commands off", "[config]") {
    const auto key_file =
        std::filesystem::temp_directory_path() / ("gimbald-opskey-" + std::to_string(::getpid()));
    std::ofstream(key_file) << std::string(64, 'a') << "\n";
    ::chmod(key_file.c_str(), 0600);
    json c = base();
    c["command"] = {
        {"auth", "signed"},
        {"keys", {{{"id", "ops"}, {"secret_file", key_file.string()}, {"roles", {"control"}}}}}};
    c["mavlink"] = {{"gimbal_manager", true}};
    const auto p = problems(c);
    REQUIRE(p.size() == 1);
    CHECK(p[0].rfind("mavlink.signing_key_file: command.auth is \"signed\"", 0) == 0);
    CHECK(p[0].find("mavlink.commands") != std::string::npos);
    c["mavlink"]["commands"] = false;
    CHECK(problems(c).empty());
    c["mavlink"]["commands"] = true;
    c["mavlink"]["signing_key_file"] = key_file.string();  // 64 hex digits: a MAVLink key too
    CHECK(problems(c).empty());
    c["mavlink"] = {{"gimbal_manager", false}};
    CHECK(problems(c).empty());
    std::filesystem::remove(key_file);
}

TEST_CASE("MAVLink signing state: where it is kept, and the file round trip", "[config]") {
    using gimbald::signing_state_path;
    CHECK(signing_state_path(std::string("/x/s.json"), "/var/lib/gimbald") == "/x/s.json");
    CHECK(signing_state_path(std::nullopt, "/var/lib/gimbald:/var/lib/gimbald/recordings") ==
          "/var/lib/gimbald/mavlink-signing.json");
    CHECK_FALSE(signing_state_path(std::nullopt, nullptr));
    CHECK_FALSE(signing_state_path(std::nullopt, ""));

    const auto dir = std::filesystem::temp_directory_path() /
                     ("gimbald-signstate-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const auto path = (dir / "mavlink-signing.json").string();
    CHECK(gimbald::load_signing_state(path).streams.empty());  // the first start
    gimbald::SigningState state;
    state.local_timestamp = 123456789012ull;
    state.streams = {{255, 190, 0, 123456789000ull}, {1, 1, 2, 5}};
    CHECK(gimbald::save_signing_state(path, state).empty());
    CHECK((std::filesystem::status(path).permissions() & std::filesystem::perms::others_read) ==
          std::filesystem::perms::none);
    const auto back = gimbald::load_signing_state(path);
    CHECK(back.local_timestamp == state.local_timestamp);
    CHECK(back.streams == state.streams);
    std::ofstream(path) << "{\"streams\": [{\"sysid\": 300}]}";
    CHECK_THROWS_WITH(gimbald::load_signing_state(path),
                      Catch::Contains(path) && Catch::Contains("sysid"));
    std::ofstream(path) << "not json";
    CHECK_THROWS(gimbald::load_signing_state(path));
    CHECK_FALSE(gimbald::save_signing_state((dir / "no" / "such.json").string(), state).empty());
    std::filesystem::remove_all(dir);
}

TEST_CASE("MAVLink signing key file: 32 raw bytes or 64 hex digits, private", "[config]") {
    const auto dir =
        std::filesystem::temp_directory_path() / ("gimbald-mavkey-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const auto write = [&](const std::string& name, const std::string& text, mode_t mode) {
        const auto path = (dir / name).string();
        std::ofstream(path, std::ios::binary) << text;
        ::chmod(path.c_str(), mode);
        return path;
    };
    std::string raw(32, '\0');
    for (std::size_t i = 0; i < raw.size(); ++i) raw[i] = static_cast<char>(i * 3);
    const auto k1 = gimbald::load_signing_key(write("raw", raw, 0600));
    CHECK(k1[1] == 3);
    CHECK(k1[31] == 93);
    std::string hex;
    for (int i = 0; i < 32; ++i) hex += "a5";
    const auto k2 = gimbald::load_signing_key(write("hex", "  " + hex + "\n", 0600));
    CHECK(k2[0] == 0xA5);
    CHECK(k2[31] == 0xA5);
    CHECK_THROWS(gimbald::load_signing_key(write("short", "abcd", 0600)));
    CHECK_THROWS(gimbald::load_signing_key(write("open", hex, 0644)));  // readable by others
    CHECK_THROWS(gimbald::load_signing_key((dir / "missing").string()));
    std::filesystem::remove_all(dir);
}
