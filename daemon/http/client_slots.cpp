#include "client_slots.hpp"

#include <utility>

namespace gimbald::http {

ClientSlots::Slot::Slot(ClientSlots* owner, boost::asio::ip::address address)
    : owner_(owner), address_(std::move(address)) {}

ClientSlots::Slot::Slot(Slot&& other) noexcept
    : owner_(std::exchange(other.owner_, nullptr)), address_(other.address_) {}

ClientSlots::Slot& ClientSlots::Slot::operator=(Slot&& other) noexcept {
    if (this != &other) {
        release();
        owner_ = std::exchange(other.owner_, nullptr);
        address_ = other.address_;
    }
    return *this;
}

ClientSlots::Slot::~Slot() {
    release();
}

void ClientSlots::Slot::release() {
    if (owner_ != nullptr) owner_->give_back(address_);
    owner_ = nullptr;
}

std::optional<ClientSlots::Slot> ClientSlots::take(const boost::asio::ip::address& address) {
    auto& count = open_[address];
    if (count >= per_client_) {
        if (count == 0) open_.erase(address);  // per_client 0: nothing is ever held
        return std::nullopt;
    }
    ++count;
    return Slot(this, address);
}

std::size_t ClientSlots::open(const boost::asio::ip::address& address) const {
    const auto it = open_.find(address);
    return it == open_.end() ? 0 : it->second;
}

void ClientSlots::give_back(const boost::asio::ip::address& address) {
    const auto it = open_.find(address);
    if (it == open_.end()) return;
    if (--it->second == 0) open_.erase(it);
}

}  // namespace gimbald::http
