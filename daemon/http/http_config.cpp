#include "http/http_config.hpp"

namespace gimbal::daemon {

bool is_xyz_template(const std::string& url) {
    return url.find("{z}") != std::string::npos && url.find("{x}") != std::string::npos &&
           url.find("{y}") != std::string::npos;
}

bool is_bare_host_name(const std::string& name) {
    return !name.empty() && name.find_first_of(":/ []") == std::string::npos;
}

}  // namespace gimbal::daemon
