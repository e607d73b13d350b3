// The simulated SIYI camera's view (what gimbal-sim --video renders and its KLV says) against
// what gimbald derives from the same camera: a geopoint gimbald aims at is at the picture's
// centre, and the view's position is the aircraft's as the vehicle feed told the camera.
#include <catch2/catch.hpp>
#include <cmath>

#include "../vehicle/vehicle_fixtures.hpp"
#include "geo/image.hpp"
#include "protocols/siyi/codec/codec.hpp"
#include "protocols/siyi/sim/siyi_sim_camera.hpp"
#include "protocols/siyi/siyi_protocol.hpp"

using namespace gimbal;
using namespace gimbal::protocols;

namespace {

constexpr double deg = 3.14159265358979323846 / 180.0;

// gimbald's session and the simulated camera, each feeding the other every 50 ms.
struct Loop {
    Loop() {
        for (const auto& b : proto.on_connect()) sim.receive(b, t);
    }
    void run(double seconds, const vehicle::VehicleState& vehicle) {
        const double end = t + seconds;
        while (t < end - 1e-9) {
            t += 0.05;
            std::vector<std::uint8_t> up;
            sim.advance(t, up);
            std::vector<session::Bytes> replies;
            proto.receive(up, t, events, replies);
            proto.steer(vehicle, t, t, replies);
            for (const auto& b : replies) sim.receive(b, t);
        }
    }
    static SiyiOptions options() {
        SiyiOptions o;
        o.geoid_undulation_m = 20;
        return o;
    }
    double t = 1.0;
    SiyiProtocol proto{options()};
    SiyiSim sim{SiyiSimOptions{}};
    std::vector<state::Event> events;
};

}  // namespace

TEST_CASE("sim camera: a point gimbald aims at is at the picture's centre", "[siyi][sim][video]") {
    Loop loop;
    vehicle::VehicleState vehicle(vehicle_fixtures::options(std::nullopt, 1e9));
    vehicle_fixtures::fix_at(vehicle, loop.t, 45.7, -121.5, 1500);
    // Heading 30 degrees, nose 5 up, rolled 10 right: the camera's pitch ignores them (its
    // pitch is stabilized), its yaw turns with the nose.
    mavlink::Attitude attitude;
    attitude.roll = static_cast<float>(10 * deg);
    attitude.pitch = static_cast<float>(5 * deg);
    attitude.yaw = static_cast<float>(30 * deg);
    vehicle.apply(vehicle_fixtures::from(1, attitude), loop.t);

    loop.run(0.5, vehicle);  // the camera's identity and attitude, the aircraft's fix

    command::Plan plan;
    const nlohmann::json request = {{"lat", 45.69}, {"lon", -121.52}, {"alt", 300}};
    REQUIRE_FALSE(loop.proto.plan("geopoint", request, {loop.t, 0}, plan));
    for (const auto& p : plan.packets) loop.sim.receive(p.frame, loop.t);
    loop.run(5.0, vehicle);

    const sim::CameraView view = siyi_camera_view(loop.sim);
    // Where the vehicle feed put the aircraft: MSL 1500, the ellipsoid 20 m above the geoid.
    CHECK(view.pose.position.lat_deg == Approx(45.7).margin(1e-7));
    CHECK(view.pose.position.lon_deg == Approx(-121.5).margin(1e-7));
    CHECK(view.pose.position.alt_m == Approx(1520).margin(0.01));
    CHECK(view.geoid_undulation_m == Approx(20).margin(0.01));
    const auto zoom1 = siyi::field_of_view(siyi::Model::zt30, 1);
    CHECK(view.pose.hfov_deg == Approx(zoom1.hfov_deg));
    CHECK(view.pose.vfov_deg == Approx(zoom1.vfov_deg));

    const auto seen = geo::project(view.pose, geo::Lla{45.69, -121.52, 300});
    REQUIRE(seen);
    CHECK(seen->visible);
    CHECK(seen->at.x == Approx(0).margin(0.01));
    CHECK(seen->at.y == Approx(0).margin(0.01));

    // The picture's centre is where gimbald says the line of sight meets the ground.
    const auto* t = loop.proto.telemetry();
    REQUIRE(t);
    REQUIRE(t->lat);
    CHECK(*t->lat == Approx(view.pose.position.lat_deg).margin(1e-7));
    CHECK(*t->alt == Approx(view.pose.position.alt_m).margin(0.01));

    // The platform is the aircraft: heading 30.
    const geo::EulerDeg platform = geo::quat_to_euler(view.platform_to_ned);
    CHECK(platform.yaw_deg == Approx(30).margin(0.01));
    CHECK(platform.roll_deg == Approx(10).margin(0.01));
}

TEST_CASE("sim camera: without the vehicle feed it sees from the options' position",
          "[siyi][sim][video]") {
    SiyiSimOptions o;
    o.lat_deg = 45.71;
    o.lon_deg = -121.48;
    o.alt_msl_m = 1200;
    o.geoid_undulation_m = -21;
    o.pitch_deg = -30;
    o.yaw_deg = 40;  // 40 degrees LEFT of the nose: bearing 320
    o.zoom = 4;
    SiyiSim sim(o);
    std::vector<std::uint8_t> out;
    sim.advance(2.0, out);
    const auto view = siyi_sim_camera(sim);
    REQUIRE(view);
    CHECK(view->model_time_s == 2.0);
    CHECK(view->pose.position.lat_deg == 45.71);
    CHECK(view->pose.position.alt_m == Approx(1179));
    CHECK(view->geoid_undulation_m == Approx(-21));
    CHECK_FALSE(view->monochrome);
    const auto los = geo::quat_to_euler(view->pose.camera_to_ned);
    CHECK(los.yaw_deg == Approx(-40).margin(1e-6));
    CHECK(los.pitch_deg == Approx(-30).margin(1e-6));
    CHECK(view->pose.hfov_deg == Approx(siyi::field_of_view(siyi::Model::zt30, 4).hfov_deg));

    // Another device is not a SIYI camera.
    struct Other final : sim::Device {
        void receive(std::span<const std::uint8_t>, double) override {}
        void advance(double, std::vector<std::uint8_t>&) override {}
    } other;
    CHECK_FALSE(siyi_sim_camera(other));
}
