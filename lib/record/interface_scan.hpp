// The interfaces a recording declares, for the readers that pick one stream out of it.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <string>

#include "record/pcapng_reader.hpp"

namespace gimbal::record {

// Calls `visit` for every interface of every section (rotated files repeat them all), also
// those of a section without packets. False with `error` when the file holds no section.
bool scan_interfaces(std::span<const std::uint8_t> file,
                     const std::function<void(const RecordedInterface&)>& visit,
                     std::string& error);

}  // namespace gimbal::record
