#include "sim/scene_renderer.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "geo/image.hpp"
#include "sim/scene_colour.hpp"
#include "sim/scene_objects.hpp"
#include "sim/scene_style.hpp"
#include "sim/terrain.hpp"
#include "sim/terrain_ray.hpp"

namespace gimbal::sim {

namespace {

std::uint8_t to_byte(float v) {
    return static_cast<std::uint8_t>(std::min(std::max(v, 0.f), 255.f) + 0.5f);
}

// Distance from v to the nearest multiple of `spacing` (inv = 1 / spacing), without a libm
// call in the pixel loop.
float to_nearest_multiple(float v, float spacing, float inv) {
    const float q = v * inv;
    const auto k = static_cast<float>(static_cast<long>(q < 0 ? q - 0.5f : q + 0.5f));
    return std::abs(v - k * spacing);
}

// What a grid node carries across its cell: premultiplied by w = 1/depth, so that linear
// interpolation in the image is perspective-correct.
enum Attr : std::size_t { attr_x, attr_y, attr_height, attr_shade, attr_river, attr_fog, n_attr };

struct Node {
    bool ground = false;
    bool below = false;  // the camera is under the terrain
    bool kink = false;   // the ground bends sharply here (see find_kinks)
    float fog = 0;
    double depth = 0;     // along the optical axis
    double x = 0, y = 0;  // TerrainXY of the hit
    float w = 0;
    std::array<float, n_attr> a{};
};

// A landmark as drawn this frame.
struct Mark {
    float x, y;  // TerrainXY
    float r_disc, r_ring;
    Colour colour;
};

constexpr double height_step_m = 2;
// A grid node whose w bends more than this (relative second difference) marks an edge.
constexpr float kink_threshold = 0.05f;
// Cells with an edge are split down to this size; there, the corners' colours are blended.
constexpr int min_cell_px = 4;
// A cell with a kink whose corners' depths differ more than this holds an edge.
constexpr double edge_depth_ratio = 1.3;
// Split cells whose corners' depths differ more than this are split again.
constexpr double fine_depth_ratio = 1.2;
// Edges in ground this deep in haze (beyond 0.45 of the max range) are not refined.
constexpr float far_fog = 0.3f;
constexpr double gradient_step_m = 5;

}  // namespace

bool valid(const SceneOptions& o) {
    return o.width >= 16 && o.width <= 4096 && o.height >= 16 && o.height <= 4096 &&
           o.width % 2 == 0 && o.height % 2 == 0 && o.grid_px >= 4 && o.grid_px <= 64 &&
           (o.grid_px & (o.grid_px - 1)) == 0 && o.max_range_m > 0 && std::isfinite(o.max_range_m);
}

struct SceneRenderer::Impl {
    SceneOptions o;
    RenderStats stats;

    // Palette, as offsets.
    std::vector<Colour> ramp;  // ground colour every height_step_m
    Colour water, grid_major, ring, haze, zenith, underground;
    std::array<float, 3> sun{};  // east, north, up

    // The frame being rendered.
    geo::CameraPose camera;
    double tan_x = 0, tan_y = 0;
    double pixel_angle = 0;  // rad per pixel at the centre
    TerrainXY eye_xy;
    std::array<double, 3> down_row{};  // NED down component of a camera-frame ray
    std::optional<TerrainRayCaster> caster;
    std::vector<Mark> all_marks;
    SceneObjects objects;     // roads, and the frame's moving objects
    std::vector<Node> nodes;  // (cells_x + 1) x (cells_y + 1)
    int cells_x = 0, cells_y = 0;
    std::uint8_t* y_out = nullptr;  // the frame's luma plane
    std::vector<std::uint8_t> u_full, v_full;

    explicit Impl(const SceneOptions& options) : o(valid(options) ? options : SceneOptions{}) {
        for (double h = 0;; h += height_step_m) {
            const auto& r = scene::ground_ramp;
            const std::size_t n = std::size(r);
            Colour c = offset(r[n - 1].colour);
            for (std::size_t i = 0; i + 1 < n; ++i)
                if (h <= r[i + 1].alt_m) {
                    const double t =
                        std::max(0.0, (h - r[i].alt_m) / (r[i + 1].alt_m - r[i].alt_m));
                    c = lerp(offset(r[i].colour), offset(r[i + 1].colour), static_cast<float>(t));
                    break;
                }
            ramp.push_back(c);
            if (h > terrain_max_alt_m) break;
        }
        water = offset(scene::water);
        grid_major = offset(scene::grid_major);
        ring = offset(scene::landmark_ring);
        haze = offset(scene::haze);
        zenith = offset(scene::zenith);
        underground = offset(scene::underground);
        const double az = scene::sun_azimuth_deg * geo::deg2rad;
        const double el = scene::sun_elevation_deg * geo::deg2rad;
        sun = {static_cast<float>(std::cos(el) * std::sin(az)),
               static_cast<float>(std::cos(el) * std::cos(az)), static_cast<float>(std::sin(el))};
        cells_x = (o.width + o.grid_px - 1) / o.grid_px;
        cells_y = (o.height + o.grid_px - 1) / o.grid_px;
        nodes.resize(static_cast<std::size_t>((cells_x + 1) * (cells_y + 1)));
        const std::size_t pixels = static_cast<std::size_t>(o.width * o.height);
        u_full.resize(pixels);
        v_full.resize(pixels);
    }

    // --- rays -------------------------------------------------------------------------------

    geo::Vec3 ray_camera(double px, double py) const {
        return {1, (2 * px / o.width - 1) * tan_x, (2 * py / o.height - 1) * tan_y};
    }

    // The node at image position (px, py) in pixels (pixel i's centre is i + 0.5).
    Node cast(double px, double py) {
        ++stats.rays;
        const geo::Vec3 ray = ray_camera(px, py);
        const auto hit = caster->cast(geo::rotate(camera.camera_to_ned, ray));
        Node n;
        if (hit.status == TerrainRayCaster::Status::below) {
            n.below = true;
            return n;
        }
        if (hit.status != TerrainRayCaster::Status::hit) {
            // Stands in for haze at max range where a cell is interpolated across the horizon.
            const geo::Vec3 ned = geo::rotate(camera.camera_to_ned, (1 / geo::norm(ray)) * ray);
            n.depth = o.max_range_m / geo::norm(ray);
            n.x = eye_xy.east_m + o.max_range_m * ned.y;
            n.y = eye_xy.north_m + o.max_range_m * ned.x;
            n.fog = 1;
            const double w = 1 / n.depth;
            n.w = static_cast<float>(w);
            n.a = {static_cast<float>(n.x * w), static_cast<float>(n.y * w), 0, 0,
                   static_cast<float>(1e4 * w), static_cast<float>(w)};
            return n;
        }
        n.ground = true;
        n.depth = std::max(hit.range_m / geo::norm(ray), 1e-3);
        n.x = hit.xy.east_m;
        n.y = hit.xy.north_m;
        const double h = terrain_height_xy(hit.xy);
        const double gx = (terrain_height_xy({n.x + gradient_step_m, n.y}) - h) / gradient_step_m;
        const double gy = (terrain_height_xy({n.x, n.y + gradient_step_m}) - h) / gradient_step_m;
        const double lambert =
            (-gx * sun[0] - gy * sun[1] + sun[2]) / std::sqrt(1 + gx * gx + gy * gy);
        const double shade = 0.35 + 0.65 * std::max(0.0, lambert) / sun[2];
        const double fog = std::min(1.0, std::pow(hit.range_m / o.max_range_m, 1.5));
        n.fog = static_cast<float>(fog);
        const double w = 1 / n.depth;
        n.w = static_cast<float>(w);
        n.a[attr_x] = static_cast<float>(n.x * w);
        n.a[attr_y] = static_cast<float>(n.y * w);
        n.a[attr_height] = static_cast<float>(h * w);
        n.a[attr_shade] = static_cast<float>(shade * w);
        n.a[attr_river] = static_cast<float>((n.y - river_north_m(n.x)) * w);
        n.a[attr_fog] = static_cast<float>(fog * w);
        return n;
    }

    // --- pixels -----------------------------------------------------------------------------

    void put(int px, int py, Colour c) {
        const auto i = static_cast<std::size_t>(py * o.width + px);
        y_out[i] = to_byte(16.f + c.y);
        u_full[i] = to_byte(128.f + c.u);
        v_full[i] = to_byte(128.f + c.v);
    }

    Colour sky(int px, int py) const {
        const geo::Vec3 r = ray_camera(px + 0.5, py + 0.5);
        const double down = down_row[0] * r.x + down_row[1] * r.y + down_row[2] * r.z;
        const double up = -down / geo::norm(r);
        const double t = up / std::sin(scene::sky_gradient_deg * geo::deg2rad);
        return lerp(haze, zenith, clamp01(static_cast<float>(t)));
    }

    // Metres of ground per pixel across a cell, for constant-x and constant-y lines.
    struct Footprint {
        float fx = 1, fy = 1;
    };

    // What the footprint means for lines and landmarks, worked out once per cell.
    struct Scale {
        float px_x, px_y;                  // pixels per metre across x, y lines
        float minor_fade_x, minor_fade_y;  // 100 m lines fade out beyond 6..12 m/px
        float major_fade_x, major_fade_y;  // 1 km lines beyond 60..120 m/px
        float mark_px;                     // pixels per metre for landmark edges
        explicit Scale(Footprint f)
            : px_x(1 / f.fx),
              px_y(1 / f.fy),
              minor_fade_x(clamp01((12.f - f.fx) / 6.f)),
              minor_fade_y(clamp01((12.f - f.fy) / 6.f)),
              major_fade_x(clamp01((120.f - f.fx) / 60.f)),
              major_fade_y(clamp01((120.f - f.fy) / 60.f)),
              mark_px(1 / std::min(f.fx, f.fy)) {}
    };

    // What may show in a cell: landmarks, roads and objects.
    struct Nearby {
        std::array<Mark, 8> marks;
        std::size_t n_marks = 0;
        SceneObjects::Near objects;
        // Something small enough that a blended edge cell would lose its shape.
        bool shaped() const { return n_marks > 0 || objects.n_bodies > 0; }
    };

    Colour ground(float x, float y, float h, float shade, float river, float fog, const Scale& s,
                  const Nearby& near) const {
        const auto hi =
            static_cast<std::size_t>(std::min(std::max(h / static_cast<float>(height_step_m), 0.f),
                                              static_cast<float>(ramp.size() - 1)));
        Colour c = ramp[hi];
        const float river_cov = clamp01(
            (static_cast<float>(scene::river_halfwidth_m) - std::abs(river)) * s.px_y + 0.5f);
        c = lerp(c, water, river_cov);
        c = scaled(c, shade);

        // Lines of constant x (north-south) and y (east-west); widths in pixels via the
        // footprint, so they stay 1 and 2 px wide at any range.
        constexpr auto minor = static_cast<float>(scene::grid_minor_m);
        constexpr auto major = static_cast<float>(scene::grid_major_m);
        const float dx_minor = to_nearest_multiple(x, minor, 1 / minor) * s.px_x;
        const float dy_minor = to_nearest_multiple(y, minor, 1 / minor) * s.px_y;
        const float minor_cov = std::max(clamp01(1.f - dx_minor) * s.minor_fade_x,
                                         clamp01(1.f - dy_minor) * s.minor_fade_y);
        c = scaled(c, 1.f - static_cast<float>(scene::grid_minor_darken) * minor_cov);
        const float dx_major = to_nearest_multiple(x, major, 1 / major) * s.px_x;
        const float dy_major = to_nearest_multiple(y, major, 1 / major) * s.px_y;
        const float major_cov = std::max(clamp01(1.5f - dx_major) * s.major_fade_x,
                                         clamp01(1.5f - dy_major) * s.major_fade_y);
        c = lerp(c, grid_major, 0.85f * major_cov);
        c = objects.roads_below(c, x, y, s.mark_px, near.objects);

        for (std::size_t k = 0; k < near.n_marks; ++k) {
            const Mark& m = near.marks[k];
            const float reach = m.r_ring + 1 / s.mark_px;
            const float dx = x - m.x, dy = y - m.y;
            if (std::abs(dx) > reach || std::abs(dy) > reach) continue;
            const float d = std::sqrt(dx * dx + dy * dy);
            c = lerp(c, ring, clamp01((m.r_ring - d) * s.mark_px + 0.5f));
            c = lerp(c, m.colour, clamp01((m.r_disc - d) * s.mark_px + 0.5f));
        }
        c = objects.above(c, x, y, s.mark_px, near.objects);
        return lerp(c, haze, clamp01(fog));
    }

    // The landmarks, roads and objects that may show in a cell with these corners.
    void nearby(const Node* const* corners, std::size_t n, Footprint f, Nearby& out) const {
        double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
        for (std::size_t i = 0; i < n; ++i) {
            if (!corners[i]->ground) continue;
            x0 = std::min(x0, corners[i]->x);
            x1 = std::max(x1, corners[i]->x);
            y0 = std::min(y0, corners[i]->y);
            y1 = std::max(y1, corners[i]->y);
        }
        const double margin = 2 * std::max(f.fx, f.fy);
        out.n_marks = 0;
        for (const Mark& m : all_marks) {
            const double r = m.r_ring + margin;
            if (m.x + r >= x0 && m.x - r <= x1 && m.y + r >= y0 && m.y - r <= y1 &&
                out.n_marks < out.marks.size())
                out.marks[out.n_marks++] = m;
        }
        if (x0 > x1) {  // no corner on the ground
            out.objects = {};
            return;
        }
        objects.near(x0, x1, y0, y1, margin, out.objects);
    }

    static Footprint footprint(const Node& n00, const Node& n10, const Node& n01, double size) {
        const auto s = static_cast<float>(size);
        return {std::max(static_cast<float>(std::hypot(n10.x - n00.x, n01.x - n00.x)) / s, 1e-3f),
                std::max(static_cast<float>(std::hypot(n10.y - n00.y, n01.y - n00.y)) / s, 1e-3f)};
    }

    // Pixels [x0, x1) x [y0, y1) of the cell whose corner nodes lie at pixel centres
    // (cx + 0.5, cy + 0.5) and (cx + size + 0.5, cy + size + 0.5), all four on the ground.
    void fill_ground(int cx, int cy, int size, int x0, int x1, int y0, int y1, const Node& n00,
                     const Node& n10, const Node& n01, const Node& n11) {
        const Node* corners[4] = {&n00, &n10, &n01, &n11};
        const Footprint f = footprint(n00, n10, n01, size);
        const Scale scale(f);
        Nearby near;
        nearby(corners, 4, f, near);
        const float inv = 1.f / static_cast<float>(size);
        for (int j = y0; j < y1; ++j) {
            const float fy = static_cast<float>(j - cy) * inv;
            const float wl = n00.w + (n01.w - n00.w) * fy, wr = n10.w + (n11.w - n10.w) * fy;
            std::array<float, n_attr> l, r;
            for (std::size_t k = 0; k < n_attr; ++k) {
                l[k] = n00.a[k] + (n01.a[k] - n00.a[k]) * fy;
                r[k] = n10.a[k] + (n11.a[k] - n10.a[k]) * fy;
            }
            for (int i = x0; i < x1; ++i) {
                const float fx = static_cast<float>(i - cx) * inv;
                const float iw = 1.f / (wl + (wr - wl) * fx);
                std::array<float, n_attr> v;
                for (std::size_t k = 0; k < n_attr; ++k) v[k] = (l[k] + (r[k] - l[k]) * fx) * iw;
                put(i, j,
                    ground(v[attr_x], v[attr_y], v[attr_height], v[attr_shade], v[attr_river],
                           v[attr_fog], scale, near));
            }
        }
    }

    // One node's ground at a pixel: its attributes unchanged (used where a cell's corners lie
    // on different surfaces and cannot be interpolated).
    Colour ground_at_node(const Node& n) const {
        const float iw = 1.f / n.w;
        const float across = static_cast<float>(n.depth * pixel_angle);
        const Node* self[1] = {&n};
        const Footprint f{across, across};
        Nearby near;
        nearby(self, 1, f, near);
        return ground(n.a[attr_x] * iw, n.a[attr_y] * iw, n.a[attr_height] * iw,
                      n.a[attr_shade] * iw, n.a[attr_river] * iw, n.a[attr_fog] * iw, Scale(f),
                      near);
    }

    // An edge cell too small to split: the corners' colours (sky, underground or each one's
    // own ground) blended across it, a soft edge rather than a staircase.
    void fill_blend(int cx, int cy, int size, int x0, int x1, int y0, int y1,
                    const Node* const* corners) {
        ++stats.blended_cells;
        std::array<Colour, 4> c;
        for (std::size_t k = 0; k < 4; ++k) {
            const Node& n = *corners[k];
            const int px = std::min(cx + static_cast<int>(k % 2) * size, o.width - 1);
            const int py = std::min(cy + static_cast<int>(k / 2) * size, o.height - 1);
            c[k] = n.below ? underground : n.ground ? ground_at_node(n) : sky(px, py);
        }
        const float inv = 1.f / static_cast<float>(size);
        for (int j = y0; j < y1; ++j) {
            const float fy = static_cast<float>(j - cy) * inv;
            const Colour l = lerp(c[0], c[2], fy), r = lerp(c[1], c[3], fy);
            for (int i = x0; i < x1; ++i) put(i, j, lerp(l, r, static_cast<float>(i - cx) * inv));
        }
    }

    void fill_by_pixel(int x0, int x1, int y0, int y1) {
        ++stats.pixel_cells;
        for (int j = y0; j < y1; ++j)
            for (int i = x0; i < x1; ++i) {
                const Node n = cast(i + 0.5, j + 0.5);
                put(i, j, n.below ? underground : n.ground ? ground_at_node(n) : sky(i, j));
            }
    }

    enum class Fill { sky, underground, ground, refine };

    // What a cell with these corners (n00, n10, n01, n11) needs.
    Fill classify(const Node* const* n, bool fine) const {
        int ground = 0, below = 0, kinks = 0;
        double lo = 1e300, hi = 0, fog = 1;
        for (std::size_t k = 0; k < 4; ++k) {
            const Node& p = *n[k];
            ground += p.ground ? 1 : 0;
            below += p.below ? 1 : 0;
            kinks += p.kink ? 1 : 0;
            if (p.ground) {
                lo = std::min(lo, p.depth);
                hi = std::max(hi, p.depth);
                fog = std::min(fog, static_cast<double>(p.fog));
            }
        }
        if (below == 4) return Fill::underground;
        if (below > 0) return Fill::refine;
        if (ground == 0) return Fill::sky;
        // Far ground next to sky is all but haze: interpolate towards the haze the missing
        // corners stand for (their nodes are placed at max range, fully hazed).
        if (ground < 4) return fog >= far_fog ? Fill::ground : Fill::refine;
        // An edge: the ground bends sharply (kink) and the depth jumps across the cell. Deep
        // in haze it is not worth finer rays.
        const bool edge =
            fine ? hi > lo * fine_depth_ratio : kinks > 0 && hi > lo * edge_depth_ratio;
        return edge && fog < far_fog ? Fill::refine : Fill::ground;
    }

    void fill_cell(int cx, int cy, int size, const Node* const* corners, bool fine) {
        const int x0 = cx, y0 = cy;
        const int x1 = std::min(cx + size, o.width), y1 = std::min(cy + size, o.height);
        if (x0 >= x1 || y0 >= y1) return;
        switch (classify(corners, fine)) {
            case Fill::sky:
                for (int j = y0; j < y1; ++j)
                    for (int i = x0; i < x1; ++i) put(i, j, sky(i, j));
                return;
            case Fill::underground:
                for (int j = y0; j < y1; ++j)
                    for (int i = x0; i < x1; ++i) put(i, j, underground);
                return;
            case Fill::ground:
                fill_ground(cx, cy, size, x0, x1, y0, y1, *corners[0], *corners[1], *corners[2],
                            *corners[3]);
                return;
            case Fill::refine:
                break;
        }
        if (size < 2 * min_cell_px) {
            // An edge across a landmark or an object gets a ray per pixel, so it keeps its
            // shape.
            Nearby near;
            float across = 0;
            for (std::size_t k = 0; k < 4; ++k)
                if (corners[k]->ground)
                    across = std::max(across, static_cast<float>(corners[k]->depth * pixel_angle));
            const auto reach = static_cast<float>(size) * across;
            if (across > 0) nearby(corners, 4, {reach, reach}, near);
            if (across > 0 && near.shaped())
                fill_by_pixel(x0, x1, y0, y1);
            else
                fill_blend(cx, cy, size, x0, x1, y0, y1, corners);
            return;
        }
        // Split in four (five more rays) and look again.
        ++stats.refined_cells;
        const int h = size / 2;
        const Node top = cast(cx + h + 0.5, cy + 0.5), left = cast(cx + 0.5, cy + h + 0.5);
        const Node centre = cast(cx + h + 0.5, cy + h + 0.5);
        const Node right = cast(cx + size + 0.5, cy + h + 0.5);
        const Node bottom = cast(cx + h + 0.5, cy + size + 0.5);
        const Node* quarters[4][4] = {{corners[0], &top, &left, &centre},
                                      {&top, corners[1], &centre, &right},
                                      {&left, &centre, corners[2], &bottom},
                                      {&centre, &right, &bottom, corners[3]}};
        for (int q = 0; q < 4; ++q)
            fill_cell(cx + (q % 2) * h, cy + (q / 2) * h, h, quarters[q], true);
    }

    // Marks nodes where the ground is not smooth: w = 1/depth is affine across the image for a
    // plane, so a large second difference means an edge - a hill hiding the ground behind it.
    void find_kinks() {
        const auto node = [&](int i, int j) -> Node& {
            return nodes[static_cast<std::size_t>(j * (cells_x + 1) + i)];
        };
        const auto bend = [](const Node& a, const Node& b, const Node& c) {
            if (!a.ground || !b.ground || !c.ground) return 0.f;
            return std::abs(a.w - 2 * b.w + c.w) / b.w;
        };
        for (int j = 0; j <= cells_y; ++j)
            for (int i = 0; i <= cells_x; ++i) {
                Node& b = node(i, j);
                float k = 0;
                if (i > 0 && i < cells_x) k = std::max(k, bend(node(i - 1, j), b, node(i + 1, j)));
                if (j > 0 && j < cells_y) k = std::max(k, bend(node(i, j - 1), b, node(i, j + 1)));
                b.kink = k > kink_threshold;
            }
    }

    void prepare(const geo::CameraPose& c) {
        camera = c;
        camera.camera_to_ned = geo::normalized(c.camera_to_ned);
        tan_x = std::tan(c.hfov_deg * geo::deg2rad / 2);
        tan_y = std::tan(c.vfov_deg * geo::deg2rad / 2);
        for (std::size_t k = 0; k < 3; ++k) {
            geo::Vec3 axis;
            (k == 0 ? axis.x : k == 1 ? axis.y : axis.z) = 1;
            down_row[k] = geo::rotate(camera.camera_to_ned, axis).z;
        }
        caster.emplace(c.position, o.max_range_m);
        eye_xy = terrain_xy(c.position.lat_deg, c.position.lon_deg);
        stats = {};
        // Landmarks keep a few pixels of radius however far they are, also where the ground
        // is seen at a grazing angle (across the line of sight they then grow wider).
        pixel_angle = 2 * tan_x / o.width;
        const geo::Vec3 eye = geo::lla_to_ecef(c.position);
        all_marks.clear();
        const auto& lm = landmarks();
        for (std::size_t i = 0; i < lm.size(); ++i) {
            const TerrainXY xy = terrain_xy(lm[i].lat_deg, lm[i].lon_deg);
            const geo::Vec3 p = geo::lla_to_ecef({lm[i].lat_deg, lm[i].lon_deg, lm[i].alt_m});
            const geo::Vec3 ray = geo::ecef_to_ned(p - eye, c.position);
            const double h = terrain_height_xy(xy);
            const double gx = (terrain_height_xy({xy.east_m + gradient_step_m, xy.north_m}) - h) /
                              gradient_step_m;
            const double gy = (terrain_height_xy({xy.east_m, xy.north_m + gradient_step_m}) - h) /
                              gradient_step_m;
            const geo::Vec3 normal_ned{-gy, -gx, -1};
            const double incidence =
                std::abs(geo::dot(ray, normal_ned)) / (geo::norm(ray) * geo::norm(normal_ned));
            const double metres_per_px = geo::norm(ray) * pixel_angle;
            const double r =
                std::max(scene::landmark_radius_m,
                         scene::landmark_min_radius_px * metres_per_px / std::max(incidence, 0.1));
            const double outer = r + std::max(0.25 * r, 1.5 * metres_per_px);
            all_marks.push_back({static_cast<float>(xy.east_m), static_cast<float>(xy.north_m),
                                 static_cast<float>(r), static_cast<float>(outer),
                                 offset(scene::landmark_colour(i))});
        }
    }

    void render(const geo::CameraPose& c, std::span<const ObjectState> moving, I420Frame& out) {
        prepare(c);
        objects.set_objects(moving);
        y_out = out.y.data();
        const int g = o.grid_px;
        const auto node = [&](int i, int j) -> Node& {
            return nodes[static_cast<std::size_t>(j * (cells_x + 1) + i)];
        };
        for (int j = 0; j <= cells_y; ++j)
            for (int i = 0; i <= cells_x; ++i) node(i, j) = cast(i * g + 0.5, j * g + 0.5);
        find_kinks();
        for (int j = 0; j < cells_y; ++j)
            for (int i = 0; i < cells_x; ++i) {
                const Node* corners[4] = {&node(i, j), &node(i + 1, j), &node(i, j + 1),
                                          &node(i + 1, j + 1)};
                fill_cell(i * g, j * g, g, corners, false);
            }
        subsample(out);
    }

    // Chroma: the mean of each 2 x 2 block.
    void subsample(I420Frame& out) const {
        const int cw = out.chroma_width(), ch = out.chroma_height();
        for (int j = 0; j < ch; ++j)
            for (int i = 0; i < cw; ++i) {
                const auto a = static_cast<std::size_t>(2 * j * o.width + 2 * i);
                const auto b = a + static_cast<std::size_t>(o.width);
                const auto k = static_cast<std::size_t>(j * cw + i);
                if (o.monochrome) {
                    out.u[k] = out.v[k] = 128;
                    continue;
                }
                out.u[k] = static_cast<std::uint8_t>(
                    (u_full[a] + u_full[a + 1] + u_full[b] + u_full[b + 1] + 2) / 4);
                out.v[k] = static_cast<std::uint8_t>(
                    (v_full[a] + v_full[a + 1] + v_full[b] + v_full[b + 1] + 2) / 4);
            }
    }
};

SceneRenderer::SceneRenderer(const SceneOptions& options)
    : impl_(std::make_unique<Impl>(options)) {}

SceneRenderer::~SceneRenderer() = default;

bool SceneRenderer::render(const geo::CameraPose& camera, I420Frame& frame,
                           std::span<const ObjectState> objects) {
    const SceneOptions& o = impl_->o;
    frame.resize(o.width, o.height);
    if (!geo::valid(camera)) {
        std::fill(frame.y.begin(), frame.y.end(), std::uint8_t{126});
        std::fill(frame.u.begin(), frame.u.end(), std::uint8_t{128});
        std::fill(frame.v.begin(), frame.v.end(), std::uint8_t{128});
        impl_->stats = {};
        return false;
    }
    impl_->render(camera, objects, frame);
    return true;
}

void SceneRenderer::set_monochrome(bool monochrome) {
    impl_->o.monochrome = monochrome;
}

const SceneOptions& SceneRenderer::options() const {
    return impl_->o;
}

const RenderStats& SceneRenderer::stats() const {
    return impl_->stats;
}

}  // namespace gimbal::sim
