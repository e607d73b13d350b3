// An IP address key of a configuration section (command.bind, http.bind,
// vehicle.source.bind): read with its problem reported, written back as text.
#pragma once

#include <boost/asio/ip/address.hpp>
#include <string_view>

#include "config/fields.hpp"

namespace gimbal::daemon {

void read_address(config::Fields& f, std::string_view key, boost::asio::ip::address& out);

template <class V>
void address(V& v, std::string_view key, boost::asio::ip::address& out) {
    if constexpr (V::reading)
        read_address(v, key, out);
    else
        v.string(key, out.to_string());
}

}  // namespace gimbal::daemon
