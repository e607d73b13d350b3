// Golden tests for the ICD section "Packets sent regularly by the gimbal". Every golden byte
// vector is written by hand from the ICD table (offset and meaning per line); the codec must
// decode it to the ICD's physical values and encode those back to the very same bytes.
#include <catch2/catch.hpp>
#include <initializer_list>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "protocols/orion/codec/framer.hpp"
#include "protocols/orion/codec/framing.hpp"
#include "protocols/orion/codec/json.hpp"
#include "protocols/orion/codec/packets.hpp"

using namespace gimbal::orion;
using Bytes = std::vector<std::uint8_t>;
using nlohmann::json;

namespace {

constexpr double deg = pi / 180.0;

template <class P>
Bytes encoded(const P& packet) {
    Payload out;
    REQUIRE(encode(packet, out));
    return Bytes(out.bytes.begin(), out.bytes.begin() + static_cast<long>(out.size));
}

// Decodes `bytes`, which must succeed, and checks that encoding the result gives them back.
template <class P>
P decode_golden(const Bytes& bytes) {
    const auto d = decode<P>(bytes);
    INFO(to_string(d.error));
    REQUIRE(d.ok);
    CHECK(encoded(d.value) == bytes);
    return d.value;
}

Bytes prefix(const Bytes& b, std::size_t n) {
    return Bytes(b.begin(), b.begin() + static_cast<long>(n));
}

Bytes concat(Bytes a, const Bytes& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

// One byte short of the minimum is an error that names `field`.
template <class P>
void check_too_short(const Bytes& golden, const std::string& field) {
    const auto d = decode<P>(prefix(golden, P::min_length - 1));
    CHECK_FALSE(d.ok);
    CHECK(to_string(d.error).find("'" + field + "'") != std::string::npos);
}

// Unknown trailing bytes (newer firmware) are ignored.
template <class P>
void check_extra_bytes_ignored(const Bytes& golden) {
    const auto d = decode<P>(concat(golden, {0xA5, 0x5A, 0x01}));
    INFO(to_string(d.error));
    REQUIRE(d.ok);
    CHECK(encoded(d.value) == golden);
}

void check_keys(const json& j, std::set<std::string> expected) {
    std::set<std::string> got;
    for (const auto& item : j.items()) got.insert(item.key());
    CHECK(got == expected);
}

// Every value of E reaches JSON as its name and comes back from it; aliases are read too;
// a value without a name is written as its number.
template <class P, class E>
void check_enum_field(E P::*member, const std::string& key,
                      std::initializer_list<std::pair<E, const char*>> canonical,
                      std::initializer_list<std::pair<E, const char*>> aliases, E unknown) {
    CHECK(enum_names(E{}).size() == canonical.size() + aliases.size());
    for (const auto& [value, name] : canonical) {
        P p;
        p.*member = value;
        CHECK(to_json(p).at(key) == name);
    }
    for (const auto& list : {canonical, aliases}) {
        for (const auto& [value, name] : list) {
            P p;
            p.*member = unknown;
            JsonError err;
            INFO(name);
            REQUIRE(from_json(json{{key, name}}, p, err));
            CHECK(p.*member == value);
        }
    }
    P p;
    p.*member = unknown;
    CHECK(to_json(p).at(key) == static_cast<int>(unknown));
}

}  // namespace

#include "golden_telemetry.hpp"

using namespace gimbal::orion::golden_vectors;

// --- GeolocateTelemetryCore ---------------------------------------------------------------------

TEST_CASE("GeolocateTelemetry golden bytes decode to ICD values and re-encode exactly",
          "[orion][telemetry]") {
    REQUIRE(geolocate_golden.size() == GeolocateTelemetry::max_length);
    const auto t = decode_golden<GeolocateTelemetry>(geolocate_golden);
    CHECK(t.system_time_ms == 74565);
    CHECK(t.gps_itow_ms == 500000000);
    CHECK(t.gps_week == 2200);
    CHECK(t.geoid_undulation == Approx(-8192 * 120.0 / 32767.0));
    CHECK(t.lat == Approx(45.7 * deg));
    CHECK(t.lon == Approx(-121.5 * deg));
    CHECK(t.alt == Approx(1234.5678));
    CHECK(t.vel_ned[0] == Approx(12.34));
    CHECK(t.vel_ned[1] == Approx(-5.67));
    CHECK(t.vel_ned[2] == Approx(0.89));
    CHECK(t.quat[0] == Approx(16384 / 32767.0));
    CHECK(t.quat[1] == Approx(-16384 / 32767.0));
    CHECK(t.quat[2] == Approx(8192 / 32767.0));
    CHECK(t.quat[3] == Approx(1.0));
    CHECK(t.pan == Approx(16384 * pi / 32767.0));
    CHECK(t.tilt == Approx(-8192 * pi / 32767.0));
    CHECK(t.hfov == Approx(4096 * 2.0 * pi / 65535.0));
    CHECK(t.vfov == Approx(3072 * 2.0 * pi / 65535.0));
    CHECK(t.los_ecef[0] == Approx(100.0));
    CHECK(t.los_ecef[1] == Approx(-200.0));
    CHECK(t.los_ecef[2] == Approx(300.0));
    CHECK(t.pixel_width == 1920);
    CHECK(t.pixel_height == 1080);
    CHECK(t.mode == Mode::path);
    CHECK(t.path_progress == Approx(128 / 255.0));
    CHECK(t.stare_time_s == Approx(1.5));
    CHECK(t.path_from == 3);
    CHECK(t.path_to == 4);
    CHECK(t.image_shifts[0] == Approx(0.001234));
    CHECK(t.image_shifts[1] == Approx(-0.000567));
    CHECK(t.image_shift_delta_time_s == Approx(0.033));
    CHECK(t.image_shift_confidence == Approx(0.8));
    CHECK(t.output_shifts[0] == Approx(256 * pi / 32767.0));
    CHECK(t.output_shifts[1] == Approx(-256 * pi / 32767.0));
    CHECK(t.range_source == RangeSource::laser);
    CHECK(t.leap_seconds == 19);
    CHECK(t.pan_alignment == Approx(0.005));
    CHECK(t.tilt_alignment == Approx(-0.005));
    CHECK(t.ins_rotation_option == InsRotation::platform);
    CHECK(t.ins_quat[0] == Approx(1.0));
    CHECK(t.ins_quat[1] == Approx(1 / 32767.0));
    CHECK(t.ins_quat[2] == Approx(-1 / 32767.0));
    CHECK(t.ins_quat[3] == Approx(4096 / 32767.0));
}

TEST_CASE("GeolocateTelemetry length rules", "[orion][telemetry]") {
    check_too_short<GeolocateTelemetry>(geolocate_golden, "vfov");
    check_extra_bytes_ignored<GeolocateTelemetry>(geolocate_golden);

    const auto d = decode<GeolocateTelemetry>(prefix(geolocate_golden, 46));
    REQUIRE(d.ok);
    CHECK(d.value.vfov == Approx(3072 * 2.0 * pi / 65535.0));
    CHECK(d.value.los_ecef == std::array<double, 3>{0, 0, 0});
    CHECK(d.value.pixel_width == 0);
    CHECK(d.value.mode == Mode::unknown);
    CHECK(d.value.range_source == RangeSource::skylink);
    CHECK(d.value.leap_seconds == 18);
    CHECK(d.value.pan_alignment == 0.0);
    CHECK(d.value.ins_rotation_option == InsRotation::gimbal_native);
    CHECK(d.value.ins_quat == std::array<double, 4>{0, 0, 0, 0});
}

TEST_CASE("GeolocateTelemetry insQuat is present only for a non-zero insRotationOption",
          "[orion][telemetry]") {
    GeolocateTelemetry t = decode<GeolocateTelemetry>(geolocate_golden).value;
    t.ins_rotation_option = InsRotation::gimbal_native;
    const Bytes off = encoded(t);
    Bytes expected = prefix(geolocate_golden, 81);  // ends after insRotationOption
    expected[80] = 0x00;
    CHECK(off == expected);

    const auto back = decode<GeolocateTelemetry>(off);
    REQUIRE(back.ok);
    CHECK(back.value.ins_quat == std::array<double, 4>{0, 0, 0, 0});

    // Flag on, insQuat cut off: still an optional tail, so the default stays.
    Bytes cut = prefix(geolocate_golden, 81);
    const auto partial = decode<GeolocateTelemetry>(cut);
    REQUIRE(partial.ok);
    CHECK(partial.value.ins_rotation_option == InsRotation::platform);
    CHECK(partial.value.ins_quat == std::array<double, 4>{0, 0, 0, 0});

    t.ins_rotation_option = InsRotation::payload_ball;
    CHECK(encoded(t).size() == 89);
}

TEST_CASE("GeolocateTelemetry JSON keys follow the contract, angles in degrees",
          "[orion][telemetry][json]") {
    const json j = to_json(decode<GeolocateTelemetry>(geolocate_golden).value);
    for (const char* key : {"system_time_ms",
                            "gps_week",
                            "gps_itow_ms",
                            "lat",
                            "lon",
                            "alt",
                            "geoid_undulation",
                            "vel_ned",
                            "quat",
                            "pan",
                            "tilt",
                            "hfov",
                            "vfov",
                            "mode",
                            "los_ecef",
                            "range_source",
                            "path_progress",
                            "path_from",
                            "path_to",
                            "stare_time_s",
                            "pixel_width",
                            "pixel_height"}) {
        INFO(key);
        CHECK(j.contains(key));
    }
    CHECK(j["lat"].get<double>() == Approx(45.7));
    CHECK(j["lon"].get<double>() == Approx(-121.5));
    CHECK(j["pan"].get<double>() == Approx(16384 * 180.0 / 32767.0));
    CHECK(j["hfov"].get<double>() == Approx(4096 * 360.0 / 65535.0));
    CHECK(j["pan_alignment"].get<double>() == Approx(0.005 / deg));
    CHECK(j["image_shifts"][0].get<double>() == Approx(0.001234 / deg));
    CHECK(j["mode"] == "path");
    CHECK(j["range_source"] == "laser");
    CHECK(j["ins_rotation_option"] == "in_platform");
    CHECK(j["vel_ned"].size() == 3);
    CHECK(j["quat"].size() == 4);
    CHECK(j["ins_quat"].size() == 4);
}

// --- OrionPerformance, OrionDiagnostics, NetworkDiagnostics ----------------------------------

TEST_CASE("Performance golden bytes", "[orion][telemetry]") {
    REQUIRE(performance_golden.size() == Performance::max_length);
    const auto p = decode_golden<Performance>(performance_golden);
    CHECK(p.rms_quad[0] == Approx(0.000123));
    CHECK(p.rms_quad[1] == Approx(0.000456));
    CHECK(p.rms_dir[0] == Approx(0.001));
    CHECK(p.rms_dir[1] == Approx(0.002));
    CHECK(p.rms_vel[0] == Approx(1.5));
    CHECK(p.rms_vel[1] == Approx(2.25));
    CHECK(p.rms_pos[0] == Approx(0.0005));
    CHECK(p.rms_pos[1] == Approx(0.00075));
    CHECK(p.iout[0] == Approx(3.2));
    CHECK(p.iout[1] == Approx(0.8));

    check_too_short<Performance>(performance_golden, "iout");
    check_extra_bytes_ignored<Performance>(performance_golden);
    const json j = to_json(p);
    check_keys(j, {"rms_quad", "rms_dir", "rms_vel", "rms_pos", "iout"});
    CHECK(j["rms_vel"][1].get<double>() == Approx(2.25));
}

TEST_CASE("Diagnostics golden bytes", "[orion][telemetry]") {
    REQUIRE(diagnostics_golden.size() == Diagnostics::max_length);
    const auto d = decode_golden<Diagnostics>(diagnostics_golden);
    CHECK(d.voltage24 == Approx(24.123));
    CHECK(d.voltage12 == Approx(12.05));
    CHECK(d.voltage3v3 == Approx(3.301));
    CHECK(d.current24 == Approx(1.25));
    CHECK(d.current12 == Approx(0.5));
    CHECK(d.current3v3 == Approx(0.125));
    CHECK(d.crown_temp == Approx(45.0));
    CHECK(d.sla_temp == Approx(-10.0));
    CHECK(d.gyro_temp == Approx(38.0));
    CHECK(d.voltage24_var == Approx(0.00123));
    CHECK(d.voltage12_var == Approx(0.00045));
    CHECK(d.voltage3v3_var == Approx(0.00001));
    CHECK(d.current24_var == Approx(0.0002));
    CHECK(d.current12_var == Approx(0.0003));
    CHECK(d.current3v3_var == Approx(0.65535));

    check_too_short<Diagnostics>(diagnostics_golden, "current3v3_var");
    check_extra_bytes_ignored<Diagnostics>(diagnostics_golden);
    check_keys(to_json(d),
               {"voltage24", "voltage12", "voltage3v3", "current24", "current12", "current3v3",
                "crown_temp", "sla_temp", "gyro_temp", "voltage24_var", "voltage12_var",
                "voltage3v3_var", "current24_var", "current12_var", "current3v3_var"});
}

TEST_CASE("NetworkDiagnostics golden bytes", "[orion][telemetry]") {
    REQUIRE(network_golden.size() == NetworkDiagnostics::max_length);
    const auto n = decode_golden<NetworkDiagnostics>(network_golden);
    CHECK(n.flags == 0x1043);
    CHECK(n.rx_bytes == 0x01020304u);
    CHECK(n.tx_bytes == 0x05060708u);
    CHECK(n.rx_packets == 0xABCDu);
    CHECK(n.tx_packets == 0x1234u);
    CHECK(n.rx_errors == 1);
    CHECK(n.tx_errors == 2);
    CHECK(n.rx_drops == 3);
    CHECK(n.tx_drops == 4);
    CHECK(n.rx_fifo_errors == 5);
    CHECK(n.tx_fifo_errors == 6);
    CHECK(n.frame_errors == 7);
    CHECK(n.collisions == 8);
    CHECK(n.carrier_errors == 9);

    check_too_short<NetworkDiagnostics>(network_golden, "carrier_errors");
    check_extra_bytes_ignored<NetworkDiagnostics>(network_golden);
    const json j = to_json(n);
    check_keys(j, {"flags", "rx_bytes", "tx_bytes", "rx_packets", "tx_packets", "rx_errors",
                   "tx_errors", "rx_drops", "tx_drops", "rx_fifo_errors", "tx_fifo_errors",
                   "frame_errors", "collisions", "carrier_errors"});
    CHECK(j["rx_bytes"] == 0x01020304);
}

// --- OrionSoftwareDiagnostics ------------------------------------------------------------------

TEST_CASE("SoftwareDiagnostics golden bytes with nested core and thread repeats",
          "[orion][telemetry]") {
    const auto s = decode_golden<SoftwareDiagnostics>(software_golden);
    CHECK(s.source_board == Board::crown);
    REQUIRE(s.cores.size() == 2);
    const auto& c0 = s.cores[0];
    CHECK(c0.cpu_load == Approx(128 / 2.55));
    CHECK(c0.heap_load == Approx(64 / 2.55));
    CHECK(c0.stack_load == Approx(32 / 2.55));
    REQUIRE(c0.threads.size() == 2);
    CHECK(c0.threads[0].cpu_load == Approx(40.0));
    CHECK(c0.threads[0].heap_load == Approx(20.0));
    CHECK(c0.threads[0].stack_load == Approx(25 / 2.55));
    CHECK(c0.threads[0].watchdog_left == Approx(80.0));
    CHECK(c0.threads[0].num_iterations == Approx(1000.0));
    CHECK(c0.threads[0].worstcase == Approx(1.5));
    CHECK(c0.threads[1].cpu_load == Approx(1 / 2.55));
    CHECK(c0.threads[1].heap_load == Approx(2 / 2.55));
    CHECK(c0.threads[1].stack_load == Approx(3 / 2.55));
    CHECK(c0.threads[1].watchdog_left == Approx(100.0));
    CHECK(c0.threads[1].num_iterations == Approx(100.0));
    CHECK(c0.threads[1].worstcase == Approx(25.5));
    const auto& c1 = s.cores[1];
    CHECK(c1.cpu_load == Approx(20.0));
    CHECK(c1.heap_load == Approx(17 / 2.55));
    CHECK(c1.stack_load == Approx(34 / 2.55));
    REQUIRE(c1.threads.size() == 1);
    CHECK(c1.threads[0].cpu_load == Approx(5 / 2.55));
    CHECK(c1.threads[0].heap_load == Approx(6 / 2.55));
    CHECK(c1.threads[0].stack_load == Approx(7 / 2.55));
    CHECK(c1.threads[0].watchdog_left == Approx(8 / 2.55));
    CHECK(c1.threads[0].num_iterations == Approx(90.0));
    CHECK(c1.threads[0].worstcase == Approx(1.0));

    const json j = to_json(s);
    check_keys(j, {"source_board", "cores"});
    CHECK(j["source_board"] == "crown");
    check_keys(j["cores"][0], {"cpu_load", "heap_load", "stack_load", "threads"});
    check_keys(j["cores"][0]["threads"][1], {"cpu_load", "heap_load", "stack_load", "watchdog_left",
                                             "num_iterations", "worstcase"});
    CHECK(j["cores"][0]["threads"][1]["worstcase"].get<double>() == Approx(25.5));
}

TEST_CASE("SoftwareDiagnostics length rules and repeat limits", "[orion][telemetry]") {
    check_too_short<SoftwareDiagnostics>(software_golden, "reserved");
    check_extra_bytes_ignored<SoftwareDiagnostics>(software_golden);

    const Bytes no_cores{0x01, 0x00, 0x00, 0x00};  // clevis, numCores 0, reserved
    const auto d = decode<SoftwareDiagnostics>(no_cores);
    REQUIRE(d.ok);
    CHECK(d.value.source_board == Board::clevis);
    CHECK(d.value.cores.empty());

    // A count promises a core that is not there: the repeat is not optional.
    const auto missing = decode<SoftwareDiagnostics>(Bytes{0x01, 0x01, 0x00, 0x00, 0x10});
    CHECK_FALSE(missing.ok);
    CHECK(to_string(missing.error).find("'heap_load'") != std::string::npos);

    // The largest packet: 2 cores of 10 threads each is the ICD's maximum of 134 bytes.
    SoftwareDiagnostics full;
    full.cores.assign(max_software_cores, CoreLoading{});
    for (auto& core : full.cores) core.threads.assign(max_software_threads, ThreadLoading{});
    CHECK(encoded(full).size() == SoftwareDiagnostics::max_length);
    full.cores[0].threads.push_back(ThreadLoading{});
    Payload out;
    CHECK_FALSE(encode(full, out));  // 11 threads do not fit the repeat
}

// --- OrionVibration ----------------------------------------------------------------------------

TEST_CASE("Vibration golden bytes with 16 FFT points", "[orion][telemetry]") {
    REQUIRE(vibration_golden.size() == Vibration::max_length);
    const auto v = decode_golden<Vibration>(vibration_golden);
    CHECK(v.max_accel[0] == Approx(16384 * 20.0 / 32767.0));
    CHECK(v.max_accel[1] == Approx(-8192 * 20.0 / 32767.0));
    CHECK(v.max_accel[2] == Approx(20.0));
    CHECK(v.max_gyro[0] == Approx(4096 * 0.1 / 32767.0));
    CHECK(v.max_gyro[1] == Approx(-4096 * 0.1 / 32767.0));
    CHECK(v.max_gyro[2] == Approx(2048 * 0.1 / 32767.0));
    REQUIRE(v.fft_data.size() == num_fft_points);
    for (std::size_t i = 0; i < num_fft_points; ++i) {
        INFO("point " << i);
        const auto& pt = v.fft_data[i];
        const auto k = static_cast<double>(i);
        CHECK(pt.frequency == Approx((k + 1) * 256.0 * 200.0 / 65535.0));
        CHECK(pt.accel[0] == Approx((0x10 + k) / 255.0));
        CHECK(pt.accel[1] == Approx((0x20 + k) / 255.0));
        CHECK(pt.accel[2] == Approx((0x30 + k) / 255.0));
        CHECK(pt.gyro[0] == Approx((0x40 + k) / 255.0));
        CHECK(pt.gyro[1] == Approx((0x50 + k) / 255.0));
        CHECK(pt.gyro[2] == Approx((0x60 + k) / 255.0));
    }

    check_too_short<Vibration>(vibration_golden, "gyro");  // the last point's gyro array
    check_extra_bytes_ignored<Vibration>(vibration_golden);

    const json j = to_json(v);
    check_keys(j, {"max_accel", "max_gyro", "fft_data"});
    CHECK(j["max_gyro"][0].get<double>() == Approx(4096 * 0.1 / 32767.0 / deg));  // deg/s
    REQUIRE(j["fft_data"].size() == num_fft_points);
    check_keys(j["fft_data"][15], {"frequency", "accel", "gyro"});
    CHECK(j["fft_data"][15]["frequency"].get<double>() == Approx(16 * 256.0 * 200.0 / 65535.0));
}

// --- OrionRetractStatus ------------------------------------------------------------------------

TEST_CASE("RetractStatus golden bytes", "[orion][telemetry]") {
    REQUIRE(retract_golden.size() == RetractStatus::max_length);
    const auto r = decode_golden<RetractStatus>(retract_golden);
    CHECK(r.cmd == RetractCmd::deploy);
    CHECK(r.state == RetractState::deploying);
    CHECK(r.pos == Approx(1.561));
    CHECK(r.flags == 0x00A5);

    check_too_short<RetractStatus>(retract_golden, "flags");
    check_extra_bytes_ignored<RetractStatus>(retract_golden);
    const json j = to_json(r);
    check_keys(j, {"cmd", "state", "pos", "flags"});
    CHECK(j["cmd"] == "deploy");
    CHECK(j["state"] == "deploying");
    CHECK(j["pos"].get<double>() == Approx(1.561 / deg));
}

// --- StareStart --------------------------------------------------------------------------------

TEST_CASE("StareStart golden bytes", "[orion][telemetry]") {
    REQUIRE(stare_golden.size() == StareStart::max_length);
    const auto s = decode_golden<StareStart>(stare_golden);
    CHECK(s.system_time_ms == 12345678);
    CHECK(s.max_stare_time_s == Approx(1.0));
    CHECK(s.along_track_stare);
    CHECK(s.prev_stare_terminated_by_time);
    CHECK(s.stare_started_by_time);
    CHECK(s.gimbal_data_valid);
    CHECK(s.stare_reset);
    CHECK(s.prev_stare_time_s == Approx(0.75));
    CHECK(s.stare_load == Approx(0.6));
    CHECK(s.lat == Approx(45.7 * deg));
    CHECK(s.lon == Approx(-121.5 * deg));
    CHECK(s.alt == Approx(250.0));
    CHECK(s.gimbal_lat == Approx(45.69 * deg));
    CHECK(s.gimbal_lon == Approx(-121.49 * deg));
    CHECK(s.gimbal_alt == Approx(1500.0));
    CHECK(s.gimbal_quat[0] == Approx(16384 / 32767.0));
    CHECK(s.gimbal_quat[1] == Approx(-16384 / 32767.0));
    CHECK(s.gimbal_quat[2] == Approx(8192 / 32767.0));
    CHECK(s.gimbal_quat[3] == Approx(-8192 / 32767.0));
    CHECK(s.pan == Approx(8192 * pi / 32767.0));
    CHECK(s.tilt == Approx(-12288 * pi / 32767.0));
    CHECK(s.range_source == RangeSource::internal_dted);
    CHECK(s.slant_range == Approx(1234.56));
    CHECK(s.along_stare_angle == Approx(1024 * pi / 32767.0));
    CHECK(s.cross_stare_angle == Approx(-1024 * pi / 32767.0));

    const json j = to_json(s);
    check_keys(j, {"system_time_ms",
                   "max_stare_time_s",
                   "along_track_stare",
                   "prev_stare_terminated_by_time",
                   "stare_started_by_time",
                   "gimbal_data_valid",
                   "stare_reset",
                   "prev_stare_time_s",
                   "stare_load",
                   "lat",
                   "lon",
                   "alt",
                   "gimbal_lat",
                   "gimbal_lon",
                   "gimbal_alt",
                   "gimbal_quat",
                   "pan",
                   "tilt",
                   "range_source",
                   "slant_range",
                   "along_stare_angle",
                   "cross_stare_angle"});
    CHECK(j["lat"].get<double>() == Approx(45.7));
    CHECK(j["gimbal_lon"].get<double>() == Approx(-121.49));
    CHECK(j["tilt"].get<double>() == Approx(-12288 * 180.0 / 32767.0));
    CHECK(j["along_track_stare"] == true);
    CHECK(j["range_source"] == "internal_dted");
}

TEST_CASE("StareStart flags are packed MSB first in byte 5", "[orion][telemetry]") {
    StareStart s;
    s.along_track_stare = true;
    CHECK(encoded(s)[5] == 0x80);
    s = StareStart{};
    s.stare_started_by_time = true;
    CHECK(encoded(s)[5] == 0x20);
    s = StareStart{};
    s.stare_reset = true;
    CHECK(encoded(s)[5] == 0x08);

    Bytes b = stare_golden;
    b[5] = 0x48;  // prevStareTerminatedByTime and stareReset only
    const auto d = decode<StareStart>(b);
    REQUIRE(d.ok);
    CHECK_FALSE(d.value.along_track_stare);
    CHECK(d.value.prev_stare_terminated_by_time);
    CHECK_FALSE(d.value.stare_started_by_time);
    CHECK_FALSE(d.value.gimbal_data_valid);
    CHECK(d.value.stare_reset);
    CHECK(d.value.prev_stare_time_s == Approx(0.75));  // unused bits 5:2..5:0 do not shift it
}

TEST_CASE("StareStart length rules", "[orion][telemetry]") {
    check_too_short<StareStart>(stare_golden, "alt");
    check_extra_bytes_ignored<StareStart>(stare_golden);
    const auto d = decode<StareStart>(prefix(stare_golden, 20));
    REQUIRE(d.ok);
    CHECK(d.value.alt == Approx(250.0));
    CHECK(d.value.gimbal_lat == 0.0);
    CHECK(d.value.gimbal_quat == std::array<double, 4>{0, 0, 0, 0});
    CHECK(d.value.range_source == RangeSource::none);
    CHECK(d.value.slant_range == 0.0);
    CHECK(d.value.cross_stare_angle == 0.0);
}

// --- OrionResetSource --------------------------------------------------------------------------

TEST_CASE("ResetSource golden bytes and optional sourceBoard", "[orion][telemetry]") {
    REQUIRE(reset_golden.size() == ResetSource::max_length);
    const auto r = decode_golden<ResetSource>(reset_golden);
    CHECK(r.vector == 0x10u);
    CHECK(r.address == 0x0800ABCDu);
    CHECK(r.source_board == Board::payload);

    check_too_short<ResetSource>(reset_golden, "address");
    check_extra_bytes_ignored<ResetSource>(reset_golden);
    const auto d = decode<ResetSource>(prefix(reset_golden, 8));
    REQUIRE(d.ok);
    CHECK(d.value.address == 0x0800ABCDu);
    CHECK(d.value.source_board == Board::clevis);  // ICD default

    const json j = to_json(r);
    check_keys(j, {"vector", "address", "source_board"});
    CHECK(j["source_board"] == "payload");
}

// --- DebugString -------------------------------------------------------------------------------

TEST_CASE("DebugString golden bytes", "[orion][telemetry]") {
    const auto s = decode_golden<DebugString>(debug_golden);
    CHECK(s.source == Board::crown);
    CHECK(s.priority == DebugPriority::warn);
    CHECK(s.description == "Gyro temp high");

    const json j = to_json(s);
    check_keys(j, {"source", "priority", "description"});
    CHECK(j["source"] == "crown");
    CHECK(j["priority"] == "warn");
    CHECK(j["description"] == "Gyro temp high");
}

TEST_CASE("DebugString length rules", "[orion][telemetry]") {
    check_too_short<DebugString>(debug_golden, "description");
    check_extra_bytes_ignored<DebugString>(debug_golden);

    const auto empty = decode<DebugString>(Bytes{0x01, 0x04, 0x00, 0x00, 0x00});
    REQUIRE(empty.ok);
    CHECK(empty.value.source == Board::clevis);
    CHECK(empty.value.priority == DebugPriority::fatal);
    CHECK(empty.value.description.empty());

    DebugString longest;
    longest.description = std::string(200, 'x');
    const Bytes b = encoded(longest);
    CHECK(b.size() == DebugString::max_length);  // 127 characters and the terminator
    CHECK(b.back() == 0x00);
    CHECK(decode<DebugString>(b).value.description == std::string(127, 'x'));
}

// --- KlvUserData -------------------------------------------------------------------------------

TEST_CASE("KlvUserData golden bytes", "[orion][telemetry]") {
    const auto k = decode_golden<KlvUserData>(klv_golden);
    CHECK(k.key == 2);
    CHECK(k.sub_key == 1);
    CHECK(k.value == std::vector<std::uint8_t>{0xDE, 0xAD, 0xBE, 0xEF, 0x42});

    const json j = to_json(k);
    check_keys(j, {"key", "sub_key", "value"});
    CHECK(j["value"] == json::array({0xDE, 0xAD, 0xBE, 0xEF, 0x42}));
}

TEST_CASE("KlvUserData length rules", "[orion][telemetry]") {
    check_too_short<KlvUserData>(klv_golden, "length");
    check_extra_bytes_ignored<KlvUserData>(klv_golden);

    const auto d = decode<KlvUserData>(Bytes{0x41, 0x00, 0x00});  // a query: no value
    REQUIRE(d.ok);
    CHECK(d.value.key == 0x41);
    CHECK(d.value.value.empty());

    const auto cut = decode<KlvUserData>(prefix(klv_golden, 6));  // Length 5, 3 bytes present
    CHECK_FALSE(cut.ok);
    CHECK(to_string(cut.error).find("'value'") != std::string::npos);

    KlvUserData big;
    big.value.assign(max_klv_value_bytes, 0x7E);
    CHECK(encoded(big).size() == KlvUserData::max_length);
    big.value.push_back(0x7E);
    Payload out;
    CHECK_FALSE(encode(big, out));
}

TEST_CASE("KlvUserData JSON from a client round-trips and is checked", "[orion][telemetry][json]") {
    const auto golden = decode<KlvUserData>(klv_golden).value;
    KlvUserData k;
    JsonError err;
    REQUIRE(from_json(to_json(golden), k, err));
    CHECK(encoded(k) == klv_golden);

    // "length" is derived from the value; a client may send it, it is not an error.
    KlvUserData set;
    REQUIRE(from_json(json{{"key", 3}, {"length", 2}, {"value", {1, 2}}}, set, err));
    CHECK(encoded(set) == Bytes{0x03, 0x00, 0x02, 0x01, 0x02});

    KlvUserData bad;
    CHECK_FALSE(from_json(json{{"key", 3}, {"tag", 1}}, bad, err));
    CHECK(err.code == "bad_request");
    CHECK(err.message.find("tag") != std::string::npos);

    CHECK_FALSE(from_json(json{{"value", "DEADBEEF"}}, bad, err));
    CHECK(err.code == "bad_request");
    CHECK(err.message.find("value") != std::string::npos);

    CHECK_FALSE(from_json(json{{"sub_key", 256}}, bad, err));
    CHECK(err.code == "out_of_range");
    CHECK(err.message.find("sub_key") != std::string::npos);

    CHECK_FALSE(from_json(json{{"value", {1, 300}}}, bad, err));
    CHECK(err.code == "out_of_range");
    CHECK(err.message.find("value[1]") != std::string::npos);

    CHECK_FALSE(from_json(json{{"value", std::vector<int>(128, 1)}}, bad, err));
    CHECK(err.code == "out_of_range");
    CHECK(err.message.find("value") != std::string::npos);
}

// --- GpsData -----------------------------------------------------------------------------------

TEST_CASE("GpsData golden bytes with every conditional field", "[orion][telemetry]") {
    REQUIRE(gps_golden.size() == GpsData::max_length);
    const auto g = decode_golden<GpsData>(gps_golden);
    CHECK(g.multi_ant_heading_valid);
    CHECK(g.fix_type == UbloxFixType::three_d_fix);
    CHECK(g.fix_state == 0x0D);
    CHECK(g.tracked_sats == 12);
    CHECK(g.pdop == Approx(1.7));
    CHECK(g.lat == Approx(45.7 * deg));
    CHECK(g.lon == Approx(-121.5 * deg));
    CHECK(g.alt == Approx(250.0));
    CHECK(g.vel_ned[0] == Approx(1.234));
    CHECK(g.vel_ned[1] == Approx(-2.5));
    CHECK(g.vel_ned[2] == Approx(0.125));
    CHECK(g.hacc == Approx(2.5));
    CHECK(g.vacc == Approx(4.0));
    CHECK(g.speed_acc == Approx(0.3));
    CHECK(g.heading_acc == Approx(50000 / 5729578.0));
    CHECK(g.itow_ms == 500000000);
    CHECK(g.week == 2200);
    CHECK(g.geoid_undulation == Approx(-30.25));
    CHECK(g.source == GpsSource::novatel);
    CHECK(g.detailed_accuracy_valid);
    CHECK(g.vertical_velocity_valid);
    CHECK(g.leap_seconds == 18);
    CHECK(g.multi_ant_heading == Approx(8192 * pi / 32767.0));
    CHECK(g.pos_accuracy[0] == Approx(1.5));
    CHECK(g.pos_accuracy[1] == Approx(2.0));
    CHECK(g.pos_accuracy[2] == Approx(3.25));
    CHECK(g.vel_accuracy[0] == Approx(0.1));
    CHECK(g.vel_accuracy[1] == Approx(0.2));
    CHECK(g.vel_accuracy[2] == Approx(0.35));
}

TEST_CASE("GpsData length rules", "[orion][telemetry]") {
    check_too_short<GpsData>(gps_golden, "reserved");  // the reserved bits open byte 53
    check_extra_bytes_ignored<GpsData>(gps_golden);

    // Exactly the minimum, flags on: the optional tail keeps the ICD defaults.
    const auto d = decode<GpsData>(prefix(gps_golden, 54));
    REQUIRE(d.ok);
    CHECK(d.value.vertical_velocity_valid);
    CHECK(d.value.leap_seconds == 17);
    CHECK(d.value.multi_ant_heading == 0.0);
    CHECK(d.value.pos_accuracy == std::array<double, 3>{0, 0, 0});
    CHECK(d.value.vel_accuracy == std::array<double, 3>{0, 0, 0});

    // The tail may end between conditional fields.
    const auto part = decode<GpsData>(prefix(gps_golden, 57));
    REQUIRE(part.ok);
    CHECK(part.value.multi_ant_heading == Approx(8192 * pi / 32767.0));
    CHECK(part.value.pos_accuracy == std::array<double, 3>{0, 0, 0});
}

TEST_CASE("GpsData conditional fields follow their valid flags", "[orion][telemetry]") {
    SECTION("both flags off: only leapSeconds follows byte 53") {
        Bytes b = prefix(gps_golden, 55);
        b[0] = 0x03;   // multiAntHeadingValid 0, fixType threeDFix
        b[53] = 0x01;  // detailedAccuracyValid 0, verticalVelocityValid 1
        const auto g = decode_golden<GpsData>(b);
        CHECK_FALSE(g.multi_ant_heading_valid);
        CHECK(g.fix_type == UbloxFixType::three_d_fix);
        CHECK_FALSE(g.detailed_accuracy_valid);
        CHECK(g.vertical_velocity_valid);
        CHECK(g.leap_seconds == 18);

        // Values in the struct are not sent while their flag is off.
        GpsData with_values = g;
        with_values.multi_ant_heading = 1.0;
        with_values.pos_accuracy = {1, 2, 3};
        CHECK(encoded(with_values) == b);
    }
    SECTION("only detailed accuracy: posAccuracy starts right after leapSeconds") {
        const Bytes accuracies(gps_golden.begin() + 57, gps_golden.end());
        Bytes b = concat(prefix(gps_golden, 55), accuracies);
        b[0] = 0x03;  // multiAntHeadingValid 0
        const auto g = decode_golden<GpsData>(b);
        CHECK(b.size() == 67);
        CHECK(g.multi_ant_heading == 0.0);
        CHECK(g.pos_accuracy[2] == Approx(3.25));
        CHECK(g.vel_accuracy[2] == Approx(0.35));
    }
    SECTION("only multi antenna heading") {
        Bytes b = prefix(gps_golden, 57);
        b[53] = 0x00;
        const auto g = decode_golden<GpsData>(b);
        CHECK(g.multi_ant_heading == Approx(8192 * pi / 32767.0));
        CHECK_FALSE(g.detailed_accuracy_valid);
    }
}

TEST_CASE("GpsData JSON: degrees, keys, and client input checks", "[orion][telemetry][json]") {
    const auto golden = decode<GpsData>(gps_golden).value;
    const json j = to_json(golden);
    check_keys(j, {"multi_ant_heading_valid",
                   "fix_type",
                   "fix_state",
                   "tracked_sats",
                   "pdop",
                   "lat",
                   "lon",
                   "alt",
                   "vel_ned",
                   "hacc",
                   "vacc",
                   "speed_acc",
                   "heading_acc",
                   "itow_ms",
                   "week",
                   "geoid_undulation",
                   "source",
                   "detailed_accuracy_valid",
                   "vertical_velocity_valid",
                   "leap_seconds",
                   "multi_ant_heading",
                   "pos_accuracy",
                   "vel_accuracy"});
    CHECK(j["lat"].get<double>() == Approx(45.7));
    CHECK(j["heading_acc"].get<double>() == Approx(0.5).epsilon(1e-6));
    CHECK(j["multi_ant_heading"].get<double>() == Approx(8192 * 180.0 / 32767.0));
    CHECK(j["fix_type"] == "three_d_fix");
    CHECK(j["source"] == "novatel_source");
    CHECK(j["multi_ant_heading_valid"] == true);

    SECTION("round trip through JSON gives the same bytes") {
        GpsData g;
        JsonError err;
        REQUIRE(from_json(j, g, err));
        CHECK(encoded(g) == gps_golden);
    }
    SECTION("unknown key") {
        GpsData g;
        JsonError err;
        CHECK_FALSE(from_json(json{{"lat", 45.0}, {"latitude", 45.0}}, g, err));
        CHECK(err.code == "bad_request");
        CHECK(err.message.find("latitude") != std::string::npos);
    }
    SECTION("wrong types") {
        GpsData g;
        JsonError err;
        CHECK_FALSE(from_json(json{{"lat", "45.7N"}}, g, err));
        CHECK(err.code == "bad_request");
        CHECK(err.message.find("lat") != std::string::npos);
        CHECK_FALSE(from_json(json{{"detailed_accuracy_valid", 1}}, g, err));
        CHECK(err.code == "bad_request");
        CHECK(err.message.find("detailed_accuracy_valid") != std::string::npos);
        CHECK_FALSE(from_json(json{{"source", "galileo"}}, g, err));
        CHECK(err.code == "bad_request");
        CHECK(err.message.find("source") != std::string::npos);
    }
    SECTION("out of range") {
        GpsData g;
        JsonError err;
        CHECK_FALSE(from_json(json{{"pdop", 25.6}}, g, err));
        CHECK(err.code == "out_of_range");
        CHECK(err.message.find("pdop") != std::string::npos);
        CHECK_FALSE(from_json(json{{"fix_type", 16}}, g, err));  // B4
        CHECK(err.code == "out_of_range");
        CHECK(err.message.find("fix_type") != std::string::npos);
        CHECK_FALSE(from_json(json{{"vel_ned", {0.0, 0.0, 3000000.0}}}, g, err));
        CHECK(err.code == "out_of_range");
        CHECK(err.message.find("vel_ned[2]") != std::string::npos);
        CHECK_FALSE(from_json(json{{"detailed_accuracy_valid", true}, {"pos_accuracy", {1, 2, 70}}},
                              g, err));
        CHECK(err.code == "out_of_range");
        CHECK(err.message.find("pos_accuracy[2]") != std::string::npos);
    }
}

// --- InsQuality --------------------------------------------------------------------------------

TEST_CASE("InsQuality golden bytes with every conditional block", "[orion][telemetry]") {
    REQUIRE(ins_golden.size() == InsQuality::max_length);
    const auto q = decode_golden<InsQuality>(ins_golden);
    CHECK(q.system_time_ms == 123456);
    CHECK(q.gps_source == GpsSource::piksi);
    CHECK(q.imu_type == ImuType::epson);
    CHECK(q.ins_mode == InsMode::run_tight);
    CHECK(q.has_gyro_bias);
    CHECK(q.has_gravity_bias);
    CHECK(q.has_accel_bias);
    CHECK(q.has_clock_bias);
    CHECK(q.has_pan_tilt_bias);
    CHECK(q.pos_rejected);
    CHECK(q.vel_rejected);
    CHECK(q.hdg_rejected);
    CHECK(q.gps_period_s == Approx(0.25));
    CHECK(q.hdg_period_s == Approx(1.0));
    CHECK(q.pos_chi_square == 1.5);
    CHECK(q.vel_chi_square == 2.0);
    CHECK(q.hdg_chi_square == 3.25);
    CHECK(q.att_confidence[0] == Approx(0.0123));
    CHECK(q.att_confidence[1] == Approx(0.0045));
    CHECK(q.att_confidence[2] == Approx(0.1));
    CHECK(q.vel_confidence[0] == Approx(0.12));
    CHECK(q.vel_confidence[1] == Approx(0.34));
    CHECK(q.vel_confidence[2] == Approx(0.56));
    CHECK(q.pos_confidence[0] == Approx(1.5));
    CHECK(q.pos_confidence[1] == Approx(2.5));
    CHECK(q.pos_confidence[2] == Approx(3.75));
    CHECK(q.gyro_confidence[0] == Approx(0.0001));
    CHECK(q.gyro_confidence[1] == Approx(0.0002));
    CHECK(q.gyro_confidence[2] == Approx(0.0003));
    CHECK(q.accel_confidence[0] == Approx(0.01));
    CHECK(q.accel_confidence[1] == Approx(0.02));
    CHECK(q.accel_confidence[2] == Approx(0.03));
    CHECK(q.gravity_confidence == Approx(0.05));
    CHECK(q.clock_bias_confidence == Approx(0.5));
    CHECK(q.clock_drift_confidence == Approx(0.25));
    CHECK(q.gyro_bias[0] == Approx(0.00012));
    CHECK(q.gyro_bias[1] == Approx(-0.00034));
    CHECK(q.gyro_bias[2] == Approx(0.00056));
    CHECK(q.accel_bias[0] == Approx(0.1));
    CHECK(q.accel_bias[1] == Approx(0.2));
    CHECK(q.accel_bias[2] == Approx(0.005));
    CHECK(q.gravity_bias == Approx(0.01));
    CHECK(q.clock_bias == Approx(-12.5));
    CHECK(q.clock_drift == Approx(1.234));
    CHECK(q.num_tight_sat_pos_updates == 7);
    CHECK(q.num_tight_sat_vel_updates == 8);
    CHECK(q.num_tight_pos_updates == 14);
    CHECK(q.num_tight_vel_updates == 16);
    CHECK(q.pan_tilt_bias[0] == Approx(2048 * (10.0 * deg) / 32767.0));
    CHECK(q.pan_tilt_bias[1] == Approx(-2048 * (10.0 * deg) / 32767.0));
    CHECK(q.pan_tilt_chi_square == Approx(2.0));
}

TEST_CASE("InsQuality length rules", "[orion][telemetry]") {
    check_too_short<InsQuality>(ins_golden, "pos_confidence");
    check_extra_bytes_ignored<InsQuality>(ins_golden);

    Bytes min = prefix(ins_golden, 34);
    min[7] = 0x07;  // no bias blocks; pos, vel, hdg rejected
    const auto q = decode_golden<InsQuality>(min);
    CHECK_FALSE(q.has_gyro_bias);
    CHECK(q.pos_rejected);
    CHECK(q.hdg_rejected);
    CHECK(q.gyro_confidence == std::array<double, 3>{0, 0, 0});
    CHECK(q.clock_bias == 0.0);
    CHECK(q.pan_tilt_chi_square == 0.0);

    // Conditional fields are not optional: a set flag without its fields is an error.
    const auto missing = decode<InsQuality>(prefix(ins_golden, 34));
    CHECK_FALSE(missing.ok);
    CHECK(to_string(missing.error).find("'gyro_confidence'") != std::string::npos);
}

TEST_CASE("InsQuality bias blocks follow their has-flags", "[orion][telemetry]") {
    SECTION("hasGyroBias only (bit 7:7)") {
        Bytes b = prefix(ins_golden, 34);
        b[7] = 0x80;
        b = concat(b, {0x00, 0x0A, 0x00, 0x14, 0x00, 0x1E});  // 34 gyroConfidence
        b = concat(b, {0x00, 0x0C, 0xFF, 0xDE, 0x00, 0x38});  // 40 gyroBias
        const auto q = decode_golden<InsQuality>(b);
        CHECK(q.has_gyro_bias);
        CHECK_FALSE(q.has_accel_bias);
        CHECK(q.gyro_confidence[2] == Approx(0.0003));
        CHECK(q.gyro_bias[1] == Approx(-0.00034));
    }
    SECTION("hasGravityBias only (bit 7:6)") {
        Bytes b = prefix(ins_golden, 34);
        b[7] = 0x40;
        b = concat(b, {0x05, 0xDC, 0x01, 0x2C});  // 34 gravityConfidence, 36 gravityBias
        const auto q = decode_golden<InsQuality>(b);
        CHECK(q.has_gravity_bias);
        CHECK_FALSE(q.has_accel_bias);
        CHECK(q.gravity_confidence == Approx(0.05));
        CHECK(q.gravity_bias == Approx(0.01));
    }
    SECTION("hasAccelBias only (bit 7:5)") {
        Bytes b = prefix(ins_golden, 34);
        b[7] = 0x20;
        b = concat(b, {0x01, 0x2C, 0x02, 0x58, 0x03, 0x84});  // 34 accelConfidence
        b = concat(b, {0x0B, 0xB8, 0x17, 0x70, 0x00, 0x96});  // 40 accelBias
        const auto q = decode_golden<InsQuality>(b);
        CHECK(q.has_accel_bias);
        CHECK_FALSE(q.has_gravity_bias);
        CHECK(q.accel_confidence[0] == Approx(0.01));
        CHECK(q.accel_bias[1] == Approx(0.2));
    }
    SECTION("hasClockBias only (bit 7:4)") {
        Bytes b = prefix(ins_golden, 34);
        b[7] = 0x10;
        b = concat(b, {0x13, 0x88, 0x09, 0xC4});                // 34 clock bias/drift confidence
        b = concat(b, {0xFB, 0x1E, 0x04, 0xD2, 7, 8, 14, 16});  // 38 clock bias, drift, counts
        const auto q = decode_golden<InsQuality>(b);
        CHECK(q.has_clock_bias);
        CHECK(q.clock_bias_confidence == Approx(0.5));
        CHECK(q.clock_bias == Approx(-12.5));
        CHECK(q.num_tight_vel_updates == 16);
        CHECK(q.gyro_bias == std::array<double, 3>{0, 0, 0});
    }
    SECTION("hasPanTiltBias only (bit 7:3)") {
        Bytes b = prefix(ins_golden, 34);
        b[7] = 0x08;
        b = concat(b, {0x08, 0x00, 0xF8, 0x00, 0x33});  // 34 panTiltBias, 38 chi-square
        const auto q = decode_golden<InsQuality>(b);
        CHECK(q.has_pan_tilt_bias);
        CHECK(q.pan_tilt_chi_square == Approx(2.0));
    }
    SECTION("each flag adds exactly its fields") {
        struct Case {
            bool InsQuality::*flag;
            std::size_t extra;
        };
        for (const Case c :
             {Case{&InsQuality::has_gyro_bias, 12}, Case{&InsQuality::has_accel_bias, 12},
              Case{&InsQuality::has_gravity_bias, 4}, Case{&InsQuality::has_clock_bias, 12},
              Case{&InsQuality::has_pan_tilt_bias, 5}}) {
            InsQuality q;
            q.gyro_bias = {0.001, 0.001, 0.001};
            q.clock_bias = 1.0;
            q.*c.flag = true;
            const Bytes b = encoded(q);
            CHECK(b.size() == InsQuality::min_length + c.extra);
            const auto back = decode<InsQuality>(b);
            REQUIRE(back.ok);
            CHECK(encoded(back.value) == b);
        }
    }
}

TEST_CASE("InsQuality JSON keys and units", "[orion][telemetry][json]") {
    const json j = to_json(decode<InsQuality>(ins_golden).value);
    CHECK(j.size() == 36);  // every field of the table
    CHECK(j["gps_source"] == "piksi_source");
    CHECK(j["imu_type"] == "epson");
    CHECK(j["ins_mode"] == "run_tight");
    CHECK(j["has_clock_bias"] == true);
    CHECK(j["gps_period_s"].get<double>() == Approx(0.25));
    CHECK(j["pos_chi_square"].get<double>() == 1.5);
    CHECK(j["att_confidence"][2].get<double>() == Approx(0.1 / deg));
    CHECK(j["gyro_confidence"][0].get<double>() == Approx(0.0001 / deg));
    CHECK(j["gyro_bias"][1].get<double>() == Approx(-0.00034 / deg));
    CHECK(j["pan_tilt_bias"][0].get<double>() == Approx(2048 * 10.0 / 32767.0));
    CHECK(j["accel_bias"][0].get<double>() == Approx(0.1));  // m/s/s, not an angle

    InsQuality off;
    check_keys(to_json(off),
               {"system_time_ms",    "gps_source",       "imu_type",       "ins_mode",
                "has_gyro_bias",     "has_gravity_bias", "has_accel_bias", "has_clock_bias",
                "has_pan_tilt_bias", "pos_rejected",     "vel_rejected",   "hdg_rejected",
                "gps_period_s",      "hdg_period_s",     "pos_chi_square", "vel_chi_square",
                "hdg_chi_square",    "att_confidence",   "vel_confidence", "pos_confidence"});
}

// --- enumerations ------------------------------------------------------------------------------

TEST_CASE("every telemetry enum value has its JSON name and back", "[orion][telemetry][enum]") {
    check_enum_field(&GeolocateTelemetry::ins_rotation_option, "ins_rotation_option",
                     {{InsRotation::gimbal_native, "in_gimbal_native"},
                      {InsRotation::platform, "in_platform"},
                      {InsRotation::payload_ball, "in_payload_ball"}},
                     {}, static_cast<InsRotation>(9));
    check_enum_field(&RetractStatus::state, "state",
                     {{RetractState::disabled, "disabled"},
                      {RetractState::retracted, "retracted"},
                      {RetractState::retracting, "retracting"},
                      {RetractState::deploying, "deploying"},
                      {RetractState::deployed, "deployed"},
                      {RetractState::fault, "fault"}},
                     {}, static_cast<RetractState>(6));
    check_enum_field(&RetractStatus::cmd, "cmd",
                     {{RetractCmd::disable, "disable"},
                      {RetractCmd::deploy, "deploy"},
                      {RetractCmd::retract, "retract"}},
                     {}, static_cast<RetractCmd>(3));
    check_enum_field(&DebugString::priority, "priority",
                     {{DebugPriority::log, "log"},
                      {DebugPriority::info, "info"},
                      {DebugPriority::warn, "warn"},
                      {DebugPriority::error, "error"},
                      {DebugPriority::fatal, "fatal"}},
                     {}, static_cast<DebugPriority>(5));
    check_enum_field(&GpsData::source, "source",
                     {{GpsSource::external, "external_source"},
                      {GpsSource::ublox, "ublox_source"},
                      {GpsSource::mavlink, "mavlink_source"},
                      {GpsSource::nmea, "nmea_source"},
                      {GpsSource::novatel, "novatel_source"},
                      {GpsSource::autopilot, "autopilot_source"},
                      {GpsSource::piksi, "piksi_source"}},
                     {{GpsSource::autopilot, "piccolo_source"}}, static_cast<GpsSource>(7));
    check_enum_field(&GpsData::fix_type, "fix_type",
                     {{UbloxFixType::no_fix, "no_fix"},
                      {UbloxFixType::dead_reckoning_only, "dead_reckoning_only"},
                      {UbloxFixType::two_d_fix, "two_d_fix"},
                      {UbloxFixType::three_d_fix, "three_d_fix"},
                      {UbloxFixType::gnss_dead_reckoning, "gnss_dead_reckoning"},
                      {UbloxFixType::time_only, "time_only"}},
                     {}, static_cast<UbloxFixType>(15));  // largest B4 value
    check_enum_field(&InsQuality::ins_mode, "ins_mode",
                     {{InsMode::init1, "init1"},
                      {InsMode::init2, "init2"},
                      {InsMode::ahrs, "ahrs"},
                      {InsMode::run_hard, "run_hard"},
                      {InsMode::run, "run"},
                      {InsMode::run_tight, "run_tight"}},
                     {}, static_cast<InsMode>(6));
    check_enum_field(&InsQuality::imu_type, "imu_type",
                     {{ImuType::internal, "internal"},
                      {ImuType::sensonor, "sensonor"},
                      {ImuType::dmu11, "dmu11"},
                      {ImuType::external, "external"},
                      {ImuType::epson, "epson"}},
                     {}, static_cast<ImuType>(7));  // largest B3 value
}

TEST_CASE("unknown enum values survive the wire and reach JSON as numbers",
          "[orion][telemetry][enum]") {
    Bytes b = ins_golden;
    b[5] = 0x07;  // imuType 7: no name
    b[6] = 0x09;  // insMode 9: no name
    const auto q = decode_golden<InsQuality>(b);
    const json j = to_json(q);
    CHECK(j["imu_type"] == 7);
    CHECK(j["ins_mode"] == 9);

    Bytes r = retract_golden;
    r[1] = 0xEE;
    CHECK(to_json(decode_golden<RetractStatus>(r))["state"] == 0xEE);
}

// --- every packet of the section ---------------------------------------------------------------

TEST_CASE("every telemetry packet is listed and round-trips through its own JSON",
          "[orion][telemetry][json]") {
    const std::vector<std::pair<std::uint8_t, Bytes>> goldens{
        {pkt::geolocate_telemetry, geolocate_golden},
        {pkt::performance, performance_golden},
        {pkt::diagnostics, diagnostics_golden},
        {pkt::software_diagnostics, software_golden},
        {pkt::network_diagnostics, network_golden},
        {pkt::retract_status, retract_golden},
        {pkt::stare_start, stare_golden},
        {pkt::reset_source, reset_golden},
        {pkt::debug_string, debug_golden},
        {pkt::klv_user_data, klv_golden},
        {pkt::gps_data, gps_golden},
        {pkt::ins_quality, ins_golden},
    };
    for (const auto& [id, bytes] : goldens) {
        INFO("packet id " << int(id));
        const Bytes& golden = bytes;
        const bool known = dispatch(id, [&]<class P>() {
            CHECK(golden.size() >= P::min_length);
            CHECK(golden.size() <= P::max_length);
            const auto d = decode<P>(golden);
            REQUIRE(d.ok);
            P back;
            JsonError err;
            REQUIRE(from_json(to_json(d.value), back, err));
            CHECK(encoded(back) == golden);
            // What clients are sent (fewest digits) reads back to the same bytes too.
            P lean;
            REQUIRE(from_json(to_json(d.value, Digits::shortest), lean, err));
            CHECK(encoded(lean) == golden);
        });
        CHECK(known);
    }
    CHECK(packet_name(pkt::vibration) == "vibration");
    CHECK(packet_name(pkt::ins_quality) == "ins_quality");
    std::uint8_t id = 0;
    REQUIRE(packet_id("gps_data", id));
    CHECK(id == 209);
}

TEST_CASE("telemetry packets survive framing and the Framer", "[orion][telemetry][framer]") {
    // Every golden packet framed back to back, delivered one byte at a time.
    const std::vector<std::pair<std::uint8_t, Bytes>> goldens{
        {pkt::gps_data, gps_golden},
        {pkt::ins_quality, ins_golden},
        {pkt::vibration, vibration_golden},
        {pkt::stare_start, stare_golden},
        {pkt::debug_string, debug_golden},
        {pkt::geolocate_telemetry, geolocate_golden},
        {pkt::software_diagnostics, software_golden},
    };
    Bytes stream;
    for (const auto& [id, data] : goldens) append_frame(id, data, stream);

    const auto typed = decode<GpsData>(gps_golden).value;
    CHECK(to_wire(typed) == frame_bytes(pkt::gps_data, gps_golden));

    Framer framer;
    std::vector<Frame> frames;
    for (const std::uint8_t byte : stream)
        framer.push(std::span<const std::uint8_t>(&byte, 1),
                    [&](const Frame& f) { frames.push_back(f); });
    REQUIRE(frames.size() == goldens.size());
    CHECK(framer.stats().dropped_bytes == 0);
    for (std::size_t i = 0; i < frames.size(); ++i) {
        const Frame& f = frames[i];
        CHECK(f.id == goldens[i].first);
        const Bytes data(f.data().begin(), f.data().end());
        CHECK(data == goldens[i].second);
        const bool known = dispatch(f.id, [&]<class P>() {
            const auto d = decode<P>(f.data());
            REQUIRE(d.ok);
            CHECK(encoded(d.value) == goldens[i].second);
        });
        CHECK(known);
    }
    const auto gps = decode<GpsData>(frames[0].data());
    REQUIRE(gps.ok);
    CHECK(to_json(gps.value) == to_json(typed));
}

TEST_CASE("clients get the fewest digits that keep the wire value", "[orion][json][digits]") {
    const auto t = decode_golden<GeolocateTelemetry>(geolocate_golden);
    const auto exact = to_json(t);
    const auto lean = to_json(t, Digits::shortest);
    // Latitude is a 1e-7 degree-ish field in radians: at most 7 decimals, never 17 digits.
    for (const char* key : {"lat", "lon", "pan", "tilt", "hfov", "alt"}) {
        INFO(key);
        const std::string text = lean[key].dump();
        const auto dot = text.find('.');
        const std::size_t decimals = dot == std::string::npos ? 0 : text.size() - dot - 1;
        CHECK(decimals <= 8);
        // Within one wire step (pan and tilt: 180/32767 degree).
        CHECK(lean[key].get<double>() == Approx(exact[key].get<double>()).margin(0.006));
    }
    CHECK(lean.dump().size() < exact.dump().size());
}
