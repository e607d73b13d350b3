// The vehicle feed (issue 5): reads the aircraft's MAVLink (VehicleSource) into a
// VehicleState and, on a 50 ms schedule, sends every gimbal what its protocol's feeder
// (protocols/vehicle_feeder.hpp, made by the registry) says is due, and what it must hear at
// once when the feed is lost or back. Without a `vehicle` section it only serves the STATE
// `vehicle` object (never connected).
#pragma once

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>
#include <chrono>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "config.hpp"
#include "gimbal_session.hpp"
#include "protocols/vehicle_feeder.hpp"
#include "state/event.hpp"
#include "vehicle/vehicle_state.hpp"
#include "vehicle_source.hpp"

namespace gimbald {

class VehicleFeed {
  public:
    using EventSink = std::function<void(const gimbal::state::Event&)>;

    // Binds the vehicle source when `config` has one (throws like VehicleSource).
    VehicleFeed(boost::asio::io_context& io,
                const std::optional<gimbal::daemon::VehicleConfig>& config, EventSink on_event,
                gimbal::mavlink::FramerOptions framer_options = {});
    ~VehicleFeed();

    // A gimbal to feed, by its protocol's feeder (Entry::make_feeder of its configuration).
    void add_gimbal(GimbalSession& session,
                    std::unique_ptr<gimbal::protocols::VehicleFeeder> feeder);

    void start();
    void stop();

    // The STATE `vehicle` object for `session` (with what that gimbal was fed).
    nlohmann::json snapshot(const GimbalSession& session) const;

    // For the MAVLink gimbal manager: every decoded message after the feed has taken it, the
    // two-way source (null without a vehicle section) and what the feed knows.
    void add_listener(std::function<void(const gimbal::mavlink::Message&)> listener) {
        listeners_.push_back(std::move(listener));
    }
    VehicleSource* source() { return source_.get(); }
    const gimbal::vehicle::VehicleState& vehicle_state() const { return state_; }
    double monotonic_s() const { return now_s(); }  // the clock vehicle_state() runs on

  private:
    struct Target {
        GimbalSession* session = nullptr;
        std::unique_ptr<gimbal::protocols::VehicleFeeder> feeder;
        std::uint64_t sent = 0;
    };

    double now_s() const;
    double unix_now_s() const;
    void on_message(const gimbal::mavlink::Message& message);
    void check_connection(double now);
    void schedule_tick();
    void on_tick();
    gimbal::protocols::FeedTime feed_time(double now) const;
    void send(Target& target, std::vector<gimbal::protocols::FeedBytes>& packets);

    gimbal::vehicle::VehicleState state_;
    std::vector<std::function<void(const gimbal::mavlink::Message&)>> listeners_;
    std::unique_ptr<VehicleSource> source_;
    EventSink on_event_;
    std::vector<Target> targets_;
    boost::asio::steady_timer timer_;
    std::chrono::steady_clock::time_point epoch_;
    std::chrono::steady_clock::time_point next_tick_;
    std::uint64_t ticks_ = 0;
    bool stopped_ = true;
};

}  // namespace gimbald
