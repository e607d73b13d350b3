#include "video/video_output.hpp"

#include <stdexcept>

#include "video/klv_packets.hpp"
#include "video/rtsp_input.hpp"
#include "video/udp_ts_input.hpp"

namespace gimbald::video {

namespace gv = gimbal::video;

namespace {

nlohmann::json with_output(nlohmann::json fields, const std::string& url) {
    fields["output"] = url;
    return fields;
}

}  // namespace

TsUdpOutput::TsUdpOutput(boost::asio::io_context& io, const gv::VideoUrl& url,
                         VideoOutputOptions options)
    : url_(url.text),
      sender_(io, url.host, url.port, url.ttl, url.iface, options.retry_s,
              with_output(options.log_fields, url.text)),
      mux_(options.mux, gv::Codec::h264,
           [this](std::span<const std::uint8_t> chunk) { sender_.send(chunk); }) {}

void TsUdpOutput::write_video(const gv::AccessUnit& au) {
    mux_.write_video(au);
}

void TsUdpOutput::write_klv(std::span<const std::uint8_t> klv, std::optional<std::uint64_t> pts) {
    mux_.write_klv(klv, pts);
}

KlvUdpOutput::KlvUdpOutput(boost::asio::io_context& io, const gv::VideoUrl& url,
                           VideoOutputOptions options)
    : url_(url.text),
      sender_(io, url.host, url.port, url.ttl, url.iface, options.retry_s,
              with_output(options.log_fields, url.text)) {}

void KlvUdpOutput::write_klv(std::span<const std::uint8_t> klv, std::optional<std::uint64_t>) {
    for (const auto set : gv::split_klv_packets(klv)) sender_.send(set);
}

std::unique_ptr<VideoOutput> make_video_output(boost::asio::io_context& io, const gv::VideoUrl& url,
                                               VideoOutputOptions options) {
    switch (url.scheme) {
        case gv::UrlScheme::udp:
            return std::make_unique<TsUdpOutput>(io, url, std::move(options));
        case gv::UrlScheme::klv_udp:
            return std::make_unique<KlvUdpOutput>(io, url, std::move(options));
        case gv::UrlScheme::rtsp:
            break;
    }
    throw std::invalid_argument("an output is udp:// or klv-udp://, not " + url.text);
}

std::unique_ptr<VideoInput> make_video_input(boost::asio::io_context& io, const gv::VideoUrl& url,
                                             VideoInputOptions options,
                                             VideoInputHandlers handlers) {
    switch (url.scheme) {
        case gv::UrlScheme::udp:
            return std::make_unique<UdpTsInput>(io, url, std::move(options), std::move(handlers));
        case gv::UrlScheme::rtsp:
            return std::make_unique<RtspInput>(io, url, std::move(options), std::move(handlers));
        case gv::UrlScheme::klv_udp:
            break;
    }
    throw std::invalid_argument("an input is udp:// or rtsp://, not " + url.text);
}

}  // namespace gimbald::video
