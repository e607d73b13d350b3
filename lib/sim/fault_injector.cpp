#include "sim/fault_injector.hpp"

#include <algorithm>

namespace gimbal::sim {

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
