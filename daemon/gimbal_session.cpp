#include "gimbal_session.hpp"

#include <cmath>

#include "logging.hpp"
#include "state/precision.hpp"
#include "state/writer.hpp"

namespace gimbald {

namespace log = gimbal::log;
using gimbal::state::Event;

namespace {
constexpr auto tick_period = std::chrono::milliseconds(100);
// A queued cease-fire not written after this long is logged (laser_cease_pending).
constexpr double cease_overdue_s = 0.5;
}  // namespace

GimbalSession::GimbalSession(boost::asio::io_context& io, std::string name,
                             std::unique_ptr<gimbal::session::Protocol> protocol,
                             std::unique_ptr<Link> link, double fire_timeout_s, EventSink on_event)
    : name_(std::move(name)),
      protocol_(std::move(protocol)),
      link_(std::move(link)),
      lasers_(fire_timeout_s),
      on_event_(std::move(on_event)),
      tick_timer_(io),
      deadman_timer_(io),
      epoch_(std::chrono::steady_clock::now()),
      bad_checksums_(log::Level::warn, "bad_checksum", "bad checksums"),
      decode_errors_(log::Level::warn, "decode_error", "undecodable packets") {}

GimbalSession::~GimbalSession() {
    stop();
}

double GimbalSession::now_s() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - epoch_).count();
}

void GimbalSession::start() {
    stopped_ = false;
    link_->start(
        [this](std::span<const std::uint8_t> bytes) { on_data(bytes); },
        [this](bool up) { on_link_state(up); },
        [this](std::string_view what, std::string_view detail) { on_link_error(what, detail); });
    schedule_tick();
}

void GimbalSession::stop() {
    if (stopped_) return;
    stopped_ = true;
    // Rule 5: cease fire on shutdown, written synchronously (ahead of everything queued)
    // before the link closes.
    for (const auto& cease : lasers_.cease_all()) {
        const bool written = link_->connected() && link_->send_now(cease.frame);
        lasers_.ceased(cease.index);
        log::warn("laser_cease",
                  written ? "laser cease-fire sent on shutdown"
                          : "laser cease-fire on shutdown could not be written (link down or "
                            "not taking bytes)",
                  {{"gimbal", name_}, {"index", cease.index}, {"sent", written}});
    }
    tick_timer_.cancel();
    deadman_timer_.cancel();
    link_->stop();
}

void GimbalSession::on_data(std::span<const std::uint8_t> bytes) {
    std::vector<Event> events;
    std::vector<gimbal::session::Bytes> replies;
    protocol_->receive(bytes, now_s(), events, replies);
    for (auto& reply : replies) link_->send(std::move(reply));
    report_counters();
    emit(events);
    for (const auto& listener : receive_listeners_) listener();
}

void GimbalSession::report_counters() {
    const auto c = protocol_->counters();
    for (; reported_bad_checksums_ < c.bad_checksums; ++reported_bad_checksums_)
        bad_checksums_.hit(
            "bad checksum from the gimbal",
            {{"gimbal", name_}, {"total", c.bad_checksums}, {"dropped_bytes", c.dropped_bytes}});
    for (; reported_decode_errors_ < c.decode_errors; ++reported_decode_errors_)
        decode_errors_.hit("packet from the gimbal did not decode", {{"gimbal", name_}});
}

void GimbalSession::on_link_state(bool up) {
    std::vector<Event> events;
    events.push_back(Event{"link", {{"connected", up}}});
    if (up) {
        log::info("link_up", "link connected",
                  {{"gimbal", name_}, {"type", link_->type()}, {"endpoint", link_->endpoint()}});
        // Rule 5: a reconnect ends any fire the gimbal might still hold from before.
        for (const auto& cease : lasers_.cease_all()) queue_cease(cease, CeaseCause::reconnect);
        for (auto& request : protocol_->on_connect()) link_->send(std::move(request));
    } else {
        log::warn("link_down", "link lost",
                  {{"gimbal", name_}, {"type", link_->type()}, {"endpoint", link_->endpoint()}});
    }
    emit(events);
}

void GimbalSession::on_link_error(std::string_view what, std::string_view detail) {
    log::warn("link_error", detail,
              {{"gimbal", name_}, {"what", what}, {"endpoint", link_->endpoint()}});
}

void GimbalSession::emit(std::vector<Event>& events) {
    for (const auto& e : events) {
        if (e.kind == "mode")
            log::info("mode_change", "gimbal mode changed",
                      {{"gimbal", name_},
                       {"from", e.fields.value("from", nlohmann::json())},
                       {"to", e.fields.value("to", nlohmann::json())}});
        else if (e.kind == "stare_start")
            log::info("stare_start", "step-stare started",
                      {{"gimbal", name_},
                       {"system_time_ms", e.fields.value("system_time_ms", nlohmann::json())}});
        else if (e.kind == "debug") {
            // The gimbal's DebugString priority sets the level: log/info/warn/error/fatal.
            const auto priority = e.fields.value("priority", nlohmann::json()).dump();
            log::Level level = log::Level::info;
            if (priority.find("log") != std::string::npos) level = log::Level::debug;
            if (priority.find("warn") != std::string::npos) level = log::Level::warn;
            if (priority.find("error") != std::string::npos ||
                priority.find("fatal") != std::string::npos)
                level = log::Level::error;
            log::write(level, "gimbal_debug", e.fields.value("text", std::string()),
                       {{"gimbal", name_},
                        {"source", e.fields.value("source", nlohmann::json())},
                        {"priority", e.fields.value("priority", nlohmann::json())}});
        } else if (e.kind == "lost")
            log::warn("telemetry_lost", "no telemetry within telemetry.stale_after_s",
                      {{"gimbal", name_}, {"age_s", e.fields.value("age_s", 0.0)}});
        if (on_event_) on_event_(name_, e);
    }
}

void GimbalSession::schedule_tick() {
    tick_timer_.expires_after(tick_period);
    tick_timer_.async_wait([this](const boost::system::error_code& ec) {
        if (ec || stopped_) return;
        std::vector<Event> events;
        protocol_->tick(now_s(), events);
        std::vector<gimbal::session::Bytes> out;
        protocol_->poll(now_s(), out);
        if (link_->connected())
            for (auto& bytes : out) link_->send(std::move(bytes));
        report_waiting_ceases();
        bad_checksums_.poll();
        decode_errors_.poll();
        emit(events);
        schedule_tick();
    });
}

std::uint64_t GimbalSession::steer(const gimbal::vehicle::VehicleState& vehicle,
                                   double vehicle_now_s) {
    std::vector<gimbal::session::Bytes> out;
    const std::size_t feed = protocol_->steer(vehicle, vehicle_now_s, now_s(), out);
    if (!link_->connected()) return 0;
    std::uint64_t fed = 0;
    for (std::size_t i = 0; i < out.size(); ++i)
        if (link_->send(std::move(out[i])) && i < feed) ++fed;
    return fed;
}

GimbalSession::Outcome GimbalSession::execute(std::string_view cmd, const nlohmann::json& request) {
    Outcome out;
    if (const auto local = commands_.find(std::string(cmd)); local != commands_.end()) {
        auto result = local->second(request);
        if (result)
            out.results = std::move(result.value());
        else
            out.error = result.error();
        return out;
    }
    gimbal::command::Plan plan;
    const gimbal::session::Now now{
        now_s(),
        std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count()};
    if (auto error = protocol_->plan(cmd, request, now, plan)) {
        out.error = std::move(error);
        return out;
    }
    if (!link_->connected()) {
        out.error = gimbal::command::Error{gimbal::command::code::link_down,
                                           "gimbal '" + name_ + "' is not connected"};
        return out;
    }
    nlohmann::json sent = nlohmann::json::array();
    for (auto& packet : plan.packets) {
        // Laser commands are never displaced by a cease-fire for the other laser: the guard's
        // record of what the gimbal was told must stay true.
        const bool queued = plan.laser ? link_->send_kept(packet.frame) : link_->send(packet.frame);
        if (!queued) {
            // Only the first packet can meet a full queue before anything went out for
            // single-packet commands; report what was written.
            out.error = gimbal::command::Error{
                gimbal::command::code::link_down,
                sent.empty() ? "the link refused the packet (disconnected or queue full)"
                             : "the link refused a packet after " + std::to_string(sent.size()) +
                                   " were written"};
            return out;
        }
        sent.push_back(packet.sent);
    }
    if (plan.laser) {
        lasers_.commanded(*plan.laser, now_s());
        arm_deadman();
    }
    out.results = std::move(plan.result);
    out.results["sent"] = std::move(sent);
    return out;
}

void GimbalSession::arm_deadman() {
    const auto deadline = lasers_.next_deadline();
    if (!deadline) {
        deadman_timer_.cancel();
        return;
    }
    const double wait_s = std::max(0.0, *deadline - now_s());
    deadman_timer_.expires_after(std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(wait_s)));
    deadman_timer_.async_wait([this](const boost::system::error_code& ec) {
        if (ec || stopped_) return;
        on_deadman();
    });
}

void GimbalSession::on_deadman() {
    std::vector<Event> events;
    for (const auto& cease : lasers_.expired(now_s())) {
        if (queue_cease(cease, CeaseCause::deadman)) continue;  // logged once written
        log::warn("laser_deadman",
                  "no laser command within laser.fire_timeout_s: link down, cease-fire will be "
                  "sent on reconnect",
                  {{"gimbal", name_}, {"index", cease.index}, {"sent", false}});
        events.push_back(Event{"laser_deadman", {{"index", cease.index}, {"sent", false}}});
    }
    emit(events);
    arm_deadman();
}

bool GimbalSession::queue_cease(const gimbal::session::LaserGuard::Cease& cease, CeaseCause cause) {
    const bool queued = link_->send_safety(cease.frame, [this, cease, cause](bool written) {
        on_cease_written(cease, cause, written);
    });
    if (queued) lasers_.cease_queued(cease, now_s());
    return queued;
}

void GimbalSession::on_cease_written(const gimbal::session::LaserGuard::Cease& cease,
                                     CeaseCause cause, bool written) {
    if (stopped_) return;
    const bool deadman = cause == CeaseCause::deadman;
    if (!written) {
        lasers_.cease_discarded(cease);
        log::warn(deadman ? "laser_deadman" : "laser_cease",
                  "the link went down before the cease-fire was written: it is sent again on "
                  "reconnect",
                  {{"gimbal", name_}, {"index", cease.index}, {"sent", false}});
        if (deadman) {
            std::vector<Event> events{
                Event{"laser_deadman", {{"index", cease.index}, {"sent", false}}}};
            emit(events);
        }
        return;
    }
    lasers_.ceased(cease);  // unless a newer laser command for the index followed it
    if (!deadman) {
        log::warn("laser_cease", "laser cease-fire sent on reconnect",
                  {{"gimbal", name_}, {"index", cease.index}, {"sent", true}});
        return;
    }
    log::warn("laser_deadman", "no laser command within laser.fire_timeout_s: cease-fire sent",
              {{"gimbal", name_}, {"index", cease.index}, {"sent", true}});
    std::vector<Event> events{Event{"laser_deadman", {{"index", cease.index}, {"sent", true}}}};
    emit(events);
}

void GimbalSession::report_waiting_ceases() {
    for (const std::uint8_t index : lasers_.overdue(now_s(), cease_overdue_s))
        log::warn("laser_cease_pending",
                  "the cease-fire waits ahead of all other traffic but the gimbal link takes no "
                  "bytes; still trying",
                  {{"gimbal", name_},
                   {"index", index},
                   {"sent", false},
                   {"displaced", link_->stats().tx_displaced}});
}

gimbal::state::LinkState GimbalSession::link_state() const {
    const auto& s = link_->stats();
    const auto c = protocol_->counters();
    gimbal::state::LinkState l;
    l.type = link_->type();
    l.endpoint = link_->endpoint();
    l.connected = link_->connected();
    l.rx_bytes = s.rx_bytes;
    l.tx_bytes = s.tx_bytes;
    l.rx_packets = c.rx_packets;
    l.tx_packets = s.tx_packets;
    l.bad_checksums = c.bad_checksums;
    l.dropped_bytes = c.dropped_bytes;
    l.reconnects = s.reconnects;
    if (s.last_rx)
        l.last_rx_age_s =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - *s.last_rx).count();
    return l;
}

bool GimbalSession::stale() const {
    return protocol_->stale(now_s());
}

nlohmann::json GimbalSession::snapshot() const {
    const double now = now_s();
    nlohmann::json state = {{"protocol", std::string(protocol_->name())},
                            {"link", gimbal::state::write(link_state())},
                            {"stale", protocol_->stale(now)}};
    // Contract section 14: lasers[i].firing is the daemon's own record (as the metric
    // gimbald_laser_firing): true from a fire command until its cease-fire was written.
    gimbal::state::JsonWriter w(state);
    protocol_->write_state(w, {now, &lasers_});
    state["vehicle"] = vehicle_snapshot_ ? vehicle_snapshot_() : nlohmann::json(nullptr);
    w.object("video", video_ ? video_() : std::nullopt);
    w.object("track", track_ ? track_() : std::nullopt);
    for (const auto& [key, fill] : state_keys_) state[key] = fill();
    return state;
}

gimbal::session::GimbalView GimbalSession::view() const {
    return {&protocol_->capabilities(),
            protocol_->telemetry(),
            link_->connected(),
            stale(),
            video_,
            track_};
}

bool GimbalSession::send_feed(std::vector<std::uint8_t> bytes) {
    return link_->connected() && link_->send(std::move(bytes));
}

std::string GimbalSession::status() const {
    return name_ + (link_->connected() ? " up" : " down");
}

}  // namespace gimbald
