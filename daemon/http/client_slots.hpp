// http.max_connections_per_client (contract section 14): how many connections one client
// address holds open, HTTP and WebSocket together, so one host trickling headers or idling
// on WebSockets cannot take every connection from the others. A Slot is held by the
// connection (and then by its WebSocket client) and given back when it goes.
#pragma once

#include <boost/asio/ip/address.hpp>
#include <cstddef>
#include <map>
#include <optional>

namespace gimbald::http {

class ClientSlots {
  public:
    class Slot {
      public:
        Slot() = default;
        Slot(Slot&& other) noexcept;
        Slot& operator=(Slot&& other) noexcept;
        Slot(const Slot&) = delete;
        Slot& operator=(const Slot&) = delete;
        ~Slot();

      private:
        friend class ClientSlots;
        Slot(ClientSlots* owner, boost::asio::ip::address address);
        void release();

        ClientSlots* owner_ = nullptr;
        boost::asio::ip::address address_;
    };

    explicit ClientSlots(std::size_t per_client) : per_client_(per_client) {}
    ClientSlots(const ClientSlots&) = delete;
    ClientSlots& operator=(const ClientSlots&) = delete;

    // A slot for one more connection from `address`, or nullopt when it holds per_client.
    std::optional<Slot> take(const boost::asio::ip::address& address);
    std::size_t open(const boost::asio::ip::address& address) const;
    std::size_t per_client() const { return per_client_; }

  private:
    void give_back(const boost::asio::ip::address& address);

    std::size_t per_client_;
    std::map<boost::asio::ip::address, std::size_t> open_;  // addresses with a slot only
};

}  // namespace gimbald::http
