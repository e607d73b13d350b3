// A protocol's simulator hook: how gimbal-sim and the daemon's `sim` link make its simulated
// gimbal, the protocol's own gimbal-sim flags, the frame shape its fault injector corrupts,
// discovery, the decoder of gimbal-sim's --rx-log and the camera the video shows. Pure.
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "framing/hex.hpp"
#include "sim/camera_view.hpp"
#include "sim/device.hpp"
#include "sim/fault_injector.hpp"

namespace gimbal::protocols {

// What every simulated gimbal is told: its clock, its seed, and the settings gimbal-sim
// shares between models, each only when given (a model keeps its own default otherwise).
struct SimScenario {
    // UTC when the model starts (the models read no clock); 2025-01-01 unless told.
    double unix_time_s = 1'735'689'600.0;
    std::uint32_t seed = 1;  // noise and faults: the same seed gives the same bytes
    std::optional<double> lat_deg, lon_deg;
    std::optional<double> alt_m;          // the aircraft's altitude (each model says which datum)
    std::optional<double> terrain_alt_m;  // flat ground (each model says which datum)
    std::optional<double> geoid_undulation_m;
    // The protocol's own flags, by key (SimFlag::key), only those given.
    nlohmann::json options = nlohmann::json::object();
};

// One of a protocol's own gimbal-sim flags.
struct SimFlag {
    enum class Type { number, integer, text, flag };  // flag: true when given
    enum class Check { none, range, non_negative, positive };
    std::string_view name;  // "--pan-rate"
    std::string_view key;   // in SimScenario::options and in defaults()
    Type type = Type::number;
    std::string_view help;
    Check check = Check::none;
    double min = 0, max = 0;  // Check::range
};

// Decodes what the controller sends the simulated gimbal, for --rx-log: one JSON object per
// valid frame (the keys after "t" and "src").
class RxDecoder {
  public:
    virtual ~RxDecoder() = default;
    virtual void push(std::span<const std::uint8_t> bytes, std::vector<nlohmann::json>& lines) = 0;
    virtual void reset() = 0;  // the sender went away: forget a partial frame
};

// Lower-case hex of `bytes` (the rx log's "hex").
inline std::string hex_text(std::span<const std::uint8_t> bytes) {
    return framing::to_hex(bytes);
}

struct Simulator {
    // gimbal-sim's manual: what the model does (DESCRIPTION) and its --rx-log lines (RX LOG),
    // as paragraphs of lines indented by 7 spaces.
    std::string_view manual;
    std::string_view rx_log_manual;
    std::unique_ptr<sim::Device> (*make)(const SimScenario& scenario) = nullptr;
    std::span<const SimFlag> flags;
    // The model's defaults of those flags, by key (shown in gimbal-sim's help).
    nlohmann::json (*defaults)() = nullptr;
    sim::FrameShape (*fault_frames)() = nullptr;
    std::unique_ptr<RxDecoder> (*make_rx_decoder)() = nullptr;
    // The gimbal's UDP broadcast discovery (as its vendor SDK does it), when the protocol has
    // one: which datagrams ask, and what gimbal-sim answers. nullptr: no discovery.
    bool (*is_discovery_request)(std::span<const std::uint8_t> datagram) = nullptr;
    std::vector<std::uint8_t> (*discovery_reply)() = nullptr;
    // What the model's camera sees at its current time (call right after advance()): the
    // simulated video and its KLV (gimbal-sim --video, gimbald's sim link with `video`) are
    // made from it. nullptr: the model has no camera.
    std::optional<sim::CameraView> (*camera)(const sim::Device& device) = nullptr;
};

}  // namespace gimbal::protocols
