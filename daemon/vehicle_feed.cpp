#include "vehicle_feed.hpp"

#include "logging.hpp"

namespace gimbald {

namespace cfg = gimbal::daemon;
namespace log = gimbal::log;
namespace vehicle = gimbal::vehicle;

namespace {

constexpr auto tick_period = std::chrono::duration_cast<std::chrono::steady_clock::duration>(
    std::chrono::duration<double>(gimbal::protocols::feed_tick_s));

vehicle::VehicleOptions options_of(const std::optional<cfg::VehicleConfig>& config) {
    vehicle::VehicleOptions o;
    if (config) {
        o.system_id = config->system_id;
        o.timeout_s = config->timeout_s;
    }
    return o;
}

}  // namespace

VehicleFeed::VehicleFeed(boost::asio::io_context& io,
                         const std::optional<cfg::VehicleConfig>& config, EventSink on_event,
                         gimbal::mavlink::FramerOptions framer_options)
    : state_(options_of(config)),
      on_event_(std::move(on_event)),
      timer_(io),
      epoch_(std::chrono::steady_clock::now()) {
    if (!config) return;
    source_ = std::make_unique<VehicleSource>(
        io, *config, [this](const gimbal::mavlink::Message& m) { on_message(m); },
        std::move(framer_options));
    auto options = options_of(config);
    options.source = source_->describe();
    state_ = vehicle::VehicleState(options);
}

VehicleFeed::~VehicleFeed() {
    stop();
}

double VehicleFeed::now_s() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - epoch_).count();
}

double VehicleFeed::unix_now_s() const {
    return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch())
        .count();
}

void VehicleFeed::add_gimbal(GimbalSession& session,
                             std::unique_ptr<gimbal::protocols::VehicleFeeder> feeder) {
    Target t;
    t.session = &session;
    t.feeder = std::move(feeder);
    targets_.push_back(std::move(t));
}

gimbal::protocols::FeedTime VehicleFeed::feed_time(double now) const {
    return {now, unix_now_s(), ticks_};
}

void VehicleFeed::start() {
    if (!source_) return;  // nothing to feed: the `vehicle` command is the way then
    stopped_ = false;
    source_->start();
    log::info("vehicle_source", "listening for the vehicle's MAVLink",
              {{"source", source_->describe()}});
    next_tick_ = std::chrono::steady_clock::now();
    schedule_tick();
}

void VehicleFeed::stop() {
    if (stopped_) return;
    stopped_ = true;
    timer_.cancel();
    if (source_) source_->stop();
}

void VehicleFeed::on_message(const gimbal::mavlink::Message& message) {
    const double now = now_s();
    const bool had_system = state_.system_id().has_value();
    state_.apply(message, now);
    if (!had_system && state_.system_id())
        log::info("vehicle_found", "vehicle system id chosen",
                  {{"system_id", *state_.system_id()}, {"component_id", state_.component_id()}});
    check_connection(now);
    for (const auto& listener : listeners_) listener(message);
}

void VehicleFeed::check_connection(double now) {
    const auto change = state_.connection_change(now);
    if (!change) return;
    if (*change)
        log::info("vehicle_connected", "vehicle feed up", {{"source", source_->describe()}});
    else
        log::warn("vehicle_lost", "no vehicle data within vehicle.timeout_s",
                  {{"source", source_->describe()}});
    // What a gimbal must hear of the change reaches it at once, not at its next slot.
    std::vector<gimbal::protocols::FeedBytes> packets;
    for (auto& t : targets_) {
        t.feeder->connection_changed(state_, feed_time(now), packets);
        send(t, packets);
    }
    if (on_event_) on_event_(gimbal::state::Event{"vehicle", {{"connected", *change}}});
}

void VehicleFeed::schedule_tick() {
    next_tick_ += tick_period;
    // After a stall, pick up from now instead of bursting the missed ticks.
    const auto now = std::chrono::steady_clock::now();
    if (next_tick_ < now) next_tick_ = now;
    timer_.expires_at(next_tick_);
    timer_.async_wait([this](const boost::system::error_code& ec) {
        if (ec || stopped_) return;
        on_tick();
        schedule_tick();
    });
}

void VehicleFeed::on_tick() {
    const double now = now_s();
    check_connection(now);
    const gimbal::protocols::FeedTime t = feed_time(now);
    ++ticks_;
    std::vector<gimbal::protocols::FeedBytes> packets;
    for (auto& target : targets_) {
        target.feeder->tick(state_, t, packets);
        send(target, packets);
        target.sent += target.session->steer(state_, now);  // a device's own feed frames
    }
}

void VehicleFeed::send(Target& target, std::vector<gimbal::protocols::FeedBytes>& packets) {
    for (auto& bytes : packets)
        if (target.session->send_feed(std::move(bytes))) ++target.sent;
    packets.clear();
}

nlohmann::json VehicleFeed::snapshot(const GimbalSession& session) const {
    nlohmann::json out = state_.snapshot(now_s());
    for (const auto& t : targets_) {
        if (t.session != &session) continue;
        out["feed"] =
            source_ ? nlohmann::json{{"kind", std::string(t.feeder->kind())}, {"sent", t.sent}}
                    : nlohmann::json(nullptr);
    }
    return out;
}

}  // namespace gimbald
