// --rx-log: one JSON line per checksum-valid packet (Orion) or frame (Viewpro) the controller
// sent, flushed at once, so a test can check the exact bytes the daemon put on the wire.
#pragma once

#include <cstdint>
#include <fstream>
#include <map>
#include <span>
#include <string>

#include "orion/framer.hpp"
#include "viewpro/input_framer.hpp"

namespace gimbal_sim {

class RxLog {
  public:
    // Opens (truncates) the file; throws on failure. `protocol`: "orion" or "viewpro".
    RxLog(const std::string& path, const std::string& protocol);

    // Bytes received from source `src` ("tcp" or "pty") at t seconds since start.
    void received(const std::string& src, std::span<const std::uint8_t> bytes, double t);
    // The source's connection ended: a partial frame from it belongs to nothing.
    void reset(const std::string& src);

  private:
    void write_line(const std::string& src, const gimbal::orion::Frame& frame, double t);
    void write_line(const std::string& src, const gimbal::viewpro::InputFrame& frame, double t);

    std::ofstream out_;
    bool viewpro_ = false;
    std::map<std::string, gimbal::orion::Framer> framers_;
    std::map<std::string, gimbal::viewpro::InputFramer> viewpro_framers_;
};

}  // namespace gimbal_sim
