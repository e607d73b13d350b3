// What every gimbal session obeys (contract section 3): `laser` (firing allowed, the fire
// timeout, the safety bypass), `stare` (answering StareStart itself) and `telemetry` (when a
// gimbal is stale). Declared once here and read and written by the generic reader
// (lib/config/fields.hpp); the daemon hands them to sessions through SessionSettings.
#pragma once

#include "config/fields.hpp"

namespace gimbal::daemon {

struct LaserConfig {
    bool allow_fire = false;
    double fire_timeout_s = 5.0;
    bool allow_safety_bypass = false;
    bool operator==(const LaserConfig&) const = default;
};

struct StareConfig {
    bool auto_ack = false;
    bool operator==(const StareConfig&) const = default;
};

struct TelemetryConfig {
    double stale_after_s = 1.0;
    bool operator==(const TelemetryConfig&) const = default;
};

template <class V>
void fields(V& v, LaserConfig& c) {
    v.boolean("allow_fire", c.allow_fire);
    v.number("fire_timeout_s", c.fire_timeout_s, {0.1, 3600});
    v.boolean("allow_safety_bypass", c.allow_safety_bypass);
}

template <class V>
void fields(V& v, StareConfig& c) {
    v.boolean("auto_ack", c.auto_ack);
}

template <class V>
void fields(V& v, TelemetryConfig& c) {
    v.number("stale_after_s", c.stale_after_s, {0.1, 60});
}

}  // namespace gimbal::daemon
