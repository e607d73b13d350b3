// libFuzzer target for the MAVLink gimbal manager's mapping: arbitrary bytes through the
// framer, every command and set-point message through GimbalManager (two gimbals, fixed STATE).
// Nothing may crash, no request may name the laser or a gimbal we do not have, and a request
// always carries finite numbers.
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "gimbal_protocol/commands.hpp"
#include "mavlink/mavlink.hpp"

namespace m = gimbal::mavlink;
namespace gp = gimbal::gimbal_protocol;

namespace {

[[noreturn]] void fail(const char* what) {
    std::fprintf(stderr, "fuzz_gimbal_protocol: %s\n", what);
    std::abort();
}

nlohmann::json state_of(const std::string& name) {
    if (name == "main")
        return {{"link", {{"connected", true}}},
                {"stale", false},
                {"telemetry", {{"pan", 10.0}, {"tilt", -5.0}, {"quat", {1.0, 0.0, 0.0, 0.0}}}},
                {"cameras",
                 {{"cameras", nlohmann::json::array({{{"min_focal_length_mm", 4.3},
                                                      {"max_focal_length_mm", 129.0}}})}}}};
    return {{"output", {{"gimbal", {{"roll", 0.0}, {"pitch", -45.0}, {"yaw", 3.0}}}}}};
}

void check(const gp::Mapped& mapped) {
    for (const auto& r : mapped.requests) {
        if (r.gimbal != "main" && r.gimbal != "nose") fail("request for an unknown gimbal");
        if (r.request.value("cmd", "") == "laser") fail("a MAVLink message became a laser request");
        for (const auto& [key, value] : r.request.items())
            if (value.is_number_float() && !std::isfinite(value.get<double>()))
                fail("a request carries a non-finite number");
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    gp::GimbalManager manager(gp::expose({{"main", "orion"}, {"nose", "viewpro"}}));
    const gp::StateLookup lookup = state_of;
    const gp::VehicleView vehicle{90.0, 100.0};
    m::Framer framer;
    framer.push(std::span<const std::uint8_t>(data, size), [&](const m::Message& msg) {
        const gp::MavId from{msg.sysid, msg.compid};
        if (const auto* c = std::get_if<m::CommandLong>(&msg.payload))
            check(manager.command(gp::view(*c), from, vehicle, lookup, 0));
        else if (const auto* ci = std::get_if<m::CommandInt>(&msg.payload))
            check(manager.command(gp::view(*ci), from, vehicle, lookup, 0));
        else
            check(manager.message(msg.payload, from, vehicle, lookup));
    });
    return 0;
}
