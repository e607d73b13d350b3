#include "viewer_queue.hpp"

namespace gimbald::http {

ViewerQueue::Offer ViewerQueue::offer(const VideoMessage& config, const VideoMessage& frame,
                                      bool key) {
    Offer result = Offer::queued;
    const std::size_t waiting = items_.size() - (writing_ ? 1 : 0);
    if (waiting >= backlog_frames_) {
        // The message being written stays (a WebSocket message cannot be cut off).
        while (items_.size() > (writing_ ? 1u : 0u)) items_.pop_back();
        waiting_key_ = true;
        result = Offer::backlog_dropped;
    }
    if (waiting_key_) {
        if (!key || !config) return result == Offer::queued ? Offer::skipped : result;
        waiting_key_ = false;
    }
    if (key && config != sent_config_) {
        items_.push_back({config, true});
        sent_config_ = config;
    }
    items_.push_back({frame, false});
    return result;
}

void ViewerQueue::written() {
    writing_ = false;
    if (!items_.empty()) items_.pop_front();
}

}  // namespace gimbald::http
