#include "track/decode/video_decoder.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavutil/error.h>
#include <libavutil/frame.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

namespace gimbal::track {

namespace {

std::string av_error(int code) {
    char text[AV_ERROR_MAX_STRING_SIZE] = {};
    av_strerror(code, text, sizeof(text));
    return text;
}

struct CodecContextFree {
    void operator()(AVCodecContext* c) const { avcodec_free_context(&c); }
};
struct PacketFree {
    void operator()(AVPacket* p) const { av_packet_free(&p); }
};
struct FrameFree {
    void operator()(AVFrame* f) const { av_frame_free(&f); }
};
struct SwsFree {
    void operator()(SwsContext* s) const { sws_freeContext(s); }
};

}  // namespace

cv::Size scaled_size(int source_width, int source_height, int width) {
    if (source_width <= 0 || source_height <= 0) return {0, 0};
    const int w = std::max(2, std::min(width, source_width) / 2 * 2);
    const double h = static_cast<double>(source_height) * w / source_width;
    return {w, std::max(2, static_cast<int>(std::lround(h / 2)) * 2)};
}

struct VideoDecoder::Impl {
    wire::Codec codec = wire::Codec::h264;
    int width = 640;
    std::unique_ptr<AVCodecContext, CodecContextFree> context;
    std::unique_ptr<AVPacket, PacketFree> packet;
    std::unique_ptr<AVFrame, FrameFree> frame;
    std::unique_ptr<SwsContext, SwsFree> scaler;
    int scaler_from_w = 0, scaler_from_h = 0, scaler_from_format = -1;
    cv::Size scaler_to;
    bool need_key = true;
    DecoderStats stats;
    std::string last_error;

    bool fail(std::string what) {
        ++stats.errors;
        last_error = std::move(what);
        need_key = true;
        return false;
    }

    bool scale(const AVFrame& f, DecodedFrame& out) {
        const cv::Size to = scaled_size(f.width, f.height, width);
        if (to.width <= 0) return false;
        if (!scaler || scaler_from_w != f.width || scaler_from_h != f.height ||
            scaler_from_format != f.format || scaler_to != to) {
            scaler.reset(sws_getContext(f.width, f.height, static_cast<AVPixelFormat>(f.format),
                                        to.width, to.height, AV_PIX_FMT_BGR24, SWS_BILINEAR,
                                        nullptr, nullptr, nullptr));
            if (!scaler) return false;
            scaler_from_w = f.width;
            scaler_from_h = f.height;
            scaler_from_format = f.format;
            scaler_to = to;
        }
        out.bgr.create(to, CV_8UC3);
        std::uint8_t* dst[4] = {out.bgr.data, nullptr, nullptr, nullptr};
        int dst_stride[4] = {static_cast<int>(out.bgr.step[0]), 0, 0, 0};
        const int rows = sws_scale(scaler.get(), f.data, f.linesize, 0, f.height, dst, dst_stride);
        return rows == to.height;
    }

    void drain(std::vector<DecodedFrame>& out) {
        for (;;) {
            const int got = avcodec_receive_frame(context.get(), frame.get());
            if (got == AVERROR(EAGAIN) || got == AVERROR_EOF) return;
            if (got < 0) {
                fail("receiving a picture: " + av_error(got));
                return;
            }
            if ((frame->flags & AV_FRAME_FLAG_CORRUPT) != 0 || frame->decode_error_flags != 0) {
                ++stats.corrupt;
                av_frame_unref(frame.get());
                continue;
            }
            DecodedFrame d;
            d.pts_90k = frame->pts != AV_NOPTS_VALUE ? frame->pts : frame->best_effort_timestamp;
            d.source_width = frame->width;
            d.source_height = frame->height;
            if (scale(*frame, d)) {
                ++stats.frames;
                out.push_back(std::move(d));
            } else {
                fail("scaling a " + std::to_string(frame->width) + "x" +
                     std::to_string(frame->height) + " picture");
            }
            av_frame_unref(frame.get());
        }
    }
};

VideoDecoder::VideoDecoder(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
VideoDecoder::~VideoDecoder() = default;

VideoDecoder::Opened VideoDecoder::open(wire::Codec codec, int width) {
    const AVCodecID id = codec == wire::Codec::h265 ? AV_CODEC_ID_HEVC : AV_CODEC_ID_H264;
    const AVCodec* decoder = avcodec_find_decoder(id);
    if (!decoder)
        return {nullptr, "this FFmpeg has no " + std::string(wire::to_string(codec)) + " decoder"};
    auto impl = std::make_unique<Impl>();
    impl->codec = codec;
    impl->width = std::clamp(width, wire::min_width, wire::max_width);
    impl->context.reset(avcodec_alloc_context3(decoder));
    impl->packet.reset(av_packet_alloc());
    impl->frame.reset(av_frame_alloc());
    if (!impl->context || !impl->packet || !impl->frame) return {nullptr, "out of memory"};
    AVCodecContext& c = *impl->context;
    c.thread_count = 1;  // one core's worth at most; no frame-threading delay
    c.flags |= AV_CODEC_FLAG_LOW_DELAY;
    c.pkt_timebase = AVRational{1, 90000};
    c.max_pixels = max_pixels;
    const int opened = avcodec_open2(&c, decoder, nullptr);
    if (opened < 0) return {nullptr, "opening the decoder: " + av_error(opened)};
    return {std::unique_ptr<VideoDecoder>(new VideoDecoder(std::move(impl))), {}};
}

bool VideoDecoder::decode(std::span<const std::uint8_t> annex_b, std::int64_t pts_90k, bool key,
                          std::vector<DecodedFrame>& out) {
    Impl& d = *impl_;
    ++d.stats.units;
    if (d.need_key && !key) {
        ++d.stats.waiting_key;
        return true;
    }
    if (annex_b.empty()) return true;
    if (annex_b.size() > wire::max_access_unit_bytes) return d.fail("access unit too large");
    if (key && d.need_key) avcodec_flush_buffers(d.context.get());
    d.need_key = false;
    AVPacket& p = *d.packet;
    // av_new_packet pads with zeros, as the decoder's bitstream reader needs.
    if (av_new_packet(&p, static_cast<int>(annex_b.size())) < 0) return d.fail("out of memory");
    std::memcpy(p.data, annex_b.data(), annex_b.size());
    p.pts = pts_90k;
    p.dts = AV_NOPTS_VALUE;  // the decoder orders by the bitstream, not by us
    if (key) p.flags |= AV_PKT_FLAG_KEY;
    const int sent = avcodec_send_packet(d.context.get(), &p);
    av_packet_unref(&p);
    if (sent < 0 && sent != AVERROR(EAGAIN)) {
        d.drain(out);
        return d.fail("decoding: " + av_error(sent));
    }
    const auto errors = d.stats.errors;
    d.drain(out);
    return d.stats.errors == errors;
}

wire::Codec VideoDecoder::codec() const {
    return impl_->codec;
}
int VideoDecoder::width() const {
    return impl_->width;
}
const DecoderStats& VideoDecoder::stats() const {
    return impl_->stats;
}
const std::string& VideoDecoder::last_error() const {
    return impl_->last_error;
}

}  // namespace gimbal::track
