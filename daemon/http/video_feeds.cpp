#include "video_feeds.hpp"

#include <algorithm>
#include <nlohmann/json.hpp>

#include "video/codec_string.hpp"
#include "video/nal.hpp"

namespace gimbald::http {

namespace gv = gimbal::video;
namespace log = gimbal::log;

std::string video_frame_message(const gv::AccessUnit& au) {
    // 90 kHz to microseconds; an access unit without timestamps (none seen from TS or RTSP
    // inputs, but allowed) gets 0.
    const std::uint64_t ticks = au.pts ? *au.pts : au.dts ? *au.dts : 0;
    const std::uint64_t us = ticks * 100 / 9;
    std::string m;
    m.reserve(9 + au.data.size());
    for (int shift = 56; shift >= 0; shift -= 8)
        m.push_back(static_cast<char>((us >> shift) & 0xFF));
    m.push_back(static_cast<char>(au.key_frame ? 1 : 0));
    m.append(reinterpret_cast<const char*>(au.data.data()), au.data.size());
    return m;
}

VideoFeeds::VideoFeeds(std::function<video::VideoTap*(const std::string&)> lookup, HttpStats& stats,
                       VideoFeedOptions options)
    : lookup_(std::move(lookup)),
      stats_(stats),
      options_(options),
      stalled_log_(log::Level::warn, "video_viewer_dropped",
                   "video viewers dropped for not reading") {}

VideoFeeds::~VideoFeeds() {
    for (auto& [gimbal, feed] : feeds_)
        if (auto* t = tap(gimbal)) t->remove_viewer(feed.viewer_id);
}

video::VideoTap* VideoFeeds::tap(const std::string& gimbal) const {
    return lookup_ ? lookup_(gimbal) : nullptr;
}

void VideoFeeds::track(VideoClient& client) {
    tracked_.insert(&client);
}

void VideoFeeds::join(VideoClient& client) {
    if (stopped_) return client.close();
    auto* t = tap(client.gimbal());
    if (!t) return client.close();
    auto& feed = feeds_[client.gimbal()];
    if (feed.clients.empty())
        feed.viewer_id = t->add_viewer([this, gimbal = client.gimbal()](const gv::AccessUnit& au) {
            on_access_unit(gimbal, au);
        });
    feed.clients.push_back(&client);
    stats_.video_viewers = 0;
    for (const auto& [name, f] : feeds_) stats_.video_viewers += f.clients.size();
    log::info("video_viewer", "video viewer joined",
              {{"src", client.address()}, {"gimbal", client.gimbal()}});
}

void VideoFeeds::leave(VideoClient& client) {
    tracked_.erase(&client);
    const auto it = feeds_.find(client.gimbal());
    if (it == feeds_.end()) return;
    auto& clients = it->second.clients;
    const auto pos = std::find(clients.begin(), clients.end(), &client);
    if (pos == clients.end()) return;
    clients.erase(pos);
    if (stats_.video_viewers > 0) --stats_.video_viewers;
    if (clients.empty()) {
        // Nobody watches: the tap goes, and the next viewer waits for a fresh SPS.
        if (auto* t = tap(it->first)) t->remove_viewer(it->second.viewer_id);
        feeds_.erase(it);
    }
}

void VideoFeeds::stalled(VideoClient& client) {
    ++stats_.video_dropped_total;
    stalled_log_.poll();
    stalled_log_.hit(
        "video viewer dropped: it stopped reading",
        {{"src", client.address()}, {"gimbal", client.gimbal()}, {"stall_s", options_.stall_s}});
}

void VideoFeeds::stop() {
    stopped_ = true;
    for (auto* client : std::vector<VideoClient*>(tracked_.begin(), tracked_.end()))
        client->close();
}

void VideoFeeds::on_access_unit(const std::string& gimbal, const gv::AccessUnit& au) {
    const auto it = feeds_.find(gimbal);
    if (it == feeds_.end()) return;
    Feed& feed = it->second;
    if (au.key_frame) {
        // The decoder's configuration from the key frame's own SPS (in-band before every key
        // frame: contract section 17 inputs put it there for RTSP too).
        const auto codec = gv::find_codec_string(au.codec, au.data);
        const auto format = gv::find_format(au.codec, au.data);
        if (codec && format &&
            (*codec != feed.codec || format->width != feed.width ||
             format->height != feed.height)) {
            feed.codec = *codec;
            feed.width = format->width;
            feed.height = format->height;
            feed.config = std::make_shared<const std::string>(nlohmann::json{
                {"type", "config"},
                {"gimbal", gimbal},
                {"codec", feed.codec},
                {"width", feed.width},
                {"height", feed.height}}.dump());
        }
    }
    const auto frame = std::make_shared<const std::string>(video_frame_message(au));
    // A copy: a viewer dropped here leaves the list only from its destructor, later.
    for (auto* client : std::vector<VideoClient*>(feed.clients))
        client->offer(feed.config, frame, au.key_frame);
}

}  // namespace gimbald::http
