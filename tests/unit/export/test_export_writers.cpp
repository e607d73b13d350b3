// gimbal-export's pieces: a flight decoded from recorded Orion frames, and the GeoJSON, KML
// and CSV writers checked against what the formats require.
#include <catch2/catch.hpp>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "export/writers.hpp"
#include "geo/wgs84.hpp"
#include "protocols/orion/codec/framing.hpp"
#include "protocols/orion/codec/packets.hpp"

namespace fe = gimbal::flight_export;
namespace o = gimbal::orion;

namespace {

constexpr double deg = M_PI / 180.0;

// Telemetry of an aircraft at lat/lon, 1000 m up, looking straight down (LOS 800 m down,
// so there is a target and a footprint).
o::GeolocateTelemetry telemetry(double lat_deg, double lon_deg, std::uint32_t system_time_ms) {
    o::GeolocateTelemetry t;
    t.system_time_ms = system_time_ms;
    t.gps_week = 2400;
    t.gps_itow_ms = 100000 + system_time_ms;
    t.geoid_undulation = 30;
    t.lat = lat_deg * deg;
    t.lon = lon_deg * deg;
    t.alt = 1000;
    t.quat = {1, 0, 0, 0};
    t.pan = 10 * deg;
    t.tilt = -90 * deg;
    t.hfov = 20 * deg;
    t.vfov = 15 * deg;
    const double up[3] = {std::cos(t.lat) * std::cos(t.lon), std::cos(t.lat) * std::sin(t.lon),
                          std::sin(t.lat)};
    t.los_ecef = {-800 * up[0], -800 * up[1], -800 * up[2]};
    t.mode = o::Mode::geopoint;
    return t;
}

gimbal::record::GimbalStream orion_stream(int points) {
    gimbal::record::GimbalStream s;
    s.gimbal = {"main", "orion", "orion tcp 127.0.0.1:8747"};
    for (int i = 0; i < points; ++i) {
        auto bytes =
            o::to_wire(telemetry(45.0 + i * 1e-4, 7.0, static_cast<std::uint32_t>(i * 100)));
        const auto other = o::request_bytes(o::pkt::geolocate_telemetry + 1);  // not telemetry
        bytes.insert(bytes.end(), other.begin(), other.end());
        // Split each frame across two chunks: the framer must join them.
        const auto half = static_cast<std::ptrdiff_t>(bytes.size() / 2);
        const std::int64_t t = 1764072000000000 + i * 1'000'000LL;
        s.chunks.push_back({t, {bytes.begin(), bytes.begin() + half}});
        s.chunks.push_back({t, {bytes.begin() + half, bytes.end()}});
    }
    return s;
}

fe::Flight flight_of(int points) {
    fe::Flight f;
    std::string error;
    REQUIRE(fe::build_flight(orion_stream(points), f, error));
    return f;
}

double signed_area(const nlohmann::json& ring) {
    double a = 0;
    for (std::size_t i = 0; i + 1 < ring.size(); ++i)
        a += ring[i][0].get<double>() * ring[i + 1][1].get<double>() -
             ring[i + 1][0].get<double>() * ring[i][1].get<double>();
    return a / 2;
}

}  // namespace

TEST_CASE("a flight decoded from recorded Orion frames", "[export]") {
    const auto f = flight_of(5);
    REQUIRE(f.points.size() == 5);  // the non-telemetry frames are not points
    CHECK(f.frames == 10);
    const auto& p = f.points[2];
    CHECK(p.time_us == 1764072002000000);
    REQUIRE(p.aircraft);
    CHECK(p.aircraft->lat == Approx(45.0002).margin(1e-7));
    CHECK(p.aircraft->lon == Approx(7.0).margin(1e-7));
    CHECK(*p.aircraft->alt == Approx(1000));
    CHECK(*p.aircraft->alt_msl == Approx(970).margin(0.01));
    CHECK(p.values["system_time_ms"] == 200);
    CHECK(p.values["mode"] == "geopoint");
    CHECK(p.values["pan"].get<double>() == Approx(10).margin(0.01));
    REQUIRE(p.target);
    CHECK(*p.target->alt == Approx(200).margin(1));
    CHECK(*p.target->alt_msl == Approx(170).margin(1));
    REQUIRE(p.footprint);
}

TEST_CASE("CSV: a header and one row per telemetry packet", "[export]") {
    const auto f = flight_of(4);
    const auto csv = fe::to_csv(f);
    std::vector<std::string> lines;
    std::size_t at = 0;
    while (at < csv.size()) {
        const auto end = csv.find("\r\n", at);
        REQUIRE(end != std::string::npos);
        lines.push_back(csv.substr(at, end - at));
        at = end + 2;
    }
    REQUIRE(lines.size() == 5);
    CHECK(lines[0].rfind("time,gimbal_time,system_time_ms,lat,lon,alt,", 0) == 0);
    const auto columns = std::count(lines[0].begin(), lines[0].end(), ',');
    for (const auto& line : lines) CHECK(std::count(line.begin(), line.end(), ',') == columns);
    INFO(lines[2]);
    CHECK(lines[2].rfind("2025-11-25T12:00:01.000Z,", 0) == 0);
    CHECK(lines[2].find(",45.0001,7,1000,969.999,0,0,0,10,-90,20,15,geopoint,") !=
          std::string::npos);
    CHECK(lines[2].find(",geopoint,") != std::string::npos);
}

TEST_CASE("GeoJSON per RFC 7946", "[export]") {
    const auto f = flight_of(25);  // 24 s of points
    const auto j = nlohmann::json::parse(fe::to_geojson(f, 10));
    CHECK(j["type"] == "FeatureCollection");
    int tracks = 0, targets = 0, footprints = 0;
    for (const auto& feature : j["features"]) {
        CHECK(feature["type"] == "Feature");
        REQUIRE(feature["properties"].is_object());
        const auto& g = feature["geometry"];
        const std::string kind = feature["properties"]["kind"];
        if (g["type"] == "LineString") {
            CHECK(g["coordinates"].size() == 25);
            for (const auto& c : g["coordinates"]) {
                REQUIRE(c.size() == 3);
                CHECK(c[0].get<double>() == Approx(7.0).margin(0.01));  // lon first
                CHECK(c[1].get<double>() == Approx(45.0).margin(0.01));
            }
            (kind == "aircraft_track" ? tracks : targets)++;
        } else {
            REQUIRE(g["type"] == "Polygon");
            CHECK(kind == "footprint");
            const auto& ring = g["coordinates"][0];
            REQUIRE(ring.size() == 5);
            CHECK(ring.front() == ring.back());
            CHECK(signed_area(ring) > 0);  // counter-clockwise
            CHECK(feature["properties"].contains("pan"));
            CHECK(feature["properties"].contains("time"));
            ++footprints;
        }
    }
    CHECK(tracks == 1);
    CHECK(targets == 1);
    CHECK(footprints == 3);  // at 0, 10 and 20 s
    CHECK(fe::footprints_every(f, 0).size() == 25);
}

TEST_CASE("footprint rings are turned counter-clockwise whatever their corner order", "[export]") {
    const auto at = [](double lat, double lon) {
        return fe::Position{lat, lon, std::nullopt, std::nullopt};
    };
    const std::array<fe::Position, 4> clockwise = {at(1, 0), at(1, 1), at(0, 1), at(0, 0)};
    const auto ring = fe::counter_clockwise_ring(clockwise);
    double a = 0;
    for (std::size_t i = 0; i < 4; ++i)
        a += ring[i].lon * ring[i + 1].lat - ring[i + 1].lon * ring[i].lat;
    CHECK(a > 0);
    CHECK(ring[0].lat == ring[4].lat);
    CHECK(ring[0].lon == ring[4].lon);
}

TEST_CASE("KML 2.2 document", "[export]") {
    auto f = flight_of(12);
    f.gimbal = "a<b&c";
    const auto kml = fe::to_kml(f, 10);
    CHECK(kml.rfind("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<kml "
                    "xmlns=\"http://www.opengis.net/kml/2.2\">",
                    0) == 0);
    CHECK(kml.find("<name>gimbal a&lt;b&amp;c</name>") != std::string::npos);
    CHECK(kml.find("<altitudeMode>absolute</altitudeMode><coordinates>7,45,969.999 ") !=
          std::string::npos);
    std::size_t polygons = 0;
    for (auto at = kml.find("<Polygon>"); at != std::string::npos;
         at = kml.find("<Polygon>", at + 1))
        ++polygons;
    CHECK(polygons == 2);
    CHECK(kml.find("<outerBoundaryIs><LinearRing><coordinates>") != std::string::npos);
    CHECK(kml.find("</Document>\n</kml>\n") != std::string::npos);
}

TEST_CASE("an unknown protocol is an error", "[export]") {
    gimbal::record::GimbalStream s;
    s.gimbal = {"x", "", "serial"};
    fe::Flight f;
    std::string error;
    CHECK_FALSE(fe::build_flight(s, f, error));
    CHECK(error.find("unknown protocol") != std::string::npos);
}
