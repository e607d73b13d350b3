// Image geometry (contract section 16): a pinhole camera at the gimbal, x to the right and y
// down across the image in -1..1 with x = tan(a) / tan(hfov/2), y = tan(b) / tan(vfov/2);
// `locate` meets a Surface, `project` is its inverse, `pan_tilt_towards` aims the line of
// sight. Pure functions of their arguments (a DEM surface reads its files).
#pragma once

#include <array>
#include <optional>

#include "geo/footprint.hpp"
#include "geo/surface.hpp"

namespace gimbal::geo {

struct ImagePoint {
    double x = 0;  // -1 left edge .. 1 right edge
    double y = 0;  // -1 top edge .. 1 bottom edge
};

struct PixelPoint {
    double px = 0;  // 0 the image's left edge .. width its right edge (pixel i's centre: i + 0.5)
    double py = 0;  // 0 the top edge .. height the bottom edge
};

// The camera of an Orion-style gimbal: the mount attitude (mount -> NED) turned by pan and
// tilt (line_of_sight_attitude), then by `image_rotation_deg` about the line of sight
// (positive turns the image's right axis towards its down axis; 0 when the video is not
// rotated).
CameraPose camera_pose(const Lla& position, const Quat& mount_to_ned, double pan_deg,
                       double tilt_deg, double hfov_deg, double vfov_deg,
                       double image_rotation_deg = 0);

// Finite position and attitude, fields of view in (0, 180) degrees.
bool valid(const CameraPose& camera);

// The ray through an image point, in the camera frame (forward, right, down; not unit
// length), in NED and in ECEF.
Vec3 image_ray_camera(const CameraPose& camera, ImagePoint p);
Vec3 image_ray_ned(const CameraPose& camera, ImagePoint p);
Vec3 image_ray_ecef(const CameraPose& camera, ImagePoint p);

// Pixel coordinates in an image of width x height pixels <-> normalised coordinates. nullopt
// for a non-positive or non-finite size.
std::optional<ImagePoint> from_pixels(PixelPoint p, double width, double height);
std::optional<PixelPoint> to_pixels(ImagePoint p, double width, double height);

struct Location {
    Intersection ray;  // status hit: point and range_m
    SurfaceKind surface = SurfaceKind::terrain;
};
// The ground point seen at an image position. status invalid for an invalid camera.
Location locate(const CameraPose& camera, ImagePoint p, Surface& surface,
                const RayOptions& options = {});

struct Projection {
    ImagePoint at;          // meaningful only when in_front
    bool in_front = false;  // the point lies ahead of the camera's image plane
    bool visible = false;   // in front, within -1..1, and (with a surface) not hidden by it
};
// Where a point appears in the image. With a surface, a point the ray meets the surface
// more than `occlusion_tolerance_m` before is not visible. nullopt for an invalid camera or
// point.
std::optional<Projection> project(const CameraPose& camera, const Lla& point,
                                  Surface* surface = nullptr, double occlusion_tolerance_m = 1.0);

// The pan and tilt (line_of_sight_attitude's) that put `to` at the image centre, seen from
// `from` on a mount with attitude mount_to_ned. Pan in (-180, 180], tilt in [-90, 90].
// nullopt when the points coincide or an input is not finite.
struct PanTilt {
    double pan_deg = 0;
    double tilt_deg = 0;
};
std::optional<PanTilt> pan_tilt_towards(const Quat& mount_to_ned, const Lla& from, const Lla& to);

// The four image corners (x, y = -1,-1; 1,-1; 1,1; -1,1: top-left, top-right, bottom-right,
// bottom-left) on the surface. nullopt when the camera is invalid or a corner ray does not
// meet it (first_failure then says why: pass a pointer to learn it).
struct SurfaceFootprint {
    std::array<Lla, 4> corners;
    std::array<double, 4> range_m{};
    SurfaceKind surface = SurfaceKind::terrain;
};
std::optional<SurfaceFootprint> footprint(const CameraPose& camera, Surface& surface,
                                          const RayOptions& options = {},
                                          RayStatus* first_failure = nullptr);

}  // namespace gimbal::geo
