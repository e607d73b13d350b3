// Declares the command-line arguments of one sub-command together with the JSON key each one
// becomes, so a sub-command reads like the parameter table of the interface contract.
//
// Sending rule: a parameter is put into the request when it was given on the command line;
// parameters declared with `always` (the laser's enable/arm/fire, ...) are always sent, so
// the daemon never has to guess them. Left-out optional parameters take the daemon's default.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "json_types.hpp"

namespace gimbalctl {

class Params {
  public:
    // `app` must outlive this object; create it with std::make_shared so the storage that
    // CLI11 writes into never moves.
    explicit Params(CLI::App* app) : app_(app) {}
    Params(const Params&) = delete;
    Params& operator=(const Params&) = delete;

    // A decimal number, sent as an integer when typed as one ("300") else as a double.
    // `names` is a CLI11 name list: "LAT" for a positional, "--focus" for an option.
    CLI::Option* number(const std::string& names, const std::string& key,
                        const std::string& description);
    // A whole number (indices, milliseconds, counts): "1.5" is a usage error.
    CLI::Option* integer(const std::string& names, const std::string& key,
                         const std::string& description);
    // Exactly `count` numbers sent as a JSON array, e.g. --vel-ned N E D.
    CLI::Option* numbers(const std::string& names, const std::string& key, std::size_t count,
                         const std::string& description);
    CLI::Option* text(const std::string& names, const std::string& key,
                      const std::string& description);
    // A comma-separated list of names sent as a JSON array of strings (--keys a,b).
    CLI::Option* names(const std::string& names, const std::string& key,
                       const std::string& description);
    // A boolean flag; "--x,!--no-x" gives a pair. Sent only when given, unless `always`
    // (then a flag left out is sent as false).
    CLI::Option* flag(const std::string& names, const std::string& key,
                      const std::string& description, bool always = false);
    // Anything else: `value` is called when `option` was given (or always when `always`).
    void custom(const std::string& key, CLI::Option* option, std::function<Json()> value,
                bool always = false);
    // Runs before the request is built; throw CLI::ValidationError to reject the arguments.
    void check(std::function<void()> check) { checks_.push_back(std::move(check)); }

    CLI::App* app() const { return app_; }

    // The parameters object, in declaration order.
    Json json() const;

  private:
    struct Entry {
        std::string key;
        CLI::Option* option;
        std::function<Json()> value;
        bool always;
    };

    CLI::App* app_;
    std::vector<Entry> entries_;
    std::vector<std::function<void()>> checks_;
    // Storage CLI11 writes into; deques keep element addresses stable.
    std::deque<std::string> strings_;
    std::deque<std::vector<std::string>> string_lists_;
    std::deque<std::int64_t> integers_;
    std::deque<bool> bools_;
};

}  // namespace gimbalctl
