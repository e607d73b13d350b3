// --rx-log: one JSON line per valid frame the controller sent, decoded by the protocol's
// registry entry (Simulator::make_rx_decoder), flushed at once, so a test can check the exact
// bytes the daemon put on the wire.
#pragma once

#include <cstdint>
#include <fstream>
#include <map>
#include <memory>
#include <span>
#include <string>

#include "protocols/registry.hpp"

namespace gimbal_sim {

class RxLog {
  public:
    // Opens (truncates) the file; throws on failure.
    RxLog(const std::string& path, const gimbal::protocols::Entry& protocol);

    // Bytes received from source `src` ("tcp" or "pty") at t seconds since start.
    void received(const std::string& src, std::span<const std::uint8_t> bytes, double t);
    // The source's connection ended: a partial frame from it belongs to nothing.
    void reset(const std::string& src);

  private:
    gimbal::protocols::RxDecoder& decoder(const std::string& src);

    std::ofstream out_;
    const gimbal::protocols::Entry& protocol_;
    std::map<std::string, std::unique_ptr<gimbal::protocols::RxDecoder>> decoders_;
};

}  // namespace gimbal_sim
