#include "vehicle_feed.hpp"

#include "logging.hpp"
#include "orion/framing.hpp"
#include "vehicle/feeds.hpp"

namespace gimbald {

namespace cfg = gimbal::daemon;
namespace log = gimbal::log;
namespace vehicle = gimbal::vehicle;

namespace {

// One tick every 50 ms: 10 Hz is every 2nd, 4 Hz every 5th, 1 Hz every 20th.
constexpr auto tick_period = std::chrono::milliseconds(50);
constexpr std::uint64_t ticks_10hz = 2;
constexpr std::uint64_t ticks_4hz = 5;
constexpr std::uint64_t ticks_1hz = 20;

vehicle::VehicleOptions options_of(const std::optional<cfg::VehicleConfig>& config) {
    vehicle::VehicleOptions o;
    if (config) {
        o.system_id = config->system_id;
        o.timeout_s = config->timeout_s;
    }
    return o;
}

std::string feed_kind(const cfg::GimbalConfig& g) {
    if (g.protocol == cfg::Protocol::orion) return "orion";
    switch (g.viewpro_feed) {
        case cfg::ViewproFeed::in1:
            return "in1";
        case cfg::ViewproFeed::mavlink:
            return "mavlink";
        case cfg::ViewproFeed::in2:
            break;
    }
    return "in2";
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

void VehicleFeed::add_gimbal(GimbalSession& session, const cfg::GimbalConfig& config) {
    Target t;
    t.session = &session;
    t.config = config;
    t.kind = feed_kind(config);
    targets_.push_back(std::move(t));
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
    // CommGood changes reach the Orions at once, not at the next 1 Hz slot.
    for (auto& t : targets_)
        if (t.kind == "orion" && t.config.orion_feed.autopilot) send_autopilot_data(t, now);
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
    const std::uint64_t tick = ticks_++;
    const double unix_now = unix_now_s();
    for (auto& t : targets_) {
        if (t.kind == "orion") {
            if (t.config.orion_feed.autopilot && tick % ticks_1hz == 0) send_autopilot_data(t, now);
            if (t.config.orion_feed.gps && tick % ticks_4hz == 0)
                if (auto gps = vehicle::orion_gps_data(state_, now, unix_now))
                    send(t, gimbal::orion::to_wire(*gps));
            continue;
        }
        if (tick % ticks_10hz != 0) continue;
        if (t.kind == "mavlink") {
            auto bytes = vehicle::mavlink_forward(state_, now, t.mavlink_seq);
            if (!bytes.empty()) send(t, std::move(bytes));
            continue;
        }
        const auto frame =
            t.kind == "in1" ? vehicle::ViewproFrame::in1 : vehicle::ViewproFrame::in2;
        if (auto bytes = vehicle::viewpro_in(state_, now, unix_now, frame))
            send(t, std::move(*bytes));
    }
}

void VehicleFeed::send_autopilot_data(Target& target, double now) {
    send(target, gimbal::orion::to_wire(vehicle::orion_autopilot_data(state_, now)));
}

void VehicleFeed::send(Target& target, std::vector<std::uint8_t> bytes) {
    if (target.session->send_feed(std::move(bytes))) ++target.sent;
}

nlohmann::json VehicleFeed::snapshot(const GimbalSession& session) const {
    nlohmann::json out = state_.snapshot(now_s());
    for (const auto& t : targets_) {
        if (t.session != &session) continue;
        out["feed"] =
            source_ ? nlohmann::json{{"kind", t.kind}, {"sent", t.sent}} : nlohmann::json(nullptr);
    }
    return out;
}

}  // namespace gimbald
