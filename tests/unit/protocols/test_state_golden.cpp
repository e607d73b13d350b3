// STATE's JSON is what every client sees, so the typed STATE must write it byte for byte as
// the JSON-built STATE did. The golden files (golden/state_<protocol>.jsonl) were written by
// the JSON-built state models, before STATE was typed, from the same bytes this test feeds
// each protocol's session now: its simulated gimbal answering the session for some seconds
// (steered from a circling aircraft), then frames with pseudo-random contents - every packet
// kind, every shape of number, text and flag - with a snapshot (compact JSON, one a line) at
// fixed times. GIMBAL_WRITE_GOLDEN=1 writes the files instead of comparing.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "../vehicle/vehicle_fixtures.hpp"
#include "geo/sampled_surface.hpp"
#include "mavlink/framing.hpp"
#include "protocols/orion/codec/framing.hpp"
#include "protocols/orion/codec/packets.hpp"
#include "protocols/registry.hpp"
#include "protocols/viewpro/codec/output.hpp"

using namespace gimbal;
using nlohmann::json;
using protocols::Entry;

namespace {

using Bytes = std::vector<std::uint8_t>;

std::string golden_path(std::string_view protocol) {
    return std::string(GIMBAL_SOURCE_DIR) + "/tests/unit/protocols/golden/state_" +
           std::string(protocol) + ".jsonl";
}

// The aircraft circling 1 km around a point east of the Columbia river gorge at 500 m MSL.
void report_vehicle(vehicle::VehicleState& v, double now_s) {
    using vehicle_fixtures::from;
    mavlink::Heartbeat hb;
    hb.system_status = static_cast<std::uint8_t>(mavlink::MavState::active);
    v.apply(from(1, hb), now_s);
    const double a = now_s * 0.03;
    mavlink::Attitude att;
    att.roll = 0.2f;
    att.pitch = 0.05f;
    att.yaw = static_cast<float>(a + 1.5707963);
    v.apply(from(1, att), now_s);
    mavlink::GlobalPositionInt p;
    p.lat = static_cast<std::int32_t>(std::lround((45.7 + 0.009 * std::sin(a)) * 1e7));
    p.lon = static_cast<std::int32_t>(std::lround((-121.5 + 0.0128 * std::cos(a)) * 1e7));
    p.alt = 500000;
    p.relative_alt = 400000;
    p.hdg = static_cast<std::uint16_t>(std::fmod(a * 5729.578 + 9000, 36000));
    v.apply(from(1, p), now_s);
}

class Recorder {
  public:
    Recorder(const Entry& e, protocols::SessionSettings settings, json gimbal)
        : session_(e.make_session(settings, gimbal)), vehicle_(vehicle_fixtures::options()) {}

    session::Protocol& session() { return *session_; }

    // The simulated gimbal and the session talk for `seconds` from `start_s`, a snapshot every
    // `every_s` (0.125 s after the tick: ages show).
    void simulate(sim::Device& device, double start_s, double seconds, double every_s) {
        for (const auto& bytes : session_->on_connect()) device.receive(bytes, start_s);
        int step = 0;
        const int snapshot_every = static_cast<int>(std::lround(every_s / 0.05));
        for (double t = start_s + 0.05; t <= start_s + seconds + 1e-9; t += 0.05, ++step) {
            Bytes out;
            device.advance(t, out);
            feed(out, t);
            report_vehicle(vehicle_, t);
            std::vector<session::Bytes> steering;
            session_->steer(vehicle_, t, t, steering);
            for (const auto& b : steering) device.receive(b, t);
            std::vector<state::Event> events;
            session_->tick(t, events);
            if (step % snapshot_every == snapshot_every - 1) snapshot(t + 0.125);
        }
    }

    void feed(const Bytes& bytes, double now_s) {
        std::vector<state::Event> events;
        std::vector<session::Bytes> replies;
        session_->receive(bytes, now_s, events, replies);
    }

    void snapshot(double now_s) { lines_.push_back(session_->snapshot(now_s).dump()); }

    void check(std::string_view protocol) const {
        const std::string path = golden_path(protocol);
        if (std::getenv("GIMBAL_WRITE_GOLDEN")) {
            std::ofstream out(path);
            for (const auto& line : lines_) out << line << '\n';
            WARN("wrote " << path);
            return;
        }
        std::ifstream in(path);
        REQUIRE(in);
        std::vector<std::string> golden;
        for (std::string line; std::getline(in, line);) golden.push_back(line);
        REQUIRE(lines_.size() == golden.size());
        for (std::size_t i = 0; i < golden.size(); ++i) {
            INFO(protocol << " snapshot " << i);
            CHECK(lines_[i] == golden[i]);
        }
    }

  private:
    std::unique_ptr<session::Protocol> session_;
    vehicle::VehicleState vehicle_;
    std::vector<std::string> lines_;
};

// Reproducible pseudo-random bytes (mt19937's sequence is fixed by the standard).
class Noise {
  public:
    explicit Noise(std::uint32_t seed) : rng_(seed) {}
    std::uint8_t byte() { return static_cast<std::uint8_t>(rng_() >> 24); }
    std::uint32_t below(std::uint32_t n) { return static_cast<std::uint32_t>(rng_() % n); }
    double uniform(double lo, double hi) {
        return lo + (hi - lo) * (static_cast<double>(rng_()) / 4294967296.0);
    }
    float any_float() {
        switch (below(8)) {
            case 0:
                return std::numeric_limits<float>::quiet_NaN();
            case 1:
                return std::numeric_limits<float>::infinity();
            case 2:
                return below(2) ? std::numeric_limits<float>::max() : -1e30f;
            default:
                return static_cast<float>(uniform(-7, 7));
        }
    }

  private:
    std::mt19937 rng_;
};

template <std::size_t N>
void name(std::array<std::uint8_t, N>& out, Noise& noise) {
    const std::size_t n = noise.below(N + 1);
    for (std::size_t i = 0; i < N; ++i) out[i] = i < n ? noise.byte() : 0;
}

protocols::SimScenario scenario() {
    protocols::SimScenario s;
    s.unix_time_s = 1'790'000'000.0;
    s.seed = 7;
    return s;
}

}  // namespace

TEST_CASE("STATE golden: an Orion's keys, byte for byte") {
    const Entry& e = *protocols::find("orion");
    // A slope rising north under the west of the view: the ground on terrain, the footprint's
    // corners leaving it (so on the flat world) - and neither for the random telemetry.
    geo::SampledSurface plateau([](double lat, double) { return 60.0 + 1400.0 * (lat - 45.0); },
                                geo::Lattice{}, 1500.0,
                                geo::GeoRect{44.0, 46.0, -123.0, -121.4805});
    protocols::SessionSettings settings;
    settings.terrain = &plateau;
    Recorder r(e, settings, {{"name", "g"}, {"protocol", "orion"}, {"link", {{"type", "sim"}}}});
    auto device = e.simulator.make(scenario());
    r.simulate(*device, 0.0, 6.0, 1.0);

    // Every packet kind with pseudo-random payloads of every allowed length class.
    Noise noise(2604);
    double t = 10.0;
    orion::for_each_packet([&]<class P>() {
        for (int k = 0; k < 3; ++k) {
            const std::size_t span = P::max_length - P::min_length;
            const std::size_t n = P::min_length + (span ? noise.below(span + 1) : 0);
            Bytes payload(n);
            for (auto& b : payload) b = noise.byte();
            r.feed(orion::frame_bytes(P::id, payload), t);
            t += 0.01;
        }
        if (P::id % 8 == 0) r.snapshot(t + 0.5);
    });
    r.snapshot(t);
    r.snapshot(t + 3.0);  // stale
    r.check("orion");
}

TEST_CASE("STATE golden: a Viewpro's keys, byte for byte") {
    const Entry& e = *protocols::find("viewpro");
    Recorder r(e, {}, {{"name", "g"}, {"protocol", "viewpro"}, {"link", {{"type", "sim"}}}});
    r.snapshot(0.0);  // nothing yet
    auto device = e.simulator.make(scenario());
    r.simulate(*device, 0.0, 4.0, 1.0);

    Noise noise(2605);
    double t = 10.0;
    for (int k = 0; k < 40; ++k) {
        viewpro::Output o;
        o.format = static_cast<viewpro::OutFormat>(noise.below(4));
        const auto maybe = [&](double lo, double hi) -> std::optional<double> {
            if (noise.below(5) == 0) return std::nullopt;
            return noise.uniform(lo, hi);
        };
        o.gimbal_roll_deg = maybe(-180, 180);
        o.gimbal_pitch_deg = maybe(-90, 90);
        o.gimbal_yaw_deg = maybe(-180, 180);
        o.lrf_m = maybe(0, 5000);
        o.uav_roll_deg = maybe(-90, 90);
        o.uav_pitch_deg = maybe(-90, 90);
        o.uav_yaw_deg = maybe(-180, 180);
        o.uav_lat_deg = maybe(-90, 90);
        o.uav_lon_deg = maybe(-180, 180);
        o.uav_alt_msl_m = maybe(-500, 9000);
        o.target_lat_deg = maybe(-90, 90);
        o.target_lon_deg = maybe(-180, 180);
        o.target_alt_msl_m = maybe(-500, 9000);
        if (noise.below(3)) o.zoom = static_cast<std::uint16_t>(noise.below(65536));
        r.feed(viewpro::encode_output(o), t);
        if (k % 5 == 4) r.snapshot(t + 0.3);
        t += 0.02;
    }
    r.snapshot(t + 3.0);  // stale
    r.check("viewpro");
}

TEST_CASE("STATE golden: a MAVLink gimbal device's keys, byte for byte") {
    const Entry& e = *protocols::find("mavlink");
    protocols::SessionSettings settings;
    settings.geoid_undulation = [](double lat, double lon) -> std::optional<double> {
        return -20.0 + 0.5 * (lat - 45.0) + 0.25 * (lon + 121.0);
    };
    Recorder r(e, settings, {{"name", "g"}, {"protocol", "mavlink"}, {"link", {{"type", "sim"}}}});
    r.snapshot(0.0);  // nothing yet
    auto device = e.simulator.make(scenario());
    r.simulate(*device, 0.0, 6.0, 1.0);

    Noise noise(2606);
    double t = 10.0;
    for (int k = 0; k < 40; ++k) {
        if (k % 4 == 0) {
            mavlink::GimbalDeviceInformation info;
            name(info.vendor_name, noise);
            name(info.model_name, noise);
            info.firmware_version = noise.below(2) ? noise.below(256) * 0x01010101u : 0x00020304u;
            info.cap_flags = static_cast<std::uint16_t>(noise.below(65536));
            info.roll_min = noise.any_float();
            info.roll_max = noise.any_float();
            info.pitch_min = noise.any_float();
            info.pitch_max = noise.any_float();
            info.yaw_min = noise.any_float();
            info.yaw_max = noise.any_float();
            r.feed(mavlink::encode_v2(info, 7, 154, static_cast<std::uint8_t>(k)), t);
        } else {
            mavlink::GimbalDeviceAttitudeStatus s;
            for (auto& c : s.q)
                c = noise.below(6) ? static_cast<float>(noise.uniform(-1, 1)) : noise.any_float();
            s.angular_velocity_x = noise.any_float();
            s.angular_velocity_y = noise.any_float();
            s.angular_velocity_z = noise.any_float();
            s.flags = static_cast<std::uint16_t>(noise.below(128));
            s.failure_flags = noise.below(8192);
            s.time_boot_ms = noise.below(1u << 30);
            r.feed(mavlink::encode_v2(s, 7, 154, static_cast<std::uint8_t>(k)), t);
        }
        if (k % 5 == 4) r.snapshot(t + 0.3);
        t += 0.02;
    }
    r.snapshot(t + 3.0);  // stale
    r.check("mavlink");
}
