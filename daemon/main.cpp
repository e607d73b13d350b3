// gimbald: ground-control daemon for camera gimbals. See `gimbald --help` and docs/.
#include <malloc.h>

#include <boost/system/system_error.hpp>
#include <cstdlib>
#include <exception>
#include <iostream>

#include "app.hpp"
#include "config.hpp"
#include "logging.hpp"
#include "options.hpp"
#include "terrain_model.hpp"

int main(int argc, char** argv) {
    namespace cfg = gimbal::daemon;
    namespace log = gimbal::log;
    // Blocks of 1 MiB and more are mapped and unmapped on their own, always: glibc would
    // otherwise raise this threshold after the first such block is freed and keep later ones
    // in its arenas, so a peer that made gimbald buffer megabytes once (a hostile camera's
    // endless frame, a large KLV set) would leave its RSS up for good (contract section 14 v4).
    mallopt(M_MMAP_THRESHOLD, 1 << 20);

    const auto cli = cfg::parse_command_line(argc, argv, std::cout, std::cerr);
    if (cli.exit_code) return *cli.exit_code;
    const auto& options = cli.options;
    if (options.check_config) return cfg::check_config(options, std::cout, std::cerr);

    const auto resolved = cfg::resolve_config(options);
    if (!resolved.ok()) {
        for (const auto& p : resolved.problems)
            std::cerr << "gimbald: " << cfg::config_source(options) << ": " << p.text() << "\n";
        return cfg::exit_config_error;
    }
    const auto& config = resolved.config;
    // Terrain files are configuration: one that cannot be used is exit 1, naming it.
    auto terrain = cfg::open_terrain(config);
    if (terrain.problem) {
        std::cerr << "gimbald: " << cfg::config_source(options) << ": " << terrain.problem->text()
                  << "\n";
        return cfg::exit_config_error;
    }
    try {
        log::configure(config.log.settings());
    } catch (const std::exception& e) {
        std::cerr << "gimbald: " << e.what() << "\n";
        return cfg::exit_config_error;
    }
    log::info("config", "configuration loaded",
              {{"source", cfg::config_source(options)}, {"config", cfg::to_json(config)}});

    try {
        int code = 0;
        {
            gimbald::App app(config, std::move(terrain.model));
            code = app.run();
        }
        // Every log line is written and flushed as it is made; nothing else is left to do.
        if (gimbald::App::left_a_terrain_read_running()) std::_Exit(code);
        return code;
    } catch (const cfg::ConfigError& e) {
        // Found only now (a key file changed since --check-config): still exit 1.
        std::cerr << "gimbald: " << cfg::config_source(options) << ": " << e.what() << "\n";
        log::error("config_error", e.what());
        return cfg::exit_config_error;
    } catch (const boost::system::system_error& e) {
        log::error("runtime_failure", e.what(), {{"code", e.code().value()}});
        return cfg::exit_runtime_failure;
    } catch (const std::exception& e) {
        log::error("runtime_failure", e.what());
        return cfg::exit_runtime_failure;
    }
}
