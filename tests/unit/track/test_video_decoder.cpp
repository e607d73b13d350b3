// The tracker's decoder: H.264 from lib/sim_video's encoder and H.265 from libx265 decoded
// and scaled to the requested width, times kept; it waits for a key frame, counts what it
// refuses, and survives garbage.
#include <catch2/catch.hpp>
#include <opencv2/imgproc.hpp>
#include <random>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavutil/log.h>
#include <libavutil/opt.h>
}

#include "encoded_scene.hpp"
#include "track/decode/video_decoder.hpp"

using namespace gimbal::track;
using namespace track_test;

namespace {

// FFmpeg reports every damaged macroblock on stderr; the counters are what is checked here.
const bool quiet = [] {
    av_log_set_level(AV_LOG_FATAL);
    return true;
}();

// Mean absolute difference of two BGR pictures of the same size, grey levels.
double difference(const cv::Mat& a, const cv::Mat& b) {
    cv::Mat d;
    cv::absdiff(a, b, d);
    const cv::Scalar m = cv::mean(d);
    return (m[0] + m[1] + m[2]) / 3;
}

struct Hevc {
    std::vector<std::vector<std::uint8_t>> units;
    std::vector<bool> key;
};

// The scene encoded to H.265 by libx265 through libavcodec (Annex B, one unit per frame).
Hevc encode_hevc(const SyntheticScene& scene, int count) {
    const AVCodec* codec = avcodec_find_encoder_by_name("libx265");
    REQUIRE(codec);
    AVCodecContext* c = avcodec_alloc_context3(codec);
    c->width = scene.options().width;
    c->height = scene.options().height;
    c->pix_fmt = AV_PIX_FMT_YUV420P;
    c->time_base = {1, 15};
    c->framerate = {15, 1};
    c->gop_size = 15;
    c->max_b_frames = 0;
    av_opt_set(c->priv_data, "preset", "ultrafast", 0);
    av_opt_set(c->priv_data, "tune", "zerolatency", 0);
    av_opt_set(c->priv_data, "x265-params", "log-level=error:repeat-headers=1", 0);
    REQUIRE(avcodec_open2(c, codec, nullptr) == 0);
    AVFrame* f = av_frame_alloc();
    f->width = c->width;
    f->height = c->height;
    f->format = c->pix_fmt;
    REQUIRE(av_frame_get_buffer(f, 0) == 0);
    AVPacket* p = av_packet_alloc();
    Hevc out;
    auto drain = [&] {
        while (avcodec_receive_packet(c, p) == 0) {
            out.units.emplace_back(p->data, p->data + p->size);
            out.key.push_back((p->flags & AV_PKT_FLAG_KEY) != 0);
            av_packet_unref(p);
        }
    };
    for (int i = 0; i <= count; ++i) {
        if (i == count) {
            avcodec_send_frame(c, nullptr);
            drain();
            break;
        }
        REQUIRE(av_frame_make_writable(f) == 0);
        const auto i420 = to_i420(scene.render(i / 15.0));
        for (int y = 0; y < f->height; ++y)
            std::memcpy(f->data[0] + y * f->linesize[0], i420.y.data() + y * f->width,
                        static_cast<std::size_t>(f->width));
        for (int y = 0; y < f->height / 2; ++y) {
            std::memcpy(f->data[1] + y * f->linesize[1], i420.u.data() + y * f->width / 2,
                        static_cast<std::size_t>(f->width / 2));
            std::memcpy(f->data[2] + y * f->linesize[2], i420.v.data() + y * f->width / 2,
                        static_cast<std::size_t>(f->width / 2));
        }
        f->pts = i;
        REQUIRE(avcodec_send_frame(c, f) == 0);
        drain();
    }
    av_packet_free(&p);
    av_frame_free(&f);
    avcodec_free_context(&c);
    return out;
}

}  // namespace

TEST_CASE("video decoder: H.264 decoded, scaled to the width, times kept", "[track][decode]") {
    SceneOptions o;
    o.width = 1280;
    o.height = 720;
    o.route = {{100, 500}, {1200, 500}};
    o.vehicle = {68, 32};
    const SyntheticScene scene(o);
    const auto units = encode_scene(scene, 20, 15);
    auto opened = VideoDecoder::open(gimbal::track::wire::Codec::h264, 640);
    REQUIRE(opened.decoder);
    std::vector<DecodedFrame> frames;
    for (const auto& u : units) CHECK(opened.decoder->decode(u.annex_b, u.pts_90k, u.key, frames));
    REQUIRE(frames.size() == 20);  // one picture per unit, none held back
    for (std::size_t i = 0; i < frames.size(); ++i) {
        const auto& f = frames[i];
        CHECK(f.pts_90k == static_cast<std::int64_t>(i) * 6000);
        CHECK(f.bgr.cols == 640);
        CHECK(f.bgr.rows == 360);
        CHECK(f.bgr.type() == CV_8UC3);
        CHECK(f.source_width == 1280);
        CHECK(f.source_height == 720);
        cv::Mat expected;
        cv::resize(scene.render(static_cast<double>(i) / 15), expected, {640, 360}, 0, 0,
                   cv::INTER_AREA);
        CHECK(difference(f.bgr, expected) < 8);  // the same picture, up to the codec's loss
    }
    CHECK(opened.decoder->stats().frames == 20);
    CHECK(opened.decoder->stats().errors == 0);
}

TEST_CASE("video decoder: H.265 decoded", "[track][decode]") {
    const SyntheticScene scene;
    const auto hevc = encode_hevc(scene, 10);
    REQUIRE(hevc.units.size() == 10);
    REQUIRE(hevc.key.front());
    auto opened = VideoDecoder::open(gimbal::track::wire::Codec::h265, 640);
    REQUIRE(opened.decoder);
    std::vector<DecodedFrame> frames;
    for (std::size_t i = 0; i < hevc.units.size(); ++i)
        CHECK(opened.decoder->decode(hevc.units[i], static_cast<std::int64_t>(i) * 6000,
                                     hevc.key[i], frames));
    REQUIRE(frames.size() == 10);
    CHECK(frames[3].pts_90k == 18000);
    CHECK(frames[3].bgr.size() == cv::Size(640, 360));
    CHECK(difference(frames[3].bgr, scene.render(3 / 15.0)) < 8);
}

TEST_CASE("video decoder: never enlarges, keeps the aspect, even sizes", "[track][decode]") {
    CHECK(scaled_size(640, 360, 1280) == cv::Size(640, 360));
    CHECK(scaled_size(1920, 1080, 640) == cv::Size(640, 360));
    CHECK(scaled_size(1920, 1080, 500) == cv::Size(500, 282));
    CHECK(scaled_size(720, 576, 640) == cv::Size(640, 512));
    CHECK(scaled_size(0, 576, 640) == cv::Size(0, 0));
}

TEST_CASE("video decoder: waits for a key frame", "[track][decode]") {
    const SyntheticScene scene;
    const auto units = encode_scene(scene, 25, 15);  // IDR at 0 and 15
    auto opened = VideoDecoder::open(gimbal::track::wire::Codec::h264, 640);
    std::vector<DecodedFrame> frames;
    for (std::size_t i = 3; i < units.size(); ++i)  // joined after the first key frame
        opened.decoder->decode(units[i].annex_b, units[i].pts_90k, units[i].key, frames);
    CHECK(opened.decoder->stats().waiting_key == 12);
    REQUIRE(frames.size() == 10);
    CHECK(frames.front().pts_90k == 15 * 6000);
}

TEST_CASE("video decoder: garbage is counted, never fatal", "[track][decode]") {
    const SyntheticScene scene;
    const auto units = encode_scene(scene, 30, 15);
    auto opened = VideoDecoder::open(gimbal::track::wire::Codec::h264, 640);
    std::mt19937 rng(27);
    std::vector<DecodedFrame> frames;
    // Random bytes claiming to be key frames, then a real stream with its slices damaged.
    for (int i = 0; i < 50; ++i) {
        std::vector<std::uint8_t> junk(static_cast<std::size_t>(rng() % 5000));
        for (auto& b : junk) b = static_cast<std::uint8_t>(rng());
        if (junk.size() > 4) junk[0] = junk[1] = junk[2] = 0, junk[3] = 1;
        opened.decoder->decode(junk, i, true, frames);
    }
    for (const auto& u : units) {
        auto damaged = u.annex_b;
        if (!u.key)
            for (std::size_t k = damaged.size() / 2; k < damaged.size(); k += 7)
                damaged[k] = static_cast<std::uint8_t>(rng());
        opened.decoder->decode(damaged, u.pts_90k, u.key, frames);
    }
    const auto& s = opened.decoder->stats();
    CHECK(s.units == 80);
    // What it decoded is whole pictures of the right size; the key frames at least.
    CHECK(frames.size() >= 2);
    for (const auto& f : frames) CHECK(f.bgr.size() == cv::Size(640, 360));
    // And a clean stream afterwards decodes normally.
    std::vector<DecodedFrame> clean;
    for (const auto& u : units) opened.decoder->decode(u.annex_b, u.pts_90k + 900000, u.key, clean);
    CHECK(clean.size() == 30);
}
