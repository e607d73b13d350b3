#include "protocols/orion/sim/orion_fault_frames.hpp"

#include "protocols/orion/codec/framing.hpp"

namespace gimbal::sim {

namespace {

std::size_t orion_frame_size_at(std::span<const std::uint8_t> in) {
    if (in.size() < orion::header_size || in[0] != orion::sync0 || in[1] != orion::sync1 ||
        in[3] > orion::max_data_length)
        return 0;
    return orion::header_size + in[3] + orion::checksum_size;
}

}  // namespace

FrameShape orion_frames() {
    return {orion_frame_size_at, orion::sync0, orion::sync1};
}

}  // namespace gimbal::sim
