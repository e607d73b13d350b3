// gimbalctl keeps JSON keys in the order they were written or received, so requests read
// "cmd" first and replies are printed as the daemon sent them.
#pragma once

#include <nlohmann/json.hpp>

namespace gimbalctl {

using Json = nlohmann::ordered_json;

}  // namespace gimbalctl
