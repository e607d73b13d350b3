#include "notify.hpp"

#include <systemd/sd-daemon.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <string>

namespace gimbal::notify {

namespace {

// A notification is newline-separated KEY=VALUE lines: a newline inside the status text
// would start a bogus assignment.
std::string one_line(std::string_view text) {
    std::string line(text);
    std::replace(line.begin(), line.end(), '\n', ' ');
    return line;
}

}  // namespace

Notifier::Notifier() {
    const char* socket = std::getenv("NOTIFY_SOCKET");
    active_ = socket != nullptr && *socket != '\0';
    std::uint64_t usec = 0;
    // > 0 only when WATCHDOG_USEC is set and WATCHDOG_PID, when set, is this process.
    if (sd_watchdog_enabled(0, &usec) > 0 && usec > 0) {
        interval_ = std::chrono::microseconds(static_cast<std::int64_t>(usec / 2));
    }
}

bool Notifier::send(const std::string& message) const {
    if (!active_) return false;
    return sd_notify(0, message.c_str()) > 0;
}

bool Notifier::ready(std::string_view status) const {
    if (status.empty()) return send("READY=1");
    return send("READY=1\nSTATUS=" + one_line(status));
}

bool Notifier::status(std::string_view text) const {
    return send("STATUS=" + one_line(text));
}

bool Notifier::stopping() const {
    return send("STOPPING=1");
}

bool Notifier::watchdog() const {
    return send("WATCHDOG=1");
}

const Notifier& notifier() {
    static const Notifier instance;
    return instance;
}

}  // namespace gimbal::notify
