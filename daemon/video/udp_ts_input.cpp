#include "video/udp_ts_input.hpp"

#include <stdexcept>

#include <boost/asio/ip/multicast.hpp>

namespace gimbald::video {

namespace asio = boost::asio;
using asio::ip::udp;
namespace gv = gimbal::video;

namespace {

constexpr auto tick_period = std::chrono::milliseconds(100);
constexpr int receive_buffer_bytes = 4 * 1024 * 1024;  // a key frame burst at 20 Mbit/s

double seconds(Clock::duration d) {
    return std::chrono::duration<double>(d).count();
}

asio::ip::address parse_address(const std::string& text, const char* what) {
    boost::system::error_code ec;
    const auto a = asio::ip::make_address(text, ec);
    if (ec) throw std::invalid_argument(std::string(what) + " '" + text + "' is not an IP address");
    return a;
}

}  // namespace

UdpTsInput::UdpTsInput(asio::io_context& io, gv::VideoUrl url, VideoInputOptions options,
                       VideoInputHandlers handlers)
    : url_(std::move(url)),
      options_(std::move(options)),
      handlers_(std::move(handlers)),
      socket_(io),
      retry_timer_(io),
      tick_timer_(io),
      backoff_(options_.backoff),
      io_(io),
      source_(options_.source, std::chrono::duration_cast<Clock::duration>(
                                   std::chrono::duration<double>(options_.source_silence_s))),
      foreign_log_(gimbal::log::Level::warn, "video_foreign",
                   "datagrams from another sender than the video source") {
    if (url_.timeout_s) options_.timeout_s = *url_.timeout_s;
    const auto host = url_.host.empty() ? asio::ip::address(asio::ip::address_v4::any())
                                        : parse_address(url_.host, "input address");
    if (!url_.iface.empty()) iface_ = parse_address(url_.iface, "iface");
    if (host.is_multicast()) group_ = host;
    // Bound to the group itself, a multicast socket gets only that group's datagrams.
    bind_ = udp::endpoint(host, url_.port);
    options_.log_fields["input"] = url_.text;
}

UdpTsInput::~UdpTsInput() {
    stop();
}

void UdpTsInput::start() {
    if (running_) return;
    running_ = true;
    TsWorkerOptions w;
    w.name = "video-" + options_.log_fields.value("gimbal", std::string("input"));
    w.klv = options_.klv;
    w.max_datagrams = options_.max_queued_datagrams;
    w.max_datagram_bytes = options_.max_queued_datagram_bytes;
    w.max_batches = options_.max_queued_units;
    w.max_unit_bytes = options_.max_queued_bytes;
    worker_ =
        std::make_unique<TsWorker>(io_, std::move(w), [this](TsBatch& batch) { on_batch(batch); });
    open();
    tick();
}

void UdpTsInput::stop() {
    running_ = false;
    lifetime_.reset();
    retry_timer_.cancel();
    tick_timer_.cancel();
    close();
    if (worker_) {
        worker_->stop();  // joined: nothing it delivered runs after this
        worker_counters_ = worker_->counters();
        worker_.reset();
    }
    connected_ = false;  // silently: no handler runs from stop()
}

void UdpTsInput::close() {
    boost::system::error_code ignored;
    socket_.close(ignored);
}

void UdpTsInput::open() {
    close();
    boost::system::error_code ec;
    socket_.open(bind_.protocol(), ec);
    if (!ec) socket_.set_option(udp::socket::reuse_address(true), ec);
    if (!ec) {
        boost::system::error_code ignored;  // the kernel caps it; smaller is not an error
        socket_.set_option(asio::socket_base::receive_buffer_size(receive_buffer_bytes), ignored);
        socket_.bind(bind_, ec);
    }
    if (!ec && group_) {
        if (group_->is_v4()) {
            const auto iface =
                iface_ && iface_->is_v4() ? iface_->to_v4() : asio::ip::address_v4::any();
            socket_.set_option(asio::ip::multicast::join_group(group_->to_v4(), iface), ec);
        } else {
            socket_.set_option(asio::ip::multicast::join_group(group_->to_v6()), ec);
        }
    }
    if (ec) return retry_later(ec.message());
    opened_at_ = Clock::now();
    receive();
}

void UdpTsInput::retry_later(const std::string& error) {
    close();
    if (error != reported_error_) {
        gimbal::log::warn("video_input_error", "video input: " + error + " (retrying)",
                          options_.log_fields);
    }
    last_error_ = error;
    reported_error_ = error;
    retry_timer_.expires_after(std::chrono::duration_cast<Clock::duration>(
        std::chrono::duration<double>(backoff_.next())));
    retry_timer_.async_wait(lifetime_.wrap([this](const boost::system::error_code& ec) {
        if (!ec && running_) {
            ++rejoins_;
            open();
        }
    }));
}

void UdpTsInput::receive() {
    socket_.async_receive_from(
        asio::buffer(buffer_), sender_,
        lifetime_.wrap([this](const boost::system::error_code& ec, std::size_t n) {
            if (ec == asio::error::operation_aborted || !running_) return;
            if (ec) return retry_later(ec.message());
            on_datagram(n);
            receive();
        }));
}

void UdpTsInput::on_datagram(std::size_t n) {
    const auto arrival = Clock::now();
    const auto verdict = source_.check(sender_, arrival);
    if (verdict == SourcePin::Verdict::foreign) {
        nlohmann::json fields = options_.log_fields;
        fields["from"] = to_string(sender_);
        fields["source"] = source_.current() ? nlohmann::json(to_string(*source_.current()))
                                             : nlohmann::json(nullptr);
        fields["total"] = source_.foreign();
        foreign_log_.hit("video datagram from another sender than the source: ignored", fields);
        return;
    }
    if (verdict == SourcePin::Verdict::pinned) {
        nlohmann::json fields = options_.log_fields;
        fields["source"] = to_string(sender_);
        gimbal::log::info("video_source", "video input takes its stream from " + to_string(sender_),
                          fields);
    }
    last_data_ = arrival;
    info_.on_bytes(n, seconds(arrival - epoch_));
    const std::span<const std::uint8_t> bytes(buffer_.data(), n);
    if (!connected_) {
        backoff_.reset();
        reported_error_.clear();
        set_connected(true);
        if (!running_) return;  // a handler stopped us
    }
    if (handlers_.ts_bytes) handlers_.ts_bytes(bytes, arrival);
    if (running_ && worker_) worker_->push(bytes, arrival);
}

void UdpTsInput::on_batch(TsBatch& batch) {
    for (const auto& au : batch.units) {
        if (!running_) return;  // a handler stopped us mid-batch
        info_.on_access_unit(au.view());
        if (handlers_.access_unit) handlers_.access_unit(au.view(), batch.arrival);
    }
    if (running_ && handlers_.klv) handlers_.klv(batch.klv, batch.arrival);
}

void UdpTsInput::tick() {
    tick_timer_.expires_after(tick_period);
    tick_timer_.async_wait(lifetime_.wrap([this](const boost::system::error_code& ec) {
        if (ec || !running_) return;
        foreign_log_.poll();
        const auto now = Clock::now();
        const auto timeout = std::chrono::duration<double>(options_.timeout_s);
        if (connected_ && now - last_data_ > timeout) set_connected(false);
        // Silent multicast: leave and join again, with backoff between rejoins.
        if (!connected_ && group_ && socket_.is_open() && now - opened_at_ > timeout &&
            now - last_data_ > timeout) {
            retry_later("no datagrams from group " + group_->to_string() + ", rejoining");
        }
        tick();
    }));
}

void UdpTsInput::set_connected(bool connected) {
    connected_ = connected;
    nlohmann::json fields = options_.log_fields;
    if (connected) {
        gimbal::log::info("video_up", "video input receiving", fields);
    } else {
        fields["timeout_s"] = options_.timeout_s;
        gimbal::log::warn("video_down", "video input silent", fields);
    }
    if (handlers_.connection) handlers_.connection(connected);
}

VideoInputStatus UdpTsInput::status() const {
    VideoInputStatus s;
    s.input = url_.text;
    s.connected = connected_;
    s.stream = info_.info(seconds(Clock::now() - epoch_));
    const TsWorkerCounters w = worker_ ? worker_->counters() : worker_counters_;
    s.klv = w.klv;
    s.demux = w.demux;
    s.klv_units = w.demux.klv_units;
    s.dropped_units = w.dropped_units + w.dropped_klv_sets + w.demux.oversized_units;
    s.dropped_datagrams = w.dropped_datagrams;
    s.foreign_datagrams = source_.foreign();
    if (const auto current = source_.current()) s.source = to_string(*current);
    s.reconnects = rejoins_;
    s.last_error = last_error_;
    return s;
}

std::uint16_t UdpTsInput::local_port() const {
    boost::system::error_code ec;
    const auto ep = socket_.local_endpoint(ec);
    return ec ? 0 : ep.port();
}

}  // namespace gimbald::video
