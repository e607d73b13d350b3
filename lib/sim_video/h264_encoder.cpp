#include "sim_video/h264_encoder.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavutil/error.h>
#include <libavutil/frame.h>
#include <libavutil/log.h>
#include <libavutil/opt.h>
}

namespace gimbal::sim_video {

namespace {

constexpr int pts_clock_hz = 90000;
constexpr int level_idc = 30;  // 3.0: 640x360 up to 30 fps, and 720x576 at 25

std::string av_error(int code) {
    char text[AV_ERROR_MAX_STRING_SIZE] = {};
    av_strerror(code, text, sizeof text);
    return text;
}

bool one_of(const std::string& value, std::initializer_list<const char*> allowed) {
    return std::any_of(allowed.begin(), allowed.end(), [&](const char* a) { return value == a; });
}

struct CodecContextDeleter {
    void operator()(AVCodecContext* c) const { avcodec_free_context(&c); }
};
struct FrameDeleter {
    void operator()(AVFrame* f) const { av_frame_free(&f); }
};
struct PacketDeleter {
    void operator()(AVPacket* p) const { av_packet_free(&p); }
};

}  // namespace

std::string check(const H264Options& o) {
    if (o.width < 16 || o.width > 4096 || o.height < 16 || o.height > 4096 || o.width % 2 != 0 ||
        o.height % 2 != 0)
        return "width and height must be even, 16..4096";
    if (o.fps < 1 || o.fps > 120) return "fps must be 1..120";
    if (o.bitrate_bps < 50000 || o.bitrate_bps > 50000000)
        return "bitrate must be 50 kbit/s..50 Mbit/s";
    if (!(o.key_interval_s > 0) || std::lround(o.key_interval_s * o.fps) < 1 ||
        o.key_interval_s > 60)
        return "key interval must be at least one frame and at most 60 s";
    if (!one_of(o.preset, {"ultrafast", "superfast", "veryfast", "faster", "fast", "medium"}))
        return "preset must be ultrafast, superfast, veryfast, faster, fast or medium";
    if (!one_of(o.profile, {"baseline", "main", "high"}))
        return "profile must be baseline, main or high";
    if (o.threads < 0 || o.threads > 16) return "threads must be 0..16";
    return {};
}

struct H264Encoder::Impl {
    H264Options options;
    int key_interval = 1;
    std::unique_ptr<AVCodecContext, CodecContextDeleter> context;
    std::unique_ptr<AVFrame, FrameDeleter> frame;
    std::unique_ptr<AVPacket, PacketDeleter> packet;
    std::optional<std::int64_t> last_pts;
    bool flushed = false;
    std::string error;

    // Moves every finished packet to `out`.
    bool drain(std::vector<AccessUnit>& out) {
        while (true) {
            const int r = avcodec_receive_packet(context.get(), packet.get());
            if (r == AVERROR(EAGAIN) || r == AVERROR_EOF) return true;
            if (r < 0) {
                error = "encoder: " + av_error(r);
                return false;
            }
            AccessUnit unit;
            unit.annex_b.assign(packet->data, packet->data + packet->size);
            unit.pts_90k = packet->pts;
            unit.key = (packet->flags & AV_PKT_FLAG_KEY) != 0;
            out.push_back(std::move(unit));
            av_packet_unref(packet.get());
        }
    }
};

H264Encoder::H264Encoder(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
H264Encoder::~H264Encoder() = default;

Result<std::unique_ptr<H264Encoder>> H264Encoder::open(const H264Options& o) {
    if (auto e = check(o); !e.empty()) return Error{code::bad_request, e};
    const AVCodec* codec = avcodec_find_encoder_by_name("libx264");
    if (!codec) return Error{code::unavailable, "this FFmpeg has no libx264 encoder"};
    auto impl = std::make_unique<Impl>();
    impl->options = o;
    impl->key_interval = std::max(1, static_cast<int>(std::lround(o.key_interval_s * o.fps)));
    impl->context.reset(avcodec_alloc_context3(codec));
    impl->frame.reset(av_frame_alloc());
    impl->packet.reset(av_packet_alloc());
    if (!impl->context || !impl->frame || !impl->packet)
        return Error{code::unavailable, "out of memory"};

    AVCodecContext* c = impl->context.get();
    // x264's informational lines (CPU flags, profile) are verbose here; warnings still show.
    c->log_level_offset = AV_LOG_VERBOSE - AV_LOG_INFO;
    c->width = o.width;
    c->height = o.height;
    c->pix_fmt = AV_PIX_FMT_YUV420P;
    c->time_base = {1, pts_clock_hz};
    c->framerate = {o.fps, 1};
    c->gop_size = impl->key_interval;
    c->keyint_min = impl->key_interval;
    c->max_b_frames = 0;
    c->bit_rate = o.bitrate_bps;
    c->rc_max_rate = o.bitrate_bps;
    c->rc_buffer_size = o.bitrate_bps / 2;
    c->thread_count = o.threads;
    c->level = level_idc;
    c->colorspace = AVCOL_SPC_SMPTE170M;
    c->color_primaries = AVCOL_PRI_SMPTE170M;
    c->color_trc = AVCOL_TRC_SMPTE170M;
    c->color_range = AVCOL_RANGE_MPEG;
    // No AV_CODEC_FLAG_GLOBAL_HEADER: SPS and PPS then go in-band before every IDR.
    void* priv = c->priv_data;
    const auto set = [&](const char* key, const char* value) {
        return av_opt_set(priv, key, value, 0);
    };
    if (set("preset", o.preset.c_str()) < 0 || set("tune", "zerolatency") < 0 ||
        set("profile", o.profile.c_str()) < 0 || av_opt_set_int(priv, "aud", 1, 0) < 0 ||
        av_opt_set_int(priv, "sc_threshold", 0, 0) < 0)
        return Error{code::unavailable, "libx264 does not take the options"};
    if (const int r = avcodec_open2(c, codec, nullptr); r < 0)
        return Error{code::unavailable, "cannot open libx264: " + av_error(r)};

    AVFrame* f = impl->frame.get();
    f->format = AV_PIX_FMT_YUV420P;
    f->width = o.width;
    f->height = o.height;
    f->color_range = AVCOL_RANGE_MPEG;
    f->colorspace = AVCOL_SPC_SMPTE170M;
    return std::unique_ptr<H264Encoder>(new H264Encoder(std::move(impl)));
}

bool H264Encoder::encode(const sim::I420Frame& in, std::int64_t pts_90k,
                         std::vector<AccessUnit>& out) {
    Impl& s = *impl_;
    if (s.flushed) {
        s.error = "the encoder was flushed";
        return false;
    }
    if (in.width != s.options.width || in.height != s.options.height ||
        in.y.size() != static_cast<std::size_t>(in.width) * static_cast<std::size_t>(in.height) ||
        in.u.size() != in.y.size() / 4 || in.v.size() != in.u.size()) {
        s.error = "frame is not " + std::to_string(s.options.width) + "x" +
                  std::to_string(s.options.height) + " I420";
        return false;
    }
    if (s.last_pts && pts_90k <= *s.last_pts) {
        s.error = "frame time does not increase";
        return false;
    }
    // The encoder may still reference the previous picture's buffers: write into fresh ones
    // when it does (av_frame_make_writable copies only then).
    AVFrame* f = s.frame.get();
    if (!f->data[0] && av_frame_get_buffer(f, 0) < 0) {
        s.error = "out of memory";
        return false;
    }
    if (av_frame_make_writable(f) < 0) {
        s.error = "out of memory";
        return false;
    }
    const auto copy_plane = [](const std::vector<std::uint8_t>& src, int w, int h,
                               std::uint8_t* dst, int stride) {
        for (int y = 0; y < h; ++y)
            std::memcpy(dst + static_cast<std::ptrdiff_t>(y) * stride,
                        src.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(w),
                        static_cast<std::size_t>(w));
    };
    copy_plane(in.y, in.width, in.height, f->data[0], f->linesize[0]);
    copy_plane(in.u, in.chroma_width(), in.chroma_height(), f->data[1], f->linesize[1]);
    copy_plane(in.v, in.chroma_width(), in.chroma_height(), f->data[2], f->linesize[2]);
    f->pts = pts_90k;
    const std::size_t before = out.size();
    if (const int r = avcodec_send_frame(s.context.get(), f); r < 0) {
        s.error = "encoder: " + av_error(r);
        return false;
    }
    s.last_pts = pts_90k;
    if (!s.drain(out)) {
        out.resize(before);
        return false;
    }
    return true;
}

bool H264Encoder::flush(std::vector<AccessUnit>& out) {
    Impl& s = *impl_;
    if (s.flushed) return true;
    s.flushed = true;
    if (const int r = avcodec_send_frame(s.context.get(), nullptr); r < 0) {
        s.error = "encoder: " + av_error(r);
        return false;
    }
    return s.drain(out);
}

const H264Options& H264Encoder::options() const {
    return impl_->options;
}

int H264Encoder::key_interval_frames() const {
    return impl_->key_interval;
}

const std::string& H264Encoder::error() const {
    return impl_->error;
}

}  // namespace gimbal::sim_video
