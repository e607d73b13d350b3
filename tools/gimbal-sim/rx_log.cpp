#include "rx_log.hpp"

#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "orion/framing.hpp"
#include "orion/json.hpp"
#include "orion/packets.hpp"
#include "viewpro/json.hpp"

namespace gimbal_sim {

namespace {

std::string hex(std::span<const std::uint8_t> bytes) {
    static constexpr char digits[] = "0123456789abcdef";
    std::string s;
    s.reserve(bytes.size() * 2);
    for (const auto b : bytes) {
        s.push_back(digits[b >> 4]);
        s.push_back(digits[b & 0x0F]);
    }
    return s;
}

}  // namespace

RxLog::RxLog(const std::string& path, const std::string& protocol)
    : out_(path, std::ios::out | std::ios::trunc), viewpro_(protocol == "viewpro") {
    if (!out_) throw std::runtime_error("cannot open rx log " + path);
}

void RxLog::received(const std::string& src, std::span<const std::uint8_t> bytes, double t) {
    if (viewpro_) {
        viewpro_framers_[src].push(
            bytes, [&](const gimbal::viewpro::InputFrame& f) { write_line(src, f, t); });
        return;
    }
    framers_[src].push(bytes, [&](const gimbal::orion::Frame& f) { write_line(src, f, t); });
}

void RxLog::reset(const std::string& src) {
    if (viewpro_) {
        viewpro_framers_[src].reset();
        return;
    }
    framers_[src].reset();
}

void RxLog::write_line(const std::string& src, const gimbal::viewpro::InputFrame& frame, double t) {
    namespace viewpro = gimbal::viewpro;
    nlohmann::json line;
    line["t"] = std::round(t * 1e6) / 1e6;
    line["src"] = src;
    line["kind"] = std::string(viewpro::to_string(frame.kind));
    line["len"] = frame.size;
    line["hex"] = hex(frame.view());
    nlohmann::json decoded = viewpro::to_json(frame);
    if (!decoded.is_null()) line["frame"] = std::move(decoded);
    out_ << line.dump() << '\n';
    out_.flush();
}

void RxLog::write_line(const std::string& src, const gimbal::orion::Frame& frame, double t) {
    namespace orion = gimbal::orion;
    nlohmann::json line;
    line["t"] = std::round(t * 1e6) / 1e6;
    line["src"] = src;
    line["id"] = frame.id;
    line["name"] = std::string(orion::packet_name(frame.id));
    line["len"] = frame.payload.size;
    line["hex"] = hex(orion::frame_bytes(frame.id, frame.data()));
    if (frame.payload.size > 0) {
        orion::dispatch(frame.id, [&]<class P>() {
            if (auto decoded = orion::decode<P>(frame.data()))
                line["packet"] = orion::to_json(decoded.value);
        });
    }
    out_ << line.dump() << '\n';
    out_.flush();
}

}  // namespace gimbal_sim
