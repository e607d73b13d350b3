// Helpers for the link tests: drive an io_context until a condition holds (bounded), record
// what a link reports, and a real TCP peer on loopback.
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/write.hpp>

#include "link/link.hpp"

namespace link_test {

using namespace std::chrono_literals;
using Bytes = std::vector<std::uint8_t>;

// Runs `io` in short slices until `done()` or `limit` passes; returns done().
inline bool run_until(boost::asio::io_context& io, const std::function<bool()>& done,
                      std::chrono::milliseconds limit = 5000ms) {
    const auto deadline = std::chrono::steady_clock::now() + limit;
    while (!done()) {
        if (std::chrono::steady_clock::now() >= deadline) return false;
        if (io.stopped()) io.restart();
        io.run_for(5ms);
    }
    return true;
}

// Runs `io` for a while regardless of conditions (to show that nothing happens).
inline void run_for(boost::asio::io_context& io, std::chrono::milliseconds duration) {
    const auto deadline = std::chrono::steady_clock::now() + duration;
    while (std::chrono::steady_clock::now() < deadline) {
        if (io.stopped()) io.restart();
        io.run_for(5ms);
    }
}

// Everything a link reported through its three handlers.
struct LinkEvents {
    Bytes received;
    int ups = 0;
    int downs = 0;
    std::vector<std::pair<std::string, std::string>> errors;

    void start(gimbald::Link& link) {
        link.start(
            [this](std::span<const std::uint8_t> bytes) {
                received.insert(received.end(), bytes.begin(), bytes.end());
            },
            [this](bool connected) { connected ? ++ups : ++downs; },
            [this](std::string_view what, std::string_view detail) {
                errors.emplace_back(what, detail);
            });
    }
    int count_errors(std::string_view what) const {
        int n = 0;
        for (const auto& e : errors) n += e.first == what ? 1 : 0;
        return n;
    }
    std::string error_detail(std::string_view what) const {
        for (const auto& e : errors) {
            if (e.first == what) return e.second;
        }
        return {};
    }
};

// A TCP server on 127.0.0.1 playing the gimbal: accepts one client at a time, records what it
// receives (when reading is enabled) and writes on request.
class TcpPeer {
  public:
    explicit TcpPeer(boost::asio::io_context& io, std::uint16_t port = 0, int backlog = 16,
                     std::optional<int> receive_buffer = std::nullopt)
        : io_(io), acceptor_(io) {
        namespace asio = boost::asio;
        const asio::ip::tcp::endpoint where(asio::ip::make_address("127.0.0.1"), port);
        acceptor_.open(where.protocol());
        acceptor_.set_option(asio::socket_base::reuse_address(true));
        if (receive_buffer) {
            acceptor_.set_option(asio::socket_base::receive_buffer_size(*receive_buffer));
        }
        acceptor_.bind(where);
        acceptor_.listen(backlog);
    }

    std::uint16_t port() const { return acceptor_.local_endpoint().port(); }

    // Accepts the next client (replacing the current one).
    void accept() {
        acceptor_.async_accept(
            [this](const boost::system::error_code& ec, boost::asio::ip::tcp::socket socket) {
                if (ec) return;
                client_ = std::make_shared<boost::asio::ip::tcp::socket>(std::move(socket));
                ++accepted;
                if (reading_) do_read(client_);
            });
    }

    bool has_client() const { return client_ && client_->is_open(); }

    void set_reading(bool reading) {
        const bool start = reading && !reading_;
        reading_ = reading;
        if (start && client_) do_read(client_);
    }

    void write(Bytes bytes) {
        auto shared = std::make_shared<Bytes>(std::move(bytes));
        boost::asio::async_write(*client_, boost::asio::buffer(*shared),
                                 [shared](const boost::system::error_code&, std::size_t) {});
    }

    void close_client() {
        if (client_) {
            boost::system::error_code ignored;
            client_->close(ignored);
        }
        client_.reset();
    }

    void close_listener() {
        boost::system::error_code ignored;
        acceptor_.close(ignored);
    }

    Bytes received;
    int closed_by_link = 0;
    int accepted = 0;

  private:
    void do_read(const std::shared_ptr<boost::asio::ip::tcp::socket>& client) {
        client->async_read_some(boost::asio::buffer(buffer_),
                                [this, client](const boost::system::error_code& ec, std::size_t n) {
                                    if (ec) {
                                        ++closed_by_link;  // eof (or reset) from the link's side
                                        return;
                                    }
                                    received.insert(
                                        received.end(), buffer_.begin(),
                                        buffer_.begin() + static_cast<std::ptrdiff_t>(n));
                                    if (reading_ && client == client_) do_read(client);
                                });
    }

    boost::asio::io_context& io_;
    boost::asio::ip::tcp::acceptor acceptor_;
    std::shared_ptr<boost::asio::ip::tcp::socket> client_;
    bool reading_ = true;
    std::array<std::uint8_t, 65536> buffer_{};
};

// A loopback TCP port nobody listens on (bound, then released).
inline std::uint16_t unused_tcp_port(boost::asio::io_context& io) {
    TcpPeer probe(io);
    return probe.port();
}

}  // namespace link_test
