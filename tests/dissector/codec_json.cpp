// codec-json: the C++ codecs' side of the dissector test.
//
//   codec-json vectors   every Orion golden vector (framed), every Viewpro golden frame and a
//                        set of Viewpro commands, one "<dissector> <hex>" line each
//   codec-json decode    reads such lines on stdin and prints, per line, the codec's JSON for
//                        the frame: {"dissector","id","name","fields"} (Orion, Digits::exact)
//                        or {"dissector","kind","fields"} (Viewpro)
#include <cmath>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "../unit/orion/golden_config.hpp"
#include "../unit/orion/golden_control.hpp"
#include "../unit/orion/golden_telemetry.hpp"
#include "../unit/viewpro/vectors.hpp"
#include "mavlink/framer.hpp"
#include "mavlink/framing.hpp"
#include "protocols/orion/codec/framing.hpp"
#include "protocols/orion/codec/json.hpp"
#include "protocols/orion/codec/packets.hpp"
#include "protocols/viewpro/codec/viewpro.hpp"
#include "schema.hpp"

using nlohmann::json;
using Bytes = std::vector<std::uint8_t>;
namespace orion = gimbal::orion;
namespace viewpro = gimbal::viewpro;

namespace {

std::string to_hex(const Bytes& b) {
    std::string out;
    char buf[3];
    for (const auto x : b) {
        std::snprintf(buf, sizeof buf, "%02x", x);
        out += buf;
    }
    return out;
}

Bytes from_hex(const std::string& s) {
    Bytes out;
    for (std::size_t i = 0; i + 1 < s.size(); i += 2)
        out.push_back(static_cast<std::uint8_t>(std::stoi(s.substr(i, 2), nullptr, 16)));
    return out;
}

template <class C>
Bytes bytes_of(const C& c) {
    return Bytes(c.begin(), c.end());
}

Bytes payload_bytes(const orion::Payload& p) {
    return Bytes(p.bytes.begin(), p.bytes.begin() + static_cast<long>(p.size));
}

// The golden packet with each of its flags or enum switches set to 0, re-encoded by the codec:
// where that drops conditional fields ("only if hasGyroBias"), a vector for the other branch.
template <class P>
void print_switched_off(const Bytes& golden) {
    const auto decoded = orion::decode<P>(golden);
    if (!decoded.ok) return;
    std::vector<gimbal::dissector::Entry> entries;
    gimbal::dissector::EnumRegistry enums;
    gimbal::dissector::SchemaVisitor schema(entries, enums);
    P copy = decoded.value;
    copy.fields(schema);
    for (const auto& e : entries) {
        if ((e.kind != "bits" && e.kind != "field") || e.n != 0 || !e.count_key.empty() ||
            (e.member != "bool" && e.member != "enum"))
            continue;
        P p = decoded.value;
        gimbal::dissector::SetVisitor set(e.key, 0);
        p.fields(set);
        const Bytes b = payload_bytes(orion::encode(p));
        if (b.size() != golden.size())
            std::cout << "orion " << to_hex(orion::frame_bytes(P::id, b)) << "\n";
    }
}

int print_vectors() {
    namespace g = orion::golden_vectors;
    std::vector<g::GoldenVector> all;
    for (const auto* list : {&g::telemetry_vectors, &g::control_vectors, &g::config_vectors})
        all.insert(all.end(), list->begin(), list->end());
    // Every packet with a layout must have a golden vector, or the comparison has a gap.
    int missing = 0;
    orion::for_each_packet([&]<class P>() {
        bool found = false;
        for (const auto& v : all) found = found || v.id == P::id;
        if (!found) {
            std::cerr << "no golden vector for " << P::name << "\n";
            ++missing;
        }
    });
    for (const auto& v : all)
        std::cout << "orion " << to_hex(orion::frame_bytes(v.id, *v.data)) << "\n";
    for (const auto& v : all) {
        orion::dispatch(v.id, [&]<class P>() {
            print_switched_off<P>(*v.data);
            // The optional tail absent: the codec's JSON keeps defaults for the absent fields,
            // so only what the dissector shows is compared ("subset").
            // A minimum-length packet whose counts ask for more is invalid for both sides.
            if (P::min_length < v.data->size()) {
                const Bytes head(v.data->begin(),
                                 v.data->begin() + static_cast<long>(P::min_length));
                std::cout << "orion " << to_hex(orion::frame_bytes(P::id, head))
                          << (orion::decode<P>(head).ok ? " subset\n" : " invalid\n");
            }
        });
    }

    using namespace viewpro_test;
    for (const auto* frame : {&icd_out1, &golden_out2, &golden_out3, &golden_out4, &golden_in1,
                              &golden_in2, &golden_in3, &icd_in2_example_40})
        std::cout << "viewpro " << to_hex(*frame) << "\n";
    for (const auto format : {viewpro::OutFormat::out1, viewpro::OutFormat::out2,
                              viewpro::OutFormat::out3, viewpro::OutFormat::out4})
        for (const bool network : {false, true})
            std::cout << "viewpro "
                      << to_hex(bytes_of(
                             viewpro::encode_mode({viewpro::Osd::uav, network, !network, format})))
                      << "\n";
    std::cout << "viewpro " << to_hex(bytes_of(viewpro::encode_mode({}))) << "\n";
    for (const std::int8_t step : {std::int8_t{100}, std::int8_t{-25}})
        std::cout << "viewpro " << to_hex(bytes_of(viewpro::encode_yaw_shift(step))) << "\n"
                  << "viewpro " << to_hex(bytes_of(viewpro::encode_pitch_shift(step))) << "\n";
    // One v1 and one v2 frame of every MAVLink message lib/mavlink knows.
    const auto print_mavlink = [&]<std::size_t... I>(std::index_sequence<I...>) {
        const auto one = [&](const gimbal::mavlink::Payload& p) {
            if (gimbal::mavlink::message_id(p) < 256)  // v1 has a one-byte message id
                std::cout << "mavlink " << to_hex(gimbal::mavlink::encode_v1(p, 1, 154, 7)) << "\n";
            std::cout << "mavlink " << to_hex(gimbal::mavlink::encode_v2(p, 1, 154, 8)) << "\n";
        };
        (one(gimbal::mavlink::Payload{std::in_place_index<I>}), ...);
    };
    print_mavlink(std::make_index_sequence<std::variant_size_v<gimbal::mavlink::Payload>>{});
    return missing == 0 ? 0 : 1;
}

// A float as tshark shows it: NaN as "nan" (JSON has no NaN).
json float_json(float v) {
    return std::isnan(v) ? json("nan") : json(static_cast<double>(v));
}

std::string text_json(const std::array<std::uint8_t, 32>& chars) {
    std::string s;
    for (const auto c : chars) {
        if (c == 0) break;
        s.push_back(static_cast<char>(c));
    }
    return s;
}

// The payload fields the dissector shows for the gimbal device messages (283..286).
void add_gimbal_device_fields(const gimbal::mavlink::Payload& p, json& f) {
    namespace mav = gimbal::mavlink;
    const auto quat = [](const std::array<float, 4>& q) {
        json a = json::array();
        for (const float c : q) a.push_back(float_json(c));
        return a;
    };
    if (const auto* m = std::get_if<mav::GimbalDeviceInformation>(&p)) {
        f["uid"] = m->uid;
        f["time_boot_ms"] = m->time_boot_ms;
        f["firmware_version"] = m->firmware_version;
        f["hardware_version"] = m->hardware_version;
        f["roll_min"] = float_json(m->roll_min);
        f["roll_max"] = float_json(m->roll_max);
        f["pitch_min"] = float_json(m->pitch_min);
        f["pitch_max"] = float_json(m->pitch_max);
        f["yaw_min"] = float_json(m->yaw_min);
        f["yaw_max"] = float_json(m->yaw_max);
        f["cap_flags"] = m->cap_flags;
        f["custom_cap_flags"] = m->custom_cap_flags;
        f["vendor_name"] = text_json(m->vendor_name);
        f["model_name"] = text_json(m->model_name);
        f["custom_name"] = text_json(m->custom_name);
        f["gimbal_device_id"] = m->gimbal_device_id;
        f["cap_flags2"] = m->cap_flags2;
    } else if (const auto* a = std::get_if<mav::GimbalDeviceSetAttitude>(&p)) {
        f["q"] = quat(a->q);
        f["angular_velocity_x"] = float_json(a->angular_velocity_x);
        f["angular_velocity_y"] = float_json(a->angular_velocity_y);
        f["angular_velocity_z"] = float_json(a->angular_velocity_z);
        f["flags"] = a->flags;
        f["target_system"] = a->target_system;
        f["target_component"] = a->target_component;
    } else if (const auto* s = std::get_if<mav::GimbalDeviceAttitudeStatus>(&p)) {
        f["time_boot_ms"] = s->time_boot_ms;
        f["q"] = quat(s->q);
        f["angular_velocity_x"] = float_json(s->angular_velocity_x);
        f["angular_velocity_y"] = float_json(s->angular_velocity_y);
        f["angular_velocity_z"] = float_json(s->angular_velocity_z);
        f["failure_flags"] = s->failure_flags;
        f["flags"] = s->flags;
        f["target_system"] = s->target_system;
        f["target_component"] = s->target_component;
        f["delta_yaw"] = float_json(s->delta_yaw);
        f["delta_yaw_velocity"] = float_json(s->delta_yaw_velocity);
        f["gimbal_device_id"] = s->gimbal_device_id;
    } else if (const auto* ap = std::get_if<mav::AutopilotStateForGimbalDevice>(&p)) {
        f["time_boot_us"] = ap->time_boot_us;
        f["q"] = quat(ap->q);
        f["q_estimated_delay_us"] = ap->q_estimated_delay_us;
        f["vx"] = float_json(ap->vx);
        f["vy"] = float_json(ap->vy);
        f["vz"] = float_json(ap->vz);
        f["v_estimated_delay_us"] = ap->v_estimated_delay_us;
        f["feed_forward_angular_velocity_z"] = float_json(ap->feed_forward_angular_velocity_z);
        f["estimator_status"] = ap->estimator_status;
        f["target_system"] = ap->target_system;
        f["target_component"] = ap->target_component;
        f["landed_state"] = ap->landed_state;
        f["angular_velocity_z"] = float_json(ap->angular_velocity_z);
    }
}

json decode_mavlink(const Bytes& frame) {
    json out = {{"dissector", "mavlink"}};
    gimbal::mavlink::Framer framer;
    for (const auto& m : framer.push(frame)) {
        out["fields"] = {{"version", m.version}, {"seq", m.seq},     {"sysid", m.sysid},
                         {"compid", m.compid},   {"msgid", m.msgid}, {"crc.status", "good"}};
        add_gimbal_device_fields(m.payload, out["fields"]);
    }
    return out;
}

json decode_orion(const Bytes& frame) {
    json out = {{"dissector", "orion"}};
    if (frame.size() < orion::header_size + orion::checksum_size) return out;
    const std::uint8_t id = frame[2];
    const std::span<const std::uint8_t> data(
        frame.data() + orion::header_size,
        frame.size() - orion::header_size - orion::checksum_size);
    out["id"] = id;
    out["name"] = std::string(orion::packet_name(id));
    orion::dispatch(id, [&]<class P>() {
        const auto d = orion::decode<P>(data);
        if (d.ok)
            out["fields"] = orion::to_json(d.value);
        else
            out["error"] = orion::to_string(d.error);
    });
    return out;
}

json decode_viewpro(const Bytes& frame) {
    json out = {{"dissector", "viewpro"}};
    if (const auto f = viewpro::make_output_frame(frame)) {
        out["kind"] = std::string(viewpro::to_string(f->format));
        if (const auto o = viewpro::decode_output(*f)) out["fields"] = viewpro::to_json(*o);
    } else if (const auto in = viewpro::make_input_frame(frame)) {
        out["kind"] = std::string(viewpro::to_string(in->kind));
        out["fields"] = viewpro::to_json(*in);
    }
    return out;
}

int decode_lines() {
    std::string line;
    while (std::getline(std::cin, line)) {
        std::istringstream in(line);
        std::string dissector, hex;
        in >> dissector >> hex;
        const Bytes frame = from_hex(hex);
        json j = dissector == "orion"     ? decode_orion(frame)
                 : dissector == "mavlink" ? decode_mavlink(frame)
                                          : decode_viewpro(frame);
        std::cout << j.dump() << "\n";
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    const std::string mode = argc > 1 ? argv[1] : "";
    if (mode == "vectors") return print_vectors();
    if (mode == "decode") return decode_lines();
    std::cerr << "usage: codec-json vectors|decode\n";
    return 2;
}
