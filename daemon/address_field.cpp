#include "address_field.hpp"

namespace gimbal::daemon {

void read_address(config::Fields& f, std::string_view key, boost::asio::ip::address& out) {
    const auto* value = f.find(key);
    if (value == nullptr) return;
    boost::system::error_code ec;
    if (value->is_string()) {
        auto address = boost::asio::ip::make_address(value->get_ref<const std::string&>(), ec);
        if (!ec) {
            out = address;
            return;
        }
    }
    f.problem(key, "must be an IPv4 or IPv6 address");
}

}  // namespace gimbal::daemon
