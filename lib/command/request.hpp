// A request parsed once (docs/architecture.md "A request parsed once"). A transport's bytes
// meet the request limits and are parsed ONCE into a JSON object (parse_object, the one
// place a request is parsed); its envelope is read here - the command from the catalogue,
// the id, gimbal and token - and its parameters by the command's planner through JsonParams
// (params.hpp), which takes every type, range, choice, length and count from the catalogue:
// ranges live in the catalogue and nowhere else. Whether a parameter is required, and rules
// across parameters ("yaw_deg and/or pitch_deg"), stay with the planner that owns them.
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

// A request's envelope and the object it was read from: the object its command's planner
// reads the parameters of (JsonParams, params.hpp).
struct Request : Envelope {
    nlohmann::json doc;
};

// The request in `bytes`: the request limits on the raw bytes (too_large, bad_json), ONE
// parse (bad_json when not a JSON object), then read_envelope.
Result<Request> parse_request(std::string_view bytes);

}  // namespace gimbal::command
