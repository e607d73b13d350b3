// Golden tests for the ICD section "Packets for gimbal control" (codec/packets_control.hpp).
// Every golden vector is written by hand from the ICD tables, one comment per field with its
// byte offset; raw wire integers are spelled out so expected physical values are raw / scale.
#include <catch2/catch.hpp>
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "protocols/orion/codec/framer.hpp"
#include "protocols/orion/codec/framing.hpp"
#include "protocols/orion/codec/json.hpp"
#include "protocols/orion/codec/packets.hpp"

using namespace gimbal::orion;
using Bytes = std::vector<std::uint8_t>;
using nlohmann::json;

namespace {

constexpr double deg = 180.0 / pi;

template <class P>
P decode_ok(const Bytes& bytes) {
    const auto r = decode<P>(bytes);
    INFO(to_string(r.error));
    REQUIRE(r.ok);
    return r.value;
}

template <class P>
Bytes encode_ok(const P& packet) {
    Payload out;
    REQUIRE(encode(packet, out));
    return Bytes(out.bytes.begin(), out.bytes.begin() + static_cast<long>(out.size));
}

// Decodes a golden vector and requires the encoder to give back exactly the same bytes.
template <class P>
P golden(const Bytes& bytes) {
    REQUIRE(bytes.size() >= P::min_length);
    REQUIRE(bytes.size() <= P::max_length);
    const P p = decode_ok<P>(bytes);
    CHECK(encode_ok(p) == bytes);
    return p;
}

template <class P>
void check_too_short(const Bytes& bytes, const std::string& field) {
    const auto r = decode<P>(bytes);
    CHECK_FALSE(r.ok);
    CHECK_THAT(to_string(r.error), Catch::Contains("'" + field + "'"));
}

// One byte under the minimum fails naming `field`; unknown trailing bytes are ignored.
template <class P>
void check_lengths(const Bytes& golden_bytes, const std::string& field) {
    INFO(P::name);
    check_too_short<P>(
        Bytes(golden_bytes.begin(), golden_bytes.begin() + static_cast<long>(P::min_length - 1)),
        field);
    Bytes longer = golden_bytes;
    longer.insert(longer.end(), {0xA5, 0x5A, 0x01});
    const P p = decode_ok<P>(longer);
    CHECK(encode_ok(p) == golden_bytes);
}

std::set<std::string> keys(const json& obj) {
    std::set<std::string> out;
    for (const auto& item : obj.items()) out.insert(item.key());
    return out;
}

// A client-sent packet: to_json of the golden packet reads back into the same bytes, and an
// unknown key is a bad_request.
template <class P>
void check_client_json(const Bytes& golden_bytes) {
    INFO(P::name);
    const json obj = to_json(decode_ok<P>(golden_bytes));
    P back;
    JsonError err;
    REQUIRE(from_json(obj, back, err));
    CHECK(encode_ok(back) == golden_bytes);

    json bad = obj;
    bad["no_such_key"] = 1;
    CHECK_FALSE(from_json(bad, back, err));
    CHECK(err.code == "bad_request");
    CHECK_THAT(err.message, Catch::Contains("no_such_key"));
}

// The golden packet's JSON with `key` set to `value` is rejected with `code`, naming the key.
template <class P>
void check_rejects(const Bytes& golden_bytes, const std::string& key, const json& value,
                   const std::string& code) {
    INFO(P::name << "." << key << " = " << value.dump());
    json obj = to_json(decode_ok<P>(golden_bytes));
    obj[key] = value;
    P back;
    JsonError err;
    CHECK_FALSE(from_json(obj, back, err));
    CHECK(err.code == code);
    CHECK_THAT(err.message, Catch::Contains(key));
}

template <class P>
void check_wrong_type(const Bytes& golden_bytes, const std::string& key, const json& value) {
    check_rejects<P>(golden_bytes, key, value, "bad_request");
}

template <class P>
void check_out_of_range(const Bytes& golden_bytes, const std::string& key, const json& value) {
    check_rejects<P>(golden_bytes, key, value, "out_of_range");
}

template <class E>
void check_enum_names(std::size_t canonical_count) {
    std::set<std::string_view> seen;
    for (const auto& entry : enum_names(E{})) {
        E back{};
        REQUIRE(enum_from_name(entry.name, back));
        CHECK(back == entry.value);
        seen.insert(entry.name);
    }
    CHECK(seen.size() == enum_names(E{}).size());  // no name used twice
    std::set<E> values;
    for (const auto& entry : enum_names(E{})) values.insert(entry.value);
    CHECK(values.size() == canonical_count);
    for (const E v : values) CHECK_FALSE(enum_name(v).empty());
}

}  // namespace

#include "golden_control.hpp"

using namespace gimbal::orion::golden_vectors;

// --- OrionCmd / OrionStartupCmd -----------------------------------------------------------------

TEST_CASE("OrionCmd golden bytes", "[orion][control]") {
    const Cmd p = golden<Cmd>(cmd_bytes);
    CHECK(p.cmd.target[0] == Approx(1.5));
    CHECK(p.cmd.target[1] == Approx(-0.25));
    CHECK(p.cmd.mode == Mode::rate);
    CHECK(p.cmd.stabilized);
    CHECK(p.cmd.impulse_time_s == Approx(2.5));
    check_lengths<Cmd>(cmd_bytes, "impulse_time_s");

    const json j = to_json(p);
    CHECK(keys(j) == std::set<std::string>{"target", "mode", "stabilized", "impulse_time_s"});
    CHECK(j["target"][0].get<double>() == Approx(1.5 * deg));  // rad/s shown as deg/s
    CHECK(j["mode"] == "rate");
    CHECK(j["stabilized"] == true);
    check_client_json<Cmd>(cmd_bytes);
    check_wrong_type<Cmd>(cmd_bytes, "impulse_time_s", "2.5");
    check_out_of_range<Cmd>(cmd_bytes, "impulse_time_s", 25.6);
    check_wrong_type<Cmd>(cmd_bytes, "mode", true);
    check_out_of_range<Cmd>(cmd_bytes, "mode", 256);
}

TEST_CASE("OrionStartupCmd golden bytes and ICD default", "[orion][control]") {
    CHECK(StartupCmd{}.cmd.mode == Mode::position);  // ICD: "Defaults to position mode"
    const StartupCmd p = golden<StartupCmd>(startup_cmd_bytes);
    CHECK(p.cmd.target[0] == Approx(0.5));
    CHECK(p.cmd.target[1] == Approx(-1.0));
    CHECK(p.cmd.mode == Mode::position);
    CHECK(p.cmd.stabilized);
    CHECK(p.cmd.impulse_time_s == Approx(0.3));
    check_lengths<StartupCmd>(startup_cmd_bytes, "impulse_time_s");
    CHECK(to_json(p)["mode"] == "position");
    // Target limits: +-32.767 rad = +-1877.4 deg.
    check_client_json<StartupCmd>(startup_cmd_bytes);
    check_wrong_type<StartupCmd>(startup_cmd_bytes, "target", json::array({1, "x"}));
    check_out_of_range<StartupCmd>(startup_cmd_bytes, "target", json::array({1880.0, 0.0}));
}

// --- GeopointCmd --------------------------------------------------------------------------------

TEST_CASE("GeopointCmd golden bytes", "[orion][control]") {
    const GeopointCmd p = golden<GeopointCmd>(geopoint_bytes);
    CHECK(p.target_lat * deg == Approx(45.0));
    CHECK(p.target_lon * deg == Approx(-122.5));
    CHECK(p.target_alt == Approx(123.4567));
    CHECK(p.target_vel_ned[0] == Approx(1.5));
    CHECK(p.target_vel_ned[1] == Approx(-2.25));
    CHECK(p.target_vel_ned[2] == Approx(0.5));
    CHECK(p.joystick_range_m == 500);
    CHECK(p.options == GeopointOptions::stare_closure);
    check_lengths<GeopointCmd>(geopoint_bytes, "vel_ned");

    const json j = to_json(p);
    CHECK(keys(j) ==
          std::set<std::string>{"lat", "lon", "alt", "vel_ned", "joystick_range_m", "options"});
    CHECK(j["lat"].get<double>() == Approx(45.0));
    CHECK(j["lon"].get<double>() == Approx(-122.5));
    CHECK(j["options"] == "stare_closure");
    check_client_json<GeopointCmd>(geopoint_bytes);
    check_wrong_type<GeopointCmd>(geopoint_bytes, "joystick_range_m", "500");
    check_out_of_range<GeopointCmd>(geopoint_bytes, "joystick_range_m", 65536);
    check_wrong_type<GeopointCmd>(geopoint_bytes, "lat", nullptr);
    check_out_of_range<GeopointCmd>(geopoint_bytes, "lat", 215.0);
}

TEST_CASE("GeopointCmd: the ICD minimum of 18 bytes decodes with defaults", "[orion][control]") {
    const Bytes min(geopoint_bytes.begin(), geopoint_bytes.begin() + 18);
    const GeopointCmd p = decode_ok<GeopointCmd>(min);
    CHECK(p.target_vel_ned[2] == Approx(0.5));
    CHECK(p.joystick_range_m == 0);
    CHECK(p.options == GeopointOptions::none);
    // 20 bytes: joystickRange present, options defaulted.
    const GeopointCmd q =
        decode_ok<GeopointCmd>(Bytes(geopoint_bytes.begin(), geopoint_bytes.end() - 1));
    CHECK(q.joystick_range_m == 500);
    CHECK(q.options == GeopointOptions::none);
}

TEST_CASE("GeopointCmd built from JSON is always 21 bytes", "[orion][control]") {
    GeopointCmd p;
    JsonError err;
    REQUIRE(from_json(json{{"lat", 10.0}, {"lon", 20.0}, {"alt", 30.0}}, p, err));
    CHECK(encode_ok(p).size() == 21);
    CHECK(encode_ok(GeopointCmd{}).size() == 21);
}

TEST_CASE("GeopointOptions names", "[orion][control][enum]") {
    check_enum_names<GeopointOptions>(4);
    CHECK(enum_name(GeopointOptions::none) == "none");
    CHECK(enum_name(GeopointOptions::stare) == "stare");
    CHECK(enum_name(GeopointOptions::closure) == "closure");
    CHECK(enum_name(GeopointOptions::stare_closure) == "stare_closure");
    GeopointCmd p;
    p.options = static_cast<GeopointOptions>(9);
    CHECK(to_json(p)["options"] == 9);
}

// --- OrionPath ----------------------------------------------------------------------------------

TEST_CASE("OrionPath golden bytes", "[orion][control]") {
    const Path p = golden<Path>(path_bytes);
    CHECK(p.point_down);
    CHECK(p.num_cross_track_steps == 3);
    REQUIRE(p.points.size() == 2);
    CHECK(p.points[0].pos_ecef == std::array<double, 3>{-2500000, -4000000, 4200000});
    CHECK(p.points[1].pos_ecef == std::array<double, 3>{1000000, -3000000, 5000000});
    CHECK(p.along_track_step_angle == Approx(4096 * pi / 65535));
    CHECK(p.cross_track_step_ratio == Approx(1.5));
    check_lengths<Path>(path_bytes, "point_down");

    const json j = to_json(p);
    CHECK(keys(j) == std::set<std::string>{"point_down", "num_cross_track_steps", "points",
                                           "along_track_step_angle", "cross_track_step_ratio"});
    CHECK(j["point_down"] == true);
    CHECK(j["along_track_step_angle"].get<double>() == Approx(4096 * 180.0 / 65535));
    CHECK(keys(j["points"][1]) == std::set<std::string>{"pos_ecef"});
    CHECK(j["points"][1]["pos_ecef"][2].get<double>() == 5000000.0);
    check_client_json<Path>(path_bytes);
    check_wrong_type<Path>(path_bytes, "cross_track_step_ratio", "1.5");
    check_out_of_range<Path>(path_bytes, "cross_track_step_ratio", 2.56);
    check_wrong_type<Path>(path_bytes, "num_cross_track_steps", 1.5);
    check_out_of_range<Path>(path_bytes, "num_cross_track_steps", 16);
    check_wrong_type<Path>(path_bytes, "point_down", 1);
}

TEST_CASE("OrionPath: lengths, repeat count and truncation", "[orion][control]") {
    // Minimum: no points, pointDown set; the optional tail takes its ICD defaults.
    const Path down = decode_ok<Path>(Bytes{0x00, 0x80});
    CHECK(down.point_down);
    CHECK(down.points.empty());
    CHECK(down.along_track_step_angle == 0.0);
    CHECK(down.cross_track_step_ratio == 0.0);
    // numPoints 0: no point bytes are expected or written.
    CHECK(encode_ok(down) == Bytes{0x00, 0x80, 0x00, 0x00, 0x00});
    // Points without the optional tail: 2 + 9n bytes.
    const Path no_tail = decode_ok<Path>(Bytes(path_bytes.begin(), path_bytes.begin() + 20));
    CHECK(no_tail.points.size() == 2);
    CHECK(no_tail.along_track_step_angle == 0.0);
    // numPoints promises more than the packet holds.
    check_too_short<Path>(Bytes(path_bytes.begin(), path_bytes.begin() + 19), "pos_ecef");
}

TEST_CASE("OrionPath data length is 5 + 9 x points, up to 15 points", "[orion][control]") {
    for (std::size_t n : {0u, 1u, 7u, 15u}) {
        Path p;
        p.points.resize(n, PathPoint{{1.0, -2.0, 3.0}});
        CHECK(encode_ok(p).size() == 5 + 9 * n);
        CHECK(encode_ok(p).size() <= Path::max_length);
    }
    json obj{{"points", json::array()}, {"along_track_step_angle", 10.0}};
    for (int i = 0; i < 15; ++i)
        obj["points"].push_back(json{{"pos_ecef", {-2500000 + i, -4000000, 4200000 - i}}});
    Path p;
    JsonError err;
    REQUIRE(from_json(obj, p, err));
    const Bytes wire = encode_ok(p);
    CHECK(wire.size() == 140);
    CHECK(wire[0] == 15);
    const Path back = decode_ok<Path>(wire);
    REQUIRE(back.points.size() == 15);
    CHECK(back.points[14].pos_ecef[2] == 4200000 - 14);
    CHECK(back.along_track_step_angle * deg == Approx(10.0).epsilon(1e-4));

    // 16 points: rejected by the JSON reader and by the encoder.
    obj["points"].push_back(json{{"pos_ecef", {1, 2, 3}}});
    CHECK_FALSE(from_json(obj, p, err));
    CHECK(err.code == "out_of_range");
    CHECK_THAT(err.message, Catch::Contains("points"));
    Path too_long;
    too_long.points.resize(16);
    Payload out;
    CHECK_FALSE(encode(too_long, out));
}

TEST_CASE("OrionPath JSON rejects bad points", "[orion][control]") {
    Path p;
    JsonError err;
    CHECK_FALSE(from_json(json{{"points", {{{"pos_ecef", {9000000, 0, 0}}}}}}, p, err));
    CHECK(err.code == "out_of_range");
    CHECK_THAT(err.message, Catch::Contains("points[0].pos_ecef[0]"));
    CHECK_FALSE(from_json(json{{"points", {{{"pos_ecef", {1, 2, 3}}, {"lat", 1}}}}}, p, err));
    CHECK(err.code == "bad_request");
    CHECK_THAT(err.message, Catch::Contains("points[0].lat"));
    CHECK_FALSE(from_json(json{{"points", {{{"pos_ecef", {1, 2}}}}}}, p, err));
    CHECK(err.code == "bad_request");
}

// --- StareAck, OrionCameraSwitch, OrionCameraState ----------------------------------------------

TEST_CASE("StareAck golden bytes", "[orion][control]") {
    const StareAck p = golden<StareAck>(stare_ack_bytes);
    CHECK(p.echo_system_time_ms == 0x12345678u);
    check_lengths<StareAck>(stare_ack_bytes, "echo_system_time_ms");
    CHECK(keys(to_json(p)) == std::set<std::string>{"echo_system_time_ms"});
    check_client_json<StareAck>(stare_ack_bytes);
    check_wrong_type<StareAck>(stare_ack_bytes, "echo_system_time_ms", "1");
    check_out_of_range<StareAck>(stare_ack_bytes, "echo_system_time_ms", -10);
}

TEST_CASE("OrionCameraSwitch golden bytes", "[orion][control]") {
    const CameraSwitch p = golden<CameraSwitch>(camera_switch_bytes);
    CHECK(p.index == 2);
    check_lengths<CameraSwitch>(camera_switch_bytes, "index");
    CHECK(to_json(p) == json{{"index", 2}});
    check_client_json<CameraSwitch>(camera_switch_bytes);
    check_wrong_type<CameraSwitch>(camera_switch_bytes, "index", "2");
    check_out_of_range<CameraSwitch>(camera_switch_bytes, "index", 256);
}

TEST_CASE("OrionCameraState golden bytes and defaults", "[orion][control]") {
    const CameraState p = golden<CameraState>(camera_state_bytes);
    CHECK(p.zoom == Approx(2.5));
    CHECK(p.focus == Approx(-0.5));
    CHECK(p.index == 1);
    check_lengths<CameraState>(camera_state_bytes, "zoom");
    const CameraState min = decode_ok<CameraState>(Bytes{0x00, 0xFA});
    CHECK(min.zoom == Approx(2.5));
    CHECK(min.focus == Approx(-1.0));
    CHECK(min.index == 0);
    CHECK(keys(to_json(p)) == std::set<std::string>{"zoom", "focus", "index"});
    check_client_json<CameraState>(camera_state_bytes);
    check_wrong_type<CameraState>(camera_state_bytes, "zoom", json::array());
    check_out_of_range<CameraState>(camera_state_bytes, "zoom", 327.68);
    check_wrong_type<CameraState>(camera_state_bytes, "focus", "near");
    check_out_of_range<CameraState>(camera_state_bytes, "focus", -3.3);
}

// --- camera settings ----------------------------------------------------------------------------

TEST_CASE("OrionFlirSettings golden bytes and defaults", "[orion][control]") {
    const FlirSettings p = golden<FlirSettings>(flir_bytes);
    CHECK(p.index == 1);
    CHECK(p.palette == 5);
    CHECK(p.nuc_type == FlirNucType::ssn_medium);
    CHECK(p.black_hot);
    CHECK(p.max_agc_gain == 200);
    CHECK(p.ace_level == -3);
    CHECK(p.dde_threshold == 17);
    CHECK(p.agc_midpoint == 100);
    CHECK(p.integration_time_ms == Approx(123 * 29.0 / 255 + 1));
    check_lengths<FlirSettings>(flir_bytes, "dde_threshold");

    const FlirSettings min =
        decode_ok<FlirSettings>(Bytes(flir_bytes.begin(), flir_bytes.begin() + 5));
    CHECK(min.dde_threshold == 17);
    CHECK(min.agc_midpoint == 128);
    CHECK(min.integration_time_ms == Approx(8.0));
    const FlirSettings six =
        decode_ok<FlirSettings>(Bytes(flir_bytes.begin(), flir_bytes.begin() + 6));
    CHECK(six.agc_midpoint == 100);
    CHECK(six.integration_time_ms == Approx(8.0));
    // The ICD default 8 ms encodes as round(7 x 255/29) = 62.
    CHECK(encode_ok(FlirSettings{})[6] == 62);

    const json j = to_json(p);
    CHECK(keys(j) == std::set<std::string>{"index", "palette", "nuc_type", "black_hot",
                                           "max_agc_gain", "ace_level", "dde_threshold",
                                           "agc_midpoint", "integration_time_ms"});
    CHECK(j["nuc_type"] == "ssn_medium");
    CHECK(j["black_hot"] == true);
    CHECK(j["ace_level"] == -3);
    check_client_json<FlirSettings>(flir_bytes);
    check_wrong_type<FlirSettings>(flir_bytes, "integration_time_ms", "8");
    check_out_of_range<FlirSettings>(flir_bytes, "integration_time_ms", 0.9);
    check_wrong_type<FlirSettings>(flir_bytes, "palette", "5");
    check_out_of_range<FlirSettings>(flir_bytes, "palette", 8);
    check_wrong_type<FlirSettings>(flir_bytes, "nuc_type", true);
    check_out_of_range<FlirSettings>(flir_bytes, "nuc_type", 8);
    check_wrong_type<FlirSettings>(flir_bytes, "ace_level", "-3");
    check_out_of_range<FlirSettings>(flir_bytes, "ace_level", -128);
}

TEST_CASE("FlirNucType names", "[orion][control][enum]") {
    check_enum_names<FlirNucType>(5);
    CHECK(enum_name(FlirNucType::manual) == "manual");
    CHECK(enum_name(FlirNucType::ssn_no_motion) == "ssn_no_motion");
    CHECK(enum_name(FlirNucType::ssn_low) == "ssn_low");
    CHECK(enum_name(FlirNucType::ssn_medium) == "ssn_medium");
    CHECK(enum_name(FlirNucType::ssn_high) == "ssn_high");
    // An unknown value off the wire (NucType 7) is reported as its number.
    const FlirSettings p = decode_ok<FlirSettings>(Bytes{0x01, 0x0E, 0, 0, 0});
    CHECK(static_cast<int>(p.nuc_type) == 7);
    CHECK(to_json(p)["nuc_type"] == 7);
    FlirSettings q;
    JsonError err;
    REQUIRE(from_json(json{{"nuc_type", "ssn_high"}}, q, err));
    CHECK(q.nuc_type == FlirNucType::ssn_high);
    CHECK_FALSE(from_json(json{{"nuc_type", "ssn_extreme"}}, q, err));
    CHECK(err.code == "bad_request");
}

TEST_CASE("OrionAptinaSettings golden bytes and defaults", "[orion][control]") {
    const AptinaSettings p = golden<AptinaSettings>(aptina_bytes);
    CHECK(p.index == 2);
    CHECK(p.min_exposure_ms == Approx(256 * 32.95 / 65535 + 0.05));
    CHECK(p.max_exposure_ms == Approx(32768 * 32.95 / 65535 + 0.05));
    CHECK(p.min_gain == Approx(2048 * 31.0 / 65535 + 1));
    CHECK(p.max_gain == Approx(61440 * 31.0 / 65535 + 1));
    CHECK(p.brightness == -5);
    CHECK(p.contrast == Approx(64 / 127.0));
    CHECK(p.saturation == Approx(-64 / 127.0));
    CHECK(p.sharpness == Approx(1.0));
    CHECK(p.debug_enable);
    CHECK(p.hue == -7);
    check_lengths<AptinaSettings>(aptina_bytes, "sharpness");

    const AptinaSettings min =
        decode_ok<AptinaSettings>(Bytes(aptina_bytes.begin(), aptina_bytes.begin() + 13));
    CHECK_FALSE(min.debug_enable);
    CHECK(min.hue == 0);
    const AptinaSettings fourteen =
        decode_ok<AptinaSettings>(Bytes(aptina_bytes.begin(), aptina_bytes.begin() + 14));
    CHECK(fourteen.debug_enable);
    CHECK(fourteen.hue == 0);

    CHECK(keys(to_json(p)) == std::set<std::string>{"index", "min_exposure_ms", "max_exposure_ms",
                                                    "min_gain", "max_gain", "brightness",
                                                    "contrast", "saturation", "sharpness",
                                                    "debug_enable", "hue"});
    check_client_json<AptinaSettings>(aptina_bytes);
    check_wrong_type<AptinaSettings>(aptina_bytes, "max_exposure_ms", "1");
    check_out_of_range<AptinaSettings>(aptina_bytes, "max_exposure_ms", 33.1);
    check_wrong_type<AptinaSettings>(aptina_bytes, "min_gain", "1");
    check_out_of_range<AptinaSettings>(aptina_bytes, "min_gain", 0.5);
    check_wrong_type<AptinaSettings>(aptina_bytes, "debug_enable", 1);
}

TEST_CASE("OrionZafiroSettings golden bytes and defaults", "[orion][control]") {
    const ZafiroSettings p = golden<ZafiroSettings>(zafiro_bytes);
    CHECK(p.index == 3);
    CHECK(p.black_hot);
    CHECK(p.integration_time_ms == Approx(64 * 29.0 / 255 + 1));
    CHECK(p.lap_enabled);
    CHECK(p.lap_gain == Approx(128 * 3.5 / 255 + 0.5));
    CHECK(p.agc_saturation == Approx(0.02));
    CHECK(p.use_nuc_table_presets);
    check_lengths<ZafiroSettings>(zafiro_bytes, "agc_saturation");
    const ZafiroSettings min =
        decode_ok<ZafiroSettings>(Bytes(zafiro_bytes.begin(), zafiro_bytes.begin() + 6));
    CHECK_FALSE(min.use_nuc_table_presets);
    CHECK(keys(to_json(p)) == std::set<std::string>{"index", "black_hot", "integration_time_ms",
                                                    "lap_enabled", "lap_gain", "agc_saturation",
                                                    "use_nuc_table_presets"});
    check_client_json<ZafiroSettings>(zafiro_bytes);
    check_wrong_type<ZafiroSettings>(zafiro_bytes, "lap_gain", "1");
    check_out_of_range<ZafiroSettings>(zafiro_bytes, "lap_gain", 0.4);
    check_wrong_type<ZafiroSettings>(zafiro_bytes, "agc_saturation", false);
    check_out_of_range<ZafiroSettings>(zafiro_bytes, "agc_saturation", 0.11);
}

TEST_CASE("OrionHitachiSettings golden bytes and defaults", "[orion][control]") {
    const HitachiSettings p = golden<HitachiSettings>(hitachi_bytes);
    CHECK(p.index == 4);
    CHECK(p.integration_time_us == -1000);
    CHECK(p.aperture == Approx(5.6));
    CHECK(p.sharpness == Approx(2.0));
    check_lengths<HitachiSettings>(hitachi_bytes, "aperture");
    const HitachiSettings min =
        decode_ok<HitachiSettings>(Bytes(hitachi_bytes.begin(), hitachi_bytes.begin() + 5));
    CHECK(min.sharpness == Approx(1.0));
    CHECK(keys(to_json(p)) ==
          std::set<std::string>{"index", "integration_time_us", "aperture", "sharpness"});
    check_client_json<HitachiSettings>(hitachi_bytes);
    check_wrong_type<HitachiSettings>(hitachi_bytes, "aperture", "5.6");
    check_out_of_range<HitachiSettings>(hitachi_bytes, "aperture", 3276.8);
    check_wrong_type<HitachiSettings>(hitachi_bytes, "integration_time_us", 1.5);
    check_out_of_range<HitachiSettings>(hitachi_bytes, "integration_time_us", 40000);
}

TEST_CASE("OrionSonySettings golden bytes", "[orion][control]") {
    const SonySettings p = golden<SonySettings>(sony_bytes);
    CHECK(p.index == 5);
    CHECK(p.min_exposure_ms == Approx(16 * 32.95 / 65535 + 0.05));
    CHECK(p.max_exposure_ms == Approx(16384 * 32.95 / 65535 + 0.05));
    CHECK(p.min_gain_db == 3);
    CHECK(p.max_gain_db == 40);
    CHECK(p.brightness == 128);
    CHECK(p.contrast == Approx(1.0));
    CHECK(p.saturation == Approx(-1.0));
    CHECK(p.sharpness == Approx(1.0));
    CHECK(p.frame_rate_hz == Approx(30.0));
    check_lengths<SonySettings>(sony_bytes, "frame_rate_hz");
    CHECK(keys(to_json(p)) == std::set<std::string>{"index", "min_exposure_ms", "max_exposure_ms",
                                                    "min_gain_db", "max_gain_db", "brightness",
                                                    "contrast", "saturation", "sharpness",
                                                    "frame_rate_hz"});
    check_client_json<SonySettings>(sony_bytes);
    check_wrong_type<SonySettings>(sony_bytes, "frame_rate_hz", "30");
    check_out_of_range<SonySettings>(sony_bytes, "frame_rate_hz", 30.5);
    check_wrong_type<SonySettings>(sony_bytes, "contrast", "1");
    check_out_of_range<SonySettings>(sony_bytes, "contrast", -1.01);
}

TEST_CASE("OrionKtncSettings golden bytes and defaults", "[orion][control]") {
    const KtncSettings p = golden<KtncSettings>(ktnc_bytes);
    CHECK(p.index == 6);
    CHECK(p.integration_time_us == -500);
    CHECK(p.aperture == Approx(-1.0));
    CHECK(p.sharpness == Approx(16 * 16.0 / 255));
    CHECK(p.vertical_flip);
    CHECK(p.exposure_comp == Approx(32 * 14.0 / 255));
    CHECK(p.contrast == Approx(48 * 32.0 / 255));
    CHECK(p.saturation == Approx(112 * 32.0 / 255));
    CHECK(p.night_mode);
    CHECK(p.reset_to_defaults);
    check_lengths<KtncSettings>(ktnc_bytes, "aperture");

    const KtncSettings min =
        decode_ok<KtncSettings>(Bytes(ktnc_bytes.begin(), ktnc_bytes.begin() + 5));
    CHECK(min.sharpness == Approx(8.0));
    CHECK_FALSE(min.vertical_flip);
    CHECK(min.exposure_comp == Approx(7.0));
    CHECK(min.contrast == Approx(8.0));
    CHECK(min.saturation == Approx(14.0));
    CHECK_FALSE(min.night_mode);
    CHECK_FALSE(min.reset_to_defaults);
    // Only NightMode's byte present with ResetToDefaults clear: each bit decodes on its own.
    Bytes night = ktnc_bytes;
    night[10] = 0x80;
    const KtncSettings n = decode_ok<KtncSettings>(night);
    CHECK(n.night_mode);
    CHECK_FALSE(n.reset_to_defaults);

    CHECK(keys(to_json(p)) == std::set<std::string>{"index", "integration_time_us", "aperture",
                                                    "sharpness", "vertical_flip", "exposure_comp",
                                                    "contrast", "saturation", "night_mode",
                                                    "reset_to_defaults"});
    check_client_json<KtncSettings>(ktnc_bytes);
    check_wrong_type<KtncSettings>(ktnc_bytes, "exposure_comp", "7");
    check_out_of_range<KtncSettings>(ktnc_bytes, "exposure_comp", 14.1);
    check_wrong_type<KtncSettings>(ktnc_bytes, "saturation", nullptr);
    check_out_of_range<KtncSettings>(ktnc_bytes, "saturation", -0.1);
}

// --- OrionRetractCommand, OrionUserData ---------------------------------------------------------

TEST_CASE("OrionRetractCommand golden bytes", "[orion][control]") {
    const RetractCommand p = golden<RetractCommand>(retract_bytes);
    CHECK(p.cmd == RetractCmd::retract);
    check_lengths<RetractCommand>(retract_bytes, "reserved");
    CHECK(to_json(p) == json{{"cmd", "retract"}});
    // The reserved byte is ignored on decode and written as zero.
    const RetractCommand r = decode_ok<RetractCommand>(Bytes{0x01, 0x7F});
    CHECK(r.cmd == RetractCmd::deploy);
    CHECK(encode_ok(r) == Bytes{0x01, 0x00});
    check_client_json<RetractCommand>(retract_bytes);
    check_wrong_type<RetractCommand>(retract_bytes, "cmd", true);
    check_out_of_range<RetractCommand>(retract_bytes, "cmd", 256);
    RetractCommand q;
    JsonError err;
    CHECK_FALSE(from_json(json{{"cmd", "stow"}}, q, err));
    CHECK(err.code == "bad_request");
    q.cmd = static_cast<RetractCmd>(5);
    CHECK(to_json(q)["cmd"] == 5);
}

TEST_CASE("OrionUserData golden bytes", "[orion][control]") {
    const UserData p = golden<UserData>(user_data_bytes);
    CHECK(p.port == UserDataPort::fp3);
    CHECK(p.block_id == 0xDEADBEEFu);
    CHECK(p.data == Bytes{1, 2, 3});
    check_lengths<UserData>(user_data_bytes, "id");

    // size 0: no data bytes expected or written.
    const Bytes empty{0xFF, 0x00, 0x00, 0x00, 0x00, 0x01};
    const UserData e = golden<UserData>(empty);
    CHECK(e.port == UserDataPort::current);
    CHECK(e.block_id == 1);
    CHECK(e.data.empty());
    // size promises more than the packet holds.
    check_too_short<UserData>(Bytes(user_data_bytes.begin(), user_data_bytes.end() - 1), "data");

    const json j = to_json(p);
    CHECK(keys(j) == std::set<std::string>{"port", "id", "data"});
    CHECK(j["port"] == "fp3");
    CHECK(j["data"] == json::array({1, 2, 3}));
    check_client_json<UserData>(user_data_bytes);
    check_wrong_type<UserData>(user_data_bytes, "id", "1");
    check_out_of_range<UserData>(user_data_bytes, "id", 4294967306.0);
    check_wrong_type<UserData>(user_data_bytes, "data", "abc");
    check_out_of_range<UserData>(user_data_bytes, "data", json::array({1, 256}));
    check_wrong_type<UserData>(user_data_bytes, "port", false);
    check_out_of_range<UserData>(user_data_bytes, "port", -1);
}

TEST_CASE("OrionUserData carries up to 128 bytes", "[orion][control]") {
    UserData p;
    p.data.resize(128, 0x5A);
    const Bytes wire = encode_ok(p);
    CHECK(wire.size() == UserData::max_length);
    CHECK(wire[1] == 128);
    CHECK(decode_ok<UserData>(wire).data == p.data);

    JsonError err;
    UserData q;
    CHECK_FALSE(from_json(json{{"data", json(Bytes(129, 1))}}, q, err));
    CHECK(err.code == "out_of_range");
    CHECK_THAT(err.message, Catch::Contains("data"));
    p.data.resize(129);
    Payload out;
    CHECK_FALSE(encode(p, out));
}

// --- OrionLaserCommand --------------------------------------------------------------------------

TEST_CASE("OrionLaserCommand golden bytes", "[orion][control]") {
    const LaserCmd p = golden<LaserCmd>(laser_cmd_bytes);
    CHECK(p.index == 1);
    CHECK(p.password == "abc");
    CHECK(p.enable);
    CHECK(p.arm);
    CHECK(p.fire);
    CHECK(p.on_time_ms == 100);
    CHECK(p.off_time_ms == 200);
    CHECK(p.prf_code == 1234);
    CHECK(p.safety_bypass);
    Bytes longer = laser_cmd_bytes;
    longer.push_back(0x77);
    CHECK(encode_ok(decode_ok<LaserCmd>(longer)) == laser_cmd_bytes);

    const json j = to_json(p);
    CHECK(keys(j) == std::set<std::string>{"index", "password", "enable", "arm", "fire",
                                           "on_time_ms", "off_time_ms", "prf_code",
                                           "safety_bypass"});
    CHECK(j["password"] == "abc");
    CHECK(j["fire"] == true);
    check_client_json<LaserCmd>(laser_cmd_bytes);
    check_wrong_type<LaserCmd>(laser_cmd_bytes, "on_time_ms", "100");
    check_out_of_range<LaserCmd>(laser_cmd_bytes, "on_time_ms", 65536);
    check_wrong_type<LaserCmd>(laser_cmd_bytes, "password", 123);
    check_out_of_range<LaserCmd>(laser_cmd_bytes, "password", "0123456789abcdef");
    check_wrong_type<LaserCmd>(laser_cmd_bytes, "fire", 1);
}

TEST_CASE("OrionLaserCommand minimum length and defaults", "[orion][control]") {
    const Bytes min{
        0x00, 0x00,  // 0..1  Reserved
        0x00,        // 2     Index 0
        0x00,        // 3     Password "" (terminator only)
        0x01,        // 4     Enable
        0x00,        // 5     Arm
        0x00,        // 6     Fire
        0x01, 0x00,  // 7..8  OnTime 256 ms
        0x00, 0x0A,  // 9..10 OffTime 10 ms
    };
    REQUIRE(min.size() == LaserCmd::min_length);
    const LaserCmd p = decode_ok<LaserCmd>(min);
    CHECK(p.password.empty());
    CHECK(p.enable);
    CHECK(p.on_time_ms == 256);
    CHECK(p.off_time_ms == 10);
    CHECK(p.prf_code == 0);
    CHECK_FALSE(p.safety_bypass);
    check_too_short<LaserCmd>(Bytes(min.begin(), min.end() - 1), "off_time_ms");
    // The password moves every later field: 13 bytes of the golden packet end inside OffTime.
    check_too_short<LaserCmd>(Bytes(laser_cmd_bytes.begin(), laser_cmd_bytes.begin() + 13),
                              "off_time_ms");
}

TEST_CASE("OrionLaserCommand data length is 14 + len(password)", "[orion][control]") {
    for (const std::string pw : {"", "x", "secret", "0123456789abcde"}) {
        LaserCmd p;
        JsonError err;
        REQUIRE(from_json(json{{"password", pw}, {"enable", true}, {"arm", true}, {"fire", false}},
                          p, err));
        const Bytes wire = encode_ok(p);
        CHECK(wire.size() == 14 + pw.size());
        CHECK(decode_ok<LaserCmd>(wire).password == pw);
    }
    LaserCmd p;
    JsonError err;
    CHECK_FALSE(from_json(json{{"password", "bad\x01"}}, p, err));
    CHECK(err.code == "bad_request");
}

// --- OrionLaserStates ---------------------------------------------------------------------------

TEST_CASE("OrionLaserStates golden bytes", "[orion][control]") {
    const LaserStates p = golden<LaserStates>(laser_states_bytes);
    REQUIRE(p.states.size() == 2);
    const LaserState& a = p.states[0];
    CHECK(a.type == LaserType::lightware);
    CHECK(a.enabled);
    CHECK(a.armed);
    CHECK(a.active);
    CHECK(a.ground_speed_lock);
    CHECK(a.altitude_lock);
    CHECK(a.password_lock);
    CHECK(a.ap_comm_lock);
    CHECK(a.ap_flying_lock);
    CHECK(a.bypass_enabled);
    CHECK(a.pitch_angle_lock);
    CHECK(a.wait_timer_ms == 3000);
    const LaserState& b = p.states[1];
    CHECK(b.type == LaserType::pointer);
    CHECK(b.enabled);
    CHECK_FALSE(b.armed);
    CHECK(b.active);
    CHECK_FALSE(b.ground_speed_lock);
    CHECK(b.altitude_lock);
    CHECK_FALSE(b.password_lock);
    CHECK(b.ap_comm_lock);
    CHECK_FALSE(b.ap_flying_lock);
    CHECK_FALSE(b.bypass_enabled);
    CHECK(b.pitch_angle_lock);
    CHECK(b.wait_timer_ms == 1);
    check_lengths<LaserStates>(laser_states_bytes, "num_lasers");

    const json j = to_json(p);
    CHECK(keys(j) == std::set<std::string>{"states"});
    CHECK(keys(j["states"][0]) ==
          std::set<std::string>{"type", "enabled", "armed", "active", "ground_speed_lock",
                                "altitude_lock", "password_lock", "ap_comm_lock", "ap_flying_lock",
                                "bypass_enabled", "pitch_angle_lock", "wait_timer_ms"});
    CHECK(j["states"][0]["type"] == "lightware");
    CHECK(j["states"][1]["armed"] == false);
    CHECK(j["states"][1]["pitch_angle_lock"] == true);
}

TEST_CASE("OrionLaserStates: count, reserved bits and truncation", "[orion][control]") {
    const LaserStates none = decode_ok<LaserStates>(Bytes{0x00});
    CHECK(none.states.empty());
    CHECK(encode_ok(none) == Bytes{0x00});
    // The 14 reserved bits that cross bytes 3 and 4 are ignored on decode, zero on encode.
    Bytes noisy = laser_states_bytes;
    noisy[3] |= 0x3F;
    noisy[4] = 0xFF;
    const LaserStates n = decode_ok<LaserStates>(noisy);
    CHECK(n.states[0].pitch_angle_lock);
    CHECK(n.states[0].wait_timer_ms == 3000);
    CHECK(encode_ok(n) == laser_states_bytes);
    // NumLasers promises two states, the second is cut short.
    check_too_short<LaserStates>(Bytes(laser_states_bytes.begin(), laser_states_bytes.end() - 1),
                                 "wait_timer_ms");
    // More than MAX_LASERS: only the first two are read; the encoder refuses three.
    Bytes three = laser_states_bytes;
    three[0] = 3;
    CHECK(decode_ok<LaserStates>(three).states.size() == 2);
    LaserStates too_many;
    too_many.states.resize(3);
    Payload out;
    CHECK_FALSE(encode(too_many, out));
}

// --- across the section -------------------------------------------------------------------------

TEST_CASE("control packets are registered under their ICD ids", "[orion][control]") {
    for_each_packet_in(ControlPackets{}, []<class P>() {
        INFO(P::name);
        std::string_view found;
        CHECK(dispatch(P::id, [&]<class Q>() { found = Q::name; }));
        CHECK(found == P::name);  // no other packet claims this id
        std::uint8_t id = 0;
        CHECK(packet_id(P::name, id));
        CHECK(id == P::id);
        CHECK(P::min_length <= P::max_length);
        CHECK(P::max_length <= max_data_length);
    });
    CHECK(packet_name(pkt::startup_cmd) == "startup_cmd");
    CHECK(packet_name(pkt::laser_states) == "laser_states");
    CHECK(packet_name(pkt::retract_cmd) == "retract_cmd");
}

TEST_CASE("control packets survive framing", "[orion][control][framer]") {
    Path path;
    path.points.resize(15);
    for (std::size_t i = 0; i < 15; ++i)
        path.points[i].pos_ecef = {-2500000.0 + static_cast<double>(i), 4000000.0, -8388607.0};
    path.num_cross_track_steps = 15;
    path.along_track_step_angle = 0.25;
    const LaserStates states = decode_ok<LaserStates>(laser_states_bytes);

    Bytes stream = to_wire(path);
    REQUIRE(stream.size() == header_size + 140 + checksum_size);
    stream.push_back(sync0);  // a stray sync byte between packets
    const Bytes second = frame_bytes(LaserStates::id, laser_states_bytes);
    stream.insert(stream.end(), second.begin(), second.end());
    CHECK(second == to_wire(states));

    Framer framer;
    std::vector<Frame> frames;
    // Split at an awkward place to make the framer hold a partial frame.
    framer.push({stream.data(), 77}, [&](const Frame& f) { frames.push_back(f); });
    framer.push({stream.data() + 77, stream.size() - 77},
                [&](const Frame& f) { frames.push_back(f); });
    REQUIRE(frames.size() == 2);
    CHECK(frames[0].id == Path::id);
    const Path path_back = decode_ok<Path>(Bytes(frames[0].data().begin(), frames[0].data().end()));
    CHECK(encode_ok(path_back) == encode_ok(path));
    REQUIRE(path_back.points.size() == 15);
    CHECK(path_back.points[14].pos_ecef[0] == -2500000.0 + 14);
    CHECK(path_back.points[14].pos_ecef[2] == -8388607.0);
    CHECK(path_back.num_cross_track_steps == 15);
    CHECK(path_back.along_track_step_angle == Approx(0.25).epsilon(1e-4));
    CHECK(frames[1].id == LaserStates::id);
    CHECK(Bytes(frames[1].data().begin(), frames[1].data().end()) == laser_states_bytes);
}

// Integer fields have exact JSON bounds: a tolerance scaled by the range (4.3 for a U32) once
// let -1 and 2^32 through, to be converted to uint32_t out of range.
TEST_CASE("U32 JSON range is exact", "[orion][control]") {
    StareAck p;
    JsonError err;
    CHECK_FALSE(from_json(json{{"echo_system_time_ms", -1}}, p, err));
    CHECK_FALSE(from_json(json{{"echo_system_time_ms", 4294967296.0}}, p, err));
}
