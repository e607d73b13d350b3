#include "video/rtsp_input.hpp"

extern "C" {
#include <libavformat/avformat.h>
#include <libavutil/avutil.h>
#include <libavutil/error.h>
#include <libavutil/mem.h>
}

#include <malloc.h>

#include <cstring>

#include <fmt/format.h>

#include <boost/asio/post.hpp>

#include "video/nal.hpp"

namespace gimbald::video {

namespace asio = boost::asio;
namespace gv = gimbal::video;

struct RtspInput::Shared {
    std::atomic<bool> stop{false};
    std::atomic<std::int64_t> deadline_ns{0};  // steady clock; blocking calls give up after
    std::mutex mutex;
    std::condition_variable wake;
    std::atomic<std::size_t> queued{0};
    std::atomic<std::size_t> queued_bytes{0};
    std::atomic<std::uint64_t> dropped{0};
    std::atomic<std::uint64_t> reconnects{0};
    std::weak_ptr<const char> alive;

    void set_deadline(double from_now_s) {
        const auto at = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                           std::chrono::duration<double>(from_now_s));
        deadline_ns =
            std::chrono::duration_cast<std::chrono::nanoseconds>(at.time_since_epoch()).count();
    }
    bool expired() const {
        const auto now =
            std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now().time_since_epoch())
                .count();
        return stop.load() || now > deadline_ns.load();
    }
};

// One connection attempt, redirects included, as the interrupt callback watches it.
// libavformat follows an RTSP redirect inside avformat_open_input: it replaces the context's
// url with the Location, connects there and sends its next request - with the credentials
// of the first URL. Every write to a connection is preceded by a call of this callback, so a
// changed url is seen here before anything reaches the new host.
struct RtspInput::Attempt {
    Shared* shared = nullptr;
    AVFormatContext* format = nullptr;  // while libavformat owns it
    std::string url;                    // being opened (ours, or a Location without userinfo)
    std::string authority;              // its host:port
    std::string seen;                   // the url libavformat is on
    const char* seen_url = nullptr;     // and the string it was in (see interrupt())
    int redirects = 0;                  // for this attempt, ours and libavformat's
    int max_redirects = 4;
    std::string redirect;  // libavformat was about to follow one to another host:port
    bool too_many = false;
    bool got_video = false;
    std::string error;  // why it ended (empty: stopped)

    // The interrupt callback: non-zero makes libavformat's blocking call return.
    static int interrupt(void* opaque) {
        auto& a = *static_cast<Attempt*>(opaque);
        // Once stopped, stopped for good: libavformat ignores some failed writes and goes on.
        if (a.shared->expired() || a.too_many || !a.redirect.empty()) return 1;
        if (a.format == nullptr || a.format->url == nullptr) return 0;
        // A redirect gives the context a newly allocated url (allocated before the old one is
        // freed, so never at the same address): a new string is a redirect even when its text
        // is the same - a camera that redirects to itself loops inside avformat_open_input.
        const char* url = a.format->url;
        const bool first_look = a.seen_url == nullptr;
        if (url == a.seen_url || (first_look && a.seen == url)) {
            a.seen_url = url;
            return 0;
        }
        a.seen_url = url;
        a.seen = url;
        if (++a.redirects > a.max_redirects) {
            a.too_many = true;
            return 1;
        }
        const auto to = gv::rtsp_authority(a.seen);
        if (!to || *to != a.authority) {
            a.redirect = a.seen;  // another host: not with our credentials
            return 1;
        }
        return 0;  // the same camera: libavformat may go on
    }
};

namespace {

// One allocation of libavformat at most (process-wide: gimbald's only other user of libav is
// the simulator's encoder, whose largest buffer is a frame): room for an access unit of
// max_access_unit_bytes (its parser grows a buffer by 1/16 at a time), and no more, since a
// camera that never ends its frame keeps that buffer for as long as its session lasts.
constexpr std::size_t max_libav_alloc_bytes = gv::max_access_unit_bytes + (1u << 20);
// RTP packets held for reordering (RTP over UDP); libavformat's default is 500.
constexpr int reorder_queue_packets = 64;

std::string av_error(int code) {
    char text[AV_ERROR_MAX_STRING_SIZE] = {};
    av_strerror(code, text, sizeof text);
    return text;
}

void init_libav() {
    static std::once_flag once;
    std::call_once(once, [] {
        avformat_network_init();
        av_max_alloc(max_libav_alloc_bytes);
        // Errors reach our own structured log lines; libav's stderr chatter would not.
        av_log_set_level(AV_LOG_FATAL);
    });
}

struct FormatCloser {
    void operator()(AVFormatContext* f) const { avformat_close_input(&f); }
};
struct PacketFree {
    void operator()(AVPacket* p) const { av_packet_free(&p); }
};

bool has_userinfo(const std::string& url) {
    return gv::without_userinfo(url) != url;
}

}  // namespace

RtspInput::RtspInput(asio::io_context& io, gv::VideoUrl url, VideoInputOptions options,
                     VideoInputHandlers handlers)
    : io_(io),
      url_(std::move(url)),
      options_(std::move(options)),
      handlers_(std::move(handlers)),
      failure_log_(gimbal::log::Level::warn, "video_input_error", "RTSP connection failures"),
      redirect_log_(gimbal::log::Level::warn, "rtsp_redirect", "RTSP redirects to another host") {
    if (url_.scheme != gv::UrlScheme::rtsp) throw std::invalid_argument("not an rtsp:// URL");
    if (url_.timeout_s) options_.timeout_s = *url_.timeout_s;
    options_.log_fields["input"] = gv::redact_userinfo(url_.text);
    init_libav();
}

RtspInput::~RtspInput() {
    stop();
}

void RtspInput::start() {
    if (thread_.joinable()) return;
    shared_ = std::make_shared<Shared>();
    alive_ = std::make_shared<const char>('\0');
    shared_->alive = alive_;
    thread_ = std::thread([this, shared = shared_] { run(shared); });
}

void RtspInput::stop() {
    if (!thread_.joinable()) return;
    {
        std::lock_guard lock(shared_->mutex);
        shared_->stop = true;
    }
    shared_->wake.notify_all();
    thread_.join();
    alive_.reset();  // handlers already posted do nothing now
    connected_ = false;
}

void RtspInput::post_connected(bool connected, std::string error) {
    asio::post(io_, [this, alive = shared_->alive, connected, error = std::move(error)] {
        if (alive.expired()) return;
        if (!error.empty()) last_error_ = error;
        nlohmann::json fields = options_.log_fields;
        if (connected == connected_) {
            // A failure before any video came: no video_down (it never was up), but said.
            if (!connected && !error.empty()) {
                fields["error"] = error;
                failure_log_.hit("video input: " + error + " (retrying)", fields);
            }
            return;
        }
        connected_ = connected;
        if (connected) {
            gimbal::log::info("video_up", "video input receiving", fields);
        } else {
            fields["error"] = last_error_;
            gimbal::log::warn("video_down", "video input lost: " + last_error_, fields);
        }
        if (handlers_.connection) handlers_.connection(connected);
    });
}

void RtspInput::post_redirect(std::string from, std::string to) {
    asio::post(io_, [this, alive = shared_->alive, from = std::move(from), to = std::move(to)] {
        if (alive.expired()) return;
        nlohmann::json fields = options_.log_fields;
        fields["from"] = from;
        fields["to"] = to;
        redirect_log_.hit(
            "RTSP camera redirected to another host: followed without the input's "
            "credentials",
            fields);
    });
}

void RtspInput::run(std::shared_ptr<Shared> shared) {
    Backoff backoff(options_.backoff);
    bool first = true;
    while (!shared->stop) {
        if (!first) ++shared->reconnects;
        first = false;
        if (read_session(*shared)) backoff.reset();
        // What libavformat allocated for the session (up to av_max_alloc per buffer) goes back
        // to the system: glibc keeps freed large blocks in its arenas once they have been used.
        malloc_trim(0);
        if (shared->stop) break;
        std::unique_lock lock(shared->mutex);
        shared->wake.wait_for(lock, std::chrono::duration<double>(backoff.next()),
                              [&] { return shared->stop.load(); });
    }
}

// One connection, following redirects to other hosts without credentials. Returns whether
// any video came (then the next attempt starts from the shortest delay).
bool RtspInput::read_session(Shared& shared) {
    Attempt attempt;
    attempt.shared = &shared;
    attempt.max_redirects = options_.max_redirects;
    attempt.url = url_.rtsp_url;
    for (;;) {
        attempt.authority = gv::rtsp_authority(attempt.url).value_or("");
        attempt.seen = attempt.url;
        attempt.seen_url = nullptr;  // a new context: its url not looked at yet
        attempt.redirect.clear();
        open_and_read(shared, attempt);
        if (shared.stop) return attempt.got_video;
        if (attempt.too_many) {
            attempt.error =
                "rtsp: more than " + std::to_string(attempt.max_redirects) + " redirects (a loop?)";
        } else if (!attempt.redirect.empty() && !gv::rtsp_authority(attempt.redirect)) {
            // Only an RTSP camera is followed: never a file, an HTTP server or a relative path.
            attempt.error = "rtsp: redirect to something that is not an rtsp:// URL: " +
                            gv::redact_userinfo(attempt.redirect);
        } else if (!attempt.redirect.empty()) {
            const std::string to = gv::without_userinfo(attempt.redirect);
            if (has_userinfo(url_.rtsp_url) || has_userinfo(attempt.redirect))
                post_redirect(gv::redact_userinfo(attempt.url), to);
            else
                post_redirect(attempt.url, to);
            attempt.url = to;
            continue;
        }
        post_connected(false, attempt.error);
        return attempt.got_video;
    }
}

void RtspInput::open_and_read(Shared& shared, Attempt& attempt) {
    AVFormatContext* raw = avformat_alloc_context();
    if (!raw) {
        attempt.error = "rtsp: out of memory";
        return;
    }
    // libavformat polls this during every blocking call; non-zero makes the call return.
    raw->interrupt_callback.callback = &Attempt::interrupt;
    raw->interrupt_callback.opaque = &attempt;
    attempt.format = raw;
    AVDictionary* opts = nullptr;
    if (url_.transport == gv::RtspTransport::tcp) av_dict_set(&opts, "rtsp_transport", "tcp", 0);
    if (url_.transport == gv::RtspTransport::udp) av_dict_set(&opts, "rtsp_transport", "udp", 0);
    const auto timeout_us = static_cast<std::int64_t>(options_.timeout_s * 1e6);
    av_dict_set_int(&opts, "timeout", timeout_us, 0);  // socket I/O timeout
    av_dict_set(&opts, "allowed_media_types", "video", 0);
    // What libavformat may open for it: the RTSP connection and RTP over TCP or UDP.
    av_dict_set(&opts, "protocol_whitelist", "tcp,udp,rtp", 0);
    av_dict_set(&opts, "fflags", "nobuffer", 0);
    av_dict_set_int(&opts, "max_delay", 200'000, 0);  // RTP reordering over UDP, microseconds
    av_dict_set_int(&opts, "reorder_queue_size", reorder_queue_packets, 0);
    av_dict_set_int(&opts, "probesize", 1 << 20, 0);
    av_dict_set_int(&opts, "analyzeduration", 1'000'000, 0);
    shared.set_deadline(options_.timeout_s * 2);  // connect + DESCRIBE + SETUP + PLAY
    const int opened = avformat_open_input(&raw, attempt.url.c_str(), nullptr, &opts);
    av_dict_free(&opts);
    if (opened < 0) {  // libavformat freed the context
        attempt.format = nullptr;
        if (!shared.stop && attempt.redirect.empty() && !attempt.too_many)
            attempt.error =
                opened == AVERROR_EXIT
                    ? fmt::format("rtsp open: no answer within {:g} s", options_.timeout_s * 2)
                    : "rtsp open: " + av_error(opened);
        return;
    }
    std::unique_ptr<AVFormatContext, FormatCloser> fmt(raw);
    read_frames(shared, fmt.get(), attempt);
    // Closing may still call the interrupt callback (TEARDOWN): attempt outlives fmt.
}

void RtspInput::read_frames(Shared& shared, void* format, Attempt& attempt) {
    auto* fmt = static_cast<AVFormatContext*>(format);
    int index = -1;
    gv::Codec codec = gv::Codec::h264;
    for (unsigned i = 0; i < fmt->nb_streams; ++i) {
        const AVCodecParameters* par = fmt->streams[i]->codecpar;
        if (par->codec_id == AV_CODEC_ID_H264 || par->codec_id == AV_CODEC_ID_HEVC) {
            index = static_cast<int>(i);
            codec = par->codec_id == AV_CODEC_ID_H264 ? gv::Codec::h264 : gv::Codec::h265;
            break;
        }
    }
    if (index < 0) {
        attempt.error = "rtsp: no H.264 or H.265 video stream";
        return;
    }
    const AVStream* stream = fmt->streams[index];
    gv::Extradata extra;
    if (stream->codecpar->extradata && stream->codecpar->extradata_size > 0) {
        if (auto e = gv::parse_extradata(
                codec, {stream->codecpar->extradata,
                        static_cast<std::size_t>(stream->codecpar->extradata_size)})) {
            extra = std::move(*e);
        }
    }

    std::unique_ptr<AVPacket, PacketFree> pkt(av_packet_alloc());
    const AVRational ts90k{1, 90'000};
    std::optional<std::uint64_t> last_pts;
    std::uint64_t last_step = 0;
    while (!shared.stop) {
        shared.set_deadline(options_.timeout_s);
        const int r = av_read_frame(fmt, pkt.get());
        if (r < 0) {
            attempt.error = r == AVERROR_EXIT
                                ? fmt::format("no data for {:g} s", options_.timeout_s)
                                : "rtsp read: " + av_error(r);
            return;
        }
        if (pkt->stream_index != index || pkt->size <= 0) {
            av_packet_unref(pkt.get());
            continue;
        }
        if (static_cast<std::size_t>(pkt->size) > gv::max_access_unit_bytes) {
            av_packet_unref(pkt.get());
            ++shared.dropped;
            continue;
        }
        const auto arrival = Clock::now();
        const std::span<const std::uint8_t> data(pkt->data, static_cast<std::size_t>(pkt->size));
        gv::AccessUnitBuffer au;
        au.codec = codec;
        std::optional<gv::Bytes> converted;
        if (extra.length_size > 0)
            converted = gv::length_prefixed_to_annexb(data, extra.length_size);
        const std::span<const std::uint8_t> annexb = converted ? std::span(*converted) : data;
        for (const auto nal : gv::split_annexb(annexb)) extra.sets.update(codec, nal);
        au.data = gv::with_parameter_sets(codec, annexb, extra.sets);
        au.key_frame = gv::is_key_frame(codec, au.data);
        if (pkt->pts != AV_NOPTS_VALUE) {
            au.pts = static_cast<std::uint64_t>(av_rescale_q(pkt->pts, stream->time_base, ts90k)) &
                     (gv::pts_modulus - 1);
        } else {
            // libavformat leaves the session's first frame without one; its RTP clock counts
            // from that frame, so it is 0; a later gap gets the last step again.
            au.pts = last_pts ? (*last_pts + last_step) & (gv::pts_modulus - 1) : 0;
        }
        if (last_pts) last_step = (*au.pts - *last_pts) & (gv::pts_modulus - 1);
        last_pts = au.pts;
        if (pkt->dts != AV_NOPTS_VALUE && pkt->dts != pkt->pts) {
            au.dts = static_cast<std::uint64_t>(av_rescale_q(pkt->dts, stream->time_base, ts90k)) &
                     (gv::pts_modulus - 1);
        }
        const std::size_t bytes = data.size();
        av_packet_unref(pkt.get());
        if (!attempt.got_video) post_connected(true, {});
        attempt.got_video = true;
        const std::size_t held = au.data.size();
        if (shared.queued.load() >= options_.max_queued_units ||
            shared.queued_bytes.load() + held > options_.max_queued_bytes) {
            ++shared.dropped;  // the io thread is behind
            continue;
        }
        ++shared.queued;
        shared.queued_bytes += held;
        asio::post(io_, [this, alive = shared.alive, keep = shared_, au = std::move(au), arrival,
                         bytes, held] {
            --keep->queued;
            keep->queued_bytes -= held;
            if (alive.expired()) return;
            info_.on_bytes(bytes, std::chrono::duration<double>(arrival - epoch_).count());
            info_.on_access_unit(au.view());
            if (handlers_.access_unit) handlers_.access_unit(au.view(), arrival);
        });
    }
}

VideoInputStatus RtspInput::status() const {
    VideoInputStatus s;
    s.input = url_.text;
    s.connected = connected_;
    s.stream = info_.info(std::chrono::duration<double>(Clock::now() - epoch_).count());
    s.last_error = last_error_;
    if (shared_) {
        s.reconnects = shared_->reconnects;
        s.dropped_units = shared_->dropped;
    }
    return s;
}

}  // namespace gimbald::video
