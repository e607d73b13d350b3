// What TCP and serial links share: the read loop, the bounded packet queue and its writer, the
// silence watchdog, reconnecting with backoff, and one place (fail()) that handles every error.
// Subclasses only open the stream: open() ends in established() or attempt_failed().
//
// Writes are done here with non-blocking write_some() plus async_wait(wait_write) rather than
// async_write(): we then always know exactly how many bytes of the front packet went out, so
// send_now() can finish a half-written packet before the cease-fire instead of interleaving.
#pragma once

#include <poll.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <boost/asio/buffer.hpp>
#include <boost/asio/error.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/steady_timer.hpp>

#include "link/backoff.hpp"
#include "link/lifetime.hpp"
#include "link/link.hpp"
#include "link/seconds.hpp"

namespace gimbald {

struct StreamLinkOptions {
    double silence_timeout_s = 0.0;  // no byte received for this long = dead peer; 0 disables
    SendQueueLimits queue;
    double send_now_timeout_s = 0.25;
};

template <class Stream>
class StreamLink : public Link {
  public:
    void start(DataHandler on_data, StateHandler on_state, ErrorHandler on_error) override {
        stop();
        on_data_ = std::move(on_data);
        on_state_ = std::move(on_state);
        on_error_ = std::move(on_error);
        // Never call back from inside start(): the first attempt runs from the io_context.
        boost::asio::post(io_, guarded([this] { open(); }));
    }

    void stop() override {
        tear_down();
        on_data_ = nullptr;
        on_state_ = nullptr;
        on_error_ = nullptr;
    }

    bool connected() const override { return connected_; }

    bool send(std::vector<std::uint8_t> packet) override {
        if (!connected_ || queue_.size() >= options_.queue.max_packets ||
            queued_bytes_ + packet.size() > options_.queue.max_bytes) {
            ++stats_.tx_dropped;
            return false;
        }
        if (packet.empty()) return true;
        queued_bytes_ += packet.size();
        queue_.push_back(std::move(packet));
        if (!writing_) {
            writing_ = true;
            // Deferred so a write error never calls the state handler from inside send().
            boost::asio::post(io_, guarded([this] { flush(); }));
        }
        return true;
    }

    void send_now(std::span<const std::uint8_t> packet) override {
        if (!connected_ || !stream_) {
            report_error("send_now",
                         "not connected: " + std::to_string(packet.size()) + " bytes not sent");
            return;
        }
        if (!packet.empty()) {
            queue_.emplace_back(packet.begin(), packet.end());
            queued_bytes_ += packet.size();
        }
        const auto deadline =
            std::chrono::steady_clock::now() + seconds_to_duration(options_.send_now_timeout_s);
        while (!queue_.empty()) {
            boost::system::error_code ec;
            const std::size_t n = write_front(ec);
            if (would_block(ec)) {
                const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                    deadline - std::chrono::steady_clock::now());
                if (left.count() <= 0) {
                    report_error("send_now", "timed out with " + std::to_string(queued_bytes_) +
                                                 " bytes unsent");
                    return;
                }
                pollfd writable{stream_->native_handle(), POLLOUT, 0};
                ::poll(&writable, 1, static_cast<int>(left.count()) + 1);
                continue;
            }
            if (ec) {
                report_error("send_now", ec.message());
                return;
            }
            account_written(n);
        }
    }

    const LinkStats& stats() const override { return stats_; }

  protected:
    StreamLink(boost::asio::io_context& io, StreamLinkOptions options, Backoff backoff)
        : io_(io),
          options_(options),
          backoff_(std::move(backoff)),
          retry_timer_(io),
          silence_timer_(io) {}

    // Begins one connection attempt; it ends in established() or attempt_failed().
    virtual void open() = 0;
    // Releases what an attempt holds besides the stream (resolver, timers, discovery).
    virtual void close_attempt() {}

    boost::asio::io_context& io() { return io_; }
    std::optional<Stream>& stream() { return stream_; }

    // Wraps a completion handler so it does nothing once this attempt or connection is over.
    template <class F>
    auto guarded(F f) const {
        return lifetime_.wrap(std::move(f));
    }

    // stream() is open: start reading and tell the owner.
    void established() {
        connected_ = true;
        if (ever_connected_) ++stats_.reconnects;
        ever_connected_ = true;
        backoff_.reset();
        boost::system::error_code ignored;
        stream_->non_blocking(true, ignored);  // write_some() must never block the io_context
        last_activity_ = std::chrono::steady_clock::now();
        if (options_.silence_timeout_s > 0.0) arm_silence_timer();
        do_read();
        if (on_state_) on_state_(true);
    }

    void attempt_failed(std::string_view what, std::string_view detail) { fail(what, detail); }

    void report_error(std::string_view what, std::string_view detail) {
        if (on_error_) on_error_(what, detail);
    }

  private:
    // The one place that handles a failed attempt or a lost connection: close everything,
    // schedule the next attempt, then tell the owner (who may call stop() from the handlers).
    void fail(std::string_view what, std::string_view detail) {
        const bool was_connected = connected_;
        tear_down();
        const double delay_s = backoff_.next();
        retry_timer_.expires_after(seconds_to_duration(delay_s));
        retry_timer_.async_wait(guarded([this](const boost::system::error_code& ec) {
            if (!ec) open();
        }));
        const std::uint64_t generation = lifetime_.generation();
        report_error(what, std::string(detail) + "; retrying in " + describe_seconds(delay_s));
        if (generation != lifetime_.generation()) return;
        if (was_connected && on_state_) on_state_(false);
    }

    void tear_down() {
        lifetime_.reset();
        close_attempt();
        if (stream_) {
            boost::system::error_code ignored;
            stream_->close(ignored);
            stream_.reset();
        }
        retry_timer_.cancel();
        silence_timer_.cancel();
        connected_ = false;
        stats_.tx_dropped += queue_.size();
        queue_.clear();
        queued_bytes_ = 0;
        front_offset_ = 0;
        writing_ = false;
    }

    void do_read() {
        stream_->async_read_some(boost::asio::buffer(read_buffer_),
                                 guarded([this](const boost::system::error_code& ec,
                                                std::size_t n) { on_read(ec, n); }));
    }

    void on_read(const boost::system::error_code& ec, std::size_t n) {
        if (ec == boost::asio::error::eof) return fail("closed", "closed by the peer");
        if (ec) return fail("read", ec.message());
        stats_.rx_bytes += n;
        last_activity_ = std::chrono::steady_clock::now();
        stats_.last_rx = last_activity_;
        // The handler runs before the next read is issued: the buffer is still ours.
        const std::uint64_t generation = lifetime_.generation();
        if (on_data_) on_data_(std::span<const std::uint8_t>(read_buffer_.data(), n));
        if (generation == lifetime_.generation()) do_read();
    }

    void arm_silence_timer() {
        silence_timer_.expires_at(last_activity_ + seconds_to_duration(options_.silence_timeout_s));
        silence_timer_.async_wait(guarded([this](const boost::system::error_code& ec) {
            if (ec) return;
            const auto deadline = last_activity_ + seconds_to_duration(options_.silence_timeout_s);
            if (std::chrono::steady_clock::now() >= deadline) {
                fail("silence", "no data for " + describe_seconds(options_.silence_timeout_s));
            } else {
                arm_silence_timer();
            }
        }));
    }

    static bool would_block(const boost::system::error_code& ec) {
        return ec == boost::asio::error::would_block || ec == boost::asio::error::try_again;
    }

    std::size_t write_front(boost::system::error_code& ec) {
        const std::vector<std::uint8_t>& front = queue_.front();
        return stream_->write_some(
            boost::asio::buffer(front.data() + front_offset_, front.size() - front_offset_), ec);
    }

    void account_written(std::size_t n) {
        stats_.tx_bytes += n;
        front_offset_ += n;
        if (front_offset_ == queue_.front().size()) {
            queued_bytes_ -= queue_.front().size();
            queue_.pop_front();
            front_offset_ = 0;
            ++stats_.tx_packets;
        }
    }

    // Writes queued packets until the queue is empty or the stream would block.
    void flush() {
        while (stream_ && !queue_.empty()) {
            boost::system::error_code ec;
            const std::size_t n = write_front(ec);
            if (would_block(ec)) {
                stream_->async_wait(Stream::wait_write,
                                    guarded([this](const boost::system::error_code& wait_ec) {
                                        if (wait_ec) return fail("write", wait_ec.message());
                                        flush();
                                    }));
                return;
            }
            if (ec) return fail("write", ec.message());
            account_written(n);
        }
        writing_ = false;
    }

    boost::asio::io_context& io_;
    StreamLinkOptions options_;
    Backoff backoff_;
    Lifetime lifetime_;
    boost::asio::steady_timer retry_timer_;
    boost::asio::steady_timer silence_timer_;
    std::optional<Stream> stream_;

    DataHandler on_data_;
    StateHandler on_state_;
    ErrorHandler on_error_;

    bool connected_ = false;
    bool ever_connected_ = false;
    LinkStats stats_;
    std::chrono::steady_clock::time_point last_activity_{};
    std::array<std::uint8_t, 4096> read_buffer_{};

    std::deque<std::vector<std::uint8_t>> queue_;
    std::size_t queued_bytes_ = 0;
    std::size_t front_offset_ = 0;  // bytes of queue_.front() already written
    bool writing_ = false;          // a flush is posted or waiting for the stream to drain
};

}  // namespace gimbald
