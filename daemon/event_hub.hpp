// Every gimbal (and vehicle) event goes to every stream that wants it: UDP subscribers, MQTT,
// WebSocket clients, MAVLink. Producers publish once; each transport adds its own sink.
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "state/event.hpp"

namespace gimbald {

class EventHub {
  public:
    using Sink = std::function<void(const std::string& gimbal, const gimbal::state::Event&)>;

    void add(Sink sink) { sinks_.push_back(std::move(sink)); }
    void publish(const std::string& gimbal, const gimbal::state::Event& event) const {
        for (const auto& sink : sinks_) sink(gimbal, event);
    }

  private:
    std::vector<Sink> sinks_;
};

}  // namespace gimbald
