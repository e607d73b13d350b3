// The lasers of the simulated gimbal and their interlocks: a laser only fires when it is
// enabled and armed in the same command, and when a password is configured every change
// needs it (a wrong one changes nothing and sets the password lock). The autopilot interlocks
// (altitude, comm, flying; set from OrionAutopilotData) refuse and stop fire unless the
// command bypasses the safety checks.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "protocols/orion/codec/enums.hpp"

namespace gimbal::sim {

struct LaserUnit {
    orion::LaserType type = orion::LaserType::none;
    bool enabled = false;
    bool armed = false;
    bool active = false;  // firing
    bool password_lock = false;
    bool bypass = false;  // the last command bypassed the safety checks
    bool altitude_lock = false;
    bool ap_comm_lock = false;
    bool ap_flying_lock = false;
    std::uint16_t on_time_ms = 0;
    std::uint16_t off_time_ms = 0;
    std::uint16_t prf_code = 0;
};

struct LaserRequest {
    std::uint8_t index = 0;
    std::string password;
    bool enable = false;
    bool arm = false;
    bool fire = false;
    std::uint16_t on_time_ms = 0;
    std::uint16_t off_time_ms = 0;
    std::uint16_t prf_code = 0;
    bool safety_bypass = false;
};

enum class LaserResult {
    applied,       // every requested state was applied
    fire_refused,  // enable/arm applied, fire refused (needs enable and arm)
    arm_refused,   // enable applied, arm refused (needs enable)
    wrong_password,
    no_such_laser,
};

// What the autopilot data says forbids fire (each one a LaserStates lock bit).
struct LaserInterlocks {
    bool altitude = false;   // AGL below the minimum, or unknown
    bool ap_comm = false;    // CommGood 0
    bool ap_flying = false;  // IsFlying 0
    bool any() const { return altitude || ap_comm || ap_flying; }
};

class LaserBank {
  public:
    LaserBank(std::vector<orion::LaserType> types, std::string password);

    LaserResult command(const LaserRequest& request);
    // New autopilot interlocks: shown by every laser; a laser firing without bypass stops.
    void set_interlocks(const LaserInterlocks& locks);
    const std::vector<LaserUnit>& units() const { return units_; }

  private:
    std::vector<LaserUnit> units_;
    std::string password_;
    LaserInterlocks locks_;
};

}  // namespace gimbal::sim
