#include "vehicle_source.hpp"

#include <algorithm>

#include "link/serial_link.hpp"
#include "logging.hpp"

namespace gimbald {

namespace cfg = gimbal::daemon;
namespace log = gimbal::log;

VehicleSource::VehicleSource(boost::asio::io_context& io, const cfg::VehicleConfig& config,
                             MessageHandler on_message,
                             gimbal::mavlink::FramerOptions framer_options)
    : on_message_(std::move(on_message)), framer_(std::move(framer_options)) {
    if (const auto* udp = std::get_if<cfg::UdpSource>(&config.source)) {
        const boost::asio::ip::udp::endpoint local(udp->bind, udp->port);
        socket_ = std::make_unique<boost::asio::ip::udp::socket>(io);
        socket_->open(local.protocol());
        socket_->bind(local);
        const auto bound = socket_->local_endpoint();
        const auto a = bound.address();
        description_ = "udp " + (a.is_v6() ? "[" + a.to_string() + "]" : a.to_string()) + ":" +
                       std::to_string(bound.port());
        return;
    }
    const auto& serial = std::get<cfg::SerialSource>(config.source);
    SerialLinkOptions o;
    o.device = serial.device;
    o.baud = serial.baud;
    serial_ = std::make_unique<SerialLink>(io, o);
    description_ = "serial " + serial.device + "@" + std::to_string(serial.baud);
}

VehicleSource::~VehicleSource() {
    stop();
}

std::string VehicleSource::describe() const {
    return description_;
}

void VehicleSource::start() {
    stopped_ = false;
    if (socket_) {
        do_receive();
        return;
    }
    serial_->start(
        [this](std::span<const std::uint8_t> bytes) { on_bytes(bytes); },
        [this](bool up) {
            framer_.reset();  // a partial frame from before belongs to nothing
            log::write(up ? log::Level::info : log::Level::warn,
                       up ? "vehicle_link_up" : "vehicle_link_down",
                       up ? "vehicle serial port open" : "vehicle serial port lost",
                       {{"source", description_}});
        },
        [this](std::string_view what, std::string_view detail) {
            log::warn("vehicle_link_error", detail, {{"source", description_}, {"what", what}});
        });
}

void VehicleSource::stop() {
    if (stopped_) return;
    stopped_ = true;
    if (socket_) {
        boost::system::error_code ignored;
        socket_->close(ignored);
    }
    if (serial_) serial_->stop();
}

void VehicleSource::do_receive() {
    socket_->async_receive_from(
        boost::asio::buffer(buffer_), sender_,
        [this](const boost::system::error_code& ec, std::size_t n) {
            if (stopped_ || ec == boost::asio::error::operation_aborted) return;
            if (!ec) on_datagram(std::span<const std::uint8_t>(buffer_.data(), n));
            do_receive();
        });
}

namespace {

std::string endpoint_text(const boost::asio::ip::udp::endpoint& e) {
    const auto a = e.address();
    return (a.is_v6() ? "[" + a.to_string() + "]" : a.to_string()) + ":" + std::to_string(e.port());
}

}  // namespace

void VehicleSource::admit_peer() {
    if (!socket_) return;
    if (!peers_.empty() && peers_.back() == sender_) return;  // the usual case: no change
    if (const auto it = std::find(peers_.begin(), peers_.end(), sender_); it != peers_.end())
        peers_.erase(it);
    else if (peers_.size() == max_peers)
        peers_.erase(peers_.begin());
    peers_.push_back(sender_);
}

bool VehicleSource::send(std::span<const std::uint8_t> frame) {
    const bool sent = send_frame(frame);
    if (sent && tap_) tap_(true, frame);
    return sent;
}

bool VehicleSource::send_frame(std::span<const std::uint8_t> frame) {
    if (serial_) return serial_->send(std::vector<std::uint8_t>(frame.begin(), frame.end()));
    if (!socket_) return false;
    bool any = false;
    const auto send_to = [&](const boost::asio::ip::udp::endpoint& to) {
        boost::system::error_code ec;  // a full buffer or an unreachable peer drops one frame
        socket_->send_to(boost::asio::buffer(frame.data(), frame.size()), to, 0, ec);
        any = any || !ec;
    };
    for (const auto& p : peers_) send_to(p);
    for (const auto& t : targets_)
        if (std::find(peers_.begin(), peers_.end(), t) == peers_.end()) send_to(t);
    return any;
}

void VehicleSource::set_targets(std::vector<boost::asio::ip::udp::endpoint> targets) {
    targets_ = std::move(targets);
}

std::string VehicleSource::current_peer() const {
    if (serial_) return description_;
    return "udp " + endpoint_text(sender_);
}

std::vector<std::string> VehicleSource::peers() const {
    std::vector<std::string> out;
    if (serial_) {
        out.push_back(description_);
        return out;
    }
    for (const auto& p : peers_) out.push_back("udp " + endpoint_text(p));
    return out;
}

void VehicleSource::on_bytes(std::span<const std::uint8_t> bytes) {
    if (tap_) tap_(false, bytes);
    framer_.push(bytes, [this](const gimbal::mavlink::Message& m) { on_message_(m); });
}

void VehicleSource::on_datagram(std::span<const std::uint8_t> bytes) {
    if (tap_) tap_(false, bytes);
    // Each datagram on its own: garbage in one cannot hold the next one's frames.
    framer_.push_datagram(bytes, [this](const gimbal::mavlink::Message& m) { on_message_(m); });
}

}  // namespace gimbald
