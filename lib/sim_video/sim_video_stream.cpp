#include "sim_video/sim_video_stream.hpp"

#include "klv/local_set.hpp"
#include "sim_video/sim_klv.hpp"

namespace gimbal::sim_video {

Result<std::unique_ptr<SimVideoStream>> SimVideoStream::open(const SimVideoStreamOptions& options,
                                                             Sink sink) {
    auto source = SimVideoSource::open(options.video);
    if (!source) return source.error();
    return std::unique_ptr<SimVideoStream>(
        new SimVideoStream(options, std::move(source).value(), std::move(sink)));
}

SimVideoStream::SimVideoStream(const SimVideoStreamOptions& options,
                               std::unique_ptr<SimVideoSource> source, Sink sink)
    : klv_(options.klv),
      source_(std::move(source)),
      sink_(std::move(sink)),
      mux_(
          [&] {
              video::MuxerOptions mux = options.mux;
              mux.klv = options.klv;
              return mux;
          }(),
          video::Codec::h264,
          [this](std::span<const std::uint8_t> chunk) {
              stats_.bytes += chunk.size();
              sink_(chunk);
          }) {}

bool SimVideoStream::frame(const sim::CameraView& view, std::uint64_t unix_us,
                           std::int64_t pts_90k) {
    units_.clear();
    if (!source_->frame(view, unix_us / 1000, pts_90k, units_)) {
        error_ = source_->error();
        return false;
    }
    const auto pts = static_cast<std::uint64_t>(pts_90k) & (video::pts_modulus - 1);
    for (const AccessUnit& unit : units_) {
        video::AccessUnit au;
        au.codec = video::Codec::h264;
        au.pts = static_cast<std::uint64_t>(unit.pts_90k) & (video::pts_modulus - 1);
        au.key_frame = unit.key;
        au.data = unit.annex_b;
        mux_.write_video(au);
        ++stats_.frames;
        if (unit.key) ++stats_.key_frames;
    }
    if (klv_) {
        const klv::Encoded set = klv::encode(klv::sensor_set(sensor_frame(view, unix_us)));
        if (set.ok()) {
            mux_.write_klv(*set, pts);
            ++stats_.klv_sets;
        }
    }
    mux_.flush();
    return true;
}

}  // namespace gimbal::sim_video
