// What one viewer of /api/video is sent, in order (contract section 18): the configuration
// (text) before the first key frame and again when it changes, then the access units
// (binary). Nothing is sent before a key frame. When more than `backlog_frames` messages
// wait behind the one being written, they are all dropped and the viewer resumes at the next
// key frame: it loses whole groups of pictures, never gets a broken one. No socket here:
// VideoClient writes what front() holds.
#pragma once

#include <cstddef>
#include <deque>
#include <memory>
#include <string>

namespace gimbald::http {

// Shared by every viewer of a gimbal: built once per access unit.
using VideoMessage = std::shared_ptr<const std::string>;

class ViewerQueue {
  public:
    struct Item {
        VideoMessage bytes;
        bool text = false;
    };
    enum class Offer {
        queued,          // the frame (and the configuration before it, if due) was queued
        skipped,         // waiting for a key frame (or for a configuration): not queued
        backlog_dropped  // the backlog was dropped; this frame too unless it is a key frame
    };

    explicit ViewerQueue(std::size_t backlog_frames) : backlog_frames_(backlog_frames) {}

    Offer offer(const VideoMessage& config, const VideoMessage& frame, bool key);

    bool empty() const { return items_.empty(); }
    std::size_t size() const { return items_.size(); }
    const Item& front() const { return items_.front(); }
    bool writing() const { return writing_; }
    // The writer took front() (it stays until written()).
    void start_write() { writing_ = true; }
    void written();
    // A write failed or the viewer went: nothing is in flight any more.
    void abort_write() { writing_ = false; }

  private:
    std::size_t backlog_frames_;
    std::deque<Item> items_;  // front: being written while writing_
    VideoMessage sent_config_;
    bool waiting_key_ = true;
    bool writing_ = false;
};

}  // namespace gimbald::http
