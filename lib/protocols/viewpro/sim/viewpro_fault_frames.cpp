#include "protocols/viewpro/sim/viewpro_fault_frames.hpp"

#include "protocols/viewpro/codec/output.hpp"

namespace gimbal::sim {

namespace {

std::size_t viewpro_frame_size_at(std::span<const std::uint8_t> in) {
    if (in.size() < 2 || in[0] != viewpro::output_header) return 0;
    switch (in[1]) {
        case viewpro::out1_id:
            return viewpro::out1_size;
        case viewpro::out2_id:
            return viewpro::out2_size;
        case viewpro::out3_id:
            return viewpro::out3_size;  // and OUT4
        default:
            return 0;
    }
}

}  // namespace

FrameShape viewpro_output_frames() {
    return {viewpro_frame_size_at, viewpro::output_header, viewpro::out3_id};
}

}  // namespace gimbal::sim
