#include "sim/scene_objects.hpp"

#include <cmath>

#include "geo/vec3.hpp"
#include "sim/scene_style.hpp"

namespace gimbal::sim {

namespace {

// Coverage of a w x h rectangle (half sizes) at local (u, v), antialiased over a pixel.
float rect(float u, float v, float half_u, float half_v, float px) {
    return clamp01(std::min(half_u - std::abs(u), half_v - std::abs(v)) * px + 0.5f);
}

float distance(float x, float y, float ax, float ay, float dx, float dy, float inv_len2) {
    const float t = clamp01(((x - ax) * dx + (y - ay) * dy) * inv_len2);
    const float ex = ax + t * dx - x, ey = ay + t * dy - y;
    return std::sqrt(ex * ex + ey * ey);
}

constexpr float wake_length_m = 25;

}  // namespace

SceneObjects::SceneObjects()
    : asphalt_(offset(scene::asphalt)),
      concrete_(offset(scene::deck)),
      parapet_(offset(scene::parapet)),
      glass_(offset(scene::glass)),
      cargo_(offset(scene::cargo)),
      cabin_(offset(scene::boat_cabin)),
      foam_(offset(scene::foam)) {
    for (const Road& road : roads())
        for (std::size_t i = 1; i < road.points.size(); ++i) {
            const TerrainXY a = road.points[i - 1], b = road.points[i];
            const auto hw = static_cast<float>(road.halfwidth_m);
            const auto dx = static_cast<float>(b.east_m - a.east_m);
            const auto dy = static_cast<float>(b.north_m - a.north_m);
            segments_.push_back({static_cast<float>(a.east_m), static_cast<float>(a.north_m), dx,
                                 dy, 1.f / (dx * dx + dy * dy), hw, road.level,
                                 static_cast<float>(std::min(a.east_m, b.east_m)) - hw,
                                 static_cast<float>(std::max(a.east_m, b.east_m)) + hw,
                                 static_cast<float>(std::min(a.north_m, b.north_m)) - hw,
                                 static_cast<float>(std::max(a.north_m, b.north_m)) + hw});
        }
}

void SceneObjects::set_objects(std::span<const ObjectState> objects) {
    bodies_.clear();
    const double sun_az = scene::sun_azimuth_deg * geo::deg2rad;
    const double shadow_per_m = 1 / std::tan(scene::sun_elevation_deg * geo::deg2rad);
    for (const ObjectState& o : objects) {
        const ObjectSpec& spec = o.spec();
        const double h = o.heading_deg * geo::deg2rad;
        // The shadow falls away from the sun.
        const double shadow = spec.kind == ObjectKind::boat ? 0.3 : spec.height_m * shadow_per_m;
        Body b;
        b.x = static_cast<float>(o.xy.east_m);
        b.y = static_cast<float>(o.xy.north_m);
        b.fe = static_cast<float>(std::sin(h));
        b.fn = static_cast<float>(std::cos(h));
        b.half_length = static_cast<float>(spec.length_m / 2);
        b.half_width = static_cast<float>(spec.width_m / 2);
        b.shadow_e = static_cast<float>(-shadow * std::sin(sun_az));
        b.shadow_n = static_cast<float>(-shadow * std::cos(sun_az));
        b.reach = b.half_length + static_cast<float>(shadow) + 1.f +
                  (spec.kind == ObjectKind::boat ? wake_length_m : 0.f);
        b.kind = spec.kind;
        b.level = o.level;
        b.body = offset(spec.colour);
        // The roof catches the sun: lighter than the body.
        b.roof = lerp(b.body, offset({255, 255, 255}), 0.3f);
        bodies_.push_back(b);
    }
}

void SceneObjects::near(double x0, double x1, double y0, double y1, double margin,
                        Near& out) const {
    out.n_segments = out.n_bodies = 0;
    const auto lx = static_cast<float>(x0 - margin), hx = static_cast<float>(x1 + margin);
    const auto ly = static_cast<float>(y0 - margin), hy = static_cast<float>(y1 + margin);
    for (std::size_t i = 0; i < segments_.size() && out.n_segments < out.segments.size(); ++i) {
        const Segment& s = segments_[i];
        if (s.x1 >= lx && s.x0 <= hx && s.y1 >= ly && s.y0 <= hy)
            out.segments[out.n_segments++] = static_cast<std::uint16_t>(i);
    }
    for (std::size_t i = 0; i < bodies_.size() && out.n_bodies < out.bodies.size(); ++i) {
        const Body& b = bodies_[i];
        if (b.x + b.reach >= lx && b.x - b.reach <= hx && b.y + b.reach >= ly &&
            b.y - b.reach <= hy)
            out.bodies[out.n_bodies++] = static_cast<std::uint16_t>(i);
    }
}

Colour SceneObjects::roads_below(Colour c, float x, float y, float px, const Near& near) const {
    for (std::size_t k = 0; k < near.n_segments; ++k) {
        const Segment& s = segments_[near.segments[k]];
        if (s.level != 0) continue;
        const float d = distance(x, y, s.ax, s.ay, s.dx, s.dy, s.inv_len2);
        c = lerp(c, asphalt_, clamp01((s.halfwidth - d) * px + 0.5f));
    }
    return c;
}

Colour SceneObjects::draw_deck(Colour c, const Segment& s, float x, float y, float px) const {
    const float d = distance(x, y, s.ax, s.ay, s.dx, s.dy, s.inv_len2);
    c = lerp(c, parapet_, clamp01((s.halfwidth - d) * px + 0.5f));
    return lerp(c, concrete_, clamp01((s.halfwidth - 0.8f - d) * px + 0.5f));
}

Colour SceneObjects::draw_body(Colour c, const Body& b, float x, float y, float px) const {
    const float dx = x - b.x, dy = y - b.y;
    if (std::abs(dx) > b.reach || std::abs(dy) > b.reach) return c;
    // Local coordinates: u along the nose, v to the right.
    const auto local_u = [&](float ex, float ey) { return ex * b.fe + ey * b.fn; };
    const auto local_v = [&](float ex, float ey) { return ex * b.fn - ey * b.fe; };
    const float u = local_u(dx, dy), v = local_v(dx, dy);
    const float su = local_u(dx - b.shadow_e, dy - b.shadow_n);
    const float sv = local_v(dx - b.shadow_e, dy - b.shadow_n);
    const float hl = b.half_length, hw = b.half_width;
    switch (b.kind) {
        case ObjectKind::car:
            c = scaled(c, 1.f - 0.55f * rect(su, sv, hl, hw, px));
            c = lerp(c, b.body, rect(u, v, hl, hw, px));
            c = lerp(c, glass_, rect(u + 0.1f, v, 1.25f, hw - 0.15f, px));
            return lerp(c, b.roof, rect(u + 0.25f, v, 0.75f, hw - 0.25f, px));
        case ObjectKind::truck:
            c = scaled(c, 1.f - 0.55f * rect(su, sv, hl, hw, px));
            c = lerp(c, b.body, rect(u - (hl - 1.1f), v, 1.1f, hw - 0.1f, px));
            c = lerp(c, glass_, rect(u - (hl - 0.35f), v, 0.3f, hw - 0.3f, px));
            return lerp(c, cargo_, rect(u + 1.25f, v, hl - 1.25f, hw, px));
        case ObjectKind::boat: {
            // The wake: foam widening and fading behind the stern.
            const float behind = -hl - u;
            if (behind > 0 && behind < wake_length_m)
                c = lerp(c, foam_,
                         0.6f * (1.f - behind / wake_length_m) *
                             clamp01((hw * (1.f + 0.15f * behind) - std::abs(v)) * px + 0.5f));
            // The hull narrows to a point over the front third.
            const float taper = std::min(1.f, (hl - u) / (0.66f * hl));
            c = lerp(c, b.body, rect(u, v / std::max(taper, 0.05f), hl, hw, px));
            return lerp(c, cabin_, rect(u + 0.8f, v, 1.5f, hw - 0.6f, px));
        }
    }
    return c;
}

Colour SceneObjects::above(Colour c, float x, float y, float px, const Near& near) const {
    for (std::size_t k = 0; k < near.n_bodies; ++k) {
        const Body& b = bodies_[near.bodies[k]];
        if (b.level == 0) c = draw_body(c, b, x, y, px);
    }
    for (std::size_t k = 0; k < near.n_segments; ++k) {
        const Segment& s = segments_[near.segments[k]];
        if (s.level != 0) c = draw_deck(c, s, x, y, px);
    }
    for (std::size_t k = 0; k < near.n_bodies; ++k) {
        const Body& b = bodies_[near.bodies[k]];
        if (b.level != 0) c = draw_body(c, b, x, y, px);
    }
    return c;
}

}  // namespace gimbal::sim
