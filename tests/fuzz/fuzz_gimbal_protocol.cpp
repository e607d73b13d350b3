// libFuzzer target for the MAVLink gimbal manager's and camera components' mapping: arbitrary
// bytes through the framer, every command and set-point message through GimbalManager and
// every command through CameraComponents (two gimbals, fixed typed state). Nothing may crash, no
// request may name the laser or a gimbal we do not have, a request always carries finite
// numbers, and a `point` stays inside the image (-1..1).
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "gimbal_protocol/camera.hpp"
#include "gimbal_protocol/commands.hpp"
#include "mavlink/mavlink.hpp"
#include "protocols/orion/orion_capabilities.hpp"
#include "protocols/viewpro/viewpro_capabilities.hpp"

namespace m = gimbal::mavlink;
namespace gp = gimbal::gimbal_protocol;

namespace {

[[noreturn]] void fail(const char* what) {
    std::fprintf(stderr, "fuzz_gimbal_protocol: %s\n", what);
    std::abort();
}

// The two gimbals' typed state, fixed: an Orion with telemetry and CAMERAS, a Viewpro with an
// output frame.
struct Gimbals {
    gimbal::state::OrionData orion;
    gimbal::protocols::OrionCapabilities orion_caps{orion};
    std::optional<gimbal::viewpro::Output> viewpro;
    gimbal::protocols::ViewproCapabilities viewpro_caps{viewpro};

    Gimbals() {
        gimbal::state::OrionTelemetry t;
        t.packet.quat = {1.0, 0.0, 0.0, 0.0};
        t.shared.pan = 10.0;
        t.shared.tilt = -5.0;
        orion.telemetry = t;
        gimbal::orion::CameraSettings cam;
        cam.min_focal_length_mm = 4.3;
        cam.max_focal_length_mm = 129.0;
        gimbal::orion::Cameras cameras;
        cameras.cameras = {cam};
        orion.packets.cameras = gimbal::state::Received<gimbal::orion::Cameras>{cameras, {}, 0};
        gimbal::viewpro::Output o;
        o.gimbal_roll_deg = 0.0;
        o.gimbal_pitch_deg = -45.0;
        o.gimbal_yaw_deg = 3.0;
        viewpro = o;
    }
};

gimbal::session::GimbalView state_of(const std::string& name) {
    static const Gimbals gimbals;
    if (name == "main")
        return {&gimbals.orion_caps, &gimbals.orion.telemetry->shared, true, false, {}, {}};
    return {&gimbals.viewpro_caps, nullptr, false, true, {}, {}};
}

void check(const gp::Mapped& mapped) {
    for (const auto& r : mapped.requests) {
        if (r.gimbal != "main" && r.gimbal != "nose") fail("request for an unknown gimbal");
        if (r.request.value("cmd", "") == "laser") fail("a MAVLink message became a laser request");
        for (const auto& [key, value] : r.request.items())
            if (value.is_number_float() && !std::isfinite(value.get<double>()))
                fail("a request carries a non-finite number");
        if (r.request.value("cmd", "") == "point")
            for (const char* k : {"x", "y"})
                if (!r.request[k].is_number() || std::abs(r.request[k].get<double>()) > 1)
                    fail("a point outside the image");
    }
}

std::vector<gp::ExposedCamera> cameras(const std::vector<gp::ExposedGimbal>& gimbals) {
    std::vector<gp::ExposedCamera> out;
    for (const auto& g : gimbals) {
        gp::ExposedCamera c;
        c.gimbal = g;
        c.component_id = gp::camera_component(g.device_id);
        c.video = c.can_point = c.can_zoom = g.protocol == "orion";
        if (c.video) c.streams = {{"main", "15010", m::video_stream::type_mpeg_ts}};
        out.push_back(std::move(c));
    }
    return out;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto gimbals = gp::expose({{"main", "orion"}, {"nose", "viewpro"}});
    gp::GimbalManager manager(gimbals);
    gp::CameraComponents camera_components(cameras(gimbals));
    const gp::StateLookup lookup = state_of;
    const gp::VehicleView vehicle{90.0, 100.0};
    m::Framer framer;
    framer.push(std::span<const std::uint8_t>(data, size), [&](const m::Message& msg) {
        const gp::MavId from{msg.sysid, msg.compid};
        std::optional<gp::CommandView> command;
        if (const auto* c = std::get_if<m::CommandLong>(&msg.payload)) command = gp::view(*c);
        if (const auto* ci = std::get_if<m::CommandInt>(&msg.payload)) command = gp::view(*ci);
        if (command) {
            check(manager.command(*command, from, vehicle, lookup, 0));
            // The camera of the gimbal the sender's component id picks.
            const auto& camera = camera_components.cameras()[msg.compid % 2];
            check(camera_components.command(*command, camera, lookup, 0).mapped);
        } else {
            check(manager.message(msg.payload, from, vehicle, lookup));
        }
    });
    return 0;
}
