// systemd service notifications (sd_notify): readiness, status line, stopping, watchdog
// keep-alives. Every call is a no-op when the process was not started by systemd with
// Type=notify (NOTIFY_SOCKET unset), so the daemon calls them unconditionally:
//
//   notify::ready();  notify::status("1/1 gimbals connected");  notify::stopping();
//   if (auto every = notify::watchdog_interval()) ... every *every: notify::watchdog();
#pragma once

#include <chrono>
#include <optional>
#include <string>
#include <string_view>

namespace gimbal::notify {

class Notifier {
  public:
    // Reads NOTIFY_SOCKET, WATCHDOG_USEC and WATCHDOG_PID once, at construction.
    Notifier();

    // True when systemd listens (NOTIFY_SOCKET is set).
    bool active() const { return active_; }

    // Each returns true when systemd got the message.
    // READY=1 (with STATUS= when given): the command socket is bound and links started.
    bool ready(std::string_view status = {}) const;
    // STATUS=<text>: one line for `systemctl status`, e.g. the link states.
    bool status(std::string_view text) const;
    // STOPPING=1: shutdown has begun.
    bool stopping() const;
    // WATCHDOG=1: the event loop is alive.
    bool watchdog() const;

    // How often to call watchdog(): half of WATCHDOG_USEC when systemd's watchdog is enabled
    // for this process, else nothing.
    std::optional<std::chrono::microseconds> watchdog_interval() const { return interval_; }

  private:
    bool send(const std::string& message) const;

    bool active_ = false;
    std::optional<std::chrono::microseconds> interval_;
};

// The process-wide notifier (created on first use).
const Notifier& notifier();
inline bool active() {
    return notifier().active();
}
inline bool ready(std::string_view status = {}) {
    return notifier().ready(status);
}
inline bool status(std::string_view text) {
    return notifier().status(text);
}
inline bool stopping() {
    return notifier().stopping();
}
inline bool watchdog() {
    return notifier().watchdog();
}
inline std::optional<std::chrono::microseconds> watchdog_interval() {
    return notifier().watchdog_interval();
}

}  // namespace gimbal::notify
