// The command line, --check-config end to end (and that it opens no device), the --sim
// configuration, and the systemd notifications over a real notify socket.
#include <catch2/catch.hpp>

#include <sys/inotify.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "options.hpp"
#include "terrain/geotiff_writer.hpp"

using namespace gimbal::daemon;
using nlohmann::json;

namespace {

const std::string source_dir = GIMBAL_SOURCE_DIR;
const std::string example_config = source_dir + "/config/gimbald.json";

struct Parsed {
    CommandLine command_line;
    std::string out;
    std::string err;
};

Parsed parse(std::initializer_list<const char*> args) {
    std::vector<const char*> argv{"gimbald"};
    argv.insert(argv.end(), args.begin(), args.end());
    std::ostringstream out;
    std::ostringstream err;
    Parsed parsed{parse_command_line(static_cast<int>(argv.size()), argv.data(), out, err), {}, {}};
    parsed.out = out.str();
    parsed.err = err.str();
    return parsed;
}

struct TempDir {
    std::filesystem::path path;
    TempDir() {
        std::string pattern =
            (std::filesystem::temp_directory_path() / "gimbald-opt-XXXXXX").string();
        REQUIRE(mkdtemp(pattern.data()) != nullptr);
        path = pattern;
    }
    ~TempDir() {
        std::error_code ignored;
        std::filesystem::remove_all(path, ignored);
    }
    std::string write(const std::string& name, const std::string& text) const {
        std::ofstream(path / name) << text;
        return (path / name).string();
    }
};

struct CheckRun {
    int code;
    std::string out;
    std::string err;
};

CheckRun run_check(const Options& options) {
    std::ostringstream out;
    std::ostringstream err;
    const int code = check_config(options, out, err);
    return {code, out.str(), err.str()};
}

// Sets an environment variable for one scope.
}  // namespace

TEST_CASE("command line defaults", "[options]") {
    const auto parsed = parse({});
    REQUIRE_FALSE(parsed.command_line.exit_code);
    const Options& o = parsed.command_line.options;
    CHECK(o.config_path == "/etc/gimbald/gimbald.json");
    CHECK_FALSE(o.config_given);
    CHECK_FALSE(o.sim);
    CHECK_FALSE(o.check_config);
    CHECK_FALSE(o.log_level);
    CHECK_FALSE(o.log_format);
}

TEST_CASE("command line options", "[options]") {
    SECTION("-c and --config") {
        auto p = parse({"-c", "/tmp/a.json"});
        CHECK(p.command_line.options.config_path == "/tmp/a.json");
        CHECK(p.command_line.options.config_given);
        p = parse({"--config=/tmp/b.json"});
        CHECK(p.command_line.options.config_path == "/tmp/b.json");
    }
    SECTION("--sim alone") {
        const auto p = parse({"--sim"});
        REQUIRE_FALSE(p.command_line.exit_code);
        CHECK(p.command_line.options.sim);
        CHECK(p.command_line.options.sim_protocols.empty());
    }
    SECTION("--sim with protocols, before another option") {
        const auto p = parse({"--sim", "orion,viewpro", "-c", "x.json"});
        REQUIRE_FALSE(p.command_line.exit_code);
        CHECK(p.command_line.options.sim_protocols ==
              std::vector<Protocol>{Protocol::orion, Protocol::viewpro});
        CHECK(p.command_line.options.config_path == "x.json");
    }
    SECTION("--sim followed by an option takes no value") {
        const auto p = parse({"--sim", "--check-config"});
        REQUIRE_FALSE(p.command_line.exit_code);
        CHECK(p.command_line.options.sim_protocols.empty());
        CHECK(p.command_line.options.check_config);
    }
    SECTION("--sim=viewpro") {
        const auto p = parse({"--sim=viewpro"});
        CHECK(p.command_line.options.sim_protocols == std::vector<Protocol>{Protocol::viewpro});
    }
    SECTION("bad --sim lists are usage errors") {
        auto p = parse({"--sim", "orion,gopro"});
        CHECK(p.command_line.exit_code == exit_config_error);
        CHECK(p.err ==
              "gimbald: --sim: unknown protocol \"gopro\" (expected orion, viewpro, mavlink, "
              "siyi)\n");
        p = parse({"--sim", "orion,orion"});
        CHECK(p.command_line.exit_code == exit_config_error);
        CHECK(p.err == "gimbald: --sim: protocol \"orion\" listed twice\n");
        p = parse({"--sim", "orion,"});
        CHECK(p.command_line.exit_code == exit_config_error);
    }
    SECTION("log overrides") {
        const auto p = parse({"--log-level", "debug", "--log-format", "text"});
        CHECK(p.command_line.options.log_level == gimbal::log::Level::debug);
        CHECK(p.command_line.options.log_format == gimbal::log::Format::text);
    }
    SECTION("bad values and unknown options exit 1 with a message") {
        for (auto args : {std::initializer_list<const char*>{"--log-level", "loud"},
                          std::initializer_list<const char*>{"--log-format", "xml"},
                          std::initializer_list<const char*>{"--frobnicate"},
                          std::initializer_list<const char*>{"-c"}}) {
            const auto p = parse(args);
            CHECK(p.command_line.exit_code == exit_config_error);
            CHECK_THAT(p.err, Catch::StartsWith("gimbald: "));
            CHECK_THAT(p.err, Catch::Contains("--help"));
            CHECK(p.out.empty());
        }
    }
    SECTION("--version") {
        const auto p = parse({"--version"});
        CHECK(p.command_line.exit_code == exit_ok);
        CHECK(p.out == std::string("gimbald ") + GIMBALD_VERSION + "\n");
    }
}

TEST_CASE("help output reads like a man page", "[options]") {
    const auto p = parse({"--help"});
    CHECK(p.command_line.exit_code == exit_ok);
    const std::string& help = p.out;
    CHECK_THAT(help,
               Catch::StartsWith("NAME\n  gimbald - ground-control daemon for camera gimbals"));
    // Wrapped text, read with the line breaks undone.
    std::string flat;
    for (char c : help) {
        const bool space = c == ' ' || c == '\n';
        if (!(space && !flat.empty() && flat.back() == ' ')) flat += space ? ' ' : c;
    }
    for (const char* text :
         {"SYNOPSIS",
          "DESCRIPTION",
          "OPTIONS",
          "-c, --config FILE",
          "--sim [PROTOCOLS]",
          "--check-config",
          "--log-level LEVEL",
          "--log-format FORMAT",
          "--version",
          "--help",
          "Default: /etc/gimbald/gimbald.json",
          "\"sim-orion\", \"sim-viewpro\", \"sim-mavlink\", \"sim-siyi\". Default:",
          "Reads every key file and opens every terrain file, no device. "
          "Default: off.",
          "gimbal-replay(1), gimbal-export(1)",
          "Default: the file's (info)",
          "Default: the file's (json)",
          "EXAMPLES",
          "EXIT STATUS",
          "SIGNALS",
          "SIGHUP",
          "SIGTERM",
          "NOTIFY_SOCKET",
          "2 runtime failure"}) {
        INFO(text);
        CHECK_THAT(flat, Catch::Contains(text));
    }
    // The footer comes after the options, and every line fits a terminal.
    CHECK(help.find("EXAMPLES") > help.find("--log-format"));
    std::istringstream lines(help);
    for (std::string line; std::getline(lines, line);) {
        INFO(line);
        CHECK(line.size() <= 80);
    }
}

// The example configuration with its terrain section naming a DEM written here (the example
// names /var/lib/gimbald/dem/*.tif, which --check-config opens).
std::string example_with_dem(const TempDir& dir) {
    const auto dem = (dir.path / "dem.tif").string();
    const gimbal::terrain::GridSpec grid{45.69, 45.71, -121.51, -121.49, 1.0 / 3600};
    REQUIRE(
        gimbal::terrain::write_geotiff(dem, grid, [](double, double) { return 400.0; }).empty());
    std::ifstream in(example_config);
    json example = json::parse(in);
    example["terrain"]["files"] = {dem};
    return dir.write("example.json", example.dump(2));
}

TEST_CASE("check_config: accepts the example configuration", "[options]") {
    TempDir dir;
    Options options;
    options.config_path = example_with_dem(dir);
    options.config_given = true;
    const auto run = run_check(options);
    CHECK(run.code == exit_ok);
    CHECK(run.err.empty());
    CHECK(run.out == options.config_path +
                         ": OK, 2 gimbals: main (orion, tcp 192.168.1.20:8747), "
                         "nose (viewpro, serial /dev/ttyUSB0@115200); terrain: 1 file\n");
}

TEST_CASE("check_config: opens every terrain file and names the one it cannot use", "[options]") {
    TempDir dir;
    Options options;
    options.config_given = true;
    const auto check_with = [&](const json& files) {
        options.config_path = dir.write(
            "terrain.json",
            json{{"gimbals", json::array()}, {"terrain", {{"files", files}, {"geoid", "none"}}}}
                .dump());
        return run_check(options);
    };
    const auto missing = (dir.path / "missing.tif").string();
    auto run = check_with({missing});
    CHECK(run.code == exit_config_error);
    CHECK(run.out.empty());
    CHECK_THAT(run.err, Catch::Contains(options.config_path + ": terrain.files: " + missing));
    CHECK_THAT(run.err, Catch::EndsWith(": 1 problem\n"));

    const auto junk = dir.write("junk.tif", "not a raster");
    run = check_with({junk});
    CHECK(run.code == exit_config_error);
    CHECK_THAT(run.err, Catch::Contains("terrain.files: " + junk));

    run = check_with({(dir.path / "*.dt2").string()});  // a glob that matches nothing
    CHECK(run.code == exit_config_error);
    CHECK_THAT(run.err, Catch::Contains("no file matches"));

    // Key problems are reported like every section's.
    options.config_path = dir.write(
        "keys.json",
        R"({"gimbals": [], "terrain": {"files": [], "geoid": "egm2008", "cache_mb": 0}})");
    run = run_check(options);
    CHECK(run.code == exit_config_error);
    CHECK_THAT(run.err, Catch::Contains("terrain.files: must be a non-empty array"));
    CHECK_THAT(run.err, Catch::Contains("terrain.geoid: must be one of \"egm96\", \"none\""));
    CHECK_THAT(run.err, Catch::Contains("terrain.cache_mb: must be between 1 and 65536"));
}

TEST_CASE("check_config: prints every problem with its path and exits 1", "[options]") {
    TempDir dir;
    const std::string path = dir.write("bad.json", R"({
      "gimbals": [{"name": "main", "protocol": "orion",
                   "link": {"type": "serial", "device": "/dev/ttyUSB0", "baud": 115201}}],
      "laser": {"fire_timeout_s": 0, "alow_fire": true}
    })");
    Options options;
    options.config_path = path;
    options.config_given = true;
    const auto run = run_check(options);
    CHECK(run.code == exit_config_error);
    CHECK(run.out.empty());
    std::vector<std::string> lines;
    std::istringstream in(run.err);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    REQUIRE(lines.size() == 4);
    CHECK_THAT(lines[0], Catch::StartsWith(path + ": gimbals[0].link.baud: must be one of 1200, "));
    CHECK(lines[1] == path + ": laser.fire_timeout_s: must be between 0.1 and 3600");
    CHECK(lines[2] == path + ": laser.alow_fire: unknown key (did you mean \"allow_fire\"?)");
    CHECK(lines[3] == path + ": 3 problems");

    SECTION("a missing file") {
        options.config_path = (dir.path / "none.json").string();
        const auto missing = run_check(options);
        CHECK(missing.code == exit_config_error);
        CHECK_THAT(missing.err, Catch::Contains("No such file or directory"));
    }
    SECTION("a syntax error") {
        options.config_path = dir.write("syntax.json", "{\n  \"laser\": {,}\n}");
        const auto broken = run_check(options);
        CHECK(broken.code == exit_config_error);
        CHECK_THAT(broken.err, Catch::StartsWith(options.config_path + ": line 2, column 13: "));
    }
}

TEST_CASE("check_config: opens no device", "[options]") {
    TempDir dir;
    // A stand-in for a serial device; inotify reports any open() of it.
    const std::string device = dir.write("ttyFAKE0", "");
    const std::string path = dir.write(
        "serial.json",
        json{{"gimbals",
              {{{"name", "nose"},
                {"protocol", "viewpro"},
                {"link", {{"type", "serial"}, {"device", device}, {"baud", 115200}}}}}},
             {"vehicle",
              {{"source", {{"type", "serial"}, {"device", device + "x"}, {"baud", 57600}}}}}}
            .dump());

    const int watch_fd = inotify_init1(IN_NONBLOCK | IN_CLOEXEC);
    REQUIRE(watch_fd >= 0);
    REQUIRE(inotify_add_watch(watch_fd, device.c_str(), IN_OPEN | IN_ACCESS) >= 0);

    Options options;
    options.config_path = path;
    options.config_given = true;
    const auto run = run_check(options);
    CHECK(run.code == exit_ok);

    char buffer[4096];
    const auto n = read(watch_fd, buffer, sizeof buffer);
    CHECK(n < 0);  // no event: nothing opened the device
    CHECK(errno == EAGAIN);

    // The watch itself works: opening the file is seen.
    std::ifstream opened(device);
    CHECK(read(watch_fd, buffer, sizeof buffer) > 0);
    close(watch_fd);
}

TEST_CASE("the configuration of a run: file, --sim and overrides", "[options]") {
    TempDir dir;
    const std::string path = dir.write("site.json", R"({
      "gimbals": [{"name": "main", "protocol": "orion",
                   "link": {"type": "tcp", "host": "10.0.0.9", "port": 8747, "nonsense": 1}}],
      "command": {"port": 9123},
      "log": {"level": "warn"}
    })");

    SECTION("--sim alone reads no file") {
        Options options;
        options.sim = true;
        options.config_path = (dir.path / "does-not-exist.json").string();
        const auto result = resolve_config(options);
        REQUIRE(result.ok());
        REQUIRE(result.config.gimbals.size() == 1);
        CHECK(result.config.gimbals[0].name == "sim");
        CHECK(result.config.command == CommandConfig{});
        CHECK(config_source(options) == "built-in --sim");
        CHECK(run_check(options).out == "built-in --sim: OK, 1 gimbal: sim (orion, sim)\n");
    }
    SECTION("--sim with a file keeps its other sections and replaces its gimbals") {
        Options options;
        options.sim = true;
        options.sim_protocols = {Protocol::orion, Protocol::viewpro};
        options.config_path = path;
        options.config_given = true;
        const auto result = resolve_config(options);
        REQUIRE(result.ok());  // the file's broken gimbal is not read
        REQUIRE(result.config.gimbals.size() == 2);
        CHECK(result.config.gimbals[0].name == "sim-orion");
        CHECK(result.config.gimbals[1].name == "sim-viewpro");
        CHECK(result.config.command.port == 9123);
        CHECK(result.config.log.level == gimbal::log::Level::warn);
    }
    SECTION("without --sim the same file is invalid") {
        Options options;
        options.config_path = path;
        const auto result = resolve_config(options);
        REQUIRE(result.problems.size() == 1);
        CHECK(result.problems[0].text() == "gimbals[0].link.nonsense: unknown key");
    }
    SECTION("--log-level and --log-format override the file") {
        Options options;
        options.sim = true;
        options.config_path = path;
        options.config_given = true;
        options.log_level = gimbal::log::Level::trace;
        options.log_format = gimbal::log::Format::text;
        const auto result = resolve_config(options);
        CHECK(result.config.log.level == gimbal::log::Level::trace);
        CHECK(result.config.log.format == gimbal::log::Format::text);
    }
}
