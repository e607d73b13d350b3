#include <cstdio>
#include <random>

#include "cli.hpp"
#include "numbers.hpp"

namespace gimbalctl {

Json request_id(const std::optional<std::string>& id_option) {
    if (id_option) {
        const auto number = parse_number(*id_option);
        if (number && number->is_number_integer()) return *number;
        return *id_option;
    }
    // Random, so a late reply to an earlier run that used the same local port is not ours.
    std::random_device entropy;
    std::uniform_int_distribution<std::uint32_t> digits;
    char text[24];
    std::snprintf(text, sizeof text, "gimbalctl-%08x", static_cast<unsigned>(digits(entropy)));
    return std::string(text);
}

}  // namespace gimbalctl
