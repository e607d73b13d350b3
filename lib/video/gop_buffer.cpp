#include "video/gop_buffer.hpp"

namespace gimbal::video {

void GopBuffer::add(const AccessUnit& unit) {
    if (unit.key_frame) clear();
    if (units_.empty() && !unit.key_frame) return;  // waiting for a key frame
    if (units_.size() >= limits_.max_units || bytes_ + unit.data.size() > limits_.max_bytes) {
        clear();
        ++overflows_;
        return;
    }
    units_.emplace_back(unit);
    bytes_ += unit.data.size();
}

void GopBuffer::clear() {
    units_.clear();
    bytes_ = 0;
}

}  // namespace gimbal::video
