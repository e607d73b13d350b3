#include "video/video_config.hpp"

#include <set>

#include <fmt/format.h>
#include <boost/asio/ip/address.hpp>

#include "video/source_pin.hpp"
#include "video/url.hpp"

namespace gimbald::video {

namespace gv = gimbal::video;
using nlohmann::json;

namespace {

bool is_address(const std::string& text) {
    boost::system::error_code ec;
    boost::asio::ip::make_address(text, ec);
    return !ec;
}

// A video URL for `role` ("input" or "output"): its scheme allowed there and its addresses
// numeric. Returns the parsed URL, or nullopt after reporting the problem.
std::optional<gv::VideoUrl> read_url(const json& value, const std::string& path, bool input,
                                     const ProblemSink& problem) {
    if (!value.is_string()) {
        problem(path, input ? "must be a string: udp://HOST:PORT or rtsp://HOST/PATH"
                            : "must be a string: udp://HOST:PORT or klv-udp://HOST:PORT");
        return std::nullopt;
    }
    const auto parsed = gv::parse_video_url(value.get<std::string>());
    if (!parsed) {
        problem(path, fmt::format("\"{}\": {}", value.get<std::string>(), parsed.error().message));
        return std::nullopt;
    }
    const gv::VideoUrl& url = *parsed;
    if (input && url.scheme == gv::UrlScheme::klv_udp) {
        problem(path, "an input is udp:// (MPEG-TS) or rtsp://, not klv-udp://");
        return std::nullopt;
    }
    if (!input && url.scheme == gv::UrlScheme::rtsp) {
        problem(path, "an output is udp:// (MPEG-TS) or klv-udp:// (KLV only), not rtsp://");
        return std::nullopt;
    }
    if (url.scheme != gv::UrlScheme::rtsp) {
        if (!url.host.empty() && !is_address(url.host)) {
            problem(path, fmt::format("\"{}\" is not a numeric IP address (names are not "
                                      "resolved for video)",
                                      url.host));
            return std::nullopt;
        }
        if (!input &&
            (url.host.empty() || boost::asio::ip::make_address(url.host).is_unspecified())) {
            problem(path, "an output needs a destination address, not " +
                              (url.host.empty() ? std::string("an empty host") : url.host));
            return std::nullopt;
        }
        if (!url.iface.empty() && !is_address(url.iface)) {
            problem(path, fmt::format("iface \"{}\" is not a numeric IP address", url.iface));
            return std::nullopt;
        }
    }
    return url;
}

// An output that sends to the input's own port on this machine would feed the relay back
// into itself.
bool loops_back(const gv::VideoUrl& input, const gv::VideoUrl& output) {
    if (input.scheme != gv::UrlScheme::udp || output.port != input.port) return false;
    const auto out = boost::asio::ip::make_address(output.host);
    if (input.host.empty()) return out.is_loopback();
    const auto in = boost::asio::ip::make_address(input.host);
    return in == out || (in.is_unspecified() && out.is_loopback());
}

}  // namespace

std::string_view to_string(KlvMode mode) {
    switch (mode) {
        case KlvMode::automatic:
            return "auto";
        case KlvMode::parse:
            return "parse";
        case KlvMode::generate:
            return "generate";
        case KlvMode::off:
            return "off";
    }
    return "auto";
}

void read_video_fields(gimbal::config::Fields& f, VideoConfig& config) {
    const auto at = [&f](std::string_view key) { return f.path(key); };
    const ProblemSink problem = [&f](std::string where, std::string message) {
        f.problems().add(std::move(where), std::move(message));
    };
    // Every key is looked up (and so known to the unknown-key check) before it is read.
    const auto lookup = [&f](std::string_view key) { return f.find(key); };
    std::optional<gv::VideoUrl> input;
    if (const json* it = lookup("input"); it == nullptr) {
        problem(at("input"), "required: udp://HOST:PORT or rtsp://HOST/PATH");
    } else if ((input = read_url(*it, at("input"), true, problem))) {
        config.input = it->get<std::string>();
    }

    if (const json* it = lookup("klv"); it != nullptr) {
        const std::string mode = it->is_string() ? it->get<std::string>() : std::string();
        if (mode == "auto") {
            config.klv = KlvMode::automatic;
        } else if (mode == "parse") {
            config.klv = KlvMode::parse;
        } else if (mode == "generate") {
            config.klv = KlvMode::generate;
        } else if (mode == "off") {
            config.klv = KlvMode::off;
        } else {
            problem(at("klv"), "must be one of \"auto\", \"parse\", \"generate\", \"off\"");
        }
    }

    if (const json* it = lookup("klv_rate_hz"); it != nullptr) {
        if (!it->is_number() || !(it->get<double>() >= min_klv_rate_hz) ||
            !(it->get<double>() <= max_klv_rate_hz)) {
            problem(at("klv_rate_hz"), fmt::format("must be a number between {:g} and {:g}",
                                                   min_klv_rate_hz, max_klv_rate_hz));
        } else {
            config.klv_rate_hz = it->get<double>();
        }
    }

    if (const json* it = lookup("outputs"); it != nullptr) {
        if (!it->is_array()) {
            problem(at("outputs"), "must be an array of udp:// or klv-udp:// URLs");
        } else if (it->size() > max_outputs) {
            problem(at("outputs"), fmt::format("at most {} outputs", max_outputs));
        } else {
            std::set<std::string> seen;
            for (std::size_t i = 0; i < it->size(); ++i) {
                const std::string item_path = fmt::format("{}[{}]", at("outputs"), i);
                const auto url = read_url((*it)[i], item_path, false, problem);
                if (!url) continue;
                if (!seen.insert(url->text).second) {
                    problem(item_path, "listed twice");
                    continue;
                }
                if (input && loops_back(*input, *url)) {
                    problem(item_path,
                            "sends to the input's own port: the relay would feed "
                            "itself");
                    continue;
                }
                config.outputs.push_back(url->text);
            }
        }
    }

    if (const json* it = lookup("mission_id"); it != nullptr && !it->is_null()) {
        if (!it->is_string()) {
            problem(at("mission_id"), "must be a string or null");
        } else if (it->get_ref<const std::string&>().empty() ||
                   it->get_ref<const std::string&>().size() > max_mission_id_bytes) {
            problem(at("mission_id"),
                    fmt::format("must be 1 to {} bytes (ST 0601 tag 3)", max_mission_id_bytes));
        } else {
            config.mission_id = it->get<std::string>();
        }
    }

    if (const json* it = lookup("source"); it != nullptr && !it->is_null()) {
        std::string error;
        if (!it->is_string()) {
            problem(at("source"), "must be a string \"ADDR[:PORT]\" or null");
        } else if (input && input->scheme != gv::UrlScheme::udp) {
            problem(at("source"), "only for a udp:// input (an RTSP input names its camera)");
        } else if (!parse_source(it->get_ref<const std::string&>(), error)) {
            problem(at("source"), fmt::format("\"{}\": {}", it->get<std::string>(), error));
        } else {
            config.source = it->get<std::string>();
        }
    }

    if (const json* it = lookup("tracking"); it != nullptr && !it->is_null()) {
        if (auto nested = f.object("tracking")) {
            TrackingConfig tracking;
            fields(*nested, tracking);
            nested->finish();
            config.tracking = tracking;
        }
    }
}

}  // namespace gimbald::video
