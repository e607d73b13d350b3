// gimbal-sim --video and its settings: the simulated camera's picture as MPEG-TS with KLV over
// UDP (contract section 17), for any protocol whose simulator hook has a camera.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "protocols/registry.hpp"
#include "video/sim_video_sender.hpp"

namespace gimbal_sim {

struct VideoToolOptions {
    std::string url;  // udp://HOST:PORT[?ttl=N]; empty: no video
    std::string size = "640x360";
    int fps = 15;
    int bitrate_bps = 1200000;
    bool klv = true;
    std::string objects = "all";  // sim::ObjectSet::parse's text
    std::string objects_log;      // the objects' truth, JSON lines (empty: none)
};

// Adds --video, --video-size, --video-fps, --video-bitrate, --no-video-klv, --objects,
// --objects-log.
void add_video_options(CLI::App& app, VideoToolOptions& options);
// The sender's settings, or the reason the options cannot be used with this protocol.
std::optional<gimbald::video::SimVideoSenderOptions> video_sender_options(
    const VideoToolOptions& options, const gimbal::protocols::Entry& entry, std::string& error);

// The manual's VIDEO section.
// The VIDEO section of the manual; names the protocols whose simulator has a camera.
std::string video_manual();

}  // namespace gimbal_sim
