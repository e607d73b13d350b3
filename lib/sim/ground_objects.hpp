// The simulator's roads and the objects that move on its ground (contract section 20,
// "Simulator"; docs/simulator.md "Moving objects"): vehicles on the roads at 5-25 m/s and a
// boat on the river, each a pure function of the model's time, so the rendered picture, the
// truth a test reads (gimbal-sim --objects-log) and any replay agree. A four-lane highway
// crosses the east-west road on an overpass: what drives under it is out of sight for about
// two seconds. Pure.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "sim/i420_frame.hpp"
#include "sim/terrain.hpp"

namespace gimbal::sim {

// A road: a polyline on the terrain's local grid, at ground height. Level 1 is raised (the
// highway's deck): where it crosses a level 0 road it hides what drives beneath.
struct Road {
    std::string name;
    std::vector<TerrainXY> points;
    double halfwidth_m = 4;
    int level = 0;
};
const std::vector<Road>& roads();

enum class ObjectKind { car, truck, boat };
std::string_view to_string(ObjectKind kind);

// One object of the catalogue: what it is and how it moves. It drives its route back and
// forth (turning round at the ends), `start_m` along it at time 0, keeping `lane_m` to the
// right of the route's line.
struct ObjectSpec {
    std::string name;
    ObjectKind kind = ObjectKind::car;
    std::string route;  // a road's name, or "river"
    double speed_mps = 15;
    double start_m = 0;
    bool reversed = false;  // sets off from the route's end towards its start
    double lane_m = 0;
    double length_m = 4.6;
    double width_m = 1.8;
    double height_m = 1.5;
    Rgb colour;
};
const std::vector<ObjectSpec>& object_catalogue();

// One object at one moment.
struct ObjectState {
    std::size_t index = 0;  // in object_catalogue()
    TerrainXY xy;
    geo::Lla position;       // WGS84; alt the ground's (the river's surface for a boat)
    double heading_deg = 0;  // where its nose points, clockwise from north
    double speed_mps = 0;    // along the route
    double north_mps = 0;    // velocity over the ground
    double east_mps = 0;
    int level = 0;  // the road's level (0 for the river)
    const ObjectSpec& spec() const { return object_catalogue()[index]; }
};

// A choice of objects from the catalogue.
class ObjectSet {
  public:
    ObjectSet() = default;  // none
    static ObjectSet all();
    // "all", "none", or a comma-separated list of catalogue names; nullopt (and `why`) for an
    // unknown or repeated name.
    static std::optional<ObjectSet> parse(std::string_view text, std::string& why);

    bool empty() const { return chosen_.empty(); }
    const std::vector<std::size_t>& indices() const { return chosen_; }
    // Every chosen object at model time t (seconds).
    std::vector<ObjectState> at(double t_s) const;

  private:
    std::vector<std::size_t> chosen_;
};

// Whether a point at ground `level` is hidden from above by a higher road (a deck).
bool under_deck(TerrainXY p, int level);

}  // namespace gimbal::sim
