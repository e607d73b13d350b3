#include "tcp_server.hpp"

#include <algorithm>
#include <boost/asio/buffer.hpp>
#include <boost/asio/write.hpp>
#include <chrono>

namespace gimbal_sim {

namespace asio = boost::asio;
using asio::ip::tcp;

namespace {
constexpr std::size_t max_queued_bytes = 1 << 20;

std::string describe(const tcp::endpoint& e) {
    return e.address().to_string() + ":" + std::to_string(e.port());
}
}  // namespace

TcpServer::TcpServer(asio::io_context& io, const std::string& address, std::uint16_t port,
                     BytesHandler on_bytes, ClientHandler on_client,
                     std::optional<int> receive_buffer)
    : acceptor_(io),
      read_timer_(io),
      on_bytes_(std::move(on_bytes)),
      on_client_(std::move(on_client)) {
    const tcp::endpoint endpoint(asio::ip::make_address(address), port);
    acceptor_.open(endpoint.protocol());
    acceptor_.set_option(asio::socket_base::reuse_address(true));
    // Set before listen(): accepted sockets inherit it, and the window is sized from it.
    if (receive_buffer)
        acceptor_.set_option(asio::socket_base::receive_buffer_size(*receive_buffer));
    acceptor_.bind(endpoint);
    acceptor_.listen();
}

tcp::endpoint TcpServer::local_endpoint() const {
    return acceptor_.local_endpoint();
}

void TcpServer::start() {
    do_accept();
}

void TcpServer::stop() {
    stopped_ = true;
    read_timer_.cancel();
    boost::system::error_code ignored;
    acceptor_.close(ignored);
    if (client_) close(client_);
}

void TcpServer::do_accept() {
    acceptor_.async_accept([this](const boost::system::error_code& ec, tcp::socket socket) {
        if (stopped_) return;
        if (!ec) {
            if (client_) close(client_);  // the newest controller wins
            boost::system::error_code ignored;
            socket.set_option(tcp::no_delay(true), ignored);
            auto client = std::make_shared<Client>(std::move(socket));
            const auto peer = client->socket.remote_endpoint(ignored);
            client->peer = describe(peer);
            client_ = client;
            if (on_client_) on_client_(true, client->peer);
            do_read(client);
        }
        do_accept();
    });
}

void TcpServer::do_read(const std::shared_ptr<Client>& client) {
    std::size_t limit = client->read_buffer.size();
    if (read_policy_) {
        const ReadBudget budget = read_policy_();
        if (budget.bytes == 0) {  // not now: the kernel's buffers fill meanwhile
            read_timer_.expires_after(std::chrono::duration_cast<std::chrono::nanoseconds>(
                std::chrono::duration<double>(budget.retry_after_s)));
            read_timer_.async_wait([this, client](const boost::system::error_code& ec) {
                if (!ec && client == client_) do_read(client);
            });
            return;
        }
        limit = std::min(limit, budget.bytes);
    }
    client->socket.async_read_some(
        asio::buffer(client->read_buffer.data(), limit),
        [this, client](const boost::system::error_code& ec, std::size_t n) {
            if (client != client_) return;  // replaced or closed meanwhile
            if (ec) {
                close(client);
                return;
            }
            if (on_bytes_) on_bytes_({client->read_buffer.data(), n});
            if (client == client_) do_read(client);
        });
}

void TcpServer::write(std::span<const std::uint8_t> bytes) {
    if (bytes.empty()) return;
    if (!client_ || client_->queued_bytes + bytes.size() > max_queued_bytes) {
        dropped_bytes_ += bytes.size();
        return;
    }
    client_->queue.emplace_back(bytes.begin(), bytes.end());
    client_->queued_bytes += bytes.size();
    if (!client_->writing) do_write(client_);
}

void TcpServer::do_write(const std::shared_ptr<Client>& client) {
    client->writing = true;
    asio::async_write(client->socket, asio::buffer(client->queue.front()),
                      [this, client](const boost::system::error_code& ec, std::size_t) {
                          client->writing = false;
                          if (client != client_) return;
                          if (ec) {
                              close(client);
                              return;
                          }
                          client->queued_bytes -= client->queue.front().size();
                          client->queue.pop_front();
                          if (!client->queue.empty()) do_write(client);
                      });
}

void TcpServer::drop_client() {
    if (client_) close(client_);
}

void TcpServer::close(std::shared_ptr<Client> client) {
    boost::system::error_code ignored;
    client->socket.shutdown(tcp::socket::shutdown_both, ignored);
    client->socket.close(ignored);
    if (client == client_) {
        client_.reset();
        if (on_client_ && !stopped_) on_client_(false, client->peer);
    }
}

}  // namespace gimbal_sim
