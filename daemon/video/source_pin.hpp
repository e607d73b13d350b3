// Which sender a UDP video input takes its stream from (contract section 14 v4,
// `video.source`): the configured one ("host[:port]"; any port when none is given), or else
// the first sender, pinned until it has been silent for a while (5 s), after which the next
// sender is taken. Datagrams from anyone else are counted, not used - a stranger on the
// network can neither feed KLV into STATE nor have it relayed. Pure: times are passed in.
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include <boost/asio/ip/udp.hpp>

namespace gimbald::video {

struct SourceSpec {
    boost::asio::ip::address address;
    std::optional<std::uint16_t> port;  // none: any port of that address
    friend bool operator==(const SourceSpec&, const SourceSpec&) = default;
};

// "ADDR", "ADDR:PORT", "[V6]", "[V6]:PORT" or a bare IPv6 address; numeric only. nullopt and
// `error` set when it is none of them.
std::optional<SourceSpec> parse_source(std::string_view text, std::string& error);
// "ADDR:PORT" ("[V6]:PORT"), an IPv4-mapped IPv6 address shown as IPv4.
std::string to_string(const boost::asio::ip::udp::endpoint& endpoint);

class SourcePin {
  public:
    using Clock = std::chrono::steady_clock;
    enum class Verdict {
        accepted,  // from the source
        pinned,    // from a sender that has just become the source (the first, or after silence)
        foreign,   // from someone else: counted, not to be used
    };

    explicit SourcePin(std::optional<SourceSpec> configured,
                       Clock::duration silence = std::chrono::seconds(5));

    Verdict check(const boost::asio::ip::udp::endpoint& sender, Clock::time_point now);

    // The sender in use: the pinned one, or the last accepted from the configured source.
    std::optional<boost::asio::ip::udp::endpoint> current() const { return current_; }
    std::uint64_t foreign() const { return foreign_; }

  private:
    std::optional<SourceSpec> configured_;
    Clock::duration silence_;
    std::optional<boost::asio::ip::udp::endpoint> current_;
    Clock::time_point last_{};
    std::uint64_t foreign_ = 0;
};

}  // namespace gimbald::video
