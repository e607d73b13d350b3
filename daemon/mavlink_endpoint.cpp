#include "mavlink_endpoint.hpp"

#include <boost/asio/ip/udp.hpp>
#include <cmath>
#include <stdexcept>

#include "gimbal_protocol/status.hpp"
#include "logging.hpp"
#include "mavlink/framing.hpp"
#include "secret_file.hpp"

namespace gimbald {

namespace mav = gimbal::mavlink;
namespace gp = gimbal::gimbal_protocol;
namespace log = gimbal::log;

namespace {

// One tick every 100 ms: attitude 10 Hz, manager status 5 Hz, FOV 2 Hz, heartbeat 1 Hz.
constexpr auto tick_period = std::chrono::milliseconds(100);

std::vector<gp::ExposedGimbal> exposed(const std::vector<GimbalSession*>& sessions) {
    std::vector<std::pair<std::string, std::string>> list;
    for (const auto* s : sessions) list.emplace_back(s->name(), std::string(s->protocol()));
    return gp::expose(list);
}

std::string source_address(const gp::MavId& id) {
    return "mavlink:" + std::to_string(id.sysid) + "/" + std::to_string(id.compid);
}

}  // namespace

mav::SigningKey load_signing_key(const std::string& path) {
    const auto read = gimbal::daemon::read_private_file(path);
    if (!gimbal::daemon::read_ok(read))
        throw std::runtime_error("mavlink.signing_key_file: " + std::get<1>(read));
    const std::string& text = std::get<0>(read);
    mav::SigningKey key{};
    if (text.size() == key.size()) {
        std::copy(text.begin(), text.end(), key.begin());
        return key;
    }
    const auto first = text.find_first_not_of(" \t\r\n");
    const auto last = text.find_last_not_of(" \t\r\n");
    const std::string hex =
        first == std::string::npos ? std::string() : text.substr(first, last - first + 1);
    if (hex.size() != 64 || hex.find_first_not_of("0123456789abcdefABCDEF") != std::string::npos)
        throw std::runtime_error("mavlink.signing_key_file: " + path +
                                 " must hold 32 bytes, or 64 hex digits");
    for (std::size_t i = 0; i < key.size(); ++i)
        key[i] = static_cast<std::uint8_t>(std::stoul(hex.substr(2 * i, 2), nullptr, 16));
    return key;
}

MavlinkEndpoint::MavlinkEndpoint(boost::asio::io_context& io,
                                 const gimbal::daemon::MavlinkConfig& config,
                                 std::optional<mav::SigningKey> key, VehicleFeed& feed,
                                 RequestPath& path, const std::vector<GimbalSession*>& sessions)
    : config_(config),
      key_(key),
      feed_(feed),
      path_(path),
      sessions_(sessions),
      manager_(exposed(sessions)),
      timer_(io),
      epoch_(std::chrono::steady_clock::now()) {
    if (!feed_.source()) throw std::runtime_error("mavlink.gimbal_manager needs vehicle.source");
    std::vector<boost::asio::ip::udp::endpoint> targets;
    boost::asio::ip::udp::resolver resolver(io);
    for (const auto& t : config_.targets) {
        const auto colon = t.rfind(':');
        std::string host = t.substr(0, colon);
        if (host.size() > 2 && host.front() == '[' && host.back() == ']')
            host = host.substr(1, host.size() - 2);
        const auto results = resolver.resolve(host, t.substr(colon + 1));
        targets.push_back(*results.begin());
    }
    feed_.source()->set_targets(std::move(targets));
    feed_.add_listener([this](const mav::Message& m) { on_message(m); });
}

MavlinkEndpoint::~MavlinkEndpoint() {
    stop();
}

void MavlinkEndpoint::start() {
    stopped_ = false;
    next_tick_ = std::chrono::steady_clock::now();
    schedule_tick();
    log::info("mavlink_start", "MAVLink gimbal manager on the vehicle endpoint",
              {{"component_id", config_.component_id},
               {"gimbals", manager_.gimbals().size()},
               {"signing", key_.has_value()}});
}

void MavlinkEndpoint::stop() {
    if (stopped_) return;
    stopped_ = true;
    timer_.cancel();
}

std::optional<std::uint8_t> MavlinkEndpoint::system_id() const {
    if (config_.system_id) return config_.system_id;
    return feed_.vehicle_state().system_id();
}

std::uint32_t MavlinkEndpoint::time_boot_ms() const {
    return static_cast<std::uint32_t>(std::chrono::duration_cast<std::chrono::milliseconds>(
                                          std::chrono::steady_clock::now() - epoch_)
                                          .count());
}

std::uint64_t MavlinkEndpoint::signing_now() const {
    return mav::signing_timestamp(
        std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count());
}

gp::VehicleView MavlinkEndpoint::vehicle_view() const {
    gp::VehicleView v;
    const auto& state = feed_.vehicle_state();
    const double now = feed_.monotonic_s();
    if (state.recent(state.attitude(), now)) {
        v.heading_deg = state.attitude()->message.yaw * 180.0 / M_PI;
    } else if (state.recent(state.position(), now) &&
               state.position()->message.hdg != mav::GlobalPositionInt::hdg_unknown) {
        v.heading_deg = state.position()->message.hdg / 100.0;
    }
    if (state.position()) {
        const auto& p = state.position()->message;
        v.home_msl_m = (static_cast<double>(p.alt) - static_cast<double>(p.relative_alt)) / 1000.0;
    }
    return v;
}

nlohmann::json MavlinkEndpoint::state_of(const std::string& gimbal) const {
    for (const auto* s : sessions_)
        if (s->name() == gimbal) return s->snapshot();
    return nlohmann::json::object();
}

bool MavlinkEndpoint::signature_ok(const mav::Message& m) {
    if (!key_) return true;
    if (!m.signature || !m.signature->verified ||
        !streams_.accept(m.sysid, m.compid, m.signature->link_id, m.signature->timestamp,
                         signing_now())) {
        ++counters_.unsigned_ignored;
        return false;
    }
    return true;
}

void MavlinkEndpoint::on_message(const mav::Message& m) {
    if (stopped_) return;
    const auto sysid = system_id();
    if (!sysid) return;  // nothing is answered before our system id is known
    const gp::MavId from{m.sysid, m.compid};
    const auto addressed = [&](std::uint8_t target_system, std::uint8_t target_component) {
        return target_system == *sysid &&
               (target_component == config_.component_id || target_component == 0);
    };
    std::optional<gp::CommandView> command;
    if (const auto* c = std::get_if<mav::CommandLong>(&m.payload)) {
        if (addressed(c->target_system, c->target_component)) command = gp::view(*c);
    } else if (const auto* ci = std::get_if<mav::CommandInt>(&m.payload)) {
        if (addressed(ci->target_system, ci->target_component)) command = gp::view(*ci);
    }
    const gp::StateLookup lookup = [this](const std::string& g) { return state_of(g); };
    if (command) {
        if (!signature_ok(m)) return;
        ++counters_.commands;
        run(manager_.command(*command, from, vehicle_view(), lookup, time_boot_ms()), from,
            command->command);
        return;
    }
    bool setpoint = false;
    if (const auto* p = std::get_if<mav::GimbalManagerSetPitchyaw>(&m.payload))
        setpoint = addressed(p->target_system, p->target_component);
    else if (const auto* a = std::get_if<mav::GimbalManagerSetAttitude>(&m.payload))
        setpoint = addressed(a->target_system, a->target_component);
    else if (const auto* d = std::get_if<mav::GimbalDeviceSetAttitude>(&m.payload))
        setpoint = addressed(d->target_system, d->target_component);
    if (!setpoint || !signature_ok(m)) return;
    ++counters_.commands;
    run(manager_.message(m.payload, from, vehicle_view(), lookup), from, std::nullopt);
}

void MavlinkEndpoint::run(gp::Mapped mapped, const gp::MavId& from,
                          std::optional<std::uint16_t> ack_command) {
    mav::MavResult result = mapped.result;
    if (!mapped.requests.empty()) {
        const RequestSource source{"mavlink", source_address(from), std::nullopt};
        std::vector<mav::MavResult> results;
        for (const auto& r : mapped.requests) {
            const nlohmann::json reply = path_.execute(r.request, source);
            if (reply.value("ok", false)) {
                results.push_back(mav::MavResult::accepted);
            } else {
                const auto* error = reply.contains("error") ? &reply["error"] : nullptr;
                const std::string code =
                    error && error->is_object() ? error->value("code", "internal") : "internal";
                results.push_back(gp::result_for_error(code));
            }
        }
        result = gp::combine(results);
    } else if (result != mav::MavResult::accepted) {
        log::debug("mavlink_refused", mapped.reason,
                   {{"src", source_address(from)},
                    {"command", ack_command ? nlohmann::json(*ack_command) : nlohmann::json()},
                    {"result", static_cast<int>(result)}});
    }
    if (result == mav::MavResult::denied) ++counters_.denied;
    if (ack_command) {
        mav::CommandAck ack;
        ack.command = *ack_command;
        ack.result = static_cast<std::uint8_t>(result);
        ack.target_system = from.sysid;
        ack.target_component = from.compid;
        send(ack);
    }
    for (const auto& reply : mapped.replies) send(reply);
}

void MavlinkEndpoint::send(const mav::Payload& payload) {
    const auto sysid = system_id();
    if (!sysid) return;
    std::vector<std::uint8_t> frame =
        mav::encode_v2(payload, *sysid, config_.component_id, seq_++, key_.has_value());
    if (key_) mav::append_signature(frame, *key_, 0, clock_.next(signing_now()));
    if (feed_.source()->send(frame)) ++counters_.sent;
}

void MavlinkEndpoint::schedule_tick() {
    next_tick_ += tick_period;
    timer_.expires_at(next_tick_);
    timer_.async_wait([this](const boost::system::error_code& ec) {
        if (ec || stopped_) return;
        on_tick();
        schedule_tick();
    });
}

void MavlinkEndpoint::on_tick() {
    ++ticks_;
    if (!system_id()) return;
    const std::uint32_t t = time_boot_ms();
    if (ticks_ % 10 == 1) send(gp::heartbeat());
    for (const auto& g : manager_.gimbals()) {
        const bool status = ticks_ % 2 == 0;
        const bool fov = ticks_ % 5 == 0;
        const nlohmann::json state = state_of(g.name);
        send(gp::attitude_status(g, state, t));
        if (status) send(gp::manager_status(g, manager_.control(g.device_id), t));
        if (fov) send(gp::fov_status(g, state, t));
    }
}

nlohmann::json MavlinkEndpoint::snapshot(const std::string& gimbal) const {
    nlohmann::json primary = nullptr;
    for (const auto& g : manager_.gimbals()) {
        if (g.name != gimbal) continue;
        if (const auto& p = manager_.control(g.device_id).primary())
            primary = {{"sysid", p->sysid}, {"compid", p->compid}};
    }
    const auto sysid = system_id();
    return {{"peers", feed_.source()->peers()},
            {"system_id", sysid ? nlohmann::json(*sysid) : nlohmann::json(nullptr)},
            {"component_id", config_.component_id},
            {"primary_control", primary},
            {"commands", counters_.commands},
            {"denied", counters_.denied},
            {"unsigned_ignored", counters_.unsigned_ignored},
            {"signing", key_.has_value()}};
}

}  // namespace gimbald
