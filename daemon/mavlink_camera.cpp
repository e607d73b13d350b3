#include "mavlink_camera.hpp"

#include <boost/asio/ip/address.hpp>

#include "video/url.hpp"

namespace gimbald {

namespace gp = gimbal::gimbal_protocol;

std::vector<gp::CameraStream> camera_streams(const std::string& gimbal,
                                             const video::VideoConfig& video) {
    std::vector<gp::CameraStream> out;
    for (const auto& output : video.outputs) {
        const auto parsed = gimbal::video::parse_video_url(output);
        if (!parsed || parsed->scheme != gimbal::video::UrlScheme::udp) continue;
        const auto& url = *parsed;
        boost::system::error_code ec;
        const auto address = boost::asio::ip::make_address(url.host, ec);
        const bool multicast = !ec && address.is_multicast();
        gp::CameraStream s;
        s.name = out.empty() ? gimbal : gimbal + " " + std::to_string(out.size() + 1);
        if (multicast) {
            const std::string host = address.is_v6() ? "[" + url.host + "]" : url.host;
            s.uri = "mpegts://" + host + ":" + std::to_string(url.port);
        } else {
            s.uri = std::to_string(url.port);
        }
        out.push_back(std::move(s));
    }
    return out;
}

std::vector<gp::ExposedCamera> expose_cameras(
    const std::vector<gp::ExposedGimbal>& gimbals, const std::vector<GimbalSession*>& sessions,
    const std::map<std::string, video::VideoConfig>& videos) {
    std::vector<gp::ExposedCamera> out;
    for (const auto& g : gimbals) {
        gp::ExposedCamera c;
        c.gimbal = g;
        c.component_id = gp::camera_component(g.device_id);
        for (const auto* s : sessions) {
            if (s->name() != g.name) continue;
            const auto features = s->capabilities().features();
            c.can_point = features.geopoint;
            c.can_zoom = features.zoom;
        }
        if (const auto it = videos.find(g.name); it != videos.end()) {
            c.video = true;
            c.streams = camera_streams(g.name, it->second);
            c.visual_tracking = it->second.tracking.has_value();
        }
        out.push_back(std::move(c));
    }
    return out;
}

}  // namespace gimbald
