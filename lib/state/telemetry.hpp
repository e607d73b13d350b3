// STATE `telemetry`'s shared part (contract sections 5, 11, 15): the derived keys every
// consumer uses, whatever the protocol - where the camera is and looks, its fields of view,
// the gimbal's target, the image's footprint and the ground on the line of sight. A protocol
// whose gimbal reports position telemetry fills it (an Orion from GeolocateTelemetry, a
// MAVLink gimbal device from its attitude and the vehicle's fix) and adds its own keys beside
// it. Values are kept at the contract's precision, as STATE shows them, so every consumer
// reads what a client reads.
#pragma once

#include <array>
#include <optional>
#include <string>

#include "geo/ground.hpp"
#include "state/writer.hpp"

namespace gimbal::state {

// A point on or above the WGS84 ellipsoid: degrees, metres above the ellipsoid.
struct GeoPoint {
    double lat = 0, lon = 0, alt = 0;
};

struct LatLon {
    double lat = 0, lon = 0;
};

// Where the camera's view meets the ground (geo/ground.hpp: the terrain where it answers, else
// the flat world): the four image corners (top-left, top-right, bottom-right, bottom-left) and
// the surface they are on, and the image centre.
struct GroundView {
    std::optional<std::array<LatLon, 4>> footprint;
    std::optional<geo::SurfaceKind> footprint_surface;
    std::optional<geo::GroundPoint> ground;  // at the contract's precision
};

// The ground seen by `camera`, computed once per telemetry report.
GroundView ground_view(const geo::CameraPose& camera, const geo::Ground& ground);
// `g` at the contract's precision (what STATE and the `locate` reply show).
geo::GroundPoint rounded(const geo::GroundPoint& g);

struct Telemetry {
    // Reported (or, for a device that reports attitude only, taken from the vehicle): the
    // camera's position, degrees and metres above the ellipsoid; the geoid's height there;
    // pan (from the mount's nose, right positive) and tilt (up positive); the full fields of
    // view.
    std::optional<double> lat, lon, alt, geoid_undulation;
    std::optional<double> pan, tilt, hfov, vfov;
    // Derived: the camera's altitude above mean sea level; the mount's (aircraft's) roll,
    // pitch and yaw; the gimbal's target (its own, or its line of sight on the ground).
    std::optional<double> alt_msl;
    std::optional<double> roll, pitch, yaw;
    std::optional<GeoPoint> target;
    GroundView view;
};

// {"lat","lon","alt","range_m","surface"}.
template <class V>
void fields(V& v, const geo::GroundPoint& g) {
    v.latlon("lat", g.point.lat_deg);
    v.latlon("lon", g.point.lon_deg);
    v.metres("alt", g.point.alt_m);
    v.metres("range_m", g.range_m);
    v.string("surface", geo::to_string(g.surface));
}

template <class V>
void fields(V& v, const GeoPoint& p) {
    v.latlon("lat", p.lat);
    v.latlon("lon", p.lon);
    v.metres("alt", p.alt);
}

template <class V>
void fields(V& v, const LatLon& p) {
    v.latlon("lat", p.lat);
    v.latlon("lon", p.lon);
}

// `footprint`, `footprint_surface`, `ground`.
template <class V>
void fields(V& v, const GroundView& g) {
    if (g.footprint)
        v.array("footprint", *g.footprint, [](const LatLon& c) { return write(c); });
    else
        v.null("footprint");
    if (g.footprint_surface)
        v.string("footprint_surface", geo::to_string(*g.footprint_surface));
    else
        v.null("footprint_surface");
    v.object("ground", g.ground);
}

// The reported keys, as a protocol without a codec's own JSON of them writes them.
template <class V>
void reported_fields(V& v, const Telemetry& t) {
    v.latlon("lat", t.lat);
    v.latlon("lon", t.lon);
    v.metres("alt", t.alt);
    v.metres("geoid_undulation", t.geoid_undulation);
    v.angle("pan", t.pan);
    v.angle("tilt", t.tilt);
    v.angle("hfov", t.hfov);
    v.angle("vfov", t.vfov);
}

template <class V>
void derived_fields(V& v, const Telemetry& t) {
    v.metres("alt_msl", t.alt_msl);
    v.angle("roll", t.roll);
    v.angle("pitch", t.pitch);
    v.angle("yaw", t.yaw);
    v.object("target", t.target);
    fields(v, t.view);
}

template <class V>
void fields(V& v, const Telemetry& t) {
    reported_fields(v, t);
    derived_fields(v, t);
}

}  // namespace gimbal::state
