// A gimbal's video outputs (contract section 17): `udp://HOST:PORT[?ttl=N][&iface=ADDR]`
// carries MPEG-TS (the input's access units unchanged plus one KLVA data stream, lib/video's
// TsMuxer, 7 packets per datagram); `klv-udp://HOST:PORT` carries one KLV local set per
// datagram. Writes never block the input (see UdpSender).
#pragma once

#include <memory>
#include <optional>
#include <span>

#include "video/codec.hpp"
#include "video/ts_muxer.hpp"
#include "video/udp_sender.hpp"
#include "video/url.hpp"

namespace gimbald::video {

struct VideoOutputOptions {
    double retry_s = 1.0;  // pause after a failed send
    gimbal::video::MuxerOptions mux;
    nlohmann::json log_fields = nlohmann::json::object();
};

class VideoOutput {
  public:
    virtual ~VideoOutput() = default;
    // Ignored by klv-udp outputs.
    virtual void write_video(const gimbal::video::AccessUnit& au) = 0;
    // One or more whole KLV packets; pts (90 kHz) when known. klv-udp splits them.
    virtual void write_klv(std::span<const std::uint8_t> klv, std::optional<std::uint64_t> pts) = 0;
    virtual const UdpSenderStats& stats() const = 0;
    virtual const std::string& url() const = 0;
    // MPEG-TS (KLV needs a PTS there) rather than bare KLV datagrams.
    virtual bool transport_stream() const = 0;
};

class TsUdpOutput final : public VideoOutput {
  public:
    TsUdpOutput(boost::asio::io_context& io, const gimbal::video::VideoUrl& url,
                VideoOutputOptions options);
    void write_video(const gimbal::video::AccessUnit& au) override;
    void write_klv(std::span<const std::uint8_t> klv, std::optional<std::uint64_t> pts) override;
    const UdpSenderStats& stats() const override { return sender_.stats(); }
    const std::string& url() const override { return url_; }
    bool transport_stream() const override { return true; }
    const gimbal::video::MuxStats& mux_stats() const { return mux_.stats(); }

  private:
    std::string url_;
    UdpSender sender_;
    gimbal::video::TsMuxer mux_;
};

class KlvUdpOutput final : public VideoOutput {
  public:
    KlvUdpOutput(boost::asio::io_context& io, const gimbal::video::VideoUrl& url,
                 VideoOutputOptions options);
    void write_video(const gimbal::video::AccessUnit&) override {}
    void write_klv(std::span<const std::uint8_t> klv, std::optional<std::uint64_t> pts) override;
    const UdpSenderStats& stats() const override { return sender_.stats(); }
    const std::string& url() const override { return url_; }
    bool transport_stream() const override { return false; }

  private:
    std::string url_;
    UdpSender sender_;
};

// udp:// -> TsUdpOutput, klv-udp:// -> KlvUdpOutput; std::invalid_argument for rtsp:// or
// an address that does not parse.
std::unique_ptr<VideoOutput> make_video_output(boost::asio::io_context& io,
                                               const gimbal::video::VideoUrl& url,
                                               VideoOutputOptions options = {});

}  // namespace gimbald::video
