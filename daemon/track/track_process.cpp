#include "track/track_process.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <variant>

#include "logging.hpp"
#include "track/wire/codec.hpp"

extern char** environ;

namespace gimbald::track {

namespace log = gimbal::log;
namespace wire = gimbal::track::wire;
using Clock = std::chrono::steady_clock;

namespace {

std::chrono::steady_clock::duration seconds(double s) {
    return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
}

// How a process ended, for the log.
nlohmann::json exit_fields(int status) {
    if (WIFEXITED(status)) return {{"exit_code", WEXITSTATUS(status)}};
    if (WIFSIGNALED(status)) return {{"signal", WTERMSIG(status)}};
    return {{"status", status}};
}

}  // namespace

TrackProcess::TrackProcess(boost::asio::io_context& io, TrackProcessOptions options,
                           MessageSink on_message, ReadySink on_ready)
    : options_(std::move(options)),
      on_message_(std::move(on_message)),
      on_ready_(std::move(on_ready)),
      socket_(io),
      exit_watch_(io),
      restart_timer_(io),
      hello_timer_(io),
      in_(64 * 1024),
      backoff_s_(options_.backoff_min_s) {}

TrackProcess::~TrackProcess() {
    stop();
}

void TrackProcess::start() {
    stopped_ = false;
    spawn();
}

void TrackProcess::stop() {
    if (stopped_) return;
    stopped_ = true;
    lifetime_.reset();
    restart_timer_.cancel();
    hello_timer_.cancel();
    close_socket();
    if (pid_) {
        ::kill(*pid_, SIGTERM);
        // Reaped now if it is already gone; otherwise init reaps it after gimbald's exit.
        int status = 0;
        ::waitpid(*pid_, &status, WNOHANG);
        pid_.reset();
    }
    boost::system::error_code ignored;
    exit_watch_.close(ignored);
    ready_ = false;
}

void TrackProcess::spawn() {
    int fds[2];
    if (::socketpair(AF_UNIX, SOCK_SEQPACKET | SOCK_CLOEXEC, 0, fds) != 0) {
        log::error("track_process_error", "socketpair failed",
                   {{"gimbal", options_.gimbal}, {"error", std::strerror(errno)}});
        schedule_restart();
        return;
    }
    const int ours = fds[0];
    const int theirs = fds[1];
    // The child keeps its end across exec; every other descriptor of ours stays close-on-exec.
    ::fcntl(theirs, F_SETFD, 0);
    const int size = static_cast<int>(options_.send_buffer_bytes);
    ::setsockopt(ours, SOL_SOCKET, SO_SNDBUF, &size, sizeof size);

    std::vector<std::string> args{options_.program, "--fd", std::to_string(theirs)};
    args.insert(args.end(), options_.args.begin(), options_.args.end());
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);

    posix_spawnattr_t attr;
    posix_spawnattr_init(&attr);
    sigset_t none, defaults;
    sigemptyset(&none);
    sigemptyset(&defaults);
    sigaddset(&defaults, SIGPIPE);
    sigaddset(&defaults, SIGINT);
    sigaddset(&defaults, SIGTERM);
    posix_spawnattr_setsigmask(&attr, &none);
    posix_spawnattr_setsigdefault(&attr, &defaults);
    // Its own process group: a Ctrl-C at gimbald's terminal reaches gimbald, which ends it.
    posix_spawnattr_setpgroup(&attr, 0);
    posix_spawnattr_setflags(
        &attr, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF | POSIX_SPAWN_SETPGROUP);
    pid_t pid = 0;
    const int spawned =
        ::posix_spawn(&pid, options_.program.c_str(), nullptr, &attr, argv.data(), environ);
    posix_spawnattr_destroy(&attr);
    ::close(theirs);
    if (spawned != 0) {
        ::close(ours);
        log::error("track_process_error", "gimbal-track could not be started",
                   {{"gimbal", options_.gimbal},
                    {"program", options_.program},
                    {"error", std::strerror(spawned)}});
        schedule_restart();
        return;
    }
    pid_ = pid;
    started_at_ = Clock::now();
    ++counters_.starts;
    boost::system::error_code ec;
    socket_.assign(boost::asio::generic::seq_packet_protocol(AF_UNIX, 0), ours, ec);
    if (!ec) socket_.non_blocking(true, ec);
    log::info("track_process_start", "gimbal-track started",
              {{"gimbal", options_.gimbal}, {"pid", pid}, {"program", options_.program}});
    watch_exit();
    if (ec) {
        kill_process("its socket could not be used");
        return;
    }
    hello_timer_.expires_after(seconds(options_.hello_timeout_s));
    hello_timer_.async_wait(lifetime_.wrap([this](const boost::system::error_code& e) {
        if (!e && !ready_) kill_process("no hello");
    }));
    do_read();
}

// Its exit as a readable pidfd on the io_context: no SIGCHLD handler shared with anything.
void TrackProcess::watch_exit() {
    // The system call itself: glibc 2.36's <sys/pidfd.h> lacks C linkage for C++.
    const int fd = static_cast<int>(::syscall(SYS_pidfd_open, *pid_, 0));
    if (fd < 0) {
        log::warn("track_process_error", "pidfd_open failed: its exit is seen at EOF only",
                  {{"gimbal", options_.gimbal}, {"error", std::strerror(errno)}});
        return;
    }
    exit_watch_.assign(fd);
    exit_watch_.async_wait(boost::asio::posix::stream_descriptor::wait_read,
                           lifetime_.wrap([this](const boost::system::error_code& ec) {
                               if (!ec) on_exit();
                           }));
}

void TrackProcess::on_exit() {
    if (!pid_) return;
    int status = 0;
    const pid_t reaped = ::waitpid(*pid_, &status, WNOHANG);
    if (reaped == 0) {  // readable but not yet reapable: look again shortly
        restart_timer_.expires_after(std::chrono::milliseconds(10));
        restart_timer_.async_wait(lifetime_.wrap([this](const boost::system::error_code& ec) {
            if (!ec) on_exit();
        }));
        return;
    }
    ++counters_.exits;
    const double lived_s = std::chrono::duration<double>(Clock::now() - started_at_).count();
    nlohmann::json fields = exit_fields(status);
    fields["gimbal"] = options_.gimbal;
    fields["pid"] = *pid_;
    fields["lived_s"] = std::round(lived_s * 1000) / 1000;
    pid_.reset();
    boost::system::error_code ignored;
    exit_watch_.close(ignored);
    hello_timer_.cancel();
    close_socket();
    if (lived_s >= options_.stable_after_s) backoff_s_ = options_.backoff_min_s;
    fields["restart_in_s"] = backoff_s_;
    log::warn("track_process_exit", "gimbal-track exited", fields);
    const bool was_ready = ready_;
    ready_ = false;
    schedule_restart();
    if (was_ready && on_ready_) on_ready_(false);
}

void TrackProcess::schedule_restart() {
    if (stopped_) return;
    const double delay = backoff_next();
    restart_timer_.expires_after(seconds(delay));
    restart_timer_.async_wait(lifetime_.wrap([this](const boost::system::error_code& ec) {
        if (!ec && !stopped_) spawn();
    }));
}

double TrackProcess::backoff_next() {
    const double delay = backoff_s_;
    backoff_s_ = std::min(backoff_s_ * 2, options_.backoff_max_s);
    return delay;
}

void TrackProcess::close_socket() {
    boost::system::error_code ignored;
    if (socket_.is_open()) socket_.close(ignored);
}

void TrackProcess::kill_process(std::string_view why) {
    if (!pid_) return;
    log::warn("track_process_kill", "gimbal-track killed",
              {{"gimbal", options_.gimbal}, {"pid", *pid_}, {"why", std::string(why)}});
    ::kill(*pid_, SIGKILL);
    close_socket();
}

void TrackProcess::do_read() {
    socket_.async_receive(
        boost::asio::buffer(in_), in_flags_,
        lifetime_.wrap([this](const boost::system::error_code& ec, std::size_t n) {
            if (ec || n == 0) {
                // EOF or a failed socket: the process is ending or unusable; its exit
                // (pidfd) restarts it.
                if (ec != boost::asio::error::operation_aborted) kill_process("its socket closed");
                return;
            }
            on_datagram(n);
            if (socket_.is_open()) do_read();
        }));
}

void TrackProcess::on_datagram(std::size_t n) {
    const auto decoded = wire::decode(std::span<const std::uint8_t>(in_.data(), n));
    if (!decoded.message || (in_flags_ & MSG_TRUNC) != 0) {
        ++counters_.refused;
        log::warn("track_message_refused", "a message from gimbal-track was refused",
                  {{"gimbal", options_.gimbal},
                   {"error", decoded.message ? "truncated" : decoded.error}});
        return;
    }
    if (const auto* hello = std::get_if<wire::Hello>(&*decoded.message)) {
        if (hello->version != wire::protocol_version) {
            log::error("track_process_error", "gimbal-track speaks another protocol version",
                       {{"gimbal", options_.gimbal}, {"version", hello->version}});
            kill_process("protocol version");
            return;
        }
        hello_timer_.cancel();
        if (!ready_) {
            ready_ = true;
            log::info("track_process_ready", "gimbal-track is ready",
                      {{"gimbal", options_.gimbal},
                       {"pid", pid_.value_or(0)},
                       {"trackers", hello->trackers}});
            if (on_ready_) on_ready_(true);
        }
        return;
    }
    if (ready_ && on_message_) on_message_(*decoded.message);
}

bool TrackProcess::send(std::span<const std::uint8_t> datagram) {
    if (!ready_ || !socket_.is_open()) {
        ++counters_.dropped;
        return false;
    }
    boost::system::error_code ec;
    socket_.send(boost::asio::buffer(datagram.data(), datagram.size()), 0, ec);
    if (ec) {
        ++counters_.dropped;
        // Full (would_block) is gimbal-track falling behind: the datagram is dropped. Anything
        // else means the socket is broken: the process is ended and restarted.
        if (ec != boost::asio::error::would_block && ec != boost::asio::error::try_again &&
            ec != boost::asio::error::no_buffer_space)
            kill_process("send failed: " + ec.message());
        return false;
    }
    ++counters_.sent;
    return true;
}

}  // namespace gimbald::track
