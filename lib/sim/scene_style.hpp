// What the simulated camera's picture shows, and in which colours (docs/simulator.md
// "Video"): the ground coloured by height and shaded by slope under a sun in the north-west,
// the river, grid lines on the terrain's local grid, the landmarks of sim/terrain.hpp as
// saturated discs with a black ring, distance haze, and a sky that brightens towards the
// horizon. Colours are picked to stay apart after 4:2:0 subsampling and H.264: the ground's
// chroma is muted (greens and browns), the landmarks' is far from it and from each other.
#pragma once

#include <cstddef>

#include "sim/i420_frame.hpp"

namespace gimbal::sim::scene {

// Landmarks: a disc of this ground radius in the landmark's colour (never smaller than
// landmark_min_radius_px on screen, so distant ones stay visible), then a black ring a quarter
// of the radius wide (at least 1.5 px).
inline constexpr double landmark_radius_m = 40;
inline constexpr double landmark_min_radius_px = 3;
// The colour of landmarks()[index] (cycles through five colours).
Rgb landmark_colour(std::size_t index);
inline constexpr Rgb landmark_ring{20, 20, 20};

// Grid lines on the terrain's local grid (TerrainXY, true north and east): a dark 1 px line
// every 100 m (fading out where a pixel spans more than 6..12 m of ground) and a light 2 px
// line every 1000 m.
inline constexpr double grid_minor_m = 100;
inline constexpr double grid_major_m = 1000;
inline constexpr Rgb grid_major{235, 235, 225};
inline constexpr double grid_minor_darken = 0.45;

// The river: a band this wide either side of river_north_m().
inline constexpr double river_halfwidth_m = 40;
inline constexpr Rgb water{50, 80, 110};

// Roads (sim/ground_objects.hpp roads()): asphalt; the highway's deck is concrete with a
// dark parapet along its last 0.8 m.
inline constexpr Rgb asphalt{95, 95, 92};
inline constexpr Rgb deck{160, 158, 150};
inline constexpr Rgb parapet{60, 60, 60};
// Moving objects: body in the catalogue's colour, roof 30 % lighter, windows, a truck's box,
// a boat's cabin and its wake on the water.
inline constexpr Rgb glass{35, 40, 50};
inline constexpr Rgb cargo{225, 225, 218};
inline constexpr Rgb boat_cabin{60, 70, 90};
inline constexpr Rgb foam{205, 215, 220};

// Ground by height above the ellipsoid: these colours at these heights, linear between.
struct HeightColour {
    double alt_m;
    Rgb colour;
};
inline constexpr HeightColour ground_ramp[] = {
    {0, {55, 90, 50}},     {250, {80, 120, 55}},   {450, {115, 135, 70}},
    {650, {145, 135, 90}}, {850, {150, 128, 108}}, {1000, {160, 152, 145}},
};
// Sun: azimuth (clockwise from north) and elevation, degrees. Flat ground has shade 1.
inline constexpr double sun_azimuth_deg = 315;
inline constexpr double sun_elevation_deg = 40;

// Sky: haze at and below the horizon (and over ground as distance grows, all haze at the
// renderer's max range), zenith blue from 25 degrees up.
inline constexpr Rgb haze{190, 205, 220};
inline constexpr Rgb zenith{70, 130, 220};
inline constexpr double sky_gradient_deg = 25;

// A camera under the terrain sees this.
inline constexpr Rgb underground{10, 10, 10};

}  // namespace gimbal::sim::scene
