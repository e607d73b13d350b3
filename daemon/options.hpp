// gimbald's command line (interface contract section 2), parsed with CLI11, and the steps
// that turn it into the configuration a run uses: the file or the built-in --sim gimbals,
// then the command-line overrides. --check-config is implemented here end to end.
#pragma once

#include <iosfwd>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "config.hpp"
#include "logging.hpp"

namespace gimbal::daemon {

inline constexpr std::string_view default_config_path = "/etc/gimbald/gimbald.json";

// Process exit codes (contract section 2).
enum ExitCode : int {
    exit_ok = 0,               // clean stop (SIGTERM/SIGINT), valid configuration
    exit_config_error = 1,     // bad configuration file or command line
    exit_runtime_failure = 2,  // e.g. the command port cannot be bound
};

struct Options {
    std::string config_path{default_config_path};
    bool config_given = false;  // -c/--config was on the command line
    bool sim = false;
    std::vector<Protocol> sim_protocols;  // empty for `--sim` alone (one gimbal "sim")
    bool check_config = false;
    std::optional<log::Level> log_level;
    std::optional<log::Format> log_format;
};

struct CommandLine {
    Options options;
    // Set when the process should exit now with this code: --help and --version (0, their
    // text already written to `out`), a usage error (1, reported on `err`).
    std::optional<int> exit_code;
};

CommandLine parse_command_line(int argc, const char* const* argv, std::ostream& out,
                               std::ostream& err);

// "a,b" (registry names) -> {a, b}; empty text -> {}. Unknown or repeated names: nullopt
// and a message in `error`.
std::optional<std::vector<Protocol>> parse_sim_protocols(std::string_view list, std::string& error);

// The configuration for a run: the file (not read under --sim unless -c was given), its
// gimbals replaced by the simulated ones under --sim, then --log-level and --log-format.
// Never throws and opens no device.
ConfigResult resolve_config(const Options& options);

// Where the configuration came from, for messages: the file path, or "built-in --sim".
std::string config_source(const Options& options);

// --check-config: resolves the configuration, prints every problem to `err` (one per line,
// "FILE: PATH: MESSAGE") or a one-line summary to `out`; returns exit_ok or exit_config_error.
int check_config(const Options& options, std::ostream& out, std::ostream& err);

}  // namespace gimbal::daemon
