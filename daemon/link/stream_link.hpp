// What TCP and serial links share: the read loop, the bounded packet queue and its writer, the
// silence watchdog, reconnecting with backoff, and one place (fail()) that handles every error.
// Subclasses only open the stream: open() ends in established() or attempt_failed().
//
// Writes are done here with non-blocking write_some() plus async_wait(wait_write) rather than
// async_write(): we then always know exactly how many bytes of the front packet went out, so
// a cease-fire (send_safety(), send_now()) can follow a half-written packet instead of
// interleaving with it. An idle link writes a new packet at once, from inside the send. The
// queue and its two lanes: link/send_queue.hpp.
#pragma once

#include <poll.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
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
#include "link/send_queue.hpp"

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
        tear_down();  // no handler is called after stop(): the discarded ones included
        on_data_ = nullptr;
        on_state_ = nullptr;
        on_error_ = nullptr;
    }

    bool connected() const override { return connected_; }

    bool send(std::vector<std::uint8_t> packet) override {
        return enqueue(std::move(packet), SendQueue::Kind::normal);
    }

    bool send_kept(std::vector<std::uint8_t> packet) override {
        return enqueue(std::move(packet), SendQueue::Kind::kept);
    }

    bool send_safety(std::vector<std::uint8_t> packet, WrittenHandler on_written) override {
        if (!connected_) return false;
        const std::size_t displaced = queue_.push_safety(std::move(packet), std::move(on_written));
        stats_.tx_displaced += displaced;
        stats_.tx_dropped += displaced;
        start_writing();
        return true;
    }

    bool send_now(std::span<const std::uint8_t> packet) override {
        if (!connected_ || !stream_) {
            report_error("send_now",
                         "not connected: " + std::to_string(packet.size()) + " bytes not sent");
            return false;
        }
        if (!packet.empty()) queue_.push_safety({packet.begin(), packet.end()}, nullptr);
        // Ours is the last safety-lane packet: it is written once every one before it was.
        std::size_t safety_left = packet.empty() ? 0 : queue_.safety_packets();
        const auto deadline =
            std::chrono::steady_clock::now() + seconds_to_duration(options_.send_now_timeout_s);
        while (!queue_.empty()) {
            boost::system::error_code ec;
            const std::size_t n = write_next(ec);
            if (would_block(ec)) {
                const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                    deadline - std::chrono::steady_clock::now());
                if (left.count() <= 0) {
                    report_error("send_now", "timed out with " + std::to_string(queue_.bytes()) +
                                                 " bytes unsent");
                    return safety_left == 0;
                }
                pollfd writable{stream_->native_handle(), POLLOUT, 0};
                ::poll(&writable, 1, static_cast<int>(left.count()) + 1);
                continue;
            }
            if (ec) {
                report_error("send_now", ec.message());
                return safety_left == 0;
            }
            auto done = account_written(n);
            if (done.safety && safety_left > 0) --safety_left;
            // Other owners hear from the io_context, as always (not at all if stopped first).
            if (done.handler)
                boost::asio::post(io_, guarded([h = std::move(done.handler)] { h(true); }));
        }
        return safety_left == 0;
    }

    const LinkStats& stats() const override { return stats_; }

  protected:
    StreamLink(boost::asio::io_context& io, StreamLinkOptions options, Backoff backoff)
        : io_(io),
          options_(options),
          backoff_(std::move(backoff)),
          retry_timer_(io),
          silence_timer_(io),
          queue_(options_.queue) {}

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
        std::vector<WrittenHandler> discarded = tear_down();
        const double delay_s = backoff_.next();
        retry_timer_.expires_after(seconds_to_duration(delay_s));
        retry_timer_.async_wait(guarded([this](const boost::system::error_code& ec) {
            if (!ec) open();
        }));
        const std::uint64_t generation = lifetime_.generation();
        report_error(what, std::string(detail) + "; retrying in " + describe_seconds(delay_s));
        if (generation != lifetime_.generation()) return;
        if (was_connected && on_state_) on_state_(false);
        // Safety packets that never went out: their owners send them again on reconnect.
        for (auto& handler : discarded) {
            if (generation != lifetime_.generation()) return;
            handler(false);
        }
    }

    // Closes everything; returns the handlers of the safety packets discarded with the queue.
    std::vector<WrittenHandler> tear_down() {
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
        const std::uint64_t before = queue_.dropped();
        std::vector<WrittenHandler> discarded = queue_.clear();
        stats_.tx_dropped += queue_.dropped() - before;
        writing_ = false;
        return discarded;
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

    bool enqueue(std::vector<std::uint8_t> packet, SendQueue::Kind kind) {
        if (!connected_ || !queue_.push(std::move(packet), kind)) {
            ++stats_.tx_dropped;
            return false;
        }
        start_writing();
        return true;
    }

    // An idle link writes at once: the command (or cease-fire) leaves before the rest of its
    // request is handled (reply, audit, logs), which is the command's latency. What the stream
    // does not take now, and any error, is handled from the io_context (flush()), so no
    // handler of ours ever runs from inside a send.
    void start_writing() {
        if (writing_ || queue_.empty()) return;
        writing_ = true;
        boost::system::error_code ec;
        const std::size_t n = stream_ ? write_next(ec) : 0;
        if (stream_ && !ec) {
            if (auto done = account_written(n); done.handler)
                boost::asio::post(io_, guarded([h = std::move(done.handler)] { h(true); }));
            if (queue_.empty()) {
                writing_ = false;
                return;
            }
        }
        boost::asio::post(io_, guarded([this] { flush(); }));  // the rest, or the error
    }

    std::size_t write_next(boost::system::error_code& ec) {
        const auto bytes = queue_.next();
        return stream_->write_some(boost::asio::buffer(bytes.data(), bytes.size()), ec);
    }

    struct Finished {
        bool safety = false;     // a safety packet was finished
        WrittenHandler handler;  // its owner's handler
    };
    // Counts `n` written bytes and says whether they finished a safety packet.
    Finished account_written(std::size_t n) {
        stats_.tx_bytes += n;
        auto done = queue_.written(n);
        if (done.packet_done) ++stats_.tx_packets;
        return {done.safety, std::move(done.safety_done)};
    }

    // Writes queued packets until the queue is empty or the stream would block.
    void flush() {
        while (stream_ && !queue_.empty()) {
            boost::system::error_code ec;
            const std::size_t n = write_next(ec);
            if (would_block(ec)) {
                stream_->async_wait(Stream::wait_write,
                                    guarded([this](const boost::system::error_code& wait_ec) {
                                        if (wait_ec) return fail("write", wait_ec.message());
                                        flush();
                                    }));
                return;
            }
            if (ec) return fail("write", ec.message());
            if (auto done = account_written(n); done.handler) {
                // The owner's code may stop or restart the link: go on only if it did not.
                const std::uint64_t generation = lifetime_.generation();
                done.handler(true);
                if (generation != lifetime_.generation()) return;
            }
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

    SendQueue queue_;
    bool writing_ = false;  // a flush is posted or waiting for the stream to drain
};

}  // namespace gimbald
