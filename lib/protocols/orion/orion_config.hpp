// An Orion gimbal's own configuration keys (contract section 3): `feed` {autopilot, gps}, how
// the vehicle feed reaches it - OrionAutopilotData at 1 Hz, GPS_DATA at 4 Hz. Declared once
// here; daemon/config.cpp reads and writes it through the registry (orion_entry.cpp).
#pragma once

#include "config/fields.hpp"

namespace gimbal::protocols {

struct OrionConfig {
    bool feed_autopilot = true;
    bool feed_gps = false;
    bool operator==(const OrionConfig&) const = default;
};

template <class V>
void fields(V& v, OrionConfig& c) {
    v.section("feed", [&](auto& feed) {
        feed.boolean("autopilot", c.feed_autopilot);
        feed.boolean("gps", c.feed_gps);
    });
}

}  // namespace gimbal::protocols
