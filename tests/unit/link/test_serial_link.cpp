#include <catch2/catch.hpp>

#include <fcntl.h>
#include <pty.h>
#include <termios.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include "link/serial_link.hpp"
#include "link_test_support.hpp"

using namespace link_test;
using gimbald::SerialLink;
using gimbald::SerialLinkOptions;
namespace fs = std::filesystem;

namespace {

// A pseudo-terminal: the link opens the slave side, the test plays the gimbal on the master.
class Pty {
  public:
    Pty() {
        if (::openpty(&master_, &slave_, nullptr, nullptr, nullptr) != 0) {
            throw std::runtime_error("openpty failed");
        }
        slave_path_ = ::ttyname(slave_);
        ::fcntl(master_, F_SETFL, ::fcntl(master_, F_GETFL) | O_NONBLOCK);
    }
    ~Pty() { close(); }
    Pty(const Pty&) = delete;
    Pty& operator=(const Pty&) = delete;

    const std::string& slave_path() const { return slave_path_; }
    int slave() const { return slave_; }

    void write(const Bytes& bytes) {
        REQUIRE(::write(master_, bytes.data(), bytes.size()) == static_cast<ssize_t>(bytes.size()));
    }
    // Appends whatever the link has written so far.
    void read_into(Bytes& out) {
        std::array<std::uint8_t, 4096> buffer{};
        for (;;) {
            const ssize_t n = ::read(master_, buffer.data(), buffer.size());
            if (n <= 0) return;
            out.insert(out.end(), buffer.begin(), buffer.begin() + n);
        }
    }
    void close() {
        if (master_ >= 0) ::close(master_);
        if (slave_ >= 0) ::close(slave_);
        master_ = slave_ = -1;
    }

  private:
    int master_ = -1;
    int slave_ = -1;
    std::string slave_path_;
};

// A private directory holding the symlink the link is configured with.
class TempDir {
  public:
    TempDir() {
        std::string pattern = (fs::temp_directory_path() / "gimbald-link-XXXXXX").string();
        if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
        path_ = pattern;
    }
    ~TempDir() {
        std::error_code ignored;
        fs::remove_all(path_, ignored);
    }
    const fs::path& path() const { return path_; }

  private:
    fs::path path_;
};

// Points `link` at `target`, atomically (like udev replacing /dev/serial/by-id links).
void point_symlink(const fs::path& link, const std::string& target) {
    const fs::path temporary = link.string() + ".new";
    fs::remove(temporary);
    fs::create_symlink(target, temporary);
    fs::rename(temporary, link);
}

SerialLinkOptions serial_options(const std::string& device) {
    SerialLinkOptions options;
    options.device = device;
    options.baud = 115200;
    options.reconnect_min_s = 0.02;
    options.reconnect_max_s = 0.1;
    return options;
}

Bytes every_byte_value() {
    Bytes bytes(256);
    for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<std::uint8_t>(i);
    return bytes;
}

}  // namespace

TEST_CASE("serial link carries every byte value both ways over a pty in raw 8N1", "[serial]") {
    boost::asio::io_context io;
    Pty pty;
    SerialLink link(io, serial_options(pty.slave_path()));
    CHECK(link.type() == "serial");
    CHECK(link.endpoint() == pty.slave_path() + "@115200");
    LinkEvents events;
    events.start(link);
    REQUIRE(run_until(io, [&] { return link.connected(); }));
    CHECK(events.ups == 1);

    termios tio{};
    REQUIRE(::tcgetattr(pty.slave(), &tio) == 0);
    CHECK(::cfgetospeed(&tio) == B115200);
    CHECK(::cfgetispeed(&tio) == B115200);
    CHECK((tio.c_cflag & CSIZE) == CS8);
    CHECK((tio.c_cflag & (PARENB | CSTOPB | CRTSCTS)) == 0);
    CHECK((tio.c_lflag & (ECHO | ICANON | ISIG)) == 0);
    CHECK((tio.c_iflag & (IXON | IXOFF | ICRNL)) == 0);
    CHECK((tio.c_oflag & OPOST) == 0);

    // 0x03 (^C), 0x0A/0x0D (line ends), 0x11/0x13 (XON/XOFF) must all pass untouched.
    const Bytes all = every_byte_value();
    CHECK(link.send(all));
    Bytes at_gimbal;
    REQUIRE(run_until(io, [&] {
        pty.read_into(at_gimbal);
        return at_gimbal.size() >= all.size();
    }));
    CHECK(at_gimbal == all);

    pty.write(all);
    REQUIRE(run_until(io, [&] { return events.received.size() >= all.size(); }));
    CHECK(events.received == all);
    CHECK(link.stats().rx_bytes == all.size());
    CHECK(link.stats().tx_bytes == all.size());
}

TEST_CASE("serial link waits for a device that is missing at start", "[serial]") {
    boost::asio::io_context io;
    TempDir dir;
    const fs::path device = dir.path() / "gimbal-tty";
    SerialLink link(io, serial_options(device.string()));
    LinkEvents events;
    events.start(link);
    REQUIRE(run_until(io, [&] { return events.count_errors("open") >= 2; }));
    CHECK_FALSE(link.connected());
    CHECK_THAT(events.error_detail("open"), Catch::Contains("No such file"));

    Pty pty;
    point_symlink(device, pty.slave_path());
    REQUIRE(run_until(io, [&] { return link.connected(); }));
    CHECK(events.ups == 1);
    CHECK(link.stats().reconnects == 0);

    pty.write({0xD0, 0x0D});
    REQUIRE(run_until(io, [&] { return events.received.size() >= 2; }));
    CHECK(events.received == Bytes{0xD0, 0x0D});
}

TEST_CASE("serial link reconnects when the pty behind its symlink is replaced", "[serial]") {
    boost::asio::io_context io;
    TempDir dir;
    const fs::path device = dir.path() / "gimbal-tty";
    auto first = std::make_unique<Pty>();
    point_symlink(device, first->slave_path());
    SerialLink link(io, serial_options(device.string()));
    LinkEvents events;
    events.start(link);
    REQUIRE(run_until(io, [&] { return link.connected(); }));

    first->close();  // the gimbal goes away (like a USB unplug)
    REQUIRE(run_until(io, [&] { return events.downs == 1; }));
    CHECK_FALSE(link.connected());
    CHECK_FALSE(link.send({1}));

    Pty second;
    point_symlink(device, second.slave_path());
    REQUIRE(run_until(io, [&] { return events.ups == 2 && link.connected(); }));
    CHECK(link.stats().reconnects == 1);

    CHECK(link.send({1, 2, 3}));
    Bytes at_gimbal;
    REQUIRE(run_until(io, [&] {
        second.read_into(at_gimbal);
        return at_gimbal.size() >= 3;
    }));
    CHECK(at_gimbal == Bytes{1, 2, 3});
    second.write({4, 5});
    REQUIRE(run_until(io, [&] { return events.received.size() >= 2; }));
    CHECK(events.received == Bytes{4, 5});
}

TEST_CASE("serial link send_now writes synchronously", "[serial]") {
    boost::asio::io_context io;
    Pty pty;
    SerialLink link(io, serial_options(pty.slave_path()));
    LinkEvents events;
    events.start(link);
    REQUIRE(run_until(io, [&] { return link.connected(); }));
    REQUIRE(link.send({1, 2}));
    link.send_now(Bytes{3, 4});
    // Written before the io_context ran again: the queued packet first, then the new one.
    CHECK(link.stats().tx_packets == 2);
    CHECK(link.stats().tx_bytes == 4);
    Bytes at_gimbal;
    REQUIRE(run_until(io, [&] {
        pty.read_into(at_gimbal);
        return at_gimbal.size() >= 4;
    }));
    CHECK(at_gimbal == Bytes{1, 2, 3, 4});
}

TEST_CASE("serial link rejects a baud rate termios does not know", "[serial]") {
    boost::asio::io_context io;
    SerialLinkOptions options = serial_options("/dev/null");
    options.baud = 12345;
    CHECK_THROWS_AS(SerialLink(io, options), std::invalid_argument);
    CHECK(gimbald::baud_to_speed(115200) == B115200);
    CHECK_FALSE(gimbald::baud_to_speed(0).has_value());
}
