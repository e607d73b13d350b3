#include "klv/sensor_set.hpp"

#include <algorithm>
#include <cmath>

namespace gimbal::klv {

double wrap360(double deg) {
    double d = std::fmod(deg, 360.0);
    if (d < 0) d += 360.0;
    return d >= 360.0 ? 0.0 : d;  // -1e-17 + 360 rounds to 360
}

namespace {

bool finite(const std::optional<double>& x) {
    return x && std::isfinite(*x);
}

}  // namespace

LocalSet sensor_set(const SensorFrame& f) {
    LocalSet set;
    // A value that is not a number is unknown: its item is left out, never refused.
    const auto add = [&set](std::uint32_t tag, const std::optional<double>& x) {
        if (finite(x)) set.add(tag, *x);
    };
    set.add(tag_of("precision_time_stamp"), f.time_us);
    if (f.mission_id && !f.mission_id->empty()) set.add(tag_of("mission_id"), *f.mission_id);
    const auto angle360 = [](const std::optional<double>& x) {
        return finite(x) ? std::optional<double>(wrap360(*x)) : std::nullopt;
    };
    add(tag_of("platform_heading_angle"), angle360(f.platform_heading_deg));
    add(tag_of("platform_pitch_angle"), f.platform_pitch_deg);
    add(tag_of("platform_roll_angle"), f.platform_roll_deg);
    if (finite(f.sensor_lat_deg) && finite(f.sensor_lon_deg)) {
        add(tag_of("sensor_latitude"), f.sensor_lat_deg);
        add(tag_of("sensor_longitude"), f.sensor_lon_deg);
    }
    add(tag_of("sensor_true_altitude"), f.sensor_alt_msl_m);
    add(tag_of("sensor_horizontal_field_of_view"), f.hfov_deg);
    add(tag_of("sensor_vertical_field_of_view"), f.vfov_deg);
    add(tag_of("sensor_relative_azimuth_angle"), angle360(f.relative_azimuth_deg));
    add(tag_of("sensor_relative_elevation_angle"), f.relative_elevation_deg);
    add(tag_of("sensor_relative_roll_angle"), angle360(f.relative_roll_deg));
    add(tag_of("slant_range"), f.slant_range_m);
    const auto point_ok = [](const std::optional<GroundPoint>& p) {
        return p && std::isfinite(p->lat_deg) && std::isfinite(p->lon_deg);
    };
    if (point_ok(f.frame_center)) {
        const GroundPoint& c = *f.frame_center;
        set.add(tag_of("frame_center_latitude"), c.lat_deg);
        set.add(tag_of("frame_center_longitude"), c.lon_deg);
        add(tag_of("frame_center_elevation"), c.alt_msl_m);
        const bool corners_ok =
            f.corners && std::all_of(f.corners->begin(), f.corners->end(), [](const LatLon& p) {
                return std::isfinite(p.lat) && std::isfinite(p.lon);
            });
        if (corners_ok) add_corners(set, {c.lat_deg, c.lon_deg}, *f.corners);
    }
    if (point_ok(f.target)) {
        set.add(tag_of("target_location_latitude"), f.target->lat_deg);
        set.add(tag_of("target_location_longitude"), f.target->lon_deg);
        add(tag_of("target_location_elevation"), f.target->alt_msl_m);
    }
    // Generic flags (tag 47): bit 0 laser range finder on, bit 4 slant range measured.
    std::uint64_t flags = 0;
    if (finite(f.slant_range_m) && f.slant_range_measured) flags |= 0x01 | 0x10;
    set.add(tag_of("generic_flag_data"), flags);
    // A VMTI set that cannot be written (a frame size of 0) is left out like any unknown item.
    if (f.vmti)
        if (Result<Bytes> vmti = encode_vmti(*f.vmti); vmti.ok())
            set.add(tag_of("vmti_local_set"), std::move(vmti).value());
    set.add(tag_of("uas_datalink_ls_version_number"), std::uint64_t{st0601_version});
    return set;
}

}  // namespace gimbal::klv
