// gimbal-track for one gimbal (contract section 20, docs/tracking.md): started with one end
// of a SOCK_SEQPACKET socketpair as `--fd N`, its `hello` awaited, and started again with
// exponential backoff (0.5 s doubling to 30 s) whenever it exits, is killed or never says
// hello. Each start and exit is logged. Decoding hostile video and tracking run there, so a
// fault in them never reaches the io thread that holds the laser dead-man: nothing here ever
// blocks - the socket is non-blocking, a datagram that does not fit now is dropped (and
// counted), and the process's exit arrives as a readable pidfd on the io_context.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <boost/asio/generic/seq_packet_protocol.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/posix/stream_descriptor.hpp>
#include <boost/asio/steady_timer.hpp>

#include "link/lifetime.hpp"
#include "track/wire/messages.hpp"

namespace gimbald::track {

struct TrackProcessOptions {
    std::string gimbal;             // for the logs
    std::string program;            // gimbal-track's path (track_program.hpp)
    std::vector<std::string> args;  // more arguments (e.g. "--log-level", "debug")
    double backoff_min_s = 0.5;     // the first restart's delay
    double backoff_max_s = 30;      // doubling up to this
    double hello_timeout_s = 10;    // no hello this long after a start: killed, restarted
    double stable_after_s = 30;     // a process that lived this long restarts at the minimum
    std::size_t send_buffer_bytes = 1u << 20;  // asked for; the kernel caps it (wmem_max)
};

class TrackProcess {
  public:
    // Every valid message after hello (box, ended, error).
    using MessageSink = std::function<void(const gimbal::track::wire::Message&)>;
    // The process became ready (hello received: true) or went away (false).
    using ReadySink = std::function<void(bool ready)>;

    TrackProcess(boost::asio::io_context& io, TrackProcessOptions options, MessageSink on_message,
                 ReadySink on_ready);
    ~TrackProcess();
    TrackProcess(const TrackProcess&) = delete;
    TrackProcess& operator=(const TrackProcess&) = delete;

    void start();
    // Closes the socket (gimbal-track ends at EOF) and sends SIGTERM; no restart follows.
    void stop();

    bool ready() const { return ready_; }
    std::optional<pid_t> pid() const { return pid_; }
    // One datagram, now or never: false when not ready or the socket is full (dropped).
    bool send(std::span<const std::uint8_t> datagram);
    // Kills the process (SIGKILL): a hung gimbal-track. Its exit restarts it as usual.
    void kill_process(std::string_view why);

    struct Counters {
        std::uint64_t starts = 0;
        std::uint64_t exits = 0;
        std::uint64_t sent = 0;
        std::uint64_t dropped = 0;  // datagrams that did not fit
        std::uint64_t refused = 0;  // datagrams from gimbal-track that did not decode
    };
    const Counters& counters() const { return counters_; }

  private:
    void spawn();
    void do_read();
    void on_datagram(std::size_t n);
    void watch_exit();
    void on_exit();
    void close_socket();
    void schedule_restart();
    double backoff_next();

    TrackProcessOptions options_;
    MessageSink on_message_;
    ReadySink on_ready_;
    boost::asio::generic::seq_packet_protocol::socket socket_;
    boost::asio::posix::stream_descriptor exit_watch_;  // the child's pidfd
    boost::asio::steady_timer restart_timer_;
    boost::asio::steady_timer hello_timer_;
    boost::asio::socket_base::message_flags in_flags_ = 0;
    std::vector<std::uint8_t> in_;
    std::optional<pid_t> pid_;
    std::chrono::steady_clock::time_point started_at_{};
    double backoff_s_;
    bool ready_ = false;
    bool stopped_ = true;
    Counters counters_;
    Lifetime lifetime_;
};

}  // namespace gimbald::track
