// The daemon's geoid for sessions that ask (MAVLink gimbal devices without a fixed
// geoid_undulation_m): Debian proj-data's EGM96 grid, or the terrain model's.
#include <catch2/catch.hpp>

#include "../vehicle/vehicle_fixtures.hpp"
#include "geoid_source.hpp"
#include "protocols/registry.hpp"
#include "terrain/geoid.hpp"

using gimbald::open_geoid;

TEST_CASE("open_geoid: the EGM96 grid when no terrain model has one", "[daemon]") {
    const auto path = gimbal::terrain::Geoid::find_egm96();
    REQUIRE(path);  // /usr/share/proj/egm96_15.gtx (proj-data)
    const auto opened = open_geoid(nullptr);
    INFO(opened.problem);
    REQUIRE(opened.undulation);
    CHECK(opened.source == *path);
    CHECK(opened.problem.empty());
    // NGA's EGM96: about -21 m at the demo area, +50 m near (38.6, 0).
    CHECK(opened.undulation(45.7, -121.5).value() == Approx(-21).margin(2));
    CHECK(opened.undulation(38.625473, -0.0005).value() == Approx(50.066).margin(1));
}

TEST_CASE("a MAVLink device session with the daemon's geoid shows EGM96 in STATE", "[daemon]") {
    using namespace gimbal;
    const auto opened = open_geoid(nullptr);
    REQUIRE(opened.undulation);
    protocols::SessionSettings settings;
    settings.geoid_undulation = opened.undulation;
    const auto* entry = protocols::find("mavlink");
    REQUIRE(entry);
    const nlohmann::json gimbal = {
        {"name", "cam"}, {"protocol", "mavlink"}, {"mavlink", {{"geoid_undulation_m", nullptr}}}};
    REQUIRE(entry->needs_geoid(gimbal));
    auto session = entry->make_session(settings, gimbal);

    // The aircraft 500 m above MSL at the demo area, the device looking down.
    vehicle::VehicleState v(vehicle_fixtures::options());
    vehicle_fixtures::fix_at(v, 1.0);
    std::vector<session::Bytes> out;
    session->steer(v, 1.0, 1.0, out);
    mavlink::GimbalDeviceAttitudeStatus status;
    status.q = {0.7071068f, 0, -0.7071068f, 0};  // pitch -90
    status.flags = 32;
    std::vector<state::Event> events;
    std::vector<session::Bytes> replies;
    session->receive(mavlink::encode_v2(status, 1, 154, 0), 1.0, events, replies);
    const auto t = session->snapshot(1.0)["telemetry"];
    INFO(t.dump());
    const double n = opened.undulation(45.7, -121.5).value();
    CHECK(t["geoid_undulation"].get<double>() == Approx(n).margin(0.001));
    CHECK(t["alt"].get<double>() == Approx(500 + n).margin(0.001));
}
