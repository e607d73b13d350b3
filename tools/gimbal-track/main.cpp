// gimbal-track: the visual tracking process (options.cpp for what it does). One thread: read
// a datagram, act on it, answer; SIGTERM and SIGINT arrive through a signalfd beside the
// socket, so a stop is handled between messages, never inside one.
#include <poll.h>
#include <signal.h>
#include <sys/signalfd.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <opencv2/core/utility.hpp>

extern "C" {
#include <libavutil/log.h>
#include <libavutil/mem.h>
}

#include "options.hpp"
#include "seqpacket.hpp"
#include "track/wire/codec.hpp"
#include "track_session.hpp"

using namespace gimbal_track;

namespace {

constexpr int start_burst_ms = 10;

int signal_fd() {
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGTERM);
    sigaddset(&set, SIGINT);
    if (sigprocmask(SIG_BLOCK, &set, nullptr) != 0) return -1;
    return signalfd(-1, &set, SFD_CLOEXEC);
}

int run(const Options& options, const Log& log) {
    SeqPacket socket =
        options.fd ? SeqPacket::adopt(*options.fd) : SeqPacket::connect(*options.socket);
    if (!socket.ok()) {
        log.error("socket_unusable", socket.error());
        return 1;
    }
    const int signals = signal_fd();
    if (signals < 0) {
        log.error("signals_unusable", "cannot block SIGTERM and SIGINT");
        return 1;
    }
    bool gone = false;
    std::vector<std::uint8_t> out;
    auto send = [&](const wire::Message& m) {
        std::string error;
        if (!wire::encode(m, out, &error)) {
            log.error("message_invalid", "an answer broke its declaration: " + error);
            return;
        }
        if (!gone && !socket.send(out)) {
            gone = true;
            log.info("socket_closed", socket.error());
        }
    };
    TrackSession session(send, log);
    send(TrackSession::hello());
    log.info("started", "waiting for gimbald",
             {{"version", GIMBALD_VERSION}, {"protocol", wire::protocol_version}});

    std::vector<std::uint8_t> buffer;
    buffer.reserve(wire::max_datagram_bytes + 1);
    for (;;) {
        pollfd fds[2] = {{socket.fd(), POLLIN, 0}, {signals, POLLIN, 0}};
        if (::poll(fds, 2, -1) < 0) {
            if (errno == EINTR) continue;
            log.error("poll_failed", std::strerror(errno));
            return 2;
        }
        if ((fds[1].revents & POLLIN) != 0) {
            signalfd_siginfo info{};
            const auto n = ::read(signals, &info, sizeof(info));
            log.info("stopping", "signal " + std::to_string(n > 0 ? info.ssi_signo : 0));
            session.shutdown();
            return 0;
        }
        if (fds[0].revents == 0) continue;
        switch (socket.receive(buffer, wire::max_datagram_bytes)) {
            case SeqPacket::Received::message:
                // Before a track's first frame, "behind" waits a little for more: gimbald
                // starts a track with a burst of the units since the latest key frame and the
                // box belongs to the newest, but on another core this process may read one
                // before gimbald has written the next (they come microseconds apart; live
                // frames tens of milliseconds apart).
                session.datagram(buffer, socket.pending(session.starting() ? start_burst_ms : 0));
                break;
            case SeqPacket::Received::too_large:
                session.refuse("a datagram larger than " +
                               std::to_string(wire::max_datagram_bytes) + " bytes");
                break;
            case SeqPacket::Received::interrupted:
                break;
            case SeqPacket::Received::closed:
                log.info(
                    "stopping", "gimbald closed the socket",
                    {{"messages", session.stats().messages}, {"tracks", session.stats().tracks}});
                return 0;
            case SeqPacket::Received::failed:
                log.error("socket_failed", socket.error());
                return 2;
        }
        if (gone) {
            log.info("stopping", "gimbald went away");
            return 0;
        }
    }
}

}  // namespace

int main(int argc, char** argv) {
    const auto parsed = parse_options(argc, argv);
    if (!parsed.options) return parsed.exit_code;
    const Log log(parsed.options->log_level);
    // Hostile video: bound every allocation, keep FFmpeg's chatter off standard error (the
    // session counts and logs what matters), one core at most for OpenCV.
    av_max_alloc(128u << 20);
    av_log_set_level(AV_LOG_QUIET);
    cv::setNumThreads(1);
    signal(SIGPIPE, SIG_IGN);
    return run(*parsed.options, log);
}
