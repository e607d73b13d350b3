// TCP server for one controller at a time: a new connection replaces the current one.
#pragma once

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/steady_timer.hpp>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "byte_port.hpp"

namespace gimbal_sim {

class TcpServer {
  public:
    // Called with true when a client connects and false when it goes away.
    using ClientHandler = std::function<void(bool connected, const std::string& peer)>;

    // Binds and listens at once; throws on failure (startup error). `receive_buffer`: the
    // clients' SO_RCVBUF (small, so a client that is not read from backs up at once).
    TcpServer(boost::asio::io_context& io, const std::string& address, std::uint16_t port,
              BytesHandler on_bytes, ClientHandler on_client,
              std::optional<int> receive_buffer = std::nullopt);

    boost::asio::ip::tcp::endpoint local_endpoint() const;
    void start();
    void stop();
    // Reads only what the policy allows (fault injection); without one, as fast as it comes.
    void set_read_policy(ReadPolicy policy) { read_policy_ = std::move(policy); }

    bool has_client() const { return client_ != nullptr; }
    // Queues bytes for the client; dropped when there is none or it lags by over 1 MB.
    void write(std::span<const std::uint8_t> bytes);
    // Closes the current client (fault injection); the server keeps listening.
    void drop_client();
    std::uint64_t dropped_bytes() const { return dropped_bytes_; }
    // Bytes queued for the client and not yet written (gimbal-replay drains them at its end).
    std::size_t queued_bytes() const { return client_ ? client_->queued_bytes : 0; }

  private:
    struct Client {
        explicit Client(boost::asio::ip::tcp::socket s) : socket(std::move(s)) {}
        boost::asio::ip::tcp::socket socket;
        std::string peer;
        std::vector<std::uint8_t> read_buffer = std::vector<std::uint8_t>(4096);
        std::deque<std::vector<std::uint8_t>> queue;
        std::size_t queued_bytes = 0;
        bool writing = false;
    };

    void do_accept();
    void do_read(const std::shared_ptr<Client>& client);
    void do_write(const std::shared_ptr<Client>& client);
    void close(std::shared_ptr<Client> client);  // by value: it may reset client_

    boost::asio::ip::tcp::acceptor acceptor_;
    boost::asio::steady_timer read_timer_;
    ReadPolicy read_policy_;
    BytesHandler on_bytes_;
    ClientHandler on_client_;
    std::shared_ptr<Client> client_;
    std::uint64_t dropped_bytes_ = 0;
    bool stopped_ = false;
};

}  // namespace gimbal_sim
