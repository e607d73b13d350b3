#include "mavlink_endpoint.hpp"

#include <algorithm>
#include <boost/asio/ip/udp.hpp>
#include <boost/asio/post.hpp>
#include <cmath>
#include <map>
#include <stdexcept>

#include "gimbal_protocol/status.hpp"
#include "logging.hpp"
#include "mavlink/framing.hpp"
#include "mavlink_camera.hpp"
#include "secret_file.hpp"
#include "session/image_commands.hpp"
#include "signing_state.hpp"

namespace gimbald {

namespace mav = gimbal::mavlink;
namespace gp = gimbal::gimbal_protocol;
namespace log = gimbal::log;

namespace {

// One tick every 100 ms: attitude 10 Hz, manager status 5 Hz, FOV 2 Hz, heartbeat 1 Hz.
constexpr auto tick_period = std::chrono::milliseconds(100);

// A status interval (ms) in ticks: at least one.
std::uint64_t ticks_every(std::uint32_t ms) {
    return std::max<std::uint64_t>(1, ms / 100);
}

std::vector<gp::ExposedGimbal> exposed(const std::vector<GimbalSession*>& sessions,
                                       std::uint8_t first_component) {
    std::vector<std::pair<std::string, std::string>> list;
    for (const auto* s : sessions) list.emplace_back(s->name(), std::string(s->protocol()));
    auto gimbals = gp::expose(list, first_component);
    // Every exposed gimbal is also a camera component (expose_cameras): the camera answers
    // CAMERA_INFORMATION, its manager does not (contract v4, section 8).
    for (auto& g : gimbals) g.camera_component = gp::camera_component(g.device_id);
    return gimbals;
}

// The commands that only ask for reports: answered even with mavlink.commands false.
constexpr const char* commands_off = "mavlink.commands is false: this gimbal manager only reports";

std::string source_address(const gp::MavId& id) {
    return "mavlink:" + std::to_string(id.sysid) + "/" + std::to_string(id.compid);
}

}  // namespace

mav::SigningKey load_signing_key(const std::string& path) {
    const auto read = gimbal::daemon::read_secret_file(path);
    if (!read)
        throw gimbal::daemon::ConfigError("mavlink.signing_key_file: " + read.error().message);
    const auto key = mav::parse_signing_key(*read);
    if (!key)
        throw gimbal::daemon::ConfigError("mavlink.signing_key_file: " + path +
                                          ": must hold 32 bytes, or 64 hex digits");
    return *key;
}

MavlinkEndpoint::MavlinkEndpoint(boost::asio::io_context& io,
                                 const gimbal::daemon::MavlinkConfig& config,
                                 std::optional<mav::SigningKey> key, VehicleFeed& feed,
                                 RequestPath& path, const std::vector<GimbalSession*>& sessions,
                                 const std::map<std::string, video::VideoConfig>& videos)
    : config_(config),
      key_(key),
      feed_(feed),
      path_(path),
      sessions_(sessions),
      manager_(exposed(sessions, config.component_id)),
      cameras_(expose_cameras(manager_.gimbals(), sessions, videos)),
      timer_(io),
      epoch_(std::chrono::steady_clock::now()) {
    if (!feed_.source())
        throw gimbal::daemon::ConfigError("mavlink.gimbal_manager needs vehicle.source");
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
    if (key_) restore_signing_state();
}

void MavlinkEndpoint::restore_signing_state() {
    if (!config_.signing_state_file) {
        log::warn("mavlink_signing_state",
                  "the signing streams are not kept across restarts (no "
                  "mavlink.signing_state_file, no $STATE_DIRECTORY): a signed frame captured "
                  "before a restart is accepted once after it",
                  {});
        return;
    }
    try {
        const SigningState state = load_signing_state(*config_.signing_state_file);
        streams_.restore(state.streams);
        clock_.raise_to(std::max(state.local_timestamp, streams_.latest()));
        log::info("mavlink_signing_state", "signing streams restored",
                  {{"file", *config_.signing_state_file},
                   {"streams", state.streams.size()},
                   {"local_timestamp", clock_.last()}});
    } catch (const std::exception& e) {
        log::error("mavlink_signing_state",
                   std::string(e.what()) + "; starting with no saved signing streams",
                   {{"file", *config_.signing_state_file}});
    }
}

void MavlinkEndpoint::save_signing_state_now() {
    if (!key_ || !config_.signing_state_file || !signing_dirty_) return;
    signing_dirty_ = false;
    const std::string error = save_signing_state(*config_.signing_state_file,
                                                 SigningState{streams_.streams(), clock_.last()});
    if (!error.empty())
        save_errors_.hit("cannot save the MAVLink signing streams",
                         {{"file", *config_.signing_state_file}, {"error", error}});
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
               {"components", manager_.components()},
               {"cameras",
                [this] {
                    std::vector<int> ids;
                    for (const auto& c : cameras_.cameras()) ids.push_back(c.component_id);
                    return ids;
                }()},
               {"gimbals", manager_.gimbals().size()},
               {"commands", config_.commands},
               {"signing", key_.has_value()}});
}

void MavlinkEndpoint::stop() {
    if (stopped_) return;
    stopped_ = true;
    timer_.cancel();
    save_signing_state_now();
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
    const std::uint64_t clock = mav::signing_timestamp(
        std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count());
    // Never behind what was sent or accepted before, also across a restart (message signing
    // spec: the local timestamp is the later of the clock and the saved one).
    return std::max(clock, clock_.last());
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
    } else {
        v.home_msl_m = config_.home_alt_msl;  // no autopilot says: the configured home
    }
    return v;
}

gimbal::session::GimbalView MavlinkEndpoint::state_of(const std::string& gimbal) const {
    for (const auto* s : sessions_)
        if (s->name() == gimbal) return s->view();
    return {};
}

bool MavlinkEndpoint::authentic(const mav::Message& m) {
    if (!key_) return true;
    // Checked once per message: accepting records the stream's timestamp, so a second look
    // at the same frame would call it a replay.
    if (!m.signature || !m.signature->verified ||
        !streams_.accept(m.sysid, m.compid, m.signature->link_id, m.signature->timestamp,
                         signing_now()))
        return false;
    clock_.raise_to(m.signature->timestamp);
    signing_dirty_ = true;  // saved within a second (on_tick) and on stop()
    return true;
}

bool MavlinkEndpoint::obeyed(bool authentic) {
    if (!authentic) ++counters_.unsigned_ignored;
    return authentic;
}

void MavlinkEndpoint::on_message(const mav::Message& m) {
    if (stopped_) return;
    // A frame that parsed (and, with signing, is signed and fresh): its sender takes a peer
    // slot. Junk and unsigned frames under signing never evict a ground station (section 14).
    const bool is_authentic = authentic(m);
    if (is_authentic) feed_.source()->admit_peer();
    const auto sysid = system_id();
    if (!sysid) return;  // nothing is answered before our system id is known
    const gp::MavId from{m.sysid, m.compid};
    // Ours: our system, and one of our gimbal manager components or every component (0).
    const auto addressed = [&](std::uint8_t target_system, std::uint8_t target_component) {
        return target_system == *sysid &&
               (target_component == 0 || manager_.owns(target_component));
    };
    std::optional<gp::CommandView> command;
    if (const auto* c = std::get_if<mav::CommandLong>(&m.payload)) {
        command = gp::view(*c);
    } else if (const auto* ci = std::get_if<mav::CommandInt>(&m.payload)) {
        command = gp::view(*ci);
    }
    // A camera component's own commands (contract section 16); broadcasts (component 0) are
    // the gimbal managers' to answer.
    if (command && command->target_system == *sysid) {
        if (const auto* camera = cameras_.find(command->target_component)) {
            if (!obeyed(is_authentic)) return;
            on_camera_command(*command, *camera, from);
            return;
        }
    }
    if (command && !addressed(command->target_system, command->target_component)) command.reset();
    const gp::StateLookup lookup = [this](const std::string& g) { return state_of(g); };
    if (command) {
        if (!obeyed(is_authentic)) return;
        ++counters_.commands;
        // The ACK comes from the component addressed (for 0: the first gimbal's manager).
        const std::uint8_t answering =
            command->target_component != 0 ? command->target_component : first_component();
        if (!config_.commands) {  // contract section 14: every command, REQUEST_MESSAGE too
            run(refused(mav::MavResult::denied, commands_off), from, command->command, answering);
            return;
        }
        gp::Mapped mapped =
            manager_.command(*command, from, vehicle_view(), lookup, time_boot_ms());
        const auto steered = steered_gimbals(mapped);
        if (run(std::move(mapped), from, command->command, answering).result ==
            mav::MavResult::accepted)
            release_steered(steered);
        return;
    }
    std::optional<std::uint8_t> setpoint_component;
    if (const auto* p = std::get_if<mav::GimbalManagerSetPitchyaw>(&m.payload)) {
        if (addressed(p->target_system, p->target_component))
            setpoint_component = p->target_component;
    } else if (const auto* a = std::get_if<mav::GimbalManagerSetAttitude>(&m.payload)) {
        if (addressed(a->target_system, a->target_component))
            setpoint_component = a->target_component;
    } else if (const auto* d = std::get_if<mav::GimbalDeviceSetAttitude>(&m.payload)) {
        if (addressed(d->target_system, d->target_component))
            setpoint_component = d->target_component;
    }
    if (!setpoint_component || !obeyed(is_authentic)) return;
    ++counters_.commands;
    const std::uint8_t answering =
        *setpoint_component != 0 ? *setpoint_component : first_component();
    if (!config_.commands) {
        run(refused(mav::MavResult::denied, commands_off), from, std::nullopt, answering, m.msgid);
        return;
    }
    gp::Mapped mapped = manager_.message(m.payload, from, vehicle_view(), lookup);
    const auto steered = steered_gimbals(mapped);
    if (run(std::move(mapped), from, std::nullopt, answering, m.msgid).result ==
        mav::MavResult::accepted)
        release_steered(steered);
}

std::vector<std::string> MavlinkEndpoint::steered_gimbals(const gp::Mapped& mapped) {
    std::vector<std::string> out;
    for (const auto& r : mapped.requests) out.push_back(r.gimbal);
    return out;
}

void MavlinkEndpoint::release_steered(const std::vector<std::string>& gimbals) {
    for (const auto& g : manager_.gimbals())
        if (std::find(gimbals.begin(), gimbals.end(), g.name) != gimbals.end())
            release(g.device_id, "the gimbal manager steered the gimbal");
}

void MavlinkEndpoint::on_camera_command(const gp::CommandView& command,
                                        const gp::ExposedCamera& camera, const gp::MavId& from) {
    ++counters_.commands;
    if (!config_.commands) {  // contract section 14: every command, requests for reports too
        run(refused(mav::MavResult::denied, commands_off), from, command.command,
            camera.component_id);
        return;
    }
    const gp::StateLookup lookup = [this](const std::string& g) { return state_of(g); };
    // Zoom is the gimbal manager's mapping, for this camera's gimbal only.
    if (command.command == mav::mav_cmd::set_camera_zoom) {
        gp::CommandView as_manager = command;
        as_manager.target_component = camera.gimbal.component_id;
        as_manager.param[2] = camera.gimbal.device_id;
        run(manager_.command(as_manager, from, vehicle_view(), lookup, time_boot_ms()), from,
            command.command, camera.component_id);
        return;
    }
    gp::CameraMapped mapped = cameras_.command(command, camera, lookup, time_boot_ms());
    // Steering from MAVLink obeys the gimbal manager's control (DO_GIMBAL_MANAGER_CONFIGURE).
    if (mapped.track != gp::TrackChange::none &&
        !manager_.control(camera.gimbal.device_id).allows(from)) {
        run(refused(mav::MavResult::denied,
                    "another system is in control of " + camera.gimbal.name),
            from, command.command, camera.component_id);
        return;
    }
    const Ran ran = run(std::move(mapped.mapped), from, command.command, camera.component_id);
    if (ran.result != mav::MavResult::accepted) return;
    if (mapped.track == gp::TrackChange::start) hold(camera, ran.results, mapped.radius);
    // A visual track replaces a held point (its status is STATE `track`).
    if (mapped.track == gp::TrackChange::visual)
        release(camera.gimbal.device_id, "a visual track (MAV_CMD_CAMERA_TRACK_*)");
    if (mapped.track == gp::TrackChange::stop)
        release(camera.gimbal.device_id, "MAV_CMD_CAMERA_STOP_TRACKING");
}

void MavlinkEndpoint::hold(const gp::ExposedCamera& camera, const nlohmann::json& located,
                           float radius) {
    const auto number = [&](const char* key) -> std::optional<double> {
        const auto it = located.is_object() ? located.find(key) : located.end();
        if (!located.is_object() || it == located.end() || !it->is_number()) return std::nullopt;
        return it->get<double>();
    };
    const auto lat = number("lat"), lon = number("lon"), alt = number("alt");
    if (!lat || !lon || !alt) return;  // `point` always says where; nothing to hold otherwise
    Held h;
    h.point.lat = *lat;
    h.point.lon = *lon;
    h.point.alt = *alt;
    h.point.radius = radius;
    const auto* t = state_of(camera.gimbal.name).telemetry;
    if (t && t->geoid_undulation) h.point.alt_msl = *alt - *t->geoid_undulation;
    h.since_tick = h.next_geo_tick = h.next_image_tick = ticks_ + 1;
    held_[camera.gimbal.device_id] = h;
    log::info("mavlink_track", "click-to-track: holding a point",
              {{"gimbal", camera.gimbal.name},
               {"lat", *lat},
               {"lon", *lon},
               {"alt", *alt},
               {"component", camera.component_id}});
}

void MavlinkEndpoint::release(std::uint8_t device_id, const char* why) {
    const auto it = held_.find(device_id);
    if (it == held_.end()) return;
    held_.erase(it);
    for (const auto& c : cameras_.cameras()) {
        if (c.gimbal.device_id != device_id) continue;
        log::info("mavlink_track", std::string("click-to-track ended: ") + why,
                  {{"gimbal", c.gimbal.name}, {"component", c.component_id}});
        // One IDLE status, so a ground station stops drawing the point.
        send(gp::tracking_geo_status(std::nullopt, {}), c.component_id);
        if (cameras_.intervals(c.component_id).image_ms != 0)
            send(gp::tracking_image_status(std::nullopt, std::nullopt), c.component_id);
    }
}

void MavlinkEndpoint::check_held() {
    constexpr std::uint64_t settle_ticks = 30;  // the gimbal reports its new mode within 3 s
    std::vector<std::uint8_t> ended;
    for (const auto& [device_id, h] : held_) {
        if (ticks_ < h.since_tick + settle_ticks) continue;
        for (const auto& c : cameras_.cameras()) {
            if (c.gimbal.device_id != device_id) continue;
            // A gimbal that reports its pointing mode and has left geopoint.
            const auto* caps = state_of(c.gimbal.name).capabilities;
            if (caps && caps->holds_geopoint() == false) ended.push_back(device_id);
        }
    }
    for (const auto id : ended) release(id, "the gimbal left geopoint mode");
}

std::optional<gp::ImageAt> MavlinkEndpoint::image_at(const std::string& gimbal,
                                                     const gp::HeldPoint& held) const {
    for (const auto* s : sessions_) {
        if (s->name() != gimbal) continue;
        const auto view = s->capabilities().image();
        if (!view) return std::nullopt;
        const nlohmann::json p = gimbal::session::project_reply(
            *view, gimbal::geo::Lla{held.lat, held.lon, held.alt}, nullptr);
        if (!p["x"].is_number() || !p["y"].is_number()) return std::nullopt;
        return gp::ImageAt{p["x"].get<double>(), p["y"].get<double>()};
    }
    return std::nullopt;
}

std::uint8_t MavlinkEndpoint::first_component() const {
    return manager_.gimbals().empty() ? config_.component_id
                                      : manager_.gimbals().front().component_id;
}

gp::Mapped MavlinkEndpoint::refused(mav::MavResult result, std::string reason) {
    gp::Mapped m;
    m.result = result;
    m.reason = std::move(reason);
    return m;
}

MavlinkEndpoint::Ran MavlinkEndpoint::run(gp::Mapped mapped, const gp::MavId& from,
                                          std::optional<std::uint16_t> ack_command,
                                          std::uint8_t component, std::uint32_t msgid) {
    mav::MavResult result = mapped.result;
    std::string reason = mapped.reason;
    nlohmann::json first_results;
    if (!mapped.requests.empty()) {
        const RequestSource source{"mavlink", source_address(from), std::nullopt};
        std::vector<mav::MavResult> results;
        for (const auto& r : mapped.requests) {
            RequestPath::Executed outcome = path_.execute_request(r.request, source);
            if (!outcome.error) {
                if (results.empty()) first_results = std::move(outcome.results);
                results.push_back(mav::MavResult::accepted);
            } else {
                const auto code = outcome.error->code;
                results.push_back(gp::result_for_error(code));
                if (reason.empty())
                    reason = r.gimbal + ": " + std::string(gimbal::command::to_string(code)) +
                             ": " + outcome.error->message;
            }
        }
        result = gp::combine(results);
    }
    if (result != mav::MavResult::accepted) {
        // MAVSDK folds every refusal into one error: the reason is only here (contract 14).
        log::info("mavlink_refused", reason.empty() ? std::string("refused") : reason,
                  {{"src", source_address(from)},
                   {"command", ack_command ? nlohmann::json(*ack_command) : nlohmann::json()},
                   {"msgid", ack_command ? nlohmann::json() : nlohmann::json(msgid)},
                   {"component", component},
                   {"result", std::string(gp::to_string(result))}});
    }
    if (result == mav::MavResult::denied) ++counters_.denied;
    std::vector<gp::Reply> out;
    if (ack_command) {
        mav::CommandAck ack;
        ack.command = *ack_command;
        ack.result = static_cast<std::uint8_t>(result);
        ack.target_system = from.sysid;
        ack.target_component = from.compid;
        out.push_back({component, ack});
    }
    for (auto& reply : mapped.replies) out.push_back(std::move(reply));
    if (out.empty()) return {result, std::move(first_results)};
    // Sent from the io_context after the gimbal link's write of what the command queued (the
    // link posts its writes too), as the JSON socket sends its replies: the ACK is not part of
    // the command's latency - its sendto() wakes the ground station before the gimbal's
    // packet went out otherwise - and ACCEPTED then follows the write.
    boost::asio::post(timer_.get_executor(), [this, out = std::move(out)] {
        for (const auto& reply : out) send(reply.payload, reply.component_id);
    });
    return {result, std::move(first_results)};
}

void MavlinkEndpoint::send(const mav::Payload& payload, std::uint8_t component) {
    const auto sysid = system_id();
    if (!sysid) return;
    std::vector<std::uint8_t> frame =
        mav::encode_v2(payload, *sysid, component, seq_[component]++, key_.has_value());
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
    if (ticks_ % 10 == 0) {
        save_signing_state_now();
        save_errors_.poll();
    }
    if (!system_id()) return;
    const std::uint32_t t = time_boot_ms();
    // Every gimbal's manager is a component of its own, with its own heartbeat and streams.
    for (const auto& g : manager_.gimbals()) {
        if (ticks_ % 10 == 1) send(gp::heartbeat(), g.component_id);
        const bool status = ticks_ % 2 == 0;
        const bool fov = ticks_ % 5 == 0;
        const gimbal::session::GimbalView state = state_of(g.name);
        send(gp::attitude_status(g, state, t), g.component_id);
        if (status) send(gp::manager_status(g, manager_.control(g.device_id), t), g.component_id);
        if (fov) send(gp::fov_status(g, state, t), g.component_id);
    }
    // Each gimbal's camera component (contract section 16).
    check_held();
    for (const auto& c : cameras_.cameras()) {
        if (ticks_ % 10 == 1) send(gp::camera_heartbeat(), c.component_id);
        if (c.visual_tracking) send_visual_status(c, state_of(c.gimbal.name));
        const auto it = held_.find(c.gimbal.device_id);
        if (ticks_ % 5 != 0 && it == held_.end()) continue;
        const gimbal::session::GimbalView state = state_of(c.gimbal.name);
        if (ticks_ % 5 == 0) send(gp::camera_fov_status(c, state, t), c.component_id);
        if (it == held_.end()) continue;
        Held& h = it->second;
        const auto& intervals = cameras_.intervals(c.component_id);
        if (intervals.geo_ms != 0 && ticks_ >= h.next_geo_tick) {
            send(gp::tracking_geo_status(h.point, state), c.component_id);
            h.next_geo_tick = ticks_ + ticks_every(intervals.geo_ms);
        }
        if (intervals.image_ms != 0 && ticks_ >= h.next_image_tick) {
            send(gp::tracking_image_status(h.point, image_at(c.gimbal.name, h.point)),
                 c.component_id);
            h.next_image_tick = ticks_ + ticks_every(intervals.image_ms);
        }
    }
}

void MavlinkEndpoint::send_visual_status(const gp::ExposedCamera& c,
                                         const gimbal::session::GimbalView& state) {
    VisualStatus& v = visual_[c.component_id];
    const auto track = state.track ? state.track() : std::nullopt;
    const auto& intervals = cameras_.intervals(c.component_id);
    if (!track) {
        if (!v.running) return;
        v.running = false;  // one IDLE status, so a ground station stops drawing the box
        send(gp::visual_tracking_geo_status(std::nullopt, state), c.component_id);
        if (intervals.image_ms != 0)
            send(gp::visual_tracking_image_status(std::nullopt), c.component_id);
        return;
    }
    if (!v.running) v = VisualStatus{true, ticks_, ticks_};
    if (intervals.geo_ms != 0 && ticks_ >= v.next_geo_tick) {
        send(gp::visual_tracking_geo_status(track, state), c.component_id);
        v.next_geo_tick = ticks_ + ticks_every(intervals.geo_ms);
    }
    if (intervals.image_ms != 0 && ticks_ >= v.next_image_tick) {
        send(gp::visual_tracking_image_status(track), c.component_id);
        v.next_image_tick = ticks_ + ticks_every(intervals.image_ms);
    }
}

nlohmann::json MavlinkEndpoint::snapshot(const std::string& gimbal) const {
    nlohmann::json primary = nullptr;
    nlohmann::json camera = nullptr;
    std::uint8_t component = config_.component_id;
    for (const auto& c : cameras_.cameras()) {
        if (c.gimbal.name != gimbal) continue;
        nlohmann::json tracking = nullptr;
        if (const auto it = held_.find(c.gimbal.device_id); it != held_.end())
            tracking = {{"lat", it->second.point.lat},
                        {"lon", it->second.point.lon},
                        {"alt", it->second.point.alt}};
        camera = {{"component_id", c.component_id}, {"tracking", tracking}};
    }
    for (const auto& g : manager_.gimbals()) {
        if (g.name != gimbal) continue;
        component = g.component_id;
        if (const auto& p = manager_.control(g.device_id).primary())
            primary = {{"sysid", p->sysid}, {"compid", p->compid}};
    }
    const auto sysid = system_id();
    return {{"peers", feed_.source()->peers()},
            {"system_id", sysid ? nlohmann::json(*sysid) : nlohmann::json(nullptr)},
            {"component_id", component},
            {"camera", camera},
            {"primary_control", primary},
            {"commands", counters_.commands},
            {"denied", counters_.denied},
            {"unsigned_ignored", counters_.unsigned_ignored},
            {"signing", key_.has_value()}};
}

}  // namespace gimbald
