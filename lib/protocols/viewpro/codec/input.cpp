#include "protocols/viewpro/codec/input.hpp"

#include <algorithm>

#include "protocols/viewpro/codec/checksum.hpp"
#include "protocols/viewpro/codec/le.hpp"

namespace gimbal::viewpro {

namespace {

constexpr double e7 = 1e7;
constexpr double e3 = 1e3;
constexpr double cm_per_m = 100.0;
constexpr int in3_year_base = 2000;

// Bytes 4..8 of every IN frame: month, day, hour, minute, second.
void put_month_to_second(std::span<std::uint8_t> f, const DateTime& t) {
    f[4] = t.month;
    f[5] = t.day;
    f[6] = t.hour;
    f[7] = t.minute;
    f[8] = t.second;
}

DateTime get_time(std::span<const std::uint8_t> f, std::uint16_t year) {
    return DateTime{year, f[4], f[5], f[6], f[7], f[8]};
}

// Bytes 21..32: lat, lon (degE7), alt (mm).
void put_position(std::span<std::uint8_t> f, double lat, double lon, double alt_m) {
    le::put(f, 21, le::scaled<std::int32_t>(lat, e7));
    le::put(f, 25, le::scaled<std::int32_t>(lon, e7));
    le::put(f, 29, le::scaled<std::int32_t>(alt_m, e3));
}

// Bytes 33..38: vx, vy, vz (cm/s).
void put_velocity(std::span<std::uint8_t> f, const std::array<double, 3>& v) {
    for (std::size_t k = 0; k < 3; ++k)
        le::put(f, 33 + 2 * k, le::scaled<std::int16_t>(v[k], cm_per_m));
}

std::array<double, 3> get_velocity(std::span<const std::uint8_t> f) {
    std::array<double, 3> v{};
    for (std::size_t k = 0; k < 3; ++k) v[k] = le::get<std::int16_t>(f, 33 + 2 * k) / cm_per_m;
    return v;
}

void seal(std::span<std::uint8_t> f) {
    f.back() = sum8(f.first(f.size() - 1));
}

}  // namespace

std::vector<std::uint8_t> encode_vehicle(const VehicleInput& v) {
    const bool in2 = v.vel_ned_mps.has_value();
    std::vector<std::uint8_t> bytes(in2 ? in2_size : in1_size, 0);
    const std::span<std::uint8_t> f{bytes};
    f[0] = input_header;
    f[1] = in2 ? in2_id : in1_id;
    le::put(f, 2, v.time.year);
    put_month_to_second(f, v.time);
    le::put(f, 9, static_cast<float>(v.roll_deg * le::deg2rad));
    le::put(f, 13, static_cast<float>(v.pitch_deg * le::deg2rad));
    le::put(f, 17, static_cast<float>(v.yaw_deg * le::deg2rad));
    put_position(f, v.lat_deg, v.lon_deg, v.alt_msl_m);
    if (in2) put_velocity(f, *v.vel_ned_mps);
    seal(f);
    return bytes;
}

std::array<std::uint8_t, in3_size> encode_in3(const In3& v) {
    std::array<std::uint8_t, in3_size> bytes{};
    const std::span<std::uint8_t> f{bytes};
    f[0] = input_header;
    f[1] = in2_id;
    f[2] = static_cast<std::uint8_t>(std::clamp(int{v.time.year} - in3_year_base, 0, 255));
    f[3] = in3_flag;
    put_month_to_second(f, v.time);
    le::put(f, 9, le::scaled<std::uint32_t>(v.lrf_m, e3));
    le::put(f, 13, le::scaled<std::int32_t>(v.pitch_deg, e3));
    le::put(f, 17, le::scaled<std::int32_t>(v.yaw_deg, e3));
    put_position(f, v.lat_deg, v.lon_deg, v.alt_msl_m);
    put_velocity(f, v.vel_ned_mps);
    seal(f);
    return bytes;
}

std::string_view to_string(InputFrame::Kind k) {
    switch (k) {
        case InputFrame::Kind::mode:
            return "mode";
        case InputFrame::Kind::yaw_shift:
            return "yaw_shift";
        case InputFrame::Kind::pitch_shift:
            return "pitch_shift";
        case InputFrame::Kind::in1:
            return "in1";
        case InputFrame::Kind::in2:
            return "in2";
        case InputFrame::Kind::in3:
            return "in3";
    }
    return "unknown";
}

std::optional<VehicleInput> decode_vehicle(const InputFrame& frame) {
    const bool in2 = frame.kind == InputFrame::Kind::in2;
    if (!in2 && frame.kind != InputFrame::Kind::in1) return std::nullopt;
    if (frame.size != (in2 ? in2_size : in1_size)) return std::nullopt;
    const auto f = frame.view();
    VehicleInput v;
    v.time = get_time(f, le::get<std::uint16_t>(f, 2));
    v.roll_deg = le::get<float>(f, 9) * le::rad2deg;
    v.pitch_deg = le::get<float>(f, 13) * le::rad2deg;
    v.yaw_deg = le::get<float>(f, 17) * le::rad2deg;
    v.lat_deg = le::get<std::int32_t>(f, 21) / e7;
    v.lon_deg = le::get<std::int32_t>(f, 25) / e7;
    v.alt_msl_m = le::get<std::int32_t>(f, 29) / e3;
    if (in2) v.vel_ned_mps = get_velocity(f);
    return v;
}

std::optional<In3> decode_in3(const InputFrame& frame) {
    if (frame.kind != InputFrame::Kind::in3 || frame.size != in3_size) return std::nullopt;
    const auto f = frame.view();
    In3 v;
    v.time = get_time(f, static_cast<std::uint16_t>(in3_year_base + f[2]));
    v.lrf_m = le::get<std::uint32_t>(f, 9) / e3;
    v.pitch_deg = le::get<std::int32_t>(f, 13) / e3;
    v.yaw_deg = le::get<std::int32_t>(f, 17) / e3;
    v.lat_deg = le::get<std::int32_t>(f, 21) / e7;
    v.lon_deg = le::get<std::int32_t>(f, 25) / e7;
    v.alt_msl_m = le::get<std::int32_t>(f, 29) / e3;
    v.vel_ned_mps = get_velocity(f);
    return v;
}

std::optional<Mode> decode_mode(const InputFrame& frame) {
    if (frame.kind != InputFrame::Kind::mode || frame.size != command_size) return std::nullopt;
    return decode_mode_byte(frame.bytes[3]);
}

std::optional<std::int8_t> decode_shift(const InputFrame& frame) {
    if ((frame.kind != InputFrame::Kind::yaw_shift &&
         frame.kind != InputFrame::Kind::pitch_shift) ||
        frame.size != command_size)
        return std::nullopt;
    return static_cast<std::int8_t>(frame.bytes[3]);
}

}  // namespace gimbal::viewpro
