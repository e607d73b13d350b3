#include "sim/viewpro_sim_faults.hpp"

#include <algorithm>

#include "viewpro/output.hpp"

namespace gimbal::sim {

namespace {

// Length of the OUTx frame starting at in[0], or 0 when no frame starts there.
std::size_t frame_size_at(std::span<const std::uint8_t> in) {
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

ViewproFaultInjector::ViewproFaultInjector(const FaultOptions& options)
    : options_(options), rng_(options.seed) {
    options_.corrupt_fraction = std::clamp(options_.corrupt_fraction, 0.0, 1.0);
}

void ViewproFaultInjector::apply(std::span<const std::uint8_t> in, std::vector<std::uint8_t>& out) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::size_t i = 0;
    while (i < in.size()) {
        const std::size_t total = frame_size_at(in.subspan(i));
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
            out[start + total - 1] ^= 0x5A;  // a wrong checksum
            ++stats_.corrupted;
        }
        if (options_.junk_every > 0 && ++frames_since_junk_ >= options_.junk_every) {
            frames_since_junk_ = 0;
            append_junk(out);
        }
    }
}

void ViewproFaultInjector::append_junk(std::vector<std::uint8_t>& out) {
    std::uniform_int_distribution<int> byte(0, 255);
    std::uniform_int_distribution<int> count(1, 8);
    out.push_back(viewpro::output_header);
    if (byte(rng_) < 128) out.push_back(viewpro::out3_id);  // a false header
    const int n = count(rng_);
    for (int k = 0; k < n; ++k) out.push_back(static_cast<std::uint8_t>(byte(rng_)));
    ++stats_.junk_inserts;
}

}  // namespace gimbal::sim
