#include "sim/fault_injector.hpp"

#include <algorithm>

#include "protocols/orion/codec/framing.hpp"
#include "protocols/viewpro/codec/output.hpp"

namespace gimbal::sim {

namespace {

std::size_t orion_frame_size_at(std::span<const std::uint8_t> in) {
    if (in.size() < orion::header_size || in[0] != orion::sync0 || in[1] != orion::sync1 ||
        in[3] > orion::max_data_length)
        return 0;
    return orion::header_size + in[3] + orion::checksum_size;
}

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

FrameShape orion_frames() {
    return {orion_frame_size_at, orion::sync0, orion::sync1};
}

FrameShape viewpro_output_frames() {
    return {viewpro_frame_size_at, viewpro::output_header, viewpro::out3_id};
}

FaultInjector::FaultInjector(const FaultOptions& options, FrameShape shape)
    : options_(options), shape_(shape), rng_(options.seed) {
    options_.corrupt_fraction = std::clamp(options_.corrupt_fraction, 0.0, 1.0);
}

void FaultInjector::apply(std::span<const std::uint8_t> in, std::vector<std::uint8_t>& out) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::size_t i = 0;
    while (i < in.size()) {
        const std::size_t total = shape_.frame_size_at(in.subspan(i));
        if (total == 0 || in.size() - i < total) {  // not a frame: pass the byte through
            out.push_back(in[i++]);
            continue;
        }
        const std::size_t start = out.size();
        out.insert(out.end(), in.begin() + static_cast<long>(i),
                   in.begin() + static_cast<long>(i + total));
        i += total;
        ++stats_.frames;
        if (options_.corrupt_fraction > 0 && unit(rng_) < options_.corrupt_fraction) {
            out[start + total - 1] ^= 0x5A;  // a wrong (last) checksum byte
            ++stats_.corrupted;
        }
        if (options_.junk_every > 0 && ++frames_since_junk_ >= options_.junk_every) {
            frames_since_junk_ = 0;
            append_junk(out);
        }
    }
}

// A stray sync (sometimes a whole false header) and a few random bytes: what a noisy serial
// line delivers, and what a framer must skip without losing the next frame.
void FaultInjector::append_junk(std::vector<std::uint8_t>& out) {
    std::uniform_int_distribution<int> byte(0, 255);
    std::uniform_int_distribution<int> count(1, 8);
    out.push_back(shape_.sync0);
    if (byte(rng_) < 128) out.push_back(shape_.sync1);
    const int n = count(rng_);
    for (int k = 0; k < n; ++k) out.push_back(static_cast<std::uint8_t>(byte(rng_)));
    ++stats_.junk_inserts;
}

}  // namespace gimbal::sim
