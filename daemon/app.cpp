#include "app.hpp"

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <map>

#include <unistd.h>

#include "command/params.hpp"
#include "geoid_source.hpp"
#include "http/static_files.hpp"
#include "link/serial_link.hpp"
#include "link/sim_link.hpp"
#include "link/tcp_link.hpp"
#include "link/udp_link.hpp"
#include "logging.hpp"
#include "notify.hpp"
#include "protocols/registry.hpp"
#include "record/recording_link.hpp"
#include "record/track_records.hpp"
#include "secret_file.hpp"
#include "signing_state.hpp"
#include "track/steering_commands.hpp"
#include "track/tracking_setup.hpp"
#include "video/url.hpp"

namespace gimbald {

namespace cfg = gimbal::daemon;
namespace log = gimbal::log;
namespace notify = gimbal::notify;
namespace protocols = gimbal::protocols;

namespace {

// STATE `capabilities`: what the gimbal can do (session/capabilities.hpp) and the commands
// its protocol plans, so clients such as the console never need to know protocols.
nlohmann::json capabilities_key(const protocols::Entry& protocol) {
    nlohmann::json commands = nlohmann::json::array();
    for (const auto& c : protocol.commands) commands.push_back(c.name);
    return {{"features", gimbal::session::feature_names(protocol.features)},
            {"commands", std::move(commands)}};
}

}  // namespace

App::App(const cfg::Config& config, std::unique_ptr<gimbal::terrain::ElevationModel> terrain)
    : config_(config),
      signals_(io_, SIGINT, SIGTERM, SIGHUP),
      watchdog_timer_(io_),
      log_timer_(io_),
      terrain_(std::move(terrain)),
      terrain_loader_(terrain_ ? std::make_unique<TerrainLoader>(io_, *terrain_) : nullptr) {
    if (config_.record) start_recorder();
    // Each protocol reads its own keys (feed, options) from its gimbal's configuration object.
    const nlohmann::json gimbal_objects = cfg::to_json(config_)["gimbals"];
    open_geoid_if_needed(gimbal_objects);
    std::vector<GimbalSession*> raw;
    for (std::size_t i = 0; i < config_.gimbals.size(); ++i) {
        const auto& g = config_.gimbals[i];
        const auto& protocol = protocols::entry(g.protocol);
        auto link = make_link(g);
        if (recorder_)  // interface i is gimbal i (start_recorder)
            link = std::make_unique<record::RecordingLink>(std::move(link), *recorder_,
                                                           static_cast<std::uint32_t>(i),
                                                           std::string(cfg::to_string(g.protocol)));
        sessions_.push_back(std::make_unique<GimbalSession>(
            io_, g.name, make_protocol(protocol, gimbal_objects[i]), std::move(link),
            config_.laser.fire_timeout_s,
            [this](const std::string& gimbal, const gimbal::state::Event& e) {
                events_.publish(gimbal, e);
                if (e.kind == "link") update_status();
            }));
        sessions_.back()->add_state_key("capabilities",
                                        [key = capabilities_key(protocol)] { return key; });
        raw.push_back(sessions_.back().get());
    }
    RequestPathOptions path_options;
    path_options.token = config_.command.token;
    path_options.signed_only = config_.command.auth == cfg::AuthMode::signed_requests;
    for (const auto& k : config_.command.keys) {
        gimbal::auth::Key key{k.id, k.secret, {}};
        for (const auto& role : k.roles) key.roles.add(*gimbal::auth::parse_role(role));
        path_options.keys.push_back(std::move(key));
    }
    path_options.max_skew_s = config_.command.max_skew_s;
    path_options.rate_per_source_hz = config_.command.rate_limit.per_source_hz;
    path_options.rate_burst = config_.command.rate_limit.burst;
    path_options.terrain = terrain_.get();
    request_path_ = std::make_unique<RequestPath>(io_, std::move(path_options), std::move(raw));

    CommandServerOptions options;
    options.bind = config_.command.bind.to_string();
    options.port = config_.command.port;
    options.max_subscribers = config_.command.max_subscribers;
    options.max_subscribers_per_host = config_.command.max_subscribers_per_host;
    options.allowed = [this](const boost::asio::ip::address& a) {
        return config_.command.allowed(a);
    };
    options.sign = [this](const std::string& key_id, const nlohmann::json& message) {
        return request_path_->sign_message(key_id, message);
    };
    server_ = std::make_unique<CommandServer>(io_, std::move(options), *request_path_);
    // STATE `command` (contract section 10): the request path's counters, daemon-wide.
    for (auto& session : sessions_)
        session->add_state_key("command", [this] {
            const auto& c = request_path_->counters();
            return nlohmann::json{{"requests", c.requests},
                                  {"rejected", c.rejected},
                                  {"rate_limited", c.rate_limited},
                                  {"dropped_source", server_->dropped_sources()},
                                  {"send_failed", server_->send_counters().failed},
                                  {"push_too_large", server_->send_counters().pushes_too_large}};
        });
    events_.add([this](const std::string& gimbal, const gimbal::state::Event& e) {
        server_->publish_event(gimbal, e);
    });
    // MAVLink gimbal manager (contract section 8): signed frames reach it only with a key.
    std::optional<gimbal::mavlink::SigningKey> mavlink_key;
    gimbal::mavlink::FramerOptions framer_options;
    if (config_.mavlink.gimbal_manager && config_.mavlink.signing_key_file) {
        mavlink_key = load_signing_key(*config_.mavlink.signing_key_file);
        framer_options = {.accept_signed = true, .signing_key = mavlink_key};
    }
    // The vehicle feed: its events go to every gimbal's streams.
    vehicle_ = std::make_unique<VehicleFeed>(
        io_, config_.vehicle,
        [this](const auto& e) {
            for (const auto& s : sessions_) events_.publish(s->name(), e);
        },
        framer_options);
    for (std::size_t i = 0; i < sessions_.size(); ++i) {
        auto& session = *sessions_[i];
        vehicle_->add_gimbal(
            session, protocols::entry(config_.gimbals[i].protocol).make_feeder(gimbal_objects[i]));
        // STATE `vehicle` is null when nothing can tell gimbald about the aircraft.
        if (config_.vehicle || config_.mavlink.gimbal_manager)
            session.set_vehicle_snapshot([this, &session] { return vehicle_->snapshot(session); });
    }
    if (config_.mavlink.gimbal_manager) {
        // Contract section 8: our system id defaults to vehicle.system_id when that is set.
        cfg::MavlinkConfig mavlink = config_.mavlink;
        if (!mavlink.system_id && config_.vehicle) mavlink.system_id = config_.vehicle->system_id;
        // The signing streams live in systemd's state directory unless configured elsewhere.
        mavlink.signing_state_file =
            signing_state_path(mavlink.signing_state_file, std::getenv("STATE_DIRECTORY"));
        // Each gimbal's camera component announces the outputs of its video (section 16).
        std::map<std::string, video::VideoConfig> videos;
        for (const auto& g : config_.gimbals)
            if (g.video) videos.emplace(g.name, *g.video);
        mavlink_ =
            std::make_unique<MavlinkEndpoint>(io_, mavlink, mavlink_key, *vehicle_, *request_path_,
                                              request_path_->sessions(), videos);
        for (auto& session : sessions_)
            session->add_state_key(
                "mavlink", [this, name = session->name()] { return mavlink_->snapshot(name); });
    }
    if (config_.mqtt)
        mqtt_ = std::make_unique<mqtt::Bridge>(io_, *config_.mqtt, *request_path_, events_);
    if (config_.http) start_http();
    tap_recorder();
    start_video();
    start_tracking();
}

// Contract section 20: `track`, `track_stop` and STATE `track` on every gimbal; a client's
// own steering command ends a running track (overridden).
void App::start_tracking() {
    for (std::size_t i = 0; i < sessions_.size(); ++i) {
        auto& session = *sessions_[i];
        trackers_.push_back(track::attach_tracking(
            io_, session, videos_[i].get(), config_.gimbals[i].video, terrain_.get(),
            [this, name = session.name()](const gimbal::state::Event& e) {
                events_.publish(name, e);
            }));
    }
    if (recorder_) tap_track_recording();
    request_path_->add_executed_listener([this](const std::string& name, std::string_view cmd) {
        if (!track::is_steering_command(cmd)) return;
        for (std::size_t i = 0; i < sessions_.size(); ++i)
            if (trackers_[i] && sessions_[i]->name() == name) trackers_[i]->overridden(cmd);
    });
}

// Each track's events and STATE `track` after every box, on its gimbal's `track:` interface:
// after every `video:` one (start_recorder), in configuration order.
void App::tap_track_recording() {
    std::size_t videos = 0;
    for (const auto& g : config_.gimbals)
        if (g.video) ++videos;
    auto interface =
        static_cast<std::uint32_t>(sessions_.size() + (config_.vehicle ? 1 : 0) + 1 + videos);
    for (std::size_t i = 0; i < sessions_.size(); ++i) {
        if (!trackers_[i]) continue;
        const std::string name = sessions_[i]->name();
        const auto write = [this, interface](const std::string& pdu) {
            recorder_->record(interface, record::Direction::outbound,
                              gimbal::record::track_dissector, pdu);
        };
        trackers_[i]->set_record_tap({[name, write](const gimbal::state::Event& e) {
                                          write(gimbal::record::track_event_record(name, e));
                                      },
                                      [name, write](const gimbal::state::TrackState& t) {
                                          write(gimbal::record::track_state_record(name, t));
                                      }});
        ++interface;
    }
}

// Contract section 17: each gimbal's video, STATE `video` (null without one) and `klv`.
void App::start_video() {
    const std::size_t first_interface =
        sessions_.size() + (config_.vehicle ? 1 : 0) + 1;  // after `json` (start_recorder)
    std::size_t recorded = 0;
    for (std::size_t i = 0; i < sessions_.size(); ++i) {
        auto& session = *sessions_[i];
        const auto& g = config_.gimbals[i];
        videos_.push_back(nullptr);
        if (!g.video) {
            session.add_command("klv", [name = g.name](const nlohmann::json& request) {
                gimbal::command::JsonParams params(request, "klv");
                params.reject_unknown();
                if (!params.ok()) return gimbal::command::Result<nlohmann::json>(params.error());
                return gimbal::command::Result<nlohmann::json>(
                    gimbal::command::code::unavailable,
                    "gimbal '" + name + "' has no video section");
            });
            continue;
        }
        video::GimbalVideoOptions o;
        o.gimbal = g.name;
        o.config = *g.video;
        o.view = [&session] { return session.view(); };
        if (recorder_) {
            const auto interface = static_cast<std::uint32_t>(first_interface + recorded++);
            o.record = [this, interface](std::span<const std::uint8_t> bytes, bool generated) {
                recorder_->record(
                    interface, generated ? record::Direction::outbound : record::Direction::inbound,
                    generated ? "data" : "mp2t", bytes);
            };
        }
        auto& v = *(videos_.back() = std::make_unique<video::GimbalVideo>(io_, std::move(o)));
        session.set_video([&v] { return std::optional(v.video_state()); });
        session.add_command("klv", [&v](const nlohmann::json& request) {
            gimbal::command::JsonParams params(request, "klv");
            params.reject_unknown();
            if (!params.ok()) return gimbal::command::Result<nlohmann::json>(params.error());
            return v.klv_reply();
        });
    }
}

void App::start_http() {
    const auto& h = *config_.http;
    http::HttpServerOptions options(h);
    options.video.idle_timeout_s = h.idle_timeout_s;
    options.api.console = h.console;
    options.api.web_root =
        h.web_root ? std::filesystem::path(*h.web_root) : http::default_web_root();
    options.api.tiles_url = h.tiles_url;
    options.api.site.allowed_hosts = h.allowed_hosts;
    // This machine's own name is safe to accept: a rebinding attacker cannot serve pages
    // under it.
    if (char name[256] = {}; ::gethostname(name, sizeof name - 1) == 0 && name[0] != 0)
        options.api.site.allowed_hosts.emplace_back(name);
    options.allowed = [this](const boost::asio::ip::address& a) {
        return config_.command.allowed(a);
    };
    http::DaemonView view;
    view.config = &config_;
    view.path = request_path_.get();
    view.udp_subscribers = [this] { return server_->subscribers(); };
    view.udp_dropped_sources = [this] { return server_->dropped_sources(); };
    view.udp_send_failed = [this] { return server_->send_counters().failed; };
    view.udp_pushes_too_large = [this] { return server_->send_counters().pushes_too_large; };
    view.vehicle_up = [this] {
        return config_.vehicle && vehicle_->vehicle_state().fresh(vehicle_->monotonic_s());
    };
    view.mqtt_up = [this] { return mqtt_ && mqtt_->state_key().value("connected", false); };
    // Contract section 18; videos_ is filled after the server starts (start_video).
    view.video = [this](const std::string& gimbal) -> video::VideoTap* {
        for (std::size_t i = 0; i < sessions_.size() && i < videos_.size(); ++i)
            if (sessions_[i]->name() == gimbal) return videos_[i].get();
        return nullptr;
    };
    // Contract section 20; trackers_ too is filled later (start_tracking).
    view.track_steer_latency =
        [this](const std::string& name) -> const gimbal::metrics::Histogram* {
        for (std::size_t i = 0; i < sessions_.size() && i < trackers_.size(); ++i)
            if (sessions_[i]->name() == name && trackers_[i]) return &trackers_[i]->steer_latency();
        return nullptr;
    };
    http_ = std::make_unique<http::HttpServer>(io_, std::move(options), std::move(view));
    events_.add([this](const std::string& gimbal, const gimbal::state::Event& e) {
        http_->publish_event(gimbal, e);
    });
}

// Interfaces (docs/recording-format.md): one per gimbal in config order, then `mavlink` when a
// vehicle source exists, then `json`, then `video:` and `track:` ones.
void App::start_recorder() {
    record::RecorderOptions options(*config_.record);
    options.user_application = std::string("gimbald ") + GIMBALD_VERSION;
    for (const auto& g : config_.gimbals) {
        const auto protocol = std::string(cfg::to_string(g.protocol));
        const auto type = std::string(cfg::link_type(g.link));
        options.interfaces.push_back(
            {"gimbal:" + g.name,
             protocol + " " + (type == "sim" ? type : type + " " + cfg::describe(g.link))});
    }
    if (config_.vehicle) {
        std::string source;
        if (const auto* udp = std::get_if<cfg::UdpSource>(&config_.vehicle->source))
            source = "udp " + udp->bind.to_string() + ":" + std::to_string(udp->port);
        else if (const auto* serial = std::get_if<cfg::SerialSource>(&config_.vehicle->source))
            source = "serial " + serial->device + "@" + std::to_string(serial->baud);
        options.interfaces.push_back({"mavlink", "mavlink " + source});
    }
    options.interfaces.push_back({"json", "gimbald JSON requests and replies"});
    // Then one per gimbal with video (contract section 17): its MPEG-TS, and generated KLV.
    for (const auto& g : config_.gimbals)
        if (g.video) options.interfaces.push_back({"video:" + g.name, "mp2t " + g.video->input});
    // Then one per gimbal with visual tracking (contract section 20): its track's events and
    // STATE `track` (tap_track_recording).
    for (const auto& g : config_.gimbals)
        if (g.video && g.video->tracking)
            options.interfaces.push_back(
                {std::string(gimbal::record::track_prefix) + g.name,
                 "gimbald-json visual track, " +
                     std::string(gimbal::track::wire::to_string(g.video->tracking->tracker))});
    recorder_ = std::make_unique<record::Recorder>(io_, std::move(options));
}

void App::tap_recorder() {
    for (auto& session : sessions_)
        session->add_state_key("record", [this] {
            return recorder_ ? recorder_->snapshot() : nlohmann::json(nullptr);
        });
    if (!recorder_) return;
    const auto json_interface =
        static_cast<std::uint32_t>(sessions_.size() + (config_.vehicle ? 1 : 0));
    request_path_->add_tap([this, json_interface](const RequestSource&, std::string_view request,
                                                  std::string_view reply) {
        recorder_->record(json_interface, record::Direction::inbound, "gimbald-json", request);
        if (!reply.empty())
            recorder_->record(json_interface, record::Direction::outbound, "gimbald-json", reply);
    });
    if (config_.vehicle && vehicle_->source()) {
        const auto mavlink_interface = static_cast<std::uint32_t>(sessions_.size());
        vehicle_->source()->set_tap([this, mavlink_interface](bool outbound,
                                                              std::span<const std::uint8_t> bytes) {
            recorder_->record(mavlink_interface,
                              outbound ? record::Direction::outbound : record::Direction::inbound,
                              "mavlink", bytes);
        });
    }
}

namespace {
std::atomic<bool> terrain_read_left{false};
}

bool App::left_a_terrain_read_running() {
    return terrain_read_left;
}

// A read GDAL cannot interrupt (docs/terrain.md "Reads off the io thread") may take seconds;
// a stopping daemon gives it a moment and then leaves it running: ~App leaves the loader and
// the model (whose GDAL handles it reads) to the process's end, and main ends the process
// without tearing GDAL down under it.
void App::stop_terrain_reads() {
    constexpr std::chrono::milliseconds grace(300);
    if (!terrain_loader_ || terrain_loader_->stop(grace)) return;
    terrain_read_left = true;
    log::warn("terrain_read_left", "a terrain read was still running at stop: not waited for",
              {{"waited_s", std::chrono::duration<double>(grace).count()}});
}

App::~App() {
    if (!terrain_read_left) return;
    // The sessions, destroyed after this body, keep pointers to the model: it stays valid.
    static_cast<void>(terrain_loader_.release());
    static_cast<void>(terrain_.release());
}

// Once, before the sessions: the geoid grid when a gimbal's protocol asks for the undulation
// where the aircraft flies; without one those sessions use 0, which is said once here.
void App::open_geoid_if_needed(const nlohmann::json& gimbal_objects) {
    std::vector<std::string> needing;
    for (std::size_t i = 0; i < config_.gimbals.size(); ++i) {
        const auto& protocol = protocols::entry(config_.gimbals[i].protocol);
        if (protocol.needs_geoid && protocol.needs_geoid(gimbal_objects[i]))
            needing.push_back(config_.gimbals[i].name);
    }
    if (needing.empty()) return;
    auto opened = open_geoid(terrain_.get());
    if (!opened.undulation) {
        log::warn("geoid_missing",
                  opened.problem + ": the geoid undulation is 0 (set geoid_undulation_m)",
                  {{"gimbals", needing}});
        return;
    }
    log::info("geoid", "EGM96 geoid for the vehicle's MSL altitudes",
              {{"gimbals", needing}, {"source", opened.source}});
    geoid_ = std::move(opened.undulation);
}

std::unique_ptr<gimbal::session::Protocol> App::make_protocol(const protocols::Entry& protocol,
                                                              const nlohmann::json& gimbal) {
    protocols::SessionSettings settings;
    settings.stale_after_s = config_.telemetry.stale_after_s;
    settings.auto_ack_stare = config_.stare.auto_ack;
    settings.allow_fire = config_.laser.allow_fire;
    settings.allow_safety_bypass = config_.laser.allow_safety_bypass;
    settings.terrain = terrain_.get();
    settings.geoid_undulation = geoid_;
    settings.unix_clock = [] {
        return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch())
            .count();
    };
    settings.read_secret = [](const std::string& path) {
        return gimbal::daemon::read_secret_file(path);
    };
    return protocol.make_session(settings, gimbal);
}

std::unique_ptr<Link> App::make_link(const cfg::GimbalConfig& g) {
    if (const auto* tcp = std::get_if<cfg::TcpLink>(&g.link)) {
        TcpLinkOptions options(*tcp);
        options.discovery = protocols::entry(g.protocol).discovery;
        return std::make_unique<TcpLink>(io_, std::move(options));
    }
    if (const auto* serial = std::get_if<cfg::SerialLink>(&g.link)) {
        return std::make_unique<SerialLink>(io_, SerialLinkOptions(*serial));
    }
    if (const auto* udp = std::get_if<cfg::UdpLink>(&g.link)) {
        return std::make_unique<UdpLink>(io_, UdpLinkOptions(*udp));
    }
    // The models read no clock: start their time at now so reported times are current.
    protocols::SimScenario scenario;
    scenario.unix_time_s =
        std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
    auto link =
        std::make_unique<SimLink>(io_, protocols::entry(g.protocol).simulator.make(scenario));
    if (g.video) add_sim_video(*link, g);
    return link;
}

// Contract section 17: `gimbald --sim` (or a sim link) with a `video` section sends the
// simulated camera's video to that video's input, as a real gimbal would.
void App::add_sim_video(SimLink& link, const cfg::GimbalConfig& g) {
    const auto camera = protocols::entry(g.protocol).simulator.camera;
    const nlohmann::json fields = {{"gimbal", g.name},
                                   {"input", gimbal::video::redact_userinfo(g.video->input)}};
    if (camera == nullptr) {
        log::warn("sim_video_off", "this protocol's simulated gimbal has no camera: no video",
                  fields);
        return;
    }
    std::string why;
    const auto target = video::sim_video_target(g.video->input, why);
    if (!target) {
        log::warn("sim_video_off", "no simulated video: " + why, fields);
        return;
    }
    video::SimVideoSenderOptions options;
    options.host = target->host;
    options.port = target->port;
    options.ttl = target->ttl;
    // The simulated world's traffic is in the picture, something to track (docs/simulator.md).
    options.stream.video.objects = gimbal::sim::ObjectSet::all();
    try {
        auto sender = std::make_unique<video::SimVideoSender>(std::move(options));
        link.set_advance_listener([camera, s = sender.get()](const gimbal::sim::Device& device) {
            if (const auto view = camera(device)) s->update(*view);
        });
        log::info("sim_video", "simulated video to " + sender->destination(), fields);
        sim_videos_.push_back(std::move(sender));
    } catch (const std::exception& e) {
        log::warn("sim_video_off", std::string("no simulated video: ") + e.what(), fields);
    }
}

void App::on_signal(const boost::system::error_code& ec, int signo) {
    if (ec) return;
    if (signo == SIGHUP) {
        log::info("reopen", "SIGHUP: reopening the log file");
        log::reopen();
        signals_.async_wait([this](const boost::system::error_code& e, int s) { on_signal(e, s); });
        return;
    }
    stop_signal_ = signo == SIGTERM ? "SIGTERM" : "SIGINT";
    log::info("stop", stop_signal_ + ": stopping", {{"signal", stop_signal_}});
    shutdown();
}

void App::shutdown() {
    if (stopping_) return;
    stopping_ = true;
    notify::stopping();
    if (mavlink_) mavlink_->stop();
    vehicle_->stop();
    // Sessions first: their cease-fire goes out before the links close.
    for (auto& s : sessions_) s->stop();
    for (auto& t : trackers_)
        if (t) t->stop();  // ends a track, closes gimbal-track's socket
    for (auto& v : videos_)
        if (v) v->stop();                   // joins an RTSP input's thread
    for (auto& s : sim_videos_) s->stop();  // joins its worker
    server_->stop();
    if (mqtt_) mqtt_->stop();  // publishes {"online": false}, then disconnects
    if (http_) http_->stop();
    // Last: the cease-fire packets above are in the recording. Joins the writer thread.
    if (recorder_) recorder_->stop();
    signals_.cancel();
    watchdog_timer_.cancel();
    log_timer_.cancel();
    log::poll(true);  // every line the roll-up still owes a count of
}

void App::update_status() {
    std::string status;
    int up = 0;
    for (const auto& s : sessions_) {
        status += (status.empty() ? "" : ", ") + s->status();
        if (s->connected()) ++up;
    }
    notify::status(std::to_string(up) + "/" + std::to_string(sessions_.size()) +
                   " gimbals connected: " + status);
}

void App::poll_logs() {
    log_timer_.expires_after(std::chrono::seconds(1));
    log_timer_.async_wait([this](const boost::system::error_code& ec) {
        if (ec || stopping_) return;
        log::poll();
        poll_logs();
    });
}

void App::arm_watchdog() {
    const auto interval = notify::watchdog_interval();
    if (!interval) return;
    watchdog_timer_.expires_after(*interval);
    watchdog_timer_.async_wait([this](const boost::system::error_code& ec) {
        if (ec || stopping_) return;
        notify::watchdog();
        arm_watchdog();
    });
}

int App::run() {
    for (auto& s : sessions_) s->start();
    for (auto& v : videos_)
        if (v) v->start();
    for (auto& s : sim_videos_) s->start();
    for (auto& t : trackers_)
        if (t) t->start();
    server_->start();
    vehicle_->start();
    if (mavlink_) mavlink_->start();
    if (mqtt_) mqtt_->start();
    if (http_) http_->start();
    signals_.async_wait([this](const boost::system::error_code& e, int s) { on_signal(e, s); });
    const auto local = server_->local_endpoint();
    nlohmann::json gimbals = nlohmann::json::array();
    for (const auto& g : config_.gimbals)
        gimbals.push_back({{"name", g.name},
                           {"protocol", std::string(cfg::to_string(g.protocol))},
                           {"link", cfg::describe(g.link)}});
    nlohmann::json started = {
        {"version", GIMBALD_VERSION},
        {"command", local.address().to_string() + ":" + std::to_string(local.port())},
        {"gimbals", gimbals}};
    if (http_) {
        const auto web = http_->local_endpoint();
        started["http"] = web.address().to_string() + ":" + std::to_string(web.port());
    }
    log::info("start", "gimbald started", started);
    notify::ready();
    update_status();
    arm_watchdog();
    poll_logs();
    io_.run();
    stop_terrain_reads();
    // Both `stop` lines name the signal, so either one answers "why did it stop".
    log::info("stop", "gimbald stopped",
              {{"signal",
                stop_signal_.empty() ? nlohmann::json(nullptr) : nlohmann::json(stop_signal_)}});
    return 0;
}

}  // namespace gimbald
