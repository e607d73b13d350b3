#include "protocols/orion/orion_state.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <string_view>

#include "geo/image.hpp"
#include "geo/wgs84.hpp"
#include "protocols/orion/codec/json.hpp"
#include "state/ground_json.hpp"
#include "state/precision.hpp"

namespace gimbal::state {
namespace {

namespace o = gimbal::orion;

// Where each packet kind lives in STATE. Version packets and per-board packets are keyed
// by board; everything else keeps its latest copy.
struct Slot {
    std::string_view packet;
    std::string_view key;
    std::string_view sub;  // fixed sub-key (versions), or empty
};

constexpr std::array<Slot, 21> slots{{
    {"ins_quality", "ins", ""},
    {"gps_data", "gps", ""},
    {"laser_states", "lasers", ""},
    {"diagnostics", "diagnostics", ""},
    {"performance", "performance", ""},
    {"software_diagnostics", "software", ""},
    {"network_diagnostics", "network_diagnostics", ""},
    {"vibration", "vibration", ""},
    {"retract_status", "retract", ""},
    {"stare_start", "stare", ""},
    {"cameras", "cameras", ""},
    {"limits", "limits", ""},
    {"network_settings", "network_settings", ""},
    {"network_video", "network_video", ""},
    {"uart_config", "uart_config", ""},
    {"ins_options", "ins_options", ""},
    {"reset_source", "reset_source", ""},
    {"board", "boards", ""},
    {"clevis_version", "versions", "clevis"},
    {"crown_version", "versions", "crown"},
    {"payload_version", "versions", "payload"},
}};
constexpr std::array<Slot, 3> more_versions{{
    {"tracker_version", "versions", "tracker"},
    {"retract_version", "versions", "retract"},
    {"lensctl_version", "versions", "lensctl"},
}};

// Every key STATE shows for an Orion gimbal, in a stable order.
constexpr std::array<std::string_view, 20> state_keys{"telemetry",     "ins",
                                                      "gps",           "lasers",
                                                      "diagnostics",   "performance",
                                                      "software",      "network_diagnostics",
                                                      "vibration",     "retract",
                                                      "stare",         "cameras",
                                                      "limits",        "network_settings",
                                                      "network_video", "uart_config",
                                                      "ins_options",   "versions",
                                                      "reset_source",  "boards"};

const Slot* find_slot(std::string_view packet) {
    for (const auto& s : slots)
        if (s.packet == packet) return &s;
    for (const auto& s : more_versions)
        if (s.packet == packet) return &s;
    return nullptr;
}

bool keyed(std::string_view key) {
    return key == "versions" || key == "software" || key == "boards";
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

nlohmann::json telemetry_json(const o::GeolocateTelemetry& t, geo::Surface* terrain) {
    nlohmann::json j = o::to_json(t, o::Digits::shortest);
    j["utc"] = t.gps_week != 0 || t.gps_itow_ms != 0
                   ? nlohmann::json(gps_to_utc_iso(t.gps_week, t.gps_itow_ms, t.leap_seconds))
                   : nlohmann::json(nullptr);
    j["alt_msl"] = metres(t.alt - t.geoid_undulation);
    const geo::Quat mount{t.quat[0], t.quat[1], t.quat[2], t.quat[3]};
    const auto att = geo::quat_to_euler(mount);
    j["roll"] = angle_deg(att.roll_deg);
    j["pitch"] = angle_deg(att.pitch_deg);
    j["yaw"] = angle_deg(att.yaw_deg);
    const geo::Lla gimbal{t.lat * o::rad2deg, t.lon * o::rad2deg, t.alt};
    const auto target = geo::target_from_los(gimbal, {t.los_ecef[0], t.los_ecef[1], t.los_ecef[2]});
    if (target)
        j["target"] = {{"lat", latlon_deg(target->lat_deg)},
                       {"lon", latlon_deg(target->lon_deg)},
                       {"alt", metres(target->alt_m)}};
    else
        j["target"] = nullptr;
    // Contract sections 11 and 15. The Orion reports no image rotation.
    const geo::CameraPose camera =
        geo::camera_pose(gimbal, mount, t.pan * o::rad2deg, t.tilt * o::rad2deg,
                         t.hfov * o::rad2deg, t.vfov * o::rad2deg);
    add_ground_keys(j, camera,
                    geo::Ground{terrain, target ? std::optional(target->alt_m) : std::nullopt});
    return j;
}

void OrionState::store(const std::string& key, nlohmann::json value, double now_s) {
    auto& e = entries_[key];
    e.value = std::move(value);
    e.received_s = now_s;
}

void OrionState::store_keyed(const std::string& key, const std::string& sub, nlohmann::json value,
                             double now_s) {
    auto& e = keyed_[key][sub];
    e.value = std::move(value);
    e.received_s = now_s;
}

void OrionState::on_telemetry(const o::GeolocateTelemetry& t, double now_s,
                              std::vector<Event>& events) {
    if (telemetry_ && telemetry_->mode != t.mode) {
        events.push_back(Event{"mode",
                               {{"from", o::JsonWriter::scalar(telemetry_->mode, o::Unit::none)},
                                {"to", o::JsonWriter::scalar(t.mode, o::Unit::none)}}});
    }
    telemetry_ = t;
    telemetry_s_ = now_s;
    ++telemetry_count_;
    lost_reported_ = false;
    store("telemetry", telemetry_json(t, terrain_), now_s);
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
            const Slot* slot = find_slot(P::name);
            if (!slot) return;  // commands echoed back, debug strings: events only
            const std::string key(slot->key);
            if (!slot->sub.empty()) {
                store_keyed(key, std::string(slot->sub), std::move(j), now_s);
            } else if (keyed(key)) {
                // Per-board packets: keyed by the board that sent them.
                std::string board = "unknown";
                for (const char* field : {"source_board", "board", "source"})
                    if (j.contains(field) && j[field].is_string()) {
                        board = j[field].get<std::string>();
                        break;
                    }
                store_keyed(key, board, std::move(j), now_s);
            } else if (key == "lasers") {
                store(key, j.value("states", nlohmann::json::array()), now_s);
            } else {
                store(key, std::move(j), now_s);
            }
        }
    });
    return decoded;
}

bool OrionState::stale(double now_s) const {
    return !telemetry_s_ || now_s - *telemetry_s_ > stale_after_s_;
}

void OrionState::tick(double now_s, std::vector<Event>& events) {
    if (telemetry_s_ && !lost_reported_ && stale(now_s)) {
        lost_reported_ = true;
        events.push_back(Event{"lost", {{"age_s", seconds(now_s - *telemetry_s_)}}});
    }
}

nlohmann::json OrionState::snapshot(double now_s) const {
    nlohmann::json out = nlohmann::json::object();
    auto with_age = [now_s](const Entry& e) {
        nlohmann::json v = e.value;
        const double age = seconds(std::max(0.0, now_s - e.received_s));
        if (v.is_object())
            v["age_s"] = age;
        else
            v = {{"items", v}, {"age_s", age}};
        return v;
    };
    for (const auto key : state_keys) {
        const std::string k(key);
        if (keyed(key)) {
            auto it = keyed_.find(k);
            if (it == keyed_.end()) {
                out[k] = nullptr;
                continue;
            }
            nlohmann::json obj = nlohmann::json::object();
            for (const auto& [sub, e] : it->second) obj[sub] = with_age(e);
            out[k] = std::move(obj);
        } else if (key == "lasers") {
            auto it = entries_.find(k);
            if (it == entries_.end()) {
                out[k] = nullptr;
                continue;
            }
            // An array: each laser carries the packet's age.
            nlohmann::json arr = it->second.value;
            for (auto& laser : arr)
                laser["age_s"] = seconds(std::max(0.0, now_s - it->second.received_s));
            out[k] = std::move(arr);
        } else {
            auto it = entries_.find(k);
            out[k] = it == entries_.end() ? nlohmann::json(nullptr) : with_age(it->second);
        }
    }
    return out;
}

}  // namespace gimbal::state
