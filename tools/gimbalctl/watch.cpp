#include "watch.hpp"

#include <algorithm>
#include <csignal>

#include <boost/asio/io_context.hpp>
#include <boost/asio/signal_set.hpp>
#include <boost/asio/steady_timer.hpp>

#include "datagram.hpp"
#include "duration.hpp"
#include "exit_status.hpp"
#include "output.hpp"
#include "signing.hpp"
#include "state_merger.hpp"
#include "transport.hpp"

namespace gimbalctl {
namespace {

namespace asio = boost::asio;

constexpr double default_ttl_s = 60.0;       // the contract's subscribe default
constexpr double min_renew_period_s = 0.05;  // never flood the daemon, whatever --ttl says

// Renew at half the lifetime, so the renewal lands well before the daemon drops us.
double renew_period_s(const Json& subscribe) {
    const auto ttl = subscribe.find("ttl_s");
    const double ttl_s =
        ttl != subscribe.end() && ttl->is_number() ? ttl->get<double>() : default_ttl_s;
    return std::max(ttl_s / 2.0, min_renew_period_s);
}

// unsubscribe for the same gimbal(s), with the same id and token as the subscribe.
Json unsubscribe_for(const Json& subscribe) {
    Json request = {{"cmd", "unsubscribe"}};
    for (const char* key : {"id", "gimbal", "token"}) {
        if (subscribe.contains(key)) request[key] = subscribe[key];
    }
    return request;
}

class Watch {
  public:
    Watch(const GlobalOptions& globals, const Json& subscribe, std::int64_t count,
          std::optional<SigningKey> key)
        : globals_(globals),
          sealer_(std::move(key)),
          subscribe_(subscribe),
          count_(count),
          transport_(
              io_, [this](std::string_view datagram) { on_datagram(datagram); },
              [this](const boost::system::error_code& error) { on_error(error); }),
          first_reply_deadline_(io_),
          renew_timer_(io_),
          signals_(io_, SIGINT, SIGTERM) {}

    int run() {
        std::string problem;
        if (!transport_.open(globals_.host, globals_.port, problem)) {
            print_diagnostic(problem);
            return exit_no_reply;
        }
        signals_.async_wait([this](const boost::system::error_code& error, int /*signal*/) {
            if (!error) finish(exit_ok);
        });
        first_reply_deadline_.expires_after(seconds(globals_.timeout_s));
        first_reply_deadline_.async_wait([this](const boost::system::error_code& error) {
            if (error || subscribed_) return;
            print_diagnostic("no reply to subscribe from " + transport_.peer() + " within " +
                             format_seconds(globals_.timeout_s));
            stop(exit_no_reply);
        });
        transport_.start_receiving();
        send_subscribe();
        io_.run();
        return exit_status_;
    }

  private:
    void send_subscribe() {
        transport_.send(sealer_.seal(subscribe_));
        renew_timer_.expires_after(seconds(renew_period_s(subscribe_)));
        renew_timer_.async_wait([this](const boost::system::error_code& error) {
            if (!error) send_subscribe();
        });
    }

    void on_datagram(std::string_view text) {
        auto datagram = parse_datagram(text);
        if (!datagram) return;
        const auto opened = sealer_.open(*datagram);
        // Signing on: only what our key signed is shown (an unsigned refusal of the
        // subscribe itself excepted, see on_reply).
        if (opened == Sealer::Opened::forged ||
            (sealer_.signing() && opened == Sealer::Opened::plain &&
             !(is_reply_to(*datagram, subscribe_) && !datagram->value("ok", true)))) {
            if (!warned_unauthenticated_)
                print_diagnostic("unauthenticated datagram from " + transport_.peer() + " dropped");
            warned_unauthenticated_ = true;
            return;
        }
        if (opened == Sealer::Opened::authentic) {
            datagram->erase("nonce");
            datagram->erase("ts");
        }
        if (is_reply_to(*datagram, subscribe_)) {
            on_reply(*datagram);
        } else if (is_subscription_datagram(*datagram)) {
            mark_subscribed();
            // --changes: the line holds the merged STATE, not the patch.
            const std::string gimbal = datagram->value("gimbal", "");
            auto line = merger_.merge(gimbal, std::move(*datagram));
            if (!line) return;
            print_json(*line, globals_.pretty);
            ++printed_;
            if (count_ > 0 && printed_ >= count_) finish(exit_ok);
        }
    }

    void on_reply(const Json& reply) {
        const bool ok = reply.value("ok", false);
        if (ok) {
            mark_subscribed();
        } else if (!subscribed_) {
            stop(report_reply(reply, globals_.pretty));
        } else {
            // A renewal was refused (daemon restarted with a token, table full, ...): say so
            // and keep trying; the next renewal may succeed.
            print_diagnostic("subscribe renewal failed: " + error_summary(reply));
        }
    }

    void on_error(const boost::system::error_code& error) {
        if (!subscribed_) {
            print_diagnostic("no reply to subscribe from " + transport_.peer() + ": " +
                             error.message());
            stop(exit_no_reply);
        } else if (!warned_unreachable_) {
            // The daemon may be restarting: keep renewing instead of giving up.
            warned_unreachable_ = true;
            print_diagnostic(transport_.peer() + ": " + error.message() + "; still trying");
        }
    }

    void mark_subscribed() {
        subscribed_ = true;
        warned_unreachable_ = false;
        first_reply_deadline_.cancel();
    }

    // A normal end: tell the daemon to stop sending, then stop.
    void finish(int status) {
        transport_.send(sealer_.seal(unsubscribe_for(subscribe_)));
        stop(status);
    }

    void stop(int status) {
        exit_status_ = status;
        first_reply_deadline_.cancel();
        renew_timer_.cancel();
        boost::system::error_code ignored;
        signals_.cancel(ignored);
        transport_.close();
        io_.stop();
    }

    const GlobalOptions& globals_;
    Sealer sealer_;
    bool warned_unauthenticated_ = false;
    const Json& subscribe_;
    const std::int64_t count_;
    asio::io_context io_;
    UdpTransport transport_;
    asio::steady_timer first_reply_deadline_;
    asio::steady_timer renew_timer_;
    asio::signal_set signals_;
    bool subscribed_ = false;
    bool warned_unreachable_ = false;
    std::int64_t printed_ = 0;
    StateMerger merger_;
    int exit_status_ = exit_ok;
};

}  // namespace

int run_watch(const GlobalOptions& globals, const Json& subscribe, std::int64_t count) {
    int status = exit_ok;
    std::optional<SigningKey> key = signing_key_for(globals, status);
    if (status != exit_ok) return status;
    Watch watch(globals, subscribe, count, std::move(key));
    return watch.run();
}

}  // namespace gimbalctl
