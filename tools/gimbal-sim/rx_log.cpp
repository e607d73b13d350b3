#include "rx_log.hpp"

#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <vector>

namespace gimbal_sim {

RxLog::RxLog(const std::string& path, const gimbal::protocols::Entry& protocol)
    : out_(path, std::ios::out | std::ios::trunc), protocol_(protocol) {
    if (!out_) throw std::runtime_error("cannot open rx log " + path);
}

gimbal::protocols::RxDecoder& RxLog::decoder(const std::string& src) {
    auto& d = decoders_[src];
    if (!d) d = protocol_.simulator.make_rx_decoder();
    return *d;
}

void RxLog::received(const std::string& src, std::span<const std::uint8_t> bytes, double t) {
    std::vector<nlohmann::json> lines;
    decoder(src).push(bytes, lines);
    for (auto& line : lines) {
        line["t"] = std::round(t * 1e6) / 1e6;
        line["src"] = src;
        out_ << line.dump() << '\n';
    }
    if (!lines.empty()) out_.flush();
}

void RxLog::reset(const std::string& src) {
    decoder(src).reset();
}

}  // namespace gimbal_sim
