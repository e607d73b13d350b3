// A simulated gimbal as a byte-level device: what the daemon's sim link and the gimbal-sim
// tool drive. Pure: time is passed in, nothing here touches sockets or clocks.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace gimbal::sim {

class Device {
  public:
    virtual ~Device() = default;
    // Bytes written by the controller (the daemon) at time now_s (seconds, any epoch,
    // monotonic). Arbitrary chunking: the device frames them itself.
    virtual void receive(std::span<const std::uint8_t> bytes, double now_s) = 0;
    // Runs the model up to now_s and appends every byte the gimbal sends meanwhile.
    virtual void advance(double now_s, std::vector<std::uint8_t>& out) = 0;
};

}  // namespace gimbal::sim
