// Simulated fixes for the ground filter's tests: an object moving on the ground near a
// reference point (north/east metres -> WGS84), located with Gaussian noise of the sigma the
// filter assumes for the slant range, from a fixed seed.
#pragma once

#include <cmath>
#include <random>

#include "geo/wgs84.hpp"
#include "track/ground/ground_filter.hpp"

namespace ground_test {

inline const gimbal::geo::Lla reference{47.3769, 8.5417, 420};

inline gimbal::geo::Lla at(double north, double east, double alt = 420) {
    using namespace gimbal::geo;
    const Vec3 origin = lla_to_ecef(reference);
    auto p = ecef_to_lla(origin + ned_to_ecef({north, east, 0}, reference));
    p.alt_m = alt;
    return p;
}

// North/east metres of p from the reference.
inline std::pair<double, double> local(const gimbal::geo::Lla& p) {
    using namespace gimbal::geo;
    const Vec3 d = ecef_to_ned(lla_to_ecef(p) - lla_to_ecef(reference), reference);
    return {d.x, d.y};
}

class Noise {
  public:
    explicit Noise(unsigned seed) : rng_(seed) {}
    double operator()(double sigma) { return std::normal_distribution<double>(0, sigma)(rng_); }

  private:
    std::mt19937 rng_;
};

}  // namespace ground_test
