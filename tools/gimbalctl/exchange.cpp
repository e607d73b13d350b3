#include "exchange.hpp"

#include <optional>

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>

#include "datagram.hpp"
#include "duration.hpp"
#include "exit_status.hpp"
#include "output.hpp"
#include "signing.hpp"
#include "transport.hpp"

namespace gimbalctl {

int run_exchange(const GlobalOptions& globals, const Json& request) {
    int status = exit_ok;
    std::optional<SigningKey> key = signing_key_for(globals, status);
    if (status != exit_ok) return status;
    Sealer sealer(std::move(key));
    boost::asio::io_context io;
    std::optional<Json> reply;
    std::optional<boost::system::error_code> failure;
    bool unauthenticated = false;

    UdpTransport transport(
        io,
        [&](std::string_view datagram) {
            auto value = parse_datagram(datagram);
            if (!value) return;
            const auto opened = sealer.open(*value);
            if (opened == Sealer::Opened::forged) {
                unauthenticated = true;
                io.stop();
                return;
            }
            if (!is_reply_to(*value, request)) return;
            // Signing on: a success must be signed and carry our nonce. An unsigned failure
            // is shown (the daemon cannot sign a reply to a request it could not verify).
            if (sealer.signing() && value->value("ok", false) &&
                (opened != Sealer::Opened::authentic ||
                 value->value("nonce", std::string()) != sealer.last_nonce())) {
                unauthenticated = true;
                io.stop();
                return;
            }
            reply = std::move(value);
            io.stop();
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
    transport.send(sealer.seal(request));
    io.run();

    if (unauthenticated) {
        print_diagnostic("unauthenticated reply from " + transport.peer() +
                         ": its signature does not verify with key '" +
                         globals.key_id.value_or("") + "'");
        return exit_no_reply;
    }
    if (reply) {
        if (sealer.signing()) {
            reply->erase("nonce");
            reply->erase("ts");
        }
        return report_reply(*reply, globals.pretty);
    }
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
