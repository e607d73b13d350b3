// gimbal-replay: plays the gimbal side of a gimbald recording back as a simulated gimbal.
// See `gimbal-replay --help` and docs/replay-export.md.
#include <boost/asio/io_context.hpp>
#include <boost/asio/signal_set.hpp>
#include <csignal>
#include <exception>
#include <iostream>

#include "options.hpp"
#include "record/gimbal_stream.hpp"
#include "record/video_stream.hpp"
#include "replay_app.hpp"

int main(int argc, char** argv) {
    const auto parsed = gimbal_replay::parse_options(argc, argv);
    if (!parsed.options) return parsed.exit_status;
    const auto& options = *parsed.options;

    std::string error;
    std::vector<std::string> warnings;
    gimbal::record::GimbalStream stream;
    if (!gimbal::record::load_gimbal_files(options.files, options.gimbal, stream, warnings,
                                           error)) {
        std::cerr << "gimbal-replay: " << error << std::endl;
        return 1;
    }
    for (const auto& w : warnings)
        std::cerr << "gimbal-replay: warning: " << w << "; playing what came before" << std::endl;
    if (stream.chunks.empty())
        std::cerr << "gimbal-replay: warning: gimbal " << stream.gimbal.name
                  << " sent nothing in this recording" << std::endl;
    gimbal::record::VideoStream video;
    if (!options.video.empty()) {
        std::vector<std::string> video_warnings;
        if (!gimbal::record::load_video_files(options.files, stream.gimbal.name, video,
                                              video_warnings, error)) {
            std::cerr << "gimbal-replay: --video: " << error << std::endl;
            return 1;
        }
    }

    std::signal(SIGPIPE, SIG_IGN);  // a client gone mid-write is an error code, not a death
    try {
        boost::asio::io_context io;
        boost::asio::signal_set signals(io, SIGINT, SIGTERM);
        gimbal_replay::ReplayApp app(io, options, std::move(stream), std::move(video));
        app.on_stop([&] { signals.cancel(); });
        signals.async_wait([&](const boost::system::error_code& ec, int) {
            if (!ec) app.stop();
        });
        app.start();
        io.run();
        return 0;
    } catch (const std::exception& e) {
        std::cerr << "gimbal-replay: " << e.what() << std::endl;
        return 2;
    }
}
