// The simulated Viewpro through its Device interface, as the daemon drives it: bytes in,
// bytes out, time passed in.
#include <catch2/catch.hpp>
#include <cmath>
#include <memory>

#include "geo/wgs84.hpp"
#include "protocols/viewpro/codec/viewpro.hpp"
#include "protocols/viewpro/sim/viewpro_sim.hpp"

using namespace gimbal;
using Catch::Matchers::WithinAbs;
using Bytes = std::vector<std::uint8_t>;

namespace {

class Harness {
  public:
    explicit Harness(const sim::ViewproSimOptions& options = {})
        : device_(sim::make_viewpro_sim(options)) {
        run(0);  // the device counts from its first call
    }

    // Advances `seconds` of simulated time in `step` increments; returns the frames sent.
    std::vector<viewpro::OutputFrame> run(double seconds, double step = 0.02) {
        std::vector<viewpro::OutputFrame> frames;
        const double end = now_ + seconds;
        do {
            now_ = std::min(end, now_ + step);
            Bytes out;
            device_->advance(now_, out);
            raw_.insert(raw_.end(), out.begin(), out.end());
            framer_.push(out, [&](const viewpro::OutputFrame& f) { frames.push_back(f); });
        } while (now_ < end);
        return frames;
    }
    // Decoded frames of the next `seconds`.
    std::vector<viewpro::Output> outputs(double seconds) {
        std::vector<viewpro::Output> out;
        for (const auto& f : run(seconds)) {
            const auto o = viewpro::decode_output(f);
            REQUIRE(o);
            out.push_back(*o);
        }
        return out;
    }
    viewpro::Output next_output() {
        const auto o = outputs(0.1);
        REQUIRE(o.size() == 1);
        return o[0];
    }

    void send(std::span<const std::uint8_t> bytes) { device_->receive(bytes, now_); }
    template <std::size_t N>
    void send(const std::array<std::uint8_t, N>& bytes) {
        send(std::span<const std::uint8_t>(bytes));
    }
    void send(const Bytes& bytes) { send(std::span<const std::uint8_t>(bytes)); }
    void set_mode(viewpro::OutFormat format, bool serial = true, bool network = false) {
        viewpro::Mode m;
        m.format = format;
        m.serial = serial;
        m.network = network;
        send(viewpro::encode_mode(m));
    }

    double now() const { return now_; }
    const Bytes& raw() const { return raw_; }
    const viewpro::FramerStats& framer_stats() const { return framer_.stats(); }

  private:
    std::unique_ptr<sim::Device> device_;
    viewpro::OutputFramer framer_;
    double now_ = 5000.0;  // any epoch
    Bytes raw_;
};

geo::LookAngles look_at_target(const viewpro::Output& o) {
    return geo::look_angles({*o.uav_lat_deg, *o.uav_lon_deg, *o.uav_alt_msl_m},
                            {*o.target_lat_deg, *o.target_lon_deg, o.target_alt_msl_m.value_or(0)});
}

viewpro::VehicleInput vehicle_east_of_zurich() {
    viewpro::VehicleInput v;
    v.time = {2024, 7, 1, 12, 0, 0};
    v.lat_deg = 47.3977419;
    v.lon_deg = 8.5455938;
    v.alt_msl_m = 600;
    v.yaw_deg = 90;
    v.vel_ned_mps = std::array<double, 3>{0, 20, 0};
    return v;
}

}  // namespace

TEST_CASE("the gimbal is silent until a mode command enables serial output",
          "[sim][viewpro][mode]") {
    Harness h;
    CHECK(h.run(5).empty());
    CHECK(h.raw().empty());
    h.set_mode(viewpro::OutFormat::out3);
    const auto frames = h.run(10 - 0.001);  // ticks at 0.1 s steps after the command
    CHECK(frames.size() == 99);
    for (const auto& f : frames) CHECK(f.format == viewpro::OutFormat::out3);
    CHECK(h.framer_stats().dropped_bytes == 0);
    CHECK(h.framer_stats().bad_checksums == 0);
}

TEST_CASE("output comes at 10 Hz on the model clock", "[sim][viewpro][rates]") {
    Harness h;
    h.set_mode(viewpro::OutFormat::out1);
    h.run(0.05);
    // However the caller's calls fall, 30 s give 300 frames.
    CHECK(h.run(30, 0.013).size() == 300);
    CHECK(h.run(30, 0.25).size() == 300);
    CHECK(h.run(30, 1.7).size() == 300);
}

TEST_CASE("the mode byte selects the format; network-only or no output is silence",
          "[sim][viewpro][mode]") {
    Harness h;
    using F = viewpro::OutFormat;
    for (const F f : {F::out1, F::out2, F::out3, F::out4}) {
        h.set_mode(f);
        const auto frames = h.run(1);
        CAPTURE(viewpro::to_string(f));
        REQUIRE(frames.size() == 10);
        for (const auto& fr : frames) {
            CHECK(fr.format == f);
            CHECK(fr.size == viewpro::output_size(f));
            CHECK(viewpro::decode_output(fr));
        }
    }
    h.set_mode(F::out4, false, true);  // RJ45 only: this port says nothing
    CHECK(h.run(2).empty());
    h.send(viewpro::encode_mode(viewpro::decode_mode_byte(0x79)));  // example 1.5: both
    CHECK(h.run(1).size() == 10);
    h.send(viewpro::encode_mode(viewpro::decode_mode_byte(viewpro::gimbal_default_mode_byte)));
    CHECK(h.run(2).empty());
}

TEST_CASE("a mode byte with an undefined OUT format is ignored", "[sim][viewpro][mode]") {
    Harness h;
    h.set_mode(viewpro::OutFormat::out2);
    h.send(Bytes{0xAA, 0x55, 0x0F, 0x91, 0xFF});  // format 4, serial
    const auto frames = h.run(1);
    REQUIRE(frames.size() == 10);
    CHECK(frames.back().format == viewpro::OutFormat::out2);
}

TEST_CASE("before any vehicle input the target is computed from the options",
          "[sim][viewpro][target]") {
    sim::ViewproSimOptions o;  // 300 m MSL, terrain 0, level, heading 0, gimbal pitch -45
    Harness h(o);
    h.set_mode(viewpro::OutFormat::out4);
    const auto out = h.next_output();
    CHECK_THAT(*out.uav_lat_deg, WithinAbs(o.lat_deg, 1e-7));
    CHECK_THAT(*out.uav_lon_deg, WithinAbs(o.lon_deg, 1e-7));
    CHECK_THAT(*out.uav_alt_msl_m, WithinAbs(300, 1e-3));
    CHECK_THAT(*out.gimbal_pitch_deg, WithinAbs(-45, 1e-3));
    CHECK_THAT(*out.gimbal_yaw_deg, WithinAbs(0, 1e-3));
    CHECK_THAT(*out.target_alt_msl_m, WithinAbs(0, 0.01));
    const auto look = look_at_target(out);
    CHECK_THAT(look.azimuth_deg, WithinAbs(0, 0.05));
    CHECK_THAT(look.elevation_deg, WithinAbs(-45, 0.05));
    CHECK_THAT(*out.lrf_m, WithinAbs(look.range_m, 0.05));  // degE7 costs ~1 cm
}

TEST_CASE("IN2 moves the vehicle, and the target with it", "[sim][viewpro][in2][target]") {
    Harness h;
    h.set_mode(viewpro::OutFormat::out3);
    const auto before = h.next_output();
    const auto v = vehicle_east_of_zurich();
    h.send(viewpro::encode_vehicle(v));
    const auto after = h.next_output();

    CHECK_THAT(*after.uav_lat_deg, WithinAbs(v.lat_deg, 1e-7));
    CHECK_THAT(*after.uav_lon_deg, WithinAbs(v.lon_deg, 1e-7));
    CHECK_THAT(*after.uav_alt_msl_m, WithinAbs(600, 1e-3));
    CHECK_THAT(*after.uav_yaw_deg, WithinAbs(90, 1e-4));
    CHECK(std::abs(*after.target_lat_deg - *before.target_lat_deg) > 1);  // it moved
    // OUT3 has no target altitude: the terrain is at 0 MSL.
    const auto look = look_at_target(after);
    CHECK_THAT(look.azimuth_deg, WithinAbs(90, 0.05));  // gimbal yaw 0 = the heading
    CHECK_THAT(look.elevation_deg, WithinAbs(-45, 0.05));
    CHECK_THAT(look.range_m, WithinAbs(600 * std::sqrt(2.0), 1.0));
    // The gimbal's clock follows the frame's time.
    CHECK(after.time == viewpro::DateTime{2024, 7, 1, 12, 0, 0});
    h.run(2.0);
    CHECK(h.next_output().time == viewpro::DateTime{2024, 7, 1, 12, 0, 2});
}

TEST_CASE("IN1 attitude turns the line of sight", "[sim][viewpro][in1][target]") {
    Harness h;
    h.set_mode(viewpro::OutFormat::out2);
    auto v = vehicle_east_of_zurich();
    v.vel_ned_mps.reset();
    v.pitch_deg = 10;  // nose up: the forward line of sight rises by as much
    h.send(viewpro::encode_vehicle(v));
    const auto out = h.next_output();
    CHECK_THAT(*out.uav_pitch_deg, WithinAbs(10, 1e-4));
    CHECK_THAT(look_at_target(out).elevation_deg, WithinAbs(-35, 0.05));
    CHECK_THAT(look_at_target(out).azimuth_deg, WithinAbs(90, 0.05));
}

TEST_CASE("shift commands move the calculated point, not the reported angles",
          "[sim][viewpro][shift]") {
    Harness h;
    h.set_mode(viewpro::OutFormat::out4);
    h.send(viewpro::encode_vehicle(vehicle_east_of_zurich()));
    const auto base = look_at_target(h.next_output());
    for (int i = 0; i < 5; ++i) h.send(viewpro::encode_yaw_shift(100));  // 5 x 1 deg right
    h.send(viewpro::encode_pitch_shift(-100));                           // 1 deg down
    const auto out = h.next_output();
    CHECK_THAT(*out.gimbal_yaw_deg, WithinAbs(0, 1e-3));
    CHECK_THAT(*out.gimbal_pitch_deg, WithinAbs(-45, 1e-3));
    const auto shifted = look_at_target(out);
    CHECK_THAT(shifted.azimuth_deg, WithinAbs(base.azimuth_deg + 5, 0.05));
    CHECK_THAT(shifted.elevation_deg, WithinAbs(base.elevation_deg - 1, 0.05));
    // And back.
    for (int i = 0; i < 5; ++i) h.send(viewpro::encode_yaw_shift(-100));
    h.send(viewpro::encode_pitch_shift(100));
    CHECK_THAT(look_at_target(h.next_output()).azimuth_deg, WithinAbs(base.azimuth_deg, 0.05));
}

TEST_CASE("IN3's laser distance sets the range until IN1/IN2 replaces it", "[sim][viewpro][in3]") {
    Harness h;
    h.set_mode(viewpro::OutFormat::out4);
    viewpro::In3 in3;
    in3.time = {2023, 11, 2, 7, 8, 9};
    in3.lrf_m = 250;
    in3.yaw_deg = -90;
    in3.lat_deg = 47.0;
    in3.lon_deg = 8.0;
    in3.alt_msl_m = 300;
    h.send(viewpro::encode_in3(in3));
    const auto out = h.next_output();
    CHECK_THAT(*out.lrf_m, WithinAbs(250, 1e-3));
    CHECK_THAT(*out.target_alt_msl_m, WithinAbs(300 - 250 / std::sqrt(2.0), 0.01));
    CHECK_THAT(look_at_target(out).azimuth_deg, WithinAbs(-90, 0.05));
    CHECK(out.time == viewpro::DateTime{2023, 11, 2, 7, 8, 9});

    h.send(viewpro::encode_vehicle(vehicle_east_of_zurich()));
    const auto back = h.next_output();
    CHECK_THAT(*back.lrf_m, WithinAbs(600 * std::sqrt(2.0), 1.0));  // the terrain again
}

TEST_CASE("looking above the horizon gives no target", "[sim][viewpro][target]") {
    sim::ViewproSimOptions o;
    o.gimbal_pitch_deg = 10;
    Harness h(o);
    h.set_mode(viewpro::OutFormat::out4);
    const auto out = h.next_output();
    CHECK(*out.target_lat_deg == 0);
    CHECK(*out.target_lon_deg == 0);
    CHECK(*out.lrf_m == 0);
}

TEST_CASE("without a laser the LRF field is zero but the target is still computed",
          "[sim][viewpro][target]") {
    sim::ViewproSimOptions o;
    o.has_laser = false;
    Harness h(o);
    h.set_mode(viewpro::OutFormat::out3);
    const auto out = h.next_output();
    CHECK(*out.lrf_m == 0);
    CHECK_THAT(look_at_target(out).elevation_deg, WithinAbs(-45, 0.05));
}

TEST_CASE("the gimbal yaw sweeps at the configured rate", "[sim][viewpro][options]") {
    sim::ViewproSimOptions o;
    o.gimbal_yaw_rate_dps = 10;
    o.gimbal_pitch_deg = -30;
    o.zoom_position = 777;
    Harness h(o);
    h.set_mode(viewpro::OutFormat::out4);
    const auto outs = h.outputs(2.0);
    REQUIRE(outs.size() == 20);
    CHECK_THAT(*outs[0].gimbal_yaw_deg - 1.0, WithinAbs(0, 1e-3));  // the tick at 0.1 s
    CHECK_THAT(*outs[19].gimbal_yaw_deg, WithinAbs(20, 1e-3));
    CHECK(*outs[0].zoom == 777);
    CHECK_THAT(*outs[0].gimbal_pitch_deg, WithinAbs(-30, 1e-3));
}

TEST_CASE("the clock starts at the configured UTC", "[sim][viewpro][time]") {
    sim::ViewproSimOptions o;
    o.unix_time_at_start_s = 1735689600.0 + 59.5;  // 2025-01-01T00:00:59.5Z
    Harness h(o);
    h.set_mode(viewpro::OutFormat::out2);
    const auto outs = h.outputs(1.0);
    REQUIRE(outs.size() == 10);
    CHECK(outs[0].time == viewpro::DateTime{2025, 1, 1, 0, 0, 59});  // 59.6
    CHECK(outs[9].time == viewpro::DateTime{2025, 1, 1, 0, 1, 0});   // 60.5
}

TEST_CASE("input arrives in any chunking, among junk", "[sim][viewpro][robustness]") {
    Harness h;
    Bytes stream{0x00, 0xAA, 0x55, 0xF9};
    const auto mode = viewpro::encode_mode(viewpro::Mode{});
    stream.insert(stream.end(), mode.begin(), mode.end());
    const auto in2 = viewpro::encode_vehicle(vehicle_east_of_zurich());
    stream.push_back(0xFE);
    stream.insert(stream.end(), in2.begin(), in2.end());
    for (const auto b : stream) h.send(Bytes{b});
    const auto out = h.next_output();
    CHECK(out.format == viewpro::OutFormat::out3);
    CHECK_THAT(*out.uav_lat_deg, WithinAbs(47.3977419, 1e-7));
}

TEST_CASE("same seed, same bytes; time never runs backwards", "[sim][viewpro][determinism]") {
    sim::ViewproSimOptions o;
    o.angle_noise_deg = 0.2;
    o.seed = 42;
    auto bytes_of = [&](std::uint32_t seed) {
        o.seed = seed;
        Harness h(o);
        h.set_mode(viewpro::OutFormat::out3);
        h.run(3);
        return h.raw();
    };
    const Bytes a = bytes_of(42);
    CHECK(a.size() == 30 * viewpro::out3_size);  // ticks 0.1 .. 3.0 (the mode came after tick 0)
    CHECK(bytes_of(42) == a);
    CHECK(bytes_of(43) != a);

    auto device = sim::make_viewpro_sim();
    device->receive(viewpro::encode_mode(viewpro::Mode{}), 100.0);
    Bytes out;
    device->advance(101.0, out);
    CHECK(out.size() == 10 * viewpro::out3_size);
    out.clear();
    device->advance(50.0, out);  // earlier: nothing happens
    CHECK(out.empty());
    device->advance(101.05, out);
    CHECK(out.empty());
    device->advance(101.1, out);
    CHECK(out.size() == viewpro::out3_size);
    // A caller gone for an hour gets at most the last minute of output.
    out.clear();
    device->advance(101.1 + 3600, out);
    CHECK(out.size() <= 601 * viewpro::out3_size);
    CHECK(out.size() >= 599 * viewpro::out3_size);
}
