#include "sim_video/sim_video_source.hpp"

#include "sim/frame_code.hpp"

namespace gimbal::sim_video {

Result<std::unique_ptr<SimVideoSource>> SimVideoSource::open(const SimVideoOptions& options) {
    if (!sim::valid(options.scene))
        return Error{code::bad_request,
                     "scene: width and height must be even, 16..4096; grid 4..64 px"};
    H264Options h264 = options.h264;
    h264.width = options.scene.width;
    h264.height = options.scene.height;
    auto opened = H264Encoder::open(h264);
    if (!opened) return opened.error();
    return std::unique_ptr<SimVideoSource>(new SimVideoSource(options, std::move(opened).value()));
}

SimVideoSource::SimVideoSource(const SimVideoOptions& options, std::unique_ptr<H264Encoder> encoder)
    : object_set_(options.objects), renderer_(options.scene), encoder_(std::move(encoder)) {}

bool SimVideoSource::encode(std::uint64_t unix_ms, std::int64_t pts_90k,
                            std::vector<AccessUnit>& out) {
    sim::draw_frame_code(picture_, unix_ms);
    return encoder_->encode(picture_, pts_90k, out);
}

bool SimVideoSource::frame(const geo::CameraPose& camera, std::uint64_t unix_ms,
                           std::int64_t pts_90k, std::vector<AccessUnit>& out) {
    truth_.clear();
    renderer_.render(camera, picture_);
    return encode(unix_ms, pts_90k, out);
}

bool SimVideoSource::frame(const sim::CameraView& view, std::uint64_t unix_ms, std::int64_t pts_90k,
                           std::vector<AccessUnit>& out) {
    renderer_.set_monochrome(view.monochrome);
    const std::vector<sim::ObjectState> moving = object_set_.at(view.model_time_s);
    renderer_.render(view.pose, picture_, moving);
    truth_ = object_truth(view.pose, moving);
    return encode(unix_ms, pts_90k, out);
}

}  // namespace gimbal::sim_video
