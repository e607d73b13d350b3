#include "protocols/orion/orion_state.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <string_view>

#include "geo/image.hpp"
#include "geo/wgs84.hpp"
#include "protocols/orion/codec/json.hpp"
#include "state/precision.hpp"

namespace gimbal::state {
namespace {

namespace o = gimbal::orion;

// Where a packet kind lives in STATE (nullptr: it is not shown, only its events).
template <class P>
std::optional<Received<P>>* latest(OrionPackets& p) {
    if constexpr (std::is_same_v<P, o::InsQuality>)
        return &p.ins;
    else if constexpr (std::is_same_v<P, o::GpsData>)
        return &p.gps;
    else if constexpr (std::is_same_v<P, o::LaserStates>)
        return &p.lasers;
    else if constexpr (std::is_same_v<P, o::Diagnostics>)
        return &p.diagnostics;
    else if constexpr (std::is_same_v<P, o::Performance>)
        return &p.performance;
    else if constexpr (std::is_same_v<P, o::NetworkDiagnostics>)
        return &p.network_diagnostics;
    else if constexpr (std::is_same_v<P, o::Vibration>)
        return &p.vibration;
    else if constexpr (std::is_same_v<P, o::RetractStatus>)
        return &p.retract;
    else if constexpr (std::is_same_v<P, o::StareStart>)
        return &p.stare;
    else if constexpr (std::is_same_v<P, o::Cameras>)
        return &p.cameras;
    else if constexpr (std::is_same_v<P, o::Limits>)
        return &p.limits;
    else if constexpr (std::is_same_v<P, o::NetworkSettings>)
        return &p.network_settings;
    else if constexpr (std::is_same_v<P, o::NetworkVideo>)
        return &p.network_video;
    else if constexpr (std::is_same_v<P, o::UartConfig>)
        return &p.uart_config;
    else if constexpr (std::is_same_v<P, o::InsOptions>)
        return &p.ins_options;
    else if constexpr (std::is_same_v<P, o::ResetSource>)
        return &p.reset_source;
    else if constexpr (std::is_same_v<P, o::ClevisVersion>)
        return &p.clevis_version;
    else if constexpr (std::is_same_v<P, o::CrownVersion>)
        return &p.crown_version;
    else if constexpr (std::is_same_v<P, o::PayloadVersion>)
        return &p.payload_version;
    else if constexpr (std::is_same_v<P, o::TrackerVersion>)
        return &p.tracker_version;
    else if constexpr (std::is_same_v<P, o::RetractVersion>)
        return &p.retract_version;
    else if constexpr (std::is_same_v<P, o::LensCtlVersion>)
        return &p.lensctl_version;
    else
        return nullptr;
}

// Per-board packets are keyed by the board that sent them.
std::string board_key(o::Board board) {
    const auto name = o::enum_name(board);
    return name.empty() ? "unknown" : std::string(name);
}

double age(double now_s, double received_s) {
    return seconds(std::max(0.0, now_s - received_s));
}

// A packet's JSON with its age.
template <class P>
nlohmann::json aged(const Received<P>& r, double now_s) {
    nlohmann::json v = r.json;
    v["age_s"] = age(now_s, r.received_s);
    return v;
}
template <class P>
nlohmann::json aged(const std::optional<Received<P>>& r, double now_s) {
    return r ? aged(*r, now_s) : nlohmann::json(nullptr);
}
template <class P>
nlohmann::json aged(const std::map<std::string, Received<P>>& by_board, double now_s) {
    if (by_board.empty()) return nullptr;
    nlohmann::json out = nlohmann::json::object();
    for (const auto& [board, r] : by_board) out[board] = aged(r, now_s);
    return out;
}

// Days since 1970-01-01 -> civil date (Howard Hinnant's algorithm).
void civil_from_days(long long z, int& y, unsigned& m, unsigned& d) {
    z += 719468;
    const long long era = (z >= 0 ? z : z - 146096) / 146097;
    const auto doe = static_cast<unsigned>(z - era * 146097);
    const unsigned yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
    const long long yy = static_cast<long long>(yoe) + era * 400;
    const unsigned doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    const unsigned mp = (5 * doy + 2) / 153;
    d = doy - (153 * mp + 2) / 5 + 1;
    m = mp < 10 ? mp + 3 : mp - 9;
    y = static_cast<int>(yy + (m <= 2 ? 1 : 0));
}

}  // namespace

std::string gps_to_utc_iso(std::uint16_t week, std::uint32_t itow_ms, std::uint8_t leap_seconds) {
    // GPS time starts 1980-01-06T00:00:00Z = 3657 days after the Unix epoch.
    const long long ms = 3657LL * 86400000LL + static_cast<long long>(week) * 604800000LL +
                         static_cast<long long>(itow_ms) -
                         static_cast<long long>(leap_seconds) * 1000LL;
    const long long days = ms / 86400000LL;
    long long rest = ms % 86400000LL;
    int y;
    unsigned mo, d;
    civil_from_days(days, y, mo, d);
    const auto hh = static_cast<int>(rest / 3600000LL);
    rest %= 3600000LL;
    const auto mm = static_cast<int>(rest / 60000LL);
    rest %= 60000LL;
    const auto ss = static_cast<int>(rest / 1000LL);
    const auto mss = static_cast<int>(rest % 1000LL);
    char buf[40];
    std::snprintf(buf, sizeof buf, "%04d-%02u-%02uT%02d:%02d:%02d.%03dZ", y, mo, d, hh, mm, ss,
                  mss);
    return buf;
}

OrionTelemetry orion_telemetry(const o::GeolocateTelemetry& t, geo::Surface* terrain) {
    OrionTelemetry out{t, o::to_json(t, o::Digits::shortest), std::nullopt, {}};
    if (t.gps_week != 0 || t.gps_itow_ms != 0)
        out.utc = gps_to_utc_iso(t.gps_week, t.gps_itow_ms, t.leap_seconds);
    // The reported keys as STATE shows them: the codec's digits.
    const auto shown = [&t](const auto& member) -> std::optional<double> {
        const nlohmann::json v = o::field_json(t, member, o::Digits::shortest);
        return v.is_number() ? std::optional(v.get<double>()) : std::nullopt;
    };
    Telemetry& s = out.shared;
    s.lat = shown(t.lat);
    s.lon = shown(t.lon);
    s.alt = shown(t.alt);
    s.geoid_undulation = shown(t.geoid_undulation);
    s.pan = shown(t.pan);
    s.tilt = shown(t.tilt);
    s.hfov = shown(t.hfov);
    s.vfov = shown(t.vfov);
    s.alt_msl = metres(t.alt - t.geoid_undulation);
    const geo::Quat mount{t.quat[0], t.quat[1], t.quat[2], t.quat[3]};
    const auto att = geo::quat_to_euler(mount);
    s.roll = angle_deg(att.roll_deg);
    s.pitch = angle_deg(att.pitch_deg);
    s.yaw = angle_deg(att.yaw_deg);
    const geo::Lla gimbal{t.lat * o::rad2deg, t.lon * o::rad2deg, t.alt};
    const auto target = geo::target_from_los(gimbal, {t.los_ecef[0], t.los_ecef[1], t.los_ecef[2]});
    if (target)
        s.target = GeoPoint{latlon_deg(target->lat_deg), latlon_deg(target->lon_deg),
                            metres(target->alt_m)};
    // Contract sections 11 and 15. The Orion reports no image rotation.
    const geo::CameraPose camera =
        geo::camera_pose(gimbal, mount, t.pan * o::rad2deg, t.tilt * o::rad2deg,
                         t.hfov * o::rad2deg, t.vfov * o::rad2deg);
    s.view = ground_view(
        camera, geo::Ground{terrain, target ? std::optional(target->alt_m) : std::nullopt});
    return out;
}

nlohmann::json telemetry_json(const o::GeolocateTelemetry& t, geo::Surface* terrain) {
    return write(orion_telemetry(t, terrain));
}

template <class P>
void OrionState::store(const P& packet, nlohmann::json json, double now_s) {
    if constexpr (std::is_same_v<P, o::SoftwareDiagnostics>) {
        data_.packets.software[board_key(packet.source_board)] = {packet, std::move(json), now_s};
    } else if constexpr (std::is_same_v<P, o::BoardInfo>) {
        data_.packets.boards[board_key(packet.board)] = {packet, std::move(json), now_s};
    } else if constexpr (std::is_same_v<P, o::LaserStates>) {
        // STATE `lasers` is the array of lasers, each as the codec writes it.
        nlohmann::json states = nlohmann::json::array();
        for (const auto& laser : packet.states)
            states.push_back(o::to_json(laser, o::Digits::shortest));
        data_.packets.lasers = Received<P>{packet, std::move(states), now_s};
    } else if (auto* slot = latest<P>(data_.packets)) {
        *slot = Received<P>{packet, std::move(json), now_s};
    }
}

void OrionState::on_telemetry(const o::GeolocateTelemetry& t, double now_s,
                              std::vector<Event>& events) {
    if (data_.telemetry && data_.telemetry->packet.mode != t.mode) {
        events.push_back(
            Event{"mode",
                  {{"from", o::JsonWriter::scalar(data_.telemetry->packet.mode, o::Unit::none)},
                   {"to", o::JsonWriter::scalar(t.mode, o::Unit::none)}}});
    }
    data_.telemetry = orion_telemetry(t, terrain_);
    telemetry_s_ = now_s;
    ++telemetry_count_;
    lost_reported_ = false;
}

bool OrionState::apply(const o::Frame& frame, double now_s, std::vector<Event>& events) {
    bool decoded = true;
    o::dispatch(frame.id, [&]<class P>() {
        auto d = o::decode<P>(frame.data());
        if (!d.ok) {
            decoded = false;
            ++decode_errors_;
            last_decode_error_ = std::string(P::name) + ": " + o::to_string(d.error);
            return;
        }
        if constexpr (std::is_same_v<P, o::GeolocateTelemetry>) {
            on_telemetry(d.value, now_s, events);
            return;
        } else {
            nlohmann::json j = o::to_json(d.value, o::Digits::shortest);
            if constexpr (std::is_same_v<P, o::StareStart>) {
                last_stare_time_ms_ = d.value.system_time_ms;
                events.push_back(Event{"stare_start", j});
            }
            if constexpr (std::is_same_v<P, o::DebugString>) {
                events.push_back(Event{"debug",
                                       {{"source", j.value("source", nlohmann::json())},
                                        {"priority", j.value("priority", nlohmann::json())},
                                        {"text", j.value("description", std::string())}}});
            }
            store(d.value, std::move(j), now_s);  // commands echoed back, debug: events only
        }
    });
    return decoded;
}

bool OrionState::stale(double now_s) const {
    return !data_.telemetry || now_s - telemetry_s_ > stale_after_s_;
}

void OrionState::tick(double now_s, std::vector<Event>& events) {
    if (data_.telemetry && !lost_reported_ && stale(now_s)) {
        lost_reported_ = true;
        events.push_back(Event{"lost", {{"age_s", seconds(now_s - telemetry_s_)}}});
    }
}

void OrionState::write(JsonWriter& w, double now_s,
                       const std::function<bool(std::uint8_t)>& firing) const {
    const OrionPackets& p = data_.packets;
    if (data_.telemetry)
        w.object("telemetry", [&](JsonWriter& t) {
            fields(t, *data_.telemetry);
            t.seconds("age_s", std::max(0.0, now_s - telemetry_s_));
        });
    else
        w.null("telemetry");
    w.json("ins", aged(p.ins, now_s));
    w.json("gps", aged(p.gps, now_s));
    if (p.lasers) {
        // An array: each laser carries the packet's age, and the daemon's record of firing.
        nlohmann::json lasers = p.lasers->json;
        for (std::size_t i = 0; i < lasers.size(); ++i) {
            lasers[i]["age_s"] = age(now_s, p.lasers->received_s);
            if (firing) lasers[i]["firing"] = firing(static_cast<std::uint8_t>(i));
        }
        w.json("lasers", std::move(lasers));
    } else {
        w.null("lasers");
    }
    w.json("diagnostics", aged(p.diagnostics, now_s));
    w.json("performance", aged(p.performance, now_s));
    w.json("software", aged(p.software, now_s));
    w.json("network_diagnostics", aged(p.network_diagnostics, now_s));
    w.json("vibration", aged(p.vibration, now_s));
    w.json("retract", aged(p.retract, now_s));
    w.json("stare", aged(p.stare, now_s));
    w.json("cameras", aged(p.cameras, now_s));
    w.json("limits", aged(p.limits, now_s));
    w.json("network_settings", aged(p.network_settings, now_s));
    w.json("network_video", aged(p.network_video, now_s));
    w.json("uart_config", aged(p.uart_config, now_s));
    w.json("ins_options", aged(p.ins_options, now_s));
    w.json("reset_source", aged(p.reset_source, now_s));
    w.json("boards", aged(p.boards, now_s));
    // The version packets, by board; null until one arrives.
    nlohmann::json versions = nlohmann::json::object();
    const auto version = [&](const char* board, const auto& r) {
        if (r) versions[board] = aged(*r, now_s);
    };
    version("clevis", p.clevis_version);
    version("crown", p.crown_version);
    version("payload", p.payload_version);
    version("tracker", p.tracker_version);
    version("retract", p.retract_version);
    version("lensctl", p.lensctl_version);
    w.json("versions", versions.empty() ? nlohmann::json(nullptr) : std::move(versions));
}

nlohmann::json OrionState::snapshot(double now_s) const {
    nlohmann::json out = nlohmann::json::object();
    JsonWriter w(out);
    write(w, now_s);
    return out;
}

}  // namespace gimbal::state
