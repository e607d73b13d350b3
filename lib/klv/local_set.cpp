#include "klv/local_set.hpp"

namespace gimbal::klv {

LocalSet& LocalSet::add(std::uint32_t tag, Value value, std::uint8_t length) {
    items.push_back({tag, std::move(value), length});
    return *this;
}

}  // namespace gimbal::klv
