// systemd notifications (notify.hpp) against a real AF_UNIX datagram socket.
#include <catch2/catch.hpp>

#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>

#include "notify.hpp"
namespace {

// Sets an environment variable for the scope of a test.
struct ScopedEnv {
    std::string name;
    ScopedEnv(std::string n, const std::string& value) : name(std::move(n)) {
        setenv(name.c_str(), value.c_str(), 1);
    }
    ~ScopedEnv() { unsetenv(name.c_str()); }
};

// A datagram socket standing in for systemd's notify socket.
struct NotifySocket {
    std::string path;
    int fd = -1;
    NotifySocket() {
        path = (std::filesystem::temp_directory_path() /
                ("gimbald-notify-" + std::to_string(getpid()) + ".sock"))
                   .string();
        std::filesystem::remove(path);
        fd = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
        REQUIRE(fd >= 0);
        sockaddr_un addr{};
        addr.sun_family = AF_UNIX;
        REQUIRE(path.size() < sizeof addr.sun_path);
        std::memcpy(addr.sun_path, path.c_str(), path.size() + 1);
        REQUIRE(bind(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) == 0);
        timeval timeout{2, 0};  // a missing message fails the test instead of hanging it
        setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
    }
    ~NotifySocket() {
        close(fd);
        std::filesystem::remove(path);
    }
    std::string receive() const {
        char buffer[1024];
        const auto n = recv(fd, buffer, sizeof buffer, 0);
        return n > 0 ? std::string(buffer, static_cast<std::size_t>(n)) : std::string();
    }
};

}  // namespace

TEST_CASE("systemd notifications are no-ops without NOTIFY_SOCKET", "[notify]") {
    unsetenv("NOTIFY_SOCKET");
    unsetenv("WATCHDOG_USEC");
    const gimbal::notify::Notifier notifier;
    CHECK_FALSE(notifier.active());
    CHECK_FALSE(notifier.ready());
    CHECK_FALSE(notifier.status("x"));
    CHECK_FALSE(notifier.stopping());
    CHECK_FALSE(notifier.watchdog());
    CHECK_FALSE(notifier.watchdog_interval());
}

TEST_CASE("systemd notifications reach the notify socket", "[notify]") {
    NotifySocket systemd;
    ScopedEnv socket("NOTIFY_SOCKET", systemd.path);
    const gimbal::notify::Notifier notifier;
    REQUIRE(notifier.active());

    CHECK(notifier.ready());
    CHECK(systemd.receive() == "READY=1");
    CHECK(notifier.ready("1/2 gimbals connected"));
    CHECK(systemd.receive() == "READY=1\nSTATUS=1/2 gimbals connected");
    CHECK(notifier.status("main up,\nnose down"));
    CHECK(systemd.receive() == "STATUS=main up, nose down");
    CHECK(notifier.watchdog());
    CHECK(systemd.receive() == "WATCHDOG=1");
    CHECK(notifier.stopping());
    CHECK(systemd.receive() == "STOPPING=1");
}

TEST_CASE("the watchdog interval is half of WATCHDOG_USEC", "[notify]") {
    using std::chrono::microseconds;
    SECTION("enabled for this process") {
        ScopedEnv usec("WATCHDOG_USEC", "10000000");
        ScopedEnv pid("WATCHDOG_PID", std::to_string(getpid()));
        CHECK(gimbal::notify::Notifier().watchdog_interval() == microseconds(5000000));
    }
    SECTION("enabled without WATCHDOG_PID") {
        ScopedEnv usec("WATCHDOG_USEC", "3000");
        CHECK(gimbal::notify::Notifier().watchdog_interval() == microseconds(1500));
    }
    SECTION("meant for another process") {
        ScopedEnv usec("WATCHDOG_USEC", "10000000");
        ScopedEnv pid("WATCHDOG_PID", std::to_string(getpid() + 1));
        CHECK_FALSE(gimbal::notify::Notifier().watchdog_interval());
    }
    SECTION("not enabled") {
        unsetenv("WATCHDOG_USEC");
        CHECK_FALSE(gimbal::notify::Notifier().watchdog_interval());
    }
}
