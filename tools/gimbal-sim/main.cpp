// gimbal-sim: a simulated gimbal of any registered protocol over TCP and/or a
// pseudo-terminal, for tests, demos and operator training. See `gimbal-sim --help` and
// docs/simulator.md.
#include <boost/asio/io_context.hpp>
#include <boost/asio/signal_set.hpp>
#include <csignal>
#include <exception>
#include <iostream>

#include "options.hpp"
#include "sim_app.hpp"
#include "write_dem.hpp"

int main(int argc, char** argv) {
    const auto parsed = gimbal_sim::parse_options(argc, argv);
    if (!parsed.options) return parsed.exit_status;
    if (!parsed.options->write_dem.empty()) return gimbal_sim::write_dem(parsed.options->write_dem);

    std::signal(SIGPIPE, SIG_IGN);  // a client gone mid-write is an error code, not a death
    try {
        boost::asio::io_context io;
        // Signals first: a test may send SIGTERM as soon as the endpoints are printed.
        boost::asio::signal_set signals(io, SIGINT, SIGTERM);
        gimbal_sim::SimApp app(io, *parsed.options);
        signals.async_wait([&](const boost::system::error_code& ec, int) {
            if (!ec) app.stop();  // closes every socket and timer: run() returns by itself
        });
        app.start();
        io.run();
        return 0;
    } catch (const std::exception& e) {
        std::cerr << "gimbal-sim: " << e.what() << std::endl;
        return 2;
    }
}
