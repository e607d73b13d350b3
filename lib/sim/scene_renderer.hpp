// The simulated camera's picture: the analytic terrain of sim/terrain.hpp seen through a
// pinhole camera (geo::CameraPose), rendered straight into I420 (scene contents and colours:
// sim/scene_style.hpp, docs/simulator.md "Video"). Pure and deterministic: the same camera
// and options give the same bytes.
//
// Rays are cast only on a grid of image points (every grid_px pixels, through
// TerrainRayCaster); between them the ground coordinates are interpolated perspective-correct
// (exact for a plane) and each pixel is textured from them. Cells whose corners disagree - the
// horizon, the edge of a hill hiding the ground behind it - are split in four and cast again,
// down to 4 px; those that still disagree blend their corners' colours (a soft edge, right to
// a couple of pixels), or cast a ray per pixel where a landmark or an object is. A landmark is
// drawn where the ray meets its ground, so it appears where geo::project puts it (within a pixel or
// two).
#pragma once

#include <memory>
#include <span>

#include "geo/footprint.hpp"
#include "sim/ground_objects.hpp"
#include "sim/i420_frame.hpp"

namespace gimbal::sim {

struct SceneOptions {
    int width = 640;   // even, 16..4096
    int height = 360;  // even, 16..4096
    int grid_px = 16;  // ray spacing, 4, 8, 16, 32 or 64 pixels
    // Ground farther than this is not drawn (the haze colour takes over towards it).
    double max_range_m = 30000;
    bool monochrome = false;  // luma only, neutral chroma (the LWIR camera)
};
bool valid(const SceneOptions& options);

struct RenderStats {
    int rays = 0;           // rays cast for the last frame
    int refined_cells = 0;  // cells split in four (each split casts five rays)
    int blended_cells = 0;  // 4 px cells blended from their corners' colours (edges)
    int pixel_cells = 0;    // 4 px cells cast pixel by pixel (edges across a landmark)
};

class SceneRenderer {
  public:
    // Invalid options (see valid) are replaced by the defaults.
    explicit SceneRenderer(const SceneOptions& options = {});
    ~SceneRenderer();
    SceneRenderer(const SceneRenderer&) = delete;
    SceneRenderer& operator=(const SceneRenderer&) = delete;

    // Renders what `camera` sees into `frame`, resized to the options' size, with these moving
    // objects (sim/ground_objects.hpp, at the frame's time) on the ground. An invalid camera
    // (geo::valid) gives a uniform mid-grey frame and false.
    bool render(const geo::CameraPose& camera, I420Frame& frame,
                std::span<const ObjectState> objects = {});

    // The LWIR camera's picture has no colour; the Orion can switch cameras any time.
    void set_monochrome(bool monochrome);
    const SceneOptions& options() const;
    const RenderStats& stats() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace gimbal::sim
