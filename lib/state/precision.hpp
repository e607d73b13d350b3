// Contract section 1, number precision of derived values: 1e-7 degree for latitude and
// longitude, 1e-4 degree for other angles, 1e-3 m for lengths (and 1e-3 s for ages).
#pragma once

#include <cmath>

namespace gimbal::state {

// `v` rounded to `decimals` decimals, as the double nearest that short decimal (so it prints
// as it). Non-finite values pass through.
inline double round_decimals(double v, int decimals) {
    if (!std::isfinite(v)) return v;
    double scale = 1.0;
    for (int i = 0; i < decimals; ++i) scale *= 10.0;
    return std::round(v * scale) / scale;
}

inline double latlon_deg(double v) {
    return round_decimals(v, 7);
}
inline double angle_deg(double v) {
    return round_decimals(v, 4);
}
inline double metres(double v) {
    return round_decimals(v, 3);
}
inline double seconds(double v) {
    return round_decimals(v, 3);
}

}  // namespace gimbal::state
