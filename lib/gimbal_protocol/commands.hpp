// MAVLink command or message -> the gimbald requests it means (contract section 8), or the
// MAV_RESULT that answers it without touching a gimbal. Pure: the gimbal STATE and the
// vehicle's heading and home altitude are passed in. Never produces a `laser` request.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "command/result.hpp"
#include "gimbal_protocol/control.hpp"
#include "mavlink/messages.hpp"
#include "session/capabilities.hpp"
#include "session/gimbal_view.hpp"

namespace gimbal::gimbal_protocol {

// A gimbal as MAVLink sees it: gimbal_device_id 1..6 in configuration order, and its own
// gimbal manager component (contract section 14: MAVSDK and QGroundControl keep one gimbal
// per manager component).
struct ExposedGimbal {
    std::string name;
    std::string protocol;  // a protocol registry entry's name (protocols/registry.hpp)
    std::uint8_t device_id = 0;
    std::uint8_t component_id = 154;
    // Its MAVLink camera component (100..105, camera.hpp), 0 for none. A ground station must
    // list each camera once (contract v4): the manager then leaves CAMERA_INFORMATION to it.
    std::uint8_t camera_component = 0;

    // What the gimbal can do, from its protocol's registry entry: the mapping asks these, never
    // the protocol's name. nullopt for a name the registry does not know (every action is then
    // unsupported). The actions themselves are its capabilities' (StateLookup).
    std::optional<session::Features> features() const;
};

// MAV_COMP_ID_GIMBAL2..6: the components of the second and later gimbals.
inline constexpr std::uint8_t first_extra_component = 171;
inline constexpr std::uint8_t last_extra_component = 175;

// At most six gimbals are exposed (gimbal_device_id 1..6 means "non-MAVLink gimbal n"). The
// first answers as `first_component`, the next ones as 171..175 (skipping `first_component`;
// 154 takes the place it leaves when it is one of them).
std::vector<ExposedGimbal> expose(const std::vector<std::pair<std::string, std::string>>& gimbals,
                                  std::uint8_t first_component = 154);

// What the vehicle feed knows: heading from ATTITUDE/GLOBAL_POSITION_INT, home MSL from
// GLOBAL_POSITION_INT (alt - relative_alt).
struct VehicleView {
    std::optional<double> heading_deg;
    std::optional<double> home_msl_m;
};

// A COMMAND_LONG or COMMAND_INT, seen the same way. For COMMAND_LONG, param5/6 are x/y as
// floats and frame is GLOBAL_RELATIVE_ALT (the contract: "COMMAND_LONG = above home").
struct CommandView {
    std::uint16_t command = 0;
    std::array<float, 4> param{};  // param1..param4
    double x = 0, y = 0;           // param5, param6 (COMMAND_INT: degrees from degE7)
    float z = 0;                   // param7
    std::uint8_t frame = mavlink::mav_frame::global_relative_alt;
    bool is_int = false;
    bool x_unset = false, y_unset = false;  // COMMAND_INT INT32_MAX
    std::uint8_t target_system = 0, target_component = 0;
};
CommandView view(const mavlink::CommandLong& c);
CommandView view(const mavlink::CommandInt& c);

struct GimbalRequest {
    std::string gimbal;
    nlohmann::json request;  // a gimbald request object for RequestPath::execute
};

// A message to send, and the component (the gimbal's manager) it comes from.
struct Reply {
    std::uint8_t component_id = 0;
    mavlink::Payload payload;
};

// The outcome of one command or message. When `requests` is empty, `result` is the answer;
// else the answer comes from executing them (see combine()). `replies`: messages to send
// after the COMMAND_ACK (REQUEST_MESSAGE).
struct Mapped {
    mavlink::MavResult result = mavlink::MavResult::accepted;
    std::vector<GimbalRequest> requests;
    std::vector<Reply> replies;
    std::string reason;  // why, for a result other than accepted
};

// A gimbal's typed state - its capabilities bound to it, telemetry, health, video - asked
// only when a mapping needs it. A view with no capabilities: no such gimbal.
using StateLookup = std::function<session::GimbalView(const std::string& gimbal)>;

class GimbalManager {
  public:
    explicit GimbalManager(std::vector<ExposedGimbal> gimbals);

    // COMMAND_LONG / COMMAND_INT addressed to us. Its target component sets the scope: one
    // gimbal's manager component (its gimbal only), or 0 (every gimbal); a gimbal device id in
    // the parameters selects within that scope (0: all of it).
    Mapped command(const CommandView& cmd, const MavId& sender, const VehicleView& vehicle,
                   const StateLookup& state, std::uint32_t time_boot_ms);
    // GIMBAL_MANAGER_SET_PITCHYAW, GIMBAL_MANAGER_SET_ATTITUDE, GIMBAL_DEVICE_SET_ATTITUDE,
    // scoped by their target component the same way.
    Mapped message(const mavlink::Payload& payload, const MavId& sender, const VehicleView& vehicle,
                   const StateLookup& state);

    const std::vector<ExposedGimbal>& gimbals() const { return gimbals_; }
    // Is `component` one of our gimbal manager components?
    bool owns(std::uint8_t component) const;
    // The components, in configuration order.
    std::vector<std::uint8_t> components() const;
    const Control& control(std::uint8_t device_id) const { return controls_.at(device_id); }
    std::uint64_t denied() const { return denied_; }

  private:
    // The gimbals a device id selects among those `component` manages (0: every gimbal);
    // device id 0 selects all of them. Empty for an id outside that scope, with the reason.
    struct Selection {
        std::vector<const ExposedGimbal*> gimbals;
        std::string refusal;  // why it is empty
    };
    Selection select(float device_id_param, std::uint8_t component) const;
    Selection select(std::uint8_t device_id, std::uint8_t component) const;
    Mapped pitchyaw(const std::vector<const ExposedGimbal*>& targets, const MavId& sender,
                    double pitch_deg, double yaw_deg, double pitch_rate, double yaw_rate,
                    std::uint32_t flags, const VehicleView& vehicle, const StateLookup& state);
    Mapped roi_location(const CommandView& cmd, const MavId& sender, const VehicleView& vehicle,
                        const StateLookup& state);
    Mapped roi_none(const CommandView& cmd, const MavId& sender, const StateLookup& state);
    Mapped configure(const CommandView& cmd, const MavId& sender);
    Mapped zoom(const CommandView& cmd, const StateLookup& state);
    Mapped request_message(const CommandView& cmd, const StateLookup& state,
                           std::uint32_t time_boot_ms);
    // DENIED for a sender that is not in control of every target.
    std::optional<Mapped> check_control(const std::vector<const ExposedGimbal*>& targets,
                                        const MavId& sender);

    std::vector<ExposedGimbal> gimbals_;
    std::map<std::uint8_t, Control> controls_;
    std::uint64_t denied_ = 0;
};

// gimbald reply error code -> MAV_RESULT: link_down, unavailable and rate_limited
// TEMPORARILY_REJECTED, unsupported UNSUPPORTED, out_of_range / bad_request / forbidden DENIED,
// others FAILED.
mavlink::MavResult result_for_error(command::ErrorCode code);
// The same for a code's wire spelling ("link_down"); FAILED for a name that is no code.
mavlink::MavResult result_for_error(std::string_view code);
// The answer for several gimbals (device id 0): ACCEPTED when any accepted, else the first.
mavlink::MavResult combine(const std::vector<mavlink::MavResult>& results);
// "MAV_RESULT_DENIED" etc. (common.xml's names), for logs.
std::string_view to_string(mavlink::MavResult result);

}  // namespace gimbal::gimbal_protocol
