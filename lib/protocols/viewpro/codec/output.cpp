#include "protocols/viewpro/codec/output.hpp"

#include <algorithm>

#include "protocols/viewpro/codec/checksum.hpp"
#include "protocols/viewpro/codec/le.hpp"

namespace gimbal::viewpro {

namespace {

constexpr double e7 = 1e7;
constexpr double e3 = 1e3;
constexpr int out4_year_base = 2000;

using Bytes = std::span<const std::uint8_t>;
using MutBytes = std::span<std::uint8_t>;

double value_or_zero(const std::optional<double>& v) {
    return v.value_or(0.0);
}

// --- decoding -----------------------------------------------------------------------------

DateTime get_time(Bytes f, std::uint16_t year) {
    return DateTime{year, f[4], f[5], f[6], f[7], f[8]};
}
double rad_f32(Bytes f, std::size_t at) {
    return le::get<float>(f, at) * le::rad2deg;
}
double rad_f64(Bytes f, std::size_t at) {
    return le::get<double>(f, at) * le::rad2deg;
}
double deg_e7(Bytes f, std::size_t at) {
    return le::get<std::int32_t>(f, at) / e7;
}
double deg_e3(Bytes f, std::size_t at) {
    return le::get<std::int32_t>(f, at) / e3;
}
double mm(Bytes f, std::size_t at) {
    return le::get<std::int32_t>(f, at) / e3;
}

void decode_out1(Bytes f, Output& o) {
    o.gimbal_pitch_deg = le::get<float>(f, 2);
    o.gimbal_yaw_deg = le::get<float>(f, 6);
    o.lrf_m = le::get<float>(f, 10);
    o.target_lon_deg = deg_e7(f, 14);  // OUT1 carries longitude first
    o.target_lat_deg = deg_e7(f, 18);
}

// OUT2 and OUT3 share bytes 2..42: time, zoom, gimbal angles, LRF, UAV attitude and altitude.
void decode_out23_common(Bytes f, Output& o) {
    o.time = get_time(f, le::get<std::uint16_t>(f, 2));
    o.zoom = le::get<std::uint16_t>(f, 9);
    o.gimbal_roll_deg = rad_f32(f, 11);
    o.gimbal_pitch_deg = rad_f32(f, 15);
    o.gimbal_yaw_deg = rad_f32(f, 19);
    o.lrf_m = le::get<float>(f, 23);
    o.uav_roll_deg = rad_f32(f, 27);
    o.uav_pitch_deg = rad_f32(f, 31);
    o.uav_yaw_deg = rad_f32(f, 35);
    o.uav_alt_msl_m = mm(f, 39);
}

void decode_out2(Bytes f, Output& o) {
    decode_out23_common(f, o);
    o.uav_lat_deg = rad_f64(f, 43);
    o.uav_lon_deg = rad_f64(f, 51);
    o.target_lat_deg = rad_f64(f, 59);
    o.target_lon_deg = rad_f64(f, 67);
}

void decode_lat_lon_e7(Bytes f, Output& o) {
    o.uav_lat_deg = deg_e7(f, 43);
    o.uav_lon_deg = deg_e7(f, 47);
    o.target_lat_deg = deg_e7(f, 51);
    o.target_lon_deg = deg_e7(f, 55);
}

void decode_out3(Bytes f, Output& o) {
    decode_out23_common(f, o);
    decode_lat_lon_e7(f, o);
}

void decode_out4(Bytes f, Output& o) {
    o.time = get_time(f, static_cast<std::uint16_t>(out4_year_base + f[2]));
    o.zoom = le::get<std::uint16_t>(f, 9);
    o.gimbal_roll_deg = deg_e3(f, 11);
    o.gimbal_pitch_deg = deg_e3(f, 15);
    o.gimbal_yaw_deg = deg_e3(f, 19);
    o.lrf_m = le::get<std::uint32_t>(f, 23) / e3;
    o.target_alt_msl_m = mm(f, 27);
    o.uav_pitch_deg = deg_e3(f, 31);
    o.uav_yaw_deg = deg_e3(f, 35);
    o.uav_alt_msl_m = mm(f, 39);
    decode_lat_lon_e7(f, o);
}

// --- encoding -----------------------------------------------------------------------------

void put_month_to_second(MutBytes f, const DateTime& t) {
    f[4] = t.month;
    f[5] = t.day;
    f[6] = t.hour;
    f[7] = t.minute;
    f[8] = t.second;
}
void put_rad_f32(MutBytes f, std::size_t at, const std::optional<double>& deg) {
    le::put(f, at, static_cast<float>(value_or_zero(deg) * le::deg2rad));
}
void put_rad_f64(MutBytes f, std::size_t at, const std::optional<double>& deg) {
    le::put(f, at, value_or_zero(deg) * le::deg2rad);
}
void put_e(MutBytes f, std::size_t at, const std::optional<double>& v, double scale) {
    le::put(f, at, le::scaled<std::int32_t>(value_or_zero(v), scale));
}

void encode_out1(const Output& o, MutBytes f) {
    le::put(f, 2, static_cast<float>(value_or_zero(o.gimbal_pitch_deg)));
    le::put(f, 6, static_cast<float>(value_or_zero(o.gimbal_yaw_deg)));
    le::put(f, 10, static_cast<float>(value_or_zero(o.lrf_m)));
    put_e(f, 14, o.target_lon_deg, e7);
    put_e(f, 18, o.target_lat_deg, e7);
}

void encode_out23_common(const Output& o, MutBytes f) {
    const DateTime t = o.time.value_or(DateTime{});
    le::put(f, 2, t.year);
    put_month_to_second(f, t);
    le::put(f, 9, o.zoom.value_or(0));
    put_rad_f32(f, 11, o.gimbal_roll_deg);
    put_rad_f32(f, 15, o.gimbal_pitch_deg);
    put_rad_f32(f, 19, o.gimbal_yaw_deg);
    le::put(f, 23, static_cast<float>(value_or_zero(o.lrf_m)));
    put_rad_f32(f, 27, o.uav_roll_deg);
    put_rad_f32(f, 31, o.uav_pitch_deg);
    put_rad_f32(f, 35, o.uav_yaw_deg);
    put_e(f, 39, o.uav_alt_msl_m, e3);
}

void encode_lat_lon_e7(const Output& o, MutBytes f) {
    put_e(f, 43, o.uav_lat_deg, e7);
    put_e(f, 47, o.uav_lon_deg, e7);
    put_e(f, 51, o.target_lat_deg, e7);
    put_e(f, 55, o.target_lon_deg, e7);
}

void encode_out2(const Output& o, MutBytes f) {
    encode_out23_common(o, f);
    put_rad_f64(f, 43, o.uav_lat_deg);
    put_rad_f64(f, 51, o.uav_lon_deg);
    put_rad_f64(f, 59, o.target_lat_deg);
    put_rad_f64(f, 67, o.target_lon_deg);
}

void encode_out3(const Output& o, MutBytes f) {
    encode_out23_common(o, f);
    encode_lat_lon_e7(o, f);
}

void encode_out4(const Output& o, MutBytes f) {
    const DateTime t = o.time.value_or(DateTime{});
    f[2] = static_cast<std::uint8_t>(std::clamp(int{t.year} - out4_year_base, 0, 255));
    f[3] = out4_flag;
    put_month_to_second(f, t);
    le::put(f, 9, o.zoom.value_or(0));
    put_e(f, 11, o.gimbal_roll_deg, e3);
    put_e(f, 15, o.gimbal_pitch_deg, e3);
    put_e(f, 19, o.gimbal_yaw_deg, e3);
    le::put(f, 23, le::scaled<std::uint32_t>(value_or_zero(o.lrf_m), e3));
    put_e(f, 27, o.target_alt_msl_m, e3);
    put_e(f, 31, o.uav_pitch_deg, e3);
    put_e(f, 35, o.uav_yaw_deg, e3);
    put_e(f, 39, o.uav_alt_msl_m, e3);
    encode_lat_lon_e7(o, f);
}

}  // namespace

std::uint8_t output_id(OutFormat f) {
    switch (f) {
        case OutFormat::out1:
            return out1_id;
        case OutFormat::out2:
            return out2_id;
        case OutFormat::out3:
        case OutFormat::out4:
            return out3_id;
    }
    return out1_id;
}

std::size_t output_size(OutFormat f) {
    switch (f) {
        case OutFormat::out1:
            return out1_size;
        case OutFormat::out2:
            return out2_size;
        case OutFormat::out3:
            return out3_size;
        case OutFormat::out4:
            return out4_size;
    }
    return out1_size;
}

std::optional<Output> decode_output(const OutputFrame& frame) {
    const Bytes f = frame.view();
    if (f.size() != output_size(frame.format) || f[0] != output_header ||
        f[1] != output_id(frame.format) || !checksum_ok(f))
        return std::nullopt;
    const bool flagged = f[3] == out4_flag;
    if (frame.format == OutFormat::out3 && flagged) return std::nullopt;
    if (frame.format == OutFormat::out4 && !flagged) return std::nullopt;
    Output o;
    o.format = frame.format;
    switch (frame.format) {
        case OutFormat::out1:
            decode_out1(f, o);
            break;
        case OutFormat::out2:
            decode_out2(f, o);
            break;
        case OutFormat::out3:
            decode_out3(f, o);
            break;
        case OutFormat::out4:
            decode_out4(f, o);
            break;
    }
    return o;
}

std::vector<std::uint8_t> encode_output(const Output& o) {
    std::vector<std::uint8_t> bytes(output_size(o.format), 0);
    const MutBytes f{bytes};
    f[0] = output_header;
    f[1] = output_id(o.format);
    switch (o.format) {
        case OutFormat::out1:
            encode_out1(o, f);
            break;
        case OutFormat::out2:
            encode_out2(o, f);
            break;
        case OutFormat::out3:
            encode_out3(o, f);
            break;
        case OutFormat::out4:
            encode_out4(o, f);
            break;
    }
    f.back() = sum8(f.first(f.size() - 1));
    return bytes;
}

}  // namespace gimbal::viewpro
