// gimbald command latency: the time from a `geopoint` datagram leaving the client to its
// GeopointCmd packet arriving at the gimbal's socket, over loopback, at a fixed command rate.
//
// This program plays both ends around the real daemon: it listens on 127.0.0.1:0 as the
// gimbal (sending GeolocateTelemetry at 10 Hz so the link never looks silent), starts
// gimbald with a temporary configuration pointing at that port, then sends numbered geopoint
// commands (distinct latitudes) on the JSON socket and matches every GeopointCmd frame it
// receives to its command by the encoded latitude. A benchmark, not a test: it is never
// registered with ctest. Run by scripts/bench-daemon.sh or by hand:
//
//   bench_daemon_latency --gimbald build/release/daemon/gimbald [--count 10000] [--rate 1000]
//                        [--poll epoll|busy] [--log-level info] [--samples FILE] [--fifo PRIO]
//                        [--mavlink]
//
// --mavlink measures the MAVLink gimbal manager instead: COMMAND_LONG
// DO_GIMBAL_MANAGER_PITCHYAW datagrams (distinct yaw angles) to the vehicle endpoint ->
// OrionCmd (position) at the gimbal; the reply is the COMMAND_ACK.
//
// Besides the latencies it prints how long gimbald (and the benchmark) waited on the run
// queue during the run (/proc/PID/schedstat): on a loaded machine that wait, not the daemon's
// code, makes the tail. --fifo runs both under SCHED_FIFO to measure without it.
//
// The daemon's command.rate_limit is set to twice the command rate, so nothing is throttled.
// Every command must reach the gimbal and get an ok reply: anything lost, refused, unmatched
// or duplicated makes the run fail (exit 3) - a figure of a run that lost commands describes
// something else.
#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sched.h>
#include <signal.h>
#include <sys/epoll.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/timerfd.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "mavlink/mavlink.hpp"
#include "protocols/orion/codec/codec.hpp"
#include "protocols/orion/codec/framer.hpp"
#include "protocols/orion/codec/framing.hpp"
#include "protocols/orion/codec/packets_control.hpp"
#include "protocols/orion/codec/packets_telemetry.hpp"

namespace {

namespace o = gimbal::orion;
using Clock = std::chrono::steady_clock;
using Nanos = std::chrono::nanoseconds;

// --- command line ------------------------------------------------------------------------

struct Options {
    std::string gimbald;
    std::size_t count = 10000;
    double rate_hz = 1000.0;
    bool busy_poll = false;
    std::string log_level = "info";
    std::string daemon_log;  // gimbald's stdout/stderr; default: a file in the temp dir
    std::string samples;     // per-command CSV, optional
    bool keep = false;       // keep the temp dir (config, daemon log)
    int fifo_priority = 0;   // > 0: bench and daemon run SCHED_FIFO at this priority
    bool mavlink = false;    // MAVLink PITCHYAW -> OrionCmd instead of JSON geopoint
};

const char* const usage =
    "usage: bench_daemon_latency --gimbald PATH [--count N] [--rate HZ] [--poll epoll|busy]\n"
    "                            [--log-level LEVEL] [--daemon-log FILE] [--samples FILE]\n"
    "                            [--fifo PRIO] [--keep] [--mavlink]\n";

std::optional<Options> parse_options(int argc, char** argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string_view arg = argv[i];
        auto value = [&]() -> std::optional<std::string> {
            if (i + 1 >= argc) return std::nullopt;
            return std::string(argv[++i]);
        };
        std::optional<std::string> v;
        if (arg == "--mavlink") {
            o.mavlink = true;
            continue;
        }
        if (arg == "--keep") {
            o.keep = true;
            continue;
        }
        if (arg == "-h" || arg == "--help") return std::nullopt;
        if (arg.substr(0, 2) != "--") {  // a bare path is the daemon
            o.gimbald = std::string(arg);
            continue;
        }
        if (!(v = value())) return std::nullopt;
        if (arg == "--gimbald") {
            o.gimbald = *v;
        } else if (arg == "--count") {
            o.count = std::strtoul(v->c_str(), nullptr, 10);
        } else if (arg == "--rate") {
            o.rate_hz = std::strtod(v->c_str(), nullptr);
        } else if (arg == "--poll") {
            if (*v != "epoll" && *v != "busy") return std::nullopt;
            o.busy_poll = *v == "busy";
        } else if (arg == "--log-level") {
            o.log_level = *v;
        } else if (arg == "--daemon-log") {
            o.daemon_log = *v;
        } else if (arg == "--samples") {
            o.samples = *v;
        } else if (arg == "--fifo") {
            o.fifo_priority = std::atoi(v->c_str());
            if (o.fifo_priority < 1 || o.fifo_priority > 99) return std::nullopt;
        } else {
            return std::nullopt;
        }
    }
    // Latitudes 45 + i * 1e-5 degrees must stay valid; 1 Hz .. 100 kHz is a sane rate.
    // A busy-polling SCHED_FIFO task would starve everything else on its core.
    if (o.busy_poll && o.fifo_priority > 0) return std::nullopt;
    if (o.gimbald.empty() || o.count == 0 || o.count > 4'000'000 || !(o.rate_hz >= 1.0) ||
        o.rate_hz > 100000.0)
        return std::nullopt;
    return o;
}

[[noreturn]] void die(const std::string& what) {
    std::cerr << "bench_daemon_latency: " << what << "\n";
    std::exit(1);
}

[[noreturn]] void die_errno(const std::string& what) {
    die(what + ": " + std::strerror(errno));
}

// --- sockets -------------------------------------------------------------------------------

sockaddr_in loopback(std::uint16_t port) {
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(port);
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    return a;
}

std::uint16_t local_port(int fd) {
    sockaddr_in a{};
    socklen_t len = sizeof a;
    if (getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len) != 0) die_errno("getsockname");
    return ntohs(a.sin_port);
}

int bound_socket(int type, std::uint16_t port) {
    const int fd = socket(AF_INET, type | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    if (fd < 0) die_errno("socket");
    const sockaddr_in a = loopback(port);
    if (bind(fd, reinterpret_cast<const sockaddr*>(&a), sizeof a) != 0) die_errno("bind");
    return fd;
}

// A UDP port nobody holds right now, for gimbald's command socket (a tiny race we accept).
std::uint16_t free_udp_port() {
    const int fd = bound_socket(SOCK_DGRAM, 0);
    const std::uint16_t port = local_port(fd);
    close(fd);
    return port;
}

void send_all(int fd, const std::vector<std::uint8_t>& bytes) {
    std::size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = send(fd, bytes.data() + done, bytes.size() - done, MSG_NOSIGNAL);
        if (n > 0) {
            done += static_cast<std::size_t>(n);
        } else if (n < 0 && (errno == EAGAIN || errno == EINTR)) {
            pollfd p{fd, POLLOUT, 0};
            poll(&p, 1, 100);
        } else {
            die_errno("send to gimbald");
        }
    }
}

// --- the daemon ----------------------------------------------------------------------------

struct Daemon {
    pid_t pid = -1;

    void start(const Options& opt, const std::string& config, const std::string& log_path) {
        const int log_fd = open(log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
        if (log_fd < 0) die_errno("open " + log_path);
        pid = fork();
        if (pid < 0) die_errno("fork");
        if (pid == 0) {
            prctl(PR_SET_PDEATHSIG, SIGTERM);  // never outlive a crashed benchmark
            dup2(log_fd, STDOUT_FILENO);
            dup2(log_fd, STDERR_FILENO);
            std::vector<std::string> args = {opt.gimbald, "-c", config, "--log-level",
                                             opt.log_level};
            std::vector<char*> argv;
            for (auto& a : args) argv.push_back(a.data());
            argv.push_back(nullptr);
            execv(argv[0], argv.data());
            std::perror("exec gimbald");
            _exit(127);
        }
        close(log_fd);
    }

    bool exited() {
        int status = 0;
        if (pid > 0 && waitpid(pid, &status, WNOHANG) == pid) {
            pid = -1;
            return true;
        }
        return pid <= 0;
    }

    void stop() {
        if (pid <= 0) return;
        kill(pid, SIGTERM);
        for (int i = 0; i < 300 && !exited(); ++i) usleep(10000);
        if (pid > 0) {
            kill(pid, SIGKILL);
            waitpid(pid, nullptr, 0);
            pid = -1;
        }
    }

    ~Daemon() { stop(); }
};

// --- what is measured ------------------------------------------------------------------------

constexpr double base_lat_deg = 45.0;
constexpr double lat_step_deg = 1e-5;  // 100 raw units of the I32 field (1e-7 degree)
constexpr std::int64_t base_lat_raw = 450'000'000;
constexpr std::int64_t lat_step_raw = 100;
constexpr std::int64_t unset = -1;

struct Sample {
    std::int64_t sent_ns = unset;   // steady clock, just before sendto()
    std::int64_t frame_ns = unset;  // just after the recv() that carried its GeopointCmd
    std::int64_t reply_ns = unset;  // just after the recv() of its JSON reply
    bool reply_ok = false;
};

std::int64_t now_ns() {
    return std::chrono::duration_cast<Nanos>(Clock::now().time_since_epoch()).count();
}

// What the scheduler says about a process: CPU time, time runnable but waiting for a CPU, and
// how often it was preempted.
struct SchedStat {
    double cpu_ms = 0;
    double wait_ms = 0;
    long preempted = 0;
};

SchedStat sched_stat(pid_t pid) {
    SchedStat out;
    const std::string dir = "/proc/" + std::to_string(pid);
    std::ifstream stat(dir + "/schedstat");
    double cpu_ns = 0, wait_ns = 0;
    if (stat >> cpu_ns >> wait_ns) {
        out.cpu_ms = cpu_ns / 1e6;
        out.wait_ms = wait_ns / 1e6;
    }
    std::ifstream status(dir + "/status");
    for (std::string line; std::getline(status, line);)
        if (line.rfind("nonvoluntary_ctxt_switches:", 0) == 0)
            out.preempted = std::atol(line.c_str() + line.find(':') + 1);
    return out;
}

SchedStat operator-(const SchedStat& a, const SchedStat& b) {
    return {a.cpu_ms - b.cpu_ms, a.wait_ms - b.wait_ms, a.preempted - b.preempted};
}

struct Percentiles {
    std::size_t n = 0;
    double p50 = 0, p90 = 0, p99 = 0, p999 = 0, max = 0, mean = 0;
};

// Nearest-rank percentiles, in microseconds.
Percentiles percentiles(std::vector<double> us) {
    Percentiles p;
    p.n = us.size();
    if (us.empty()) return p;
    std::sort(us.begin(), us.end());
    auto rank = [&](double q) {
        const auto r = static_cast<std::size_t>(std::ceil(q * static_cast<double>(us.size())));
        return us[std::clamp<std::size_t>(r, 1, us.size()) - 1];
    };
    p.p50 = rank(0.50);
    p.p90 = rank(0.90);
    p.p99 = rank(0.99);
    p.p999 = rank(0.999);
    p.max = us.back();
    double sum = 0;
    for (double v : us) sum += v;
    p.mean = sum / static_cast<double>(us.size());
    return p;
}

// --- the run -------------------------------------------------------------------------------

class Bench {
  public:
    Bench(const Options& opt, int listener, int client, std::uint16_t command_port,
          std::string daemon_log, int mav = -1, std::uint16_t vehicle_port = 0)
        : opt_(opt),
          daemon_log_(std::move(daemon_log)),
          listener_(listener),
          client_(client),
          command_(loopback(command_port)),
          samples_(opt.count),
          mav_(mav),
          vehicle_(loopback(vehicle_port)) {}

    ~Bench() {
        if (gimbal_ >= 0) close(gimbal_);
    }

    // Accepts gimbald's TCP connection and waits until the daemon reports it connected.
    void connect(Daemon& daemon) {
        const auto deadline = Clock::now() + std::chrono::seconds(10);
        while (gimbal_ < 0) {
            if (Clock::now() > deadline)
                die("gimbald did not connect within 10 s; its log: " + daemon_log_);
            if (daemon.exited()) die("gimbald exited during start-up; its log: " + daemon_log_);
            pollfd p{listener_, POLLIN, 0};
            if (poll(&p, 1, 50) <= 0) continue;
            gimbal_ = accept4(listener_, nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC);
        }
        const int one = 1;
        setsockopt(gimbal_, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
        next_telemetry_ns_ = now_ns();
        std::int64_t next_probe = 0;
        while (!ready_) {
            if (Clock::now() > deadline)
                die("gimbald never reported the link connected; its log: " + daemon_log_);
            if (daemon.exited()) die("gimbald exited during start-up; its log: " + daemon_log_);
            const std::int64_t t = now_ns();
            if (t >= next_probe) {
                send_json(R"({"cmd":"state","id":"ready"})");
                next_probe = t + 50'000'000;
            }
            service();
            usleep(1000);
        }
    }

    void run(pid_t daemon_pid) {
        const SchedStat daemon_before = sched_stat(daemon_pid);
        const SchedStat self_before = sched_stat(getpid());
        const auto period = static_cast<std::int64_t>(1e9 / opt_.rate_hz);
        const std::int64_t start = now_ns() + 20'000'000;  // a quiet moment after the probes
        if (opt_.busy_poll)
            run_busy(start, period);
        else
            run_epoll(start, period);
        finished_ns_ = now_ns();
        // Stragglers: one more second for frames and replies still in flight.
        const std::int64_t drain_until = finished_ns_ + 1'000'000'000;
        while (now_ns() < drain_until && (frames_ < sent_ || replies_ < sent_)) {
            service();
            usleep(200);
        }
        daemon_sched_ = sched_stat(daemon_pid) - daemon_before;
        self_sched_ = sched_stat(getpid()) - self_before;
    }

    // True when every command reached the gimbal once and got an ok reply.
    bool complete() const {
        std::size_t ok = 0;
        for (std::size_t i = 0; i < sent_; ++i)
            if (samples_[i].frame_ns != unset && samples_[i].reply_ns != unset &&
                samples_[i].reply_ok)
                ++ok;
        return sent_ == opt_.count && ok == sent_ && unmatched_ == 0 && duplicates_ == 0;
    }

    void report() const {
        std::vector<double> frame_us, reply_us;
        for (std::size_t i = 0; i < sent_; ++i) {
            const Sample& s = samples_[i];
            if (s.frame_ns != unset)
                frame_us.push_back(static_cast<double>(s.frame_ns - s.sent_ns) / 1e3);
            if (s.reply_ns != unset)
                reply_us.push_back(static_cast<double>(s.reply_ns - s.sent_ns) / 1e3);
        }
        std::size_t reply_errors = 0;
        for (std::size_t i = 0; i < sent_; ++i)
            if (samples_[i].reply_ns != unset && !samples_[i].reply_ok) ++reply_errors;
        const Percentiles f = percentiles(frame_us);
        const Percentiles r = percentiles(reply_us);
        const double seconds = static_cast<double>(finished_ns_ - first_send_ns_) / 1e9;
        const std::size_t lost = sent_ - f.n;

        std::printf(opt_.mavlink ? "gimbald command latency: MAVLink DO_GIMBAL_MANAGER_PITCHYAW "
                                   "datagram sent -> OrionCmd at the gimbal\n"
                                 : "gimbald command latency: geopoint datagram sent -> "
                                   "GeopointCmd at the gimbal\n");
        std::printf("  loop %s%s, sent %zu in %.2f s (%.0f/s, %zu late ticks), log level %s\n",
                    opt_.busy_poll ? "busy-poll" : "epoll",
                    opt_.fifo_priority > 0 ? " (SCHED_FIFO)" : "", sent_, seconds,
                    static_cast<double>(sent_) / seconds, late_ticks_, opt_.log_level.c_str());
        std::printf("  frames: count %zu  lost %zu  unmatched %zu  duplicates %zu\n", f.n, lost,
                    unmatched_, duplicates_);
        std::printf(
            "  frame latency us: p50 %.1f  p90 %.1f  p99 %.1f  p99.9 %.1f  max %.1f  "
            "mean %.1f\n",
            f.p50, f.p90, f.p99, f.p999, f.max, f.mean);
        std::printf(
            "  reply latency us: p50 %.1f  p90 %.1f  p99 %.1f  p99.9 %.1f  max %.1f  "
            "(%zu replies, %zu not ok)\n",
            r.p50, r.p90, r.p99, r.p999, r.max, r.n, reply_errors);
        std::printf(
            "  run queue: gimbald ran %.1f ms and waited %.1f ms for a CPU (%ld "
            "preemptions); the benchmark waited %.1f ms (%ld)\n",
            daemon_sched_.cpu_ms, daemon_sched_.wait_ms, daemon_sched_.preempted,
            self_sched_.wait_ms, self_sched_.preempted);
        const double target_us = opt_.mavlink ? 300.0 : 200.0;  // issue 9: MAVLink < 300 us
        std::printf("  target p99 < %.0f us: %s\n", target_us,
                    f.n > 0 && f.p99 < target_us && lost == 0 ? "met" : "MISSED");
        std::printf(
            "RESULT count=%zu lost=%zu p50_us=%.1f p90_us=%.1f p99_us=%.1f "
            "p999_us=%.1f max_us=%.1f reply_p50_us=%.1f reply_p99_us=%.1f "
            "late_ticks=%zu reply_errors=%zu daemon_cpu_ms=%.1f daemon_wait_ms=%.1f "
            "daemon_preempted=%ld\n",
            f.n, lost, f.p50, f.p90, f.p99, f.p999, f.max, r.p50, r.p99, late_ticks_, reply_errors,
            daemon_sched_.cpu_ms, daemon_sched_.wait_ms, daemon_sched_.preempted);
    }

    void write_samples(const std::string& path) const {
        std::ofstream out(path);
        out << "index,sent_ns,frame_us,reply_us,reply_ok\n";
        for (std::size_t i = 0; i < sent_; ++i) {
            const Sample& s = samples_[i];
            out << i << ',' << s.sent_ns - first_send_ns_ << ',';
            if (s.frame_ns != unset) out << static_cast<double>(s.frame_ns - s.sent_ns) / 1e3;
            out << ',';
            if (s.reply_ns != unset) out << static_cast<double>(s.reply_ns - s.sent_ns) / 1e3;
            out << ',' << (s.reply_ok ? 1 : 0) << '\n';
        }
    }

  private:
    // Sends at t0 + i * period without bursts: a tick missed while busy is skipped.
    void run_busy(std::int64_t start, std::int64_t period) {
        std::int64_t next = start;
        while (sent_ < opt_.count) {
            const std::int64_t t = now_ns();
            if (t >= next) {
                send_command();
                next += period;
                if (next <= t) {
                    ++late_ticks_;
                    next = t + period;
                }
            }
            service();
        }
    }

    // Sleeps in epoll_wait on the two sockets and a periodic timerfd that paces the sends.
    void run_epoll(std::int64_t start, std::int64_t period) {
        const int timer = timerfd_create(CLOCK_MONOTONIC, TFD_NONBLOCK | TFD_CLOEXEC);
        const int ep = epoll_create1(EPOLL_CLOEXEC);
        if (timer < 0 || ep < 0) die_errno("timerfd/epoll");
        itimerspec spec{};
        spec.it_value.tv_sec = static_cast<time_t>(start / 1'000'000'000);
        spec.it_value.tv_nsec = static_cast<long>(start % 1'000'000'000);
        spec.it_interval.tv_sec = static_cast<time_t>(period / 1'000'000'000);
        spec.it_interval.tv_nsec = static_cast<long>(period % 1'000'000'000);
        // steady_clock is CLOCK_MONOTONIC on Linux, so its epoch is the timer's.
        if (timerfd_settime(timer, TFD_TIMER_ABSTIME, &spec, nullptr) != 0)
            die_errno("timerfd_settime");
        // The MAVLink socket too: its COMMAND_ACK may come after the gimbal's packet.
        for (const int fd : {timer, gimbal_, client_, mav_}) {
            if (fd < 0) continue;
            epoll_event ev{};
            ev.events = EPOLLIN;
            ev.data.fd = fd;
            if (epoll_ctl(ep, EPOLL_CTL_ADD, fd, &ev) != 0) die_errno("epoll_ctl");
        }
        std::array<epoll_event, 5> events{};
        while (sent_ < opt_.count) {
            const int n = epoll_wait(ep, events.data(), static_cast<int>(events.size()), 100);
            if (n < 0 && errno != EINTR) die_errno("epoll_wait");
            bool tick = false;
            for (int i = 0; i < n; ++i) {
                if (events[static_cast<std::size_t>(i)].data.fd != timer) continue;
                std::uint64_t expirations = 0;
                if (read(timer, &expirations, sizeof expirations) == sizeof expirations) {
                    tick = expirations > 0;
                    if (expirations > 1) late_ticks_ += expirations - 1;
                }
            }
            if (tick) send_command();  // the send first: it is what is being timed
            service();
        }
        close(ep);
        close(timer);
    }

    void send_command() {
        if (opt_.mavlink)
            send_pitchyaw();
        else
            send_geopoint();
    }

    // Yaw (pan) -150 + 0.1 * (i mod 3000) degrees: distinct on the wire (1 mrad steps).
    static constexpr std::size_t pan_slots = 3000;
    static double pan_of(std::size_t i) {
        return -150.0 + 0.1 * static_cast<double>(i % pan_slots);
    }

    void send_pitchyaw() {
        const std::size_t i = sent_;
        gimbal::mavlink::CommandLong c;
        c.command = gimbal::mavlink::mav_cmd::do_gimbal_manager_pitchyaw;
        c.param = {-10.0f, static_cast<float>(pan_of(i)), std::nanf(""), std::nanf(""), 0, 0, 1};
        c.target_system = 1;
        c.target_component = 154;
        const auto frame = gimbal::mavlink::encode_v2(c, 255, 190, static_cast<std::uint8_t>(i));
        const std::int64_t t = now_ns();
        const ssize_t n = sendto(mav_, frame.data(), frame.size(), 0,
                                 reinterpret_cast<const sockaddr*>(&vehicle_), sizeof vehicle_);
        if (n != static_cast<ssize_t>(frame.size())) die_errno("sendto gimbald (MAVLink)");
        samples_[i].sent_ns = t;
        if (i == 0) first_send_ns_ = t;
        ++sent_;
    }

    void send_geopoint() {
        const std::size_t i = sent_;
        std::array<char, 160> text{};
        const int len = std::snprintf(text.data(), text.size(),
                                      R"({"cmd":"geopoint","id":%zu,"lat":%.7f,"lon":-121.5,)"
                                      R"("alt":100.0})",
                                      i, base_lat_deg + static_cast<double>(i) * lat_step_deg);
        const std::int64_t t = now_ns();
        const ssize_t n = sendto(client_, text.data(), static_cast<std::size_t>(len), 0,
                                 reinterpret_cast<const sockaddr*>(&command_), sizeof command_);
        if (n != len) die_errno("sendto gimbald");
        samples_[i].sent_ns = t;
        if (i == 0) first_send_ns_ = t;
        ++sent_;
    }

    void send_json(std::string_view text) {
        sendto(client_, text.data(), text.size(), 0, reinterpret_cast<const sockaddr*>(&command_),
               sizeof command_);
    }

    // One pass over everything that is not the measured send: gimbal bytes, replies, telemetry.
    void service() {
        drain_gimbal();
        drain_replies();
        drain_mavlink();
        if (now_ns() >= next_telemetry_ns_) {
            send_telemetry();
            next_telemetry_ns_ += 100'000'000;
        }
    }

    // COMMAND_ACKs come back in command order; the streams (attitude, status) are ignored.
    void drain_mavlink() {
        if (mav_ < 0) return;
        for (;;) {
            const ssize_t n = recv(mav_, rx_mav_.data(), rx_mav_.size(), MSG_DONTWAIT);
            const std::int64_t t = now_ns();
            if (n <= 0) return;
            mav_framer_.push(
                std::span<const std::uint8_t>(rx_mav_.data(), static_cast<std::size_t>(n)),
                [&](const gimbal::mavlink::Message& m) {
                    const auto* ack = std::get_if<gimbal::mavlink::CommandAck>(&m.payload);
                    if (!ack || ack_next_ >= sent_) return;
                    samples_[ack_next_].reply_ns = t;
                    samples_[ack_next_].reply_ok = ack->result == 0;
                    ++ack_next_;
                    ++replies_;
                });
        }
    }

    void drain_gimbal() {
        for (;;) {
            const ssize_t n = recv(gimbal_, rx_.data(), rx_.size(), MSG_DONTWAIT);
            const std::int64_t t = now_ns();
            if (n == 0) die("gimbald closed the gimbal link; its log: " + daemon_log_);
            if (n < 0) {
                if (errno == EAGAIN || errno == EINTR) return;
                die_errno("recv from gimbald");
            }
            framer_.push(std::span<const std::uint8_t>(rx_.data(), static_cast<std::size_t>(n)),
                         [&](const o::Frame& f) { on_frame(f, t); });
        }
    }

    void on_cmd_frame(const o::Frame& frame, std::int64_t t) {
        const auto cmd = o::decode<o::Cmd>(frame.data());
        if (!cmd || cmd.value.cmd.mode != o::Mode::position) {
            ++unmatched_;
            return;
        }
        const double pan_deg = cmd.value.cmd.target[0] * o::rad2deg;
        const auto slot = static_cast<std::int64_t>(std::llround((pan_deg + 150.0) / 0.1));
        if (slot < 0 || slot >= static_cast<std::int64_t>(pan_slots)) {
            ++unmatched_;
            return;
        }
        // The earliest command of that slot still without its frame.
        for (auto i = static_cast<std::size_t>(slot); i < sent_; i += pan_slots) {
            if (samples_[i].frame_ns != unset) continue;
            samples_[i].frame_ns = t;
            ++frames_;
            return;
        }
        ++duplicates_;
    }

    void on_frame(const o::Frame& frame, std::int64_t t) {
        if (opt_.mavlink) {
            if (frame.id == o::Cmd::id) on_cmd_frame(frame, t);
            return;
        }
        if (frame.id != o::GeopointCmd::id) return;  // the daemon's on-connect requests
        const auto cmd = o::decode<o::GeopointCmd>(frame.data());
        const auto raw =
            static_cast<std::int64_t>(std::llround(cmd.value.target_lat * 1e7 * o::rad2deg));
        const std::int64_t offset = raw - base_lat_raw;
        const std::int64_t index = (offset + lat_step_raw / 2) / lat_step_raw;
        if (!cmd || offset < 0 || index >= static_cast<std::int64_t>(sent_)) {
            ++unmatched_;
            return;
        }
        Sample& s = samples_[static_cast<std::size_t>(index)];
        if (s.frame_ns != unset) {
            ++duplicates_;
            return;
        }
        s.frame_ns = t;
        ++frames_;
    }

    void drain_replies() {
        for (;;) {
            const ssize_t n = recv(client_, reply_.data(), reply_.size() - 1, MSG_DONTWAIT);
            const std::int64_t t = now_ns();
            if (n < 0) return;
            reply_[static_cast<std::size_t>(n)] = '\0';
            const char* text = reply_.data();
            if (std::strstr(text, R"("id":"ready")")) {
                ready_ = std::strstr(text, R"("connected":true)") != nullptr;
                continue;
            }
            const char* id = std::strstr(text, R"("id":)");
            if (!id) continue;
            const unsigned long index = std::strtoul(id + 5, nullptr, 10);
            if (index >= sent_ || samples_[index].reply_ns != unset) continue;
            samples_[index].reply_ns = t;
            samples_[index].reply_ok = std::strstr(text, R"("ok":true)") != nullptr;
            ++replies_;
        }
    }

    void send_telemetry() {
        o::GeolocateTelemetry tm;
        tm.system_time_ms = static_cast<std::uint32_t>(telemetry_sent_ * 100);
        tm.gps_week = 2400;
        tm.gps_itow_ms = static_cast<std::uint32_t>(telemetry_sent_ * 100);
        tm.lat = base_lat_deg / o::rad2deg;
        tm.lon = -121.5 / o::rad2deg;
        tm.alt = 1500.0;
        tm.quat = {1.0, 0.0, 0.0, 0.0};
        tm.tilt = -0.5;
        tm.hfov = 0.5;
        tm.vfov = 0.3;
        tm.mode = o::Mode::position;
        send_all(gimbal_, o::to_wire(tm));
        ++telemetry_sent_;
    }

    const Options& opt_;
    std::string daemon_log_;
    int listener_;
    int client_;
    int gimbal_ = -1;
    sockaddr_in command_;
    std::vector<Sample> samples_;
    o::Framer framer_;
    std::array<std::uint8_t, 65536> rx_{};
    std::array<char, 65537> reply_{};
    int mav_ = -1;
    sockaddr_in vehicle_;
    gimbal::mavlink::Framer mav_framer_;
    std::array<std::uint8_t, 65536> rx_mav_{};
    std::size_t ack_next_ = 0;
    bool ready_ = false;
    std::size_t sent_ = 0, frames_ = 0, replies_ = 0;
    std::size_t unmatched_ = 0, duplicates_ = 0, late_ticks_ = 0;
    std::int64_t first_send_ns_ = 0, finished_ns_ = 0, next_telemetry_ns_ = 0;
    std::uint64_t telemetry_sent_ = 0;
    SchedStat daemon_sched_, self_sched_;
};

std::string write_config(const std::filesystem::path& dir, const Options& opt,
                         std::uint16_t gimbal_port, std::uint16_t command_port,
                         std::uint16_t vehicle_port) {
    const auto path = dir / "gimbald.json";
    std::ofstream out(path);
    // The default rate limit (200/s, burst 400) would throttle the run: allow twice its rate.
    const double limit = std::max(200.0, 2.0 * opt.rate_hz);
    out << R"({"gimbals":[{"name":"bench","protocol":"orion","link":{"type":"tcp",)"
        << R"("host":"127.0.0.1","port":)" << gimbal_port << R"(}}],)"
        << R"("command":{"bind":"127.0.0.1","port":)" << command_port
        << R"(,"rate_limit":{"per_source_hz":)" << limit << R"(,"burst":)" << 2.0 * limit << "}}";
    if (vehicle_port != 0)
        out << R"(,"vehicle":{"source":{"type":"udp","bind":"127.0.0.1","port":)" << vehicle_port
            << R"(}},"mavlink":{"gimbal_manager":true,"system_id":1})";
    out << "}\n";
    if (!out) die("cannot write " + path.string());
    return path.string();
}

}  // namespace

int main(int argc, char** argv) {
    const auto parsed = parse_options(argc, argv);
    if (!parsed) {
        std::cerr << usage;
        return 1;
    }
    const Options& opt = *parsed;
    signal(SIGPIPE, SIG_IGN);
    if (opt.fifo_priority > 0) {  // inherited by gimbald through fork and exec
        sched_param param{};
        param.sched_priority = opt.fifo_priority;
        if (sched_setscheduler(0, SCHED_FIFO, &param) != 0) die_errno("SCHED_FIFO (--fifo)");
    }

    std::string dir_template = (std::filesystem::temp_directory_path() / "gimbald-bench-XXXXXX");
    if (!mkdtemp(dir_template.data())) die_errno("mkdtemp");
    const std::filesystem::path dir = dir_template;

    const int listener = bound_socket(SOCK_STREAM, 0);
    if (listen(listener, 1) != 0) die_errno("listen");
    const int client = bound_socket(SOCK_DGRAM, 0);
    const int big = 4 << 20;  // replies must never be dropped for want of buffer
    setsockopt(client, SOL_SOCKET, SO_RCVBUF, &big, sizeof big);
    const std::uint16_t command_port = free_udp_port();
    int mav = -1;
    std::uint16_t vehicle_port = 0;
    if (opt.mavlink) {
        mav = bound_socket(SOCK_DGRAM, 0);
        setsockopt(mav, SOL_SOCKET, SO_RCVBUF, &big, sizeof big);
        vehicle_port = free_udp_port();
    }
    const std::string config =
        write_config(dir, opt, local_port(listener), command_port, vehicle_port);
    const std::string log_path =
        opt.daemon_log.empty() ? (dir / "gimbald.log").string() : opt.daemon_log;

    bool complete = false;
    {
        Daemon daemon;
        daemon.start(opt, config, log_path);
        Bench bench(opt, listener, client, command_port, log_path, mav, vehicle_port);
        bench.connect(daemon);
        bench.run(daemon.pid);
        daemon.stop();
        bench.report();
        if (!opt.samples.empty()) bench.write_samples(opt.samples);
        complete = bench.complete();
    }
    close(client);
    close(listener);
    if (mav >= 0) close(mav);
    if (opt.keep || !complete)
        std::printf("kept %s (config, daemon log)\n", dir.c_str());
    else
        std::filesystem::remove_all(dir);
    if (!complete) {
        std::fprintf(stderr,
                     "bench_daemon_latency: FAILED: commands were lost, refused, unmatched or "
                     "duplicated (see the frames and replies lines above); the figures do not "
                     "describe a complete run\n");
        return 3;
    }
    return 0;
}
