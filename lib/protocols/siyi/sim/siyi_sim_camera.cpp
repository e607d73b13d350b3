#include "protocols/siyi/sim/siyi_sim_camera.hpp"

#include "geo/attitude.hpp"

namespace gimbal::protocols {

sim::CameraView siyi_camera_view(const SiyiSim& sim) {
    const SiyiSimAircraft a = sim.aircraft();
    const auto fov = siyi::field_of_view(sim.model().model, sim.zoom());
    // SIYI's yaw is positive to the left: the bearing is the heading minus it (any turn; the
    // quaternion needs no wrapping).
    const geo::Quat line_of_sight = geo::normalized(
        geo::euler_to_quat(geo::EulerDeg{0, sim.pitch_deg(), a.yaw_deg - sim.yaw_deg()}));
    sim::CameraView view;
    view.model_time_s = sim.time_s();
    view.pose = geo::CameraPose{geo::Lla{a.lat_deg, a.lon_deg, a.alt_ellipsoid_m}, line_of_sight,
                                fov.hfov_deg, fov.vfov_deg};
    view.platform_to_ned =
        geo::normalized(geo::euler_to_quat(geo::EulerDeg{a.roll_deg, a.pitch_deg, a.yaw_deg}));
    view.geoid_undulation_m = a.alt_ellipsoid_m - a.alt_msl_m;
    return view;
}

std::optional<sim::CameraView> siyi_sim_camera(const sim::Device& device) {
    const auto* sim = dynamic_cast<const SiyiSim*>(&device);
    if (sim == nullptr) return std::nullopt;
    return siyi_camera_view(*sim);
}

}  // namespace gimbal::protocols
