#include "exchange.hpp"

#include <optional>

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>

#include "datagram.hpp"
#include "duration.hpp"
#include "exit_status.hpp"
#include "output.hpp"
#include "transport.hpp"

namespace gimbalctl {

int run_exchange(const GlobalOptions& globals, const Json& request) {
    boost::asio::io_context io;
    std::optional<Json> reply;
    std::optional<boost::system::error_code> failure;

    UdpTransport transport(
        io,
        [&](std::string_view datagram) {
            auto value = parse_datagram(datagram);
            if (value && is_reply_to(*value, request)) {
                reply = std::move(value);
                io.stop();
            }
        },
        [&](const boost::system::error_code& error) {
            failure = error;
            io.stop();
        });

    std::string problem;
    if (!transport.open(globals.host, globals.port, problem)) {
        print_diagnostic(problem);
        return exit_no_reply;
    }
    boost::asio::steady_timer deadline(io, seconds(globals.timeout_s));
    deadline.async_wait([&](const boost::system::error_code& error) {
        if (!error) io.stop();
    });
    transport.start_receiving();
    transport.send(format_json(request, false));
    io.run();

    if (reply) return report_reply(*reply, globals.pretty);
    if (failure) {
        print_diagnostic(
            "no reply from " + transport.peer() + ": " + failure->message() +
            (*failure == boost::asio::error::connection_refused ? " (is gimbald running?)" : ""));
    } else {
        print_diagnostic("no reply from " + transport.peer() + " within " +
                         format_seconds(globals.timeout_s));
    }
    return exit_no_reply;
}

}  // namespace gimbalctl
