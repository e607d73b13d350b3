#include "sim/ground_objects.hpp"

#include <algorithm>
#include <cmath>

#include "geo/vec3.hpp"

namespace gimbal::sim {

namespace {

// The overpass: the highway (level 1, four lanes) crosses the east-west road at x = 800 m.
constexpr double highway_east_m = 800;

std::vector<TerrainXY> river_line() {
    std::vector<TerrainXY> line;
    for (double x = -7000; x <= 7000; x += 100) line.push_back({x, river_north_m(x)});
    return line;
}

// A route with its cumulative lengths.
struct Route {
    std::vector<TerrainXY> points;
    std::vector<double> at;  // distance from the start to points[i]
    int level = 0;
    double length() const { return at.back(); }
};

Route make_route(std::vector<TerrainXY> points, int level) {
    Route r{std::move(points), {0.0}, level};
    for (std::size_t i = 1; i < r.points.size(); ++i)
        r.at.push_back(r.at.back() + std::hypot(r.points[i].east_m - r.points[i - 1].east_m,
                                                r.points[i].north_m - r.points[i - 1].north_m));
    return r;
}

const Route& route_named(const std::string& name) {
    static const std::vector<std::pair<std::string, Route>> routes = [] {
        std::vector<std::pair<std::string, Route>> r;
        for (const Road& road : roads())
            r.emplace_back(road.name, make_route(road.points, road.level));
        r.emplace_back("river", make_route(river_line(), 0));
        return r;
    }();
    for (const auto& [n, route] : routes)
        if (n == name) return route;
    return routes.front().second;  // the catalogue names only routes that exist
}

// The distance along `route` of its point nearest to p.
double along(const Route& route, TerrainXY p) {
    double best = 1e300, best_s = 0;
    for (std::size_t i = 1; i < route.points.size(); ++i) {
        const TerrainXY a = route.points[i - 1], b = route.points[i];
        const double dx = b.east_m - a.east_m, dy = b.north_m - a.north_m;
        const double len2 = dx * dx + dy * dy;
        const double u = std::clamp(
            ((p.east_m - a.east_m) * dx + (p.north_m - a.north_m) * dy) / len2, 0.0, 1.0);
        const double d = std::hypot(a.east_m + u * dx - p.east_m, a.north_m + u * dy - p.north_m);
        if (d < best) {
            best = d;
            best_s = route.at[i - 1] + u * std::sqrt(len2);
        }
    }
    return best_s;
}

// The point at distance s along the route, and the unit direction of travel there.
struct RoutePoint {
    TerrainXY xy;
    double dir_east = 0, dir_north = 1;
};
RoutePoint point_at(const Route& route, double s) {
    const auto it = std::upper_bound(route.at.begin(), route.at.end(), s);
    const std::size_t i = std::clamp<std::size_t>(static_cast<std::size_t>(it - route.at.begin()),
                                                  1, route.points.size() - 1);
    const TerrainXY a = route.points[i - 1], b = route.points[i];
    const double len = route.at[i] - route.at[i - 1];
    const double u = std::clamp((s - route.at[i - 1]) / len, 0.0, 1.0);
    return {{a.east_m + u * (b.east_m - a.east_m), a.north_m + u * (b.north_m - a.north_m)},
            (b.east_m - a.east_m) / len,
            (b.north_m - a.north_m) / len};
}

ObjectSpec car(std::string name, std::string route, double speed, TerrainXY from, bool reversed,
               Rgb colour) {
    ObjectSpec s;
    s.name = std::move(name);
    s.kind = ObjectKind::car;
    s.route = std::move(route);
    s.speed_mps = speed;
    s.start_m = along(route_named(s.route), from);
    s.reversed = reversed;
    s.lane_m = 1.75;
    s.colour = colour;
    return s;
}

ObjectState state_of(std::size_t index, double t) {
    const ObjectSpec& spec = object_catalogue()[index];
    const Route& route = route_named(spec.route);
    const double length = route.length();
    // Back and forth: the distance travelled folded onto 0..length (a triangle wave).
    const double period = 2 * length;
    const double travelled =
        (spec.reversed ? period - spec.start_m : spec.start_m) + spec.speed_mps * t;
    double phase = std::fmod(travelled, period);
    if (phase < 0) phase += period;
    const bool outbound = phase <= length;
    const double s = outbound ? phase : period - phase;
    const RoutePoint p = point_at(route, s);
    const double sign = outbound ? 1.0 : -1.0;
    const double de = sign * p.dir_east, dn = sign * p.dir_north;
    ObjectState o;
    o.index = index;
    // The lane, to the right of the direction of travel (de, dn): (dn, -de).
    o.xy = {p.xy.east_m + spec.lane_m * dn, p.xy.north_m - spec.lane_m * de};
    const geo::LatLon ll = terrain_lat_lon(o.xy);
    o.position = {ll.lat_deg, ll.lon_deg, terrain_height_xy(o.xy)};
    o.heading_deg = std::fmod(std::atan2(de, dn) * geo::rad2deg + 360.0, 360.0);
    o.speed_mps = spec.speed_mps;
    o.north_mps = spec.speed_mps * dn;
    o.east_mps = spec.speed_mps * de;
    o.level = route.level;
    return o;
}

double distance_to_segment(TerrainXY p, TerrainXY a, TerrainXY b) {
    const double dx = b.east_m - a.east_m, dy = b.north_m - a.north_m;
    const double len2 = dx * dx + dy * dy;
    const double u =
        len2 > 0 ? std::clamp(((p.east_m - a.east_m) * dx + (p.north_m - a.north_m) * dy) / len2,
                              0.0, 1.0)
                 : 0.0;
    return std::hypot(a.east_m + u * dx - p.east_m, a.north_m + u * dy - p.north_m);
}

}  // namespace

const std::vector<Road>& roads() {
    static const std::vector<Road> r{
        // North of the river, clear of the farm (300 m) and the radio mast.
        {"east_west",
         {{-6000, -750},
          {-3000, -700},
          {-1000, -620},
          {highway_east_m, -600},
          {2500, -560},
          {4500, -420},
          {6000, -300}},
         4,
         0},
        // Four lanes of 3.5 m and a metre of shoulder each side: 28 m of deck over the
        // east-west road, hiding a car at 15 m/s for about two seconds.
        {"highway", {{highway_east_m, -4500}, {highway_east_m, 3800}}, 14, 1},
        // Round the east hill's far side (seen from the circle, the hill hides parts of it).
        {"hill_road",
         {{3500, -490},
          {4600, 900},
          {5000, 2400},
          {4300, 3900},
          {2800, 4600},
          {1500, 4300},
          {highway_east_m + 14, 3800}},
         3.5,
         0},
    };
    return r;
}

std::string_view to_string(ObjectKind kind) {
    switch (kind) {
        case ObjectKind::car:
            return "car";
        case ObjectKind::truck:
            return "truck";
        case ObjectKind::boat:
            return "boat";
    }
    return "car";
}

const std::vector<ObjectSpec>& object_catalogue() {
    static const std::vector<ObjectSpec> catalogue = [] {
        std::vector<ObjectSpec> c;
        // A white car eastbound 1.5 km west of the circle's centre: two and a half minutes
        // of open road before the overpass.
        c.push_back(car("car", "east_west", 15, {-1500, -640}, false, {235, 235, 230}));
        // Five cars westbound, 180 m apart, reaching the overpass 24, 36, ... 72 s after
        // the start: one occlusion every 12 s.
        const Rgb convoy_colours[] = {
            {150, 25, 25}, {30, 55, 140}, {185, 185, 190}, {35, 35, 38}, {215, 125, 30}};
        for (int k = 0; k < 5; ++k)
            c.push_back(car("convoy" + std::to_string(k + 1), "east_west", 15,
                            {highway_east_m + 15.0 * (24 + 12 * k), -590}, true,
                            convoy_colours[k]));
        ObjectSpec truck;
        truck.name = "truck";
        truck.kind = ObjectKind::truck;
        truck.route = "highway";
        truck.speed_mps = 20;
        truck.start_m = along(route_named("highway"), {highway_east_m, -3000});
        truck.lane_m = 5.25;
        truck.length_m = 12;
        truck.width_m = 2.5;
        truck.height_m = 3.5;
        truck.colour = {200, 60, 40};
        c.push_back(truck);
        c.push_back(
            car("highway_car", "highway", 25, {highway_east_m, 3000}, true, {185, 185, 190}));
        c.push_back(car("hill_car", "hill_road", 12, {4600, 900}, false, {40, 90, 160}));
        c.push_back(car("tractor", "hill_road", 5, {2800, 4600}, true, {200, 170, 30}));
        ObjectSpec boat;
        boat.name = "boat";
        boat.kind = ObjectKind::boat;
        boat.route = "river";
        boat.speed_mps = 6;
        boat.start_m = along(route_named("river"), {-2500, river_north_m(-2500)});
        boat.length_m = 9;
        boat.width_m = 3;
        boat.height_m = 2;
        boat.colour = {225, 225, 220};
        c.push_back(boat);
        return c;
    }();
    return catalogue;
}

ObjectSet ObjectSet::all() {
    ObjectSet s;
    for (std::size_t i = 0; i < object_catalogue().size(); ++i) s.chosen_.push_back(i);
    return s;
}

std::optional<ObjectSet> ObjectSet::parse(std::string_view text, std::string& why) {
    if (text == "all") return all();
    if (text == "none") return ObjectSet{};
    ObjectSet s;
    std::size_t from = 0;
    while (from <= text.size()) {
        const std::size_t comma = std::min(text.find(',', from), text.size());
        const std::string_view name = text.substr(from, comma - from);
        const auto& catalogue = object_catalogue();
        const auto it = std::find_if(catalogue.begin(), catalogue.end(),
                                     [&](const ObjectSpec& o) { return o.name == name; });
        if (it == catalogue.end()) {
            why = "unknown object '" + std::string(name) + "' (all, none, or names from:";
            for (const ObjectSpec& o : catalogue) why += " " + o.name;
            why += ")";
            return std::nullopt;
        }
        const auto index = static_cast<std::size_t>(it - catalogue.begin());
        if (std::find(s.chosen_.begin(), s.chosen_.end(), index) != s.chosen_.end()) {
            why = "object '" + std::string(name) + "' given twice";
            return std::nullopt;
        }
        s.chosen_.push_back(index);
        from = comma + 1;
    }
    return s;
}

std::vector<ObjectState> ObjectSet::at(double t_s) const {
    std::vector<ObjectState> out;
    out.reserve(chosen_.size());
    for (std::size_t i : chosen_) out.push_back(state_of(i, t_s));
    return out;
}

bool under_deck(TerrainXY p, int level) {
    for (const Road& road : roads()) {
        if (road.level <= level) continue;
        for (std::size_t i = 1; i < road.points.size(); ++i)
            if (distance_to_segment(p, road.points[i - 1], road.points[i]) < road.halfwidth_m)
                return true;
    }
    return false;
}

}  // namespace gimbal::sim
