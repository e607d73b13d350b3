// Where the aircraft's MAVLink comes from (config `vehicle.source`): a UDP port the daemon
// listens on like a GCS, or a serial device. Bytes go through a mavlink::Framer (UDP: each
// datagram parsed on its own; serial: a stream); every decoded message is handed on. No state here:
// VehicleFeed owns it. With the MAVLink gimbal manager the endpoint is two-way: send() writes to
// every UDP peer heard (and the configured targets), or to the serial port.
#pragma once

#include <array>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/udp.hpp>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "config.hpp"
#include "link/link.hpp"
#include "mavlink/framer.hpp"

namespace gimbald {

class VehicleSource {
  public:
    using MessageHandler = std::function<void(const gimbal::mavlink::Message&)>;

    // Binds the UDP socket (throws boost::system::system_error when it cannot) or prepares
    // the serial link (opened, and reopened, by start()).
    VehicleSource(boost::asio::io_context& io, const gimbal::daemon::VehicleConfig& config,
                  MessageHandler on_message, gimbal::mavlink::FramerOptions framer_options = {});
    ~VehicleSource();

    void start();
    void stop();

    // "udp 127.0.0.1:14550", "serial /dev/ttyACM0@57600"
    std::string describe() const;
    const gimbal::mavlink::FramerStats& stats() const { return framer_.stats(); }

    // Two-way use (gimbal manager). A frame to every UDP peer heard and every target, or to
    // the serial port; false when it could not be queued anywhere.
    bool send(std::span<const std::uint8_t> frame);
    void set_targets(std::vector<boost::asio::ip::udp::endpoint> targets);
    // The flight recorder: every chunk received (a UDP datagram, a serial read) and every
    // frame sent. `outbound` is false for received bytes.
    using Tap = std::function<void(bool outbound, std::span<const std::uint8_t> bytes)>;
    void set_tap(Tap tap) { tap_ = std::move(tap); }
    // Inside a MessageHandler call: where the message came from ("udp 127.0.0.1:14551",
    // "serial /dev/ttyACM0").
    std::string current_peer() const;
    // Inside a MessageHandler call: the message passed its listener's checks (a frame that
    // parsed, signed when signing is on), so its UDP sender takes a peer slot, or refreshes
    // its own. Only admitted peers are sent to: junk cannot evict a ground station (contract
    // section 14, v4). No-op on serial.
    void admit_peer();
    // Every admitted UDP peer (at most max_peers; a new one replaces the one silent longest).
    std::vector<std::string> peers() const;
    static constexpr std::size_t max_peers = 16;

  private:
    void do_receive();
    void on_bytes(std::span<const std::uint8_t> bytes);     // serial: one byte stream
    void on_datagram(std::span<const std::uint8_t> bytes);  // UDP: whole frames per datagram
    bool send_frame(std::span<const std::uint8_t> frame);

    MessageHandler on_message_;
    gimbal::mavlink::Framer framer_;
    std::unique_ptr<boost::asio::ip::udp::socket> socket_;  // udp source
    boost::asio::ip::udp::endpoint sender_;
    std::array<std::uint8_t, 65536> buffer_{};
    std::vector<boost::asio::ip::udp::endpoint> peers_;  // least recently admitted first
    std::vector<boost::asio::ip::udp::endpoint> targets_;
    std::unique_ptr<Link> serial_;  // serial source
    std::string description_;
    Tap tap_;
    bool stopped_ = true;
};

}  // namespace gimbald
