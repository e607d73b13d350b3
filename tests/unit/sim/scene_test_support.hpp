// Cameras and pixel checks shared by the scene tests (tests/unit/sim) and the encoded-video
// tests (tests/unit/sim_video). Not a test file itself.
#pragma once

#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "geo/image.hpp"
#include "sim/ground_objects.hpp"
#include "sim/i420_frame.hpp"
#include "sim/scene_style.hpp"
#include "sim/terrain.hpp"

namespace scene_test {

using namespace gimbal;

// The vertical field of view that keeps pixels square in a width x height picture.
inline double vfov_for(double hfov_deg, double width = 640, double height = 360) {
    return 2 * std::atan(std::tan(hfov_deg * geo::deg2rad / 2) * height / width) * geo::rad2deg;
}

// A camera at `from` on a mount with the given attitude, looking at `to` turned by
// (pan_offset, tilt_offset) degrees.
inline geo::CameraPose aimed(const geo::Lla& from, const geo::Lla& to, double hfov_deg,
                             const geo::Quat& mount = {}, double pan_offset = 0,
                             double tilt_offset = 0) {
    const auto pt = geo::pan_tilt_towards(mount, from, to);
    return geo::camera_pose(from, mount, pt->pan_deg + pan_offset, pt->tilt_deg + tilt_offset,
                            hfov_deg, vfov_for(hfov_deg));
}

// The object of that name among these (sim/ground_objects.hpp); fails the test without one.
inline const sim::ObjectState& object_named(const std::vector<sim::ObjectState>& all,
                                            const std::string& name) {
    for (const auto& o : all)
        if (o.spec().name == name) return o;
    FAIL("no object " << name);
    return all.front();
}

inline geo::Lla landmark_lla(std::size_t i) {
    const auto& m = sim::landmarks()[i];
    return {m.lat_deg, m.lon_deg, m.alt_m};
}

// A point `east`, `north` metres from a landmark on the terrain's grid, on the ground.
inline geo::Lla ground_near(std::size_t i, double east, double north, double above = 0) {
    const auto& m = sim::landmarks()[i];
    sim::TerrainXY xy = sim::terrain_xy(m.lat_deg, m.lon_deg);
    xy.east_m += east;
    xy.north_m += north;
    const geo::LatLon ll = sim::terrain_lat_lon(xy);
    return {ll.lat_deg, ll.lon_deg, sim::terrain_height_xy(xy) + above};
}

inline std::optional<geo::PixelPoint> projected(const geo::CameraPose& camera,
                                                const geo::Lla& point, int width = 640,
                                                int height = 360) {
    const auto p = geo::project(camera, point);
    if (!p || !p->visible) return std::nullopt;
    return geo::to_pixels(p->at, width, height);
}

struct Pixel {
    int y, u, v;
};

// A pixel with its 2x2 block's chroma, from planes with any stride.
struct PlaneView {
    const std::uint8_t* y;
    const std::uint8_t* u;
    const std::uint8_t* v;
    int width, height;
    int y_stride, c_stride;

    Pixel at(int px, int py) const {
        return {y[py * y_stride + px], u[(py / 2) * c_stride + px / 2],
                v[(py / 2) * c_stride + px / 2]};
    }
};

inline PlaneView view(const sim::I420Frame& f) {
    return {f.y.data(), f.u.data(), f.v.data(), f.width, f.height, f.width, f.width / 2};
}

inline int distance(Pixel p, sim::Yuv c) {
    return std::max({std::abs(p.y - c.y), std::abs(p.u - c.u), std::abs(p.v - c.v)});
}

// The landmark whose colour the pixel is closest to, when within `tolerance` (per component).
inline std::optional<std::size_t> landmark_colour_at(Pixel p, int tolerance) {
    std::optional<std::size_t> best;
    int best_d = tolerance + 1;
    for (std::size_t i = 0; i < sim::landmarks().size(); ++i) {
        const int d = distance(p, sim::to_yuv(sim::scene::landmark_colour(i)));
        if (d < best_d) {
            best_d = d;
            best = i;
        }
    }
    return best;
}

// The centroid of the 4-connected region around (px, py) whose pixels have landmark i's
// colour (within tolerance); nullopt when (px, py) itself does not.
inline std::optional<std::pair<double, double>> blob_centroid(const PlaneView& f, int px, int py,
                                                              std::size_t i, int tolerance) {
    const sim::Yuv c = sim::to_yuv(sim::scene::landmark_colour(i));
    if (distance(f.at(px, py), c) > tolerance) return std::nullopt;
    std::vector<std::uint8_t> seen(static_cast<std::size_t>(f.width * f.height), 0);
    std::vector<std::pair<int, int>> stack{{px, py}};
    seen[static_cast<std::size_t>(py * f.width + px)] = 1;
    double sx = 0, sy = 0, n = 0;
    while (!stack.empty()) {
        const auto [x, y] = stack.back();
        stack.pop_back();
        sx += x + 0.5;
        sy += y + 0.5;
        ++n;
        const int next[4][2] = {{x + 1, y}, {x - 1, y}, {x, y + 1}, {x, y - 1}};
        for (const auto& q : next) {
            if (q[0] < 0 || q[1] < 0 || q[0] >= f.width || q[1] >= f.height) continue;
            auto& s = seen[static_cast<std::size_t>(q[1] * f.width + q[0])];
            if (s || distance(f.at(q[0], q[1]), c) > tolerance) continue;
            s = 1;
            stack.push_back({q[0], q[1]});
        }
    }
    return std::pair{sx / n, sy / n};
}

}  // namespace scene_test
