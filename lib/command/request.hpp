// A request parsed once (docs/architecture.md "A request parsed once"). A transport's bytes
// meet the request limits and are parsed ONCE into a JSON object (parse_object, the one
// place a request is parsed); the object is read once into a typed Request: the command
// from the catalogue, the envelope's id, gimbal and token, and the parameters checked
// against the catalogue's ParamSpecs - types, ranges, choices, counts, required ones,
// unknown ones refused, each with the contract's message naming the key. Ranges live in the
// catalogue and nowhere else: planners read values without ranges. Rules across parameters
// ("yaw_deg and/or pitch_deg") stay with the planner that owns them.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "command/catalogue.hpp"
#include "result/result.hpp"

namespace gimbal::command {

// Keys every request may carry that are not parameters: cmd, id, gimbal, token, and a signed
// payload's ts and nonce.
bool is_envelope_key(std::string_view key);

// The one place a request's bytes are parsed: the JSON object they hold, or nullopt when
// they are not a JSON object. The bytes must have passed check_request_limits
// (request_limits.hpp). Every call is counted (request_parses()).
std::optional<nlohmann::json> parse_object(std::string_view bytes);
// How many times parse_object() has parsed since the process started: tests prove one
// parse per request on every transport with it.
std::uint64_t request_parses();

// What a reply echoes of a request, whatever else is wrong with it: `id` when present, `cmd`
// when a string.
struct Echo {
    std::optional<nlohmann::json> id;
    std::optional<std::string> cmd;
};
Echo echo_of(const nlohmann::json& doc);

// One point of a `points` parameter: degrees, and metres above the WGS84 ellipsoid (absent
// where the daemon's terrain gives it).
struct Point {
    double lat = 0;
    double lon = 0;
    std::optional<double> alt;
};

// A command's parameters, every one checked against its ParamSpec. Getters take no range:
// the catalogue's held. An absent optional parameter reads as nullopt (or the fallback);
// naming a parameter the command does not declare is a bug (std::logic_error, which the
// request path answers `internal`).
class Params {
  public:
    Params() = default;

    const CommandSpec* command() const { return spec_; }
    bool has(std::string_view key) const;

    std::optional<double> number(std::string_view key) const;
    double number_or(std::string_view key, double fallback) const {
        return number(key).value_or(fallback);
    }
    std::optional<std::int64_t> integer(std::string_view key) const;
    std::int64_t integer_or(std::string_view key, std::int64_t fallback) const {
        return integer(key).value_or(fallback);
    }
    std::optional<bool> boolean(std::string_view key) const;
    bool boolean_or(std::string_view key, bool fallback) const {
        return boolean(key).value_or(fallback);
    }
    std::optional<std::string> text(std::string_view key) const;    // text and choice
    std::optional<std::string> choice(std::string_view key) const;  // one of the choices
    std::optional<std::vector<double>> numbers(std::string_view key) const;
    std::optional<std::vector<Point>> points(std::string_view key) const;
    // The value as given (keys: an array of strings), nullptr when absent.
    const nlohmann::json* raw(std::string_view key) const;
    // Every parameter given, as a JSON object (envelope keys and nulls left out).
    const nlohmann::json& values() const { return values_; }

    // Gives a parameter a value (the daemon filling in what the terrain says), checked as a
    // request's own would be: a value beyond the catalogue's range is refused the same way.
    Status set(std::string_view key, nlohmann::json value);

  private:
    friend Result<Params> read_params(const CommandSpec& command, const nlohmann::json& doc);
    const ParamSpec& spec_of(std::string_view key) const;

    const CommandSpec* spec_ = nullptr;
    nlohmann::json values_ = nlohmann::json::object();
};

// The parameters of a request object (envelope keys skipped) for `command`: each of its
// ParamSpecs in the catalogue's order (the first problem wins and names the key), then any
// key it does not declare (bad_request "unknown parameter 'x'").
Result<Params> read_params(const CommandSpec& command, const nlohmann::json& doc);

// The outside of a request: a command the catalogue lists, `gimbal` and `token` strings.
struct Envelope {
    const CommandSpec* spec = nullptr;
    std::optional<nlohmann::json> id;  // echoed unchanged when given
    std::optional<std::string> gimbal;
    std::optional<std::string> token;

    std::string_view cmd() const { return spec ? spec->name : std::string_view(); }
};
// unknown_cmd (no cmd, not a string, not in the catalogue) or bad_request (gimbal or token
// not a string); echo_of(doc) gives what the refusal still echoes.
Result<Envelope> read_envelope(const nlohmann::json& doc);

struct Request : Envelope {
    Params params;
};

// read_envelope() and read_params() of a parsed request object.
Result<Request> read_request(const nlohmann::json& doc);
// The request in `bytes`: the request limits on the raw bytes (too_large, bad_json), ONE
// parse (bad_json when not a JSON object), then read_request.
Result<Request> parse_request(std::string_view bytes);
// The request as a JSON object (cmd, id, gimbal, token and the parameters given): what a
// recording shows of a request an adapter built itself.
nlohmann::json request_object(const Request& request);

// A request an adapter builds itself (MAVLink: a capability's action), through the
// catalogue's checks with no JSON text: `params` is the parameters object.
Result<Request> make_request(std::string_view cmd, nlohmann::json params,
                             std::optional<std::string> gimbal = std::nullopt);

}  // namespace gimbal::command
