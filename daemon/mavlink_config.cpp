#include "mavlink_config.hpp"

namespace gimbal::daemon {

bool valid_target(const std::string& text) {
    const auto colon = text.rfind(':');
    if (colon == std::string::npos || colon == 0) return false;
    const std::string digits = text.substr(colon + 1);
    if (digits.empty() || digits.size() > 5 ||
        digits.find_first_not_of("0123456789") != std::string::npos)
        return false;
    const int port = std::stoi(digits);
    return port >= 1 && port <= 65535;
}

}  // namespace gimbal::daemon
