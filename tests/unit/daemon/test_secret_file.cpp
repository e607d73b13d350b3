// Secret files answer with the result type: the text, or a coded error naming the file.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <catch2/catch.hpp>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "secret_file.hpp"

using gimbal::command::ErrorCode;
using gimbal::daemon::read_secret_file;
namespace fs = std::filesystem;

namespace {

fs::path temp_file(const std::string& text, mode_t mode) {
    const fs::path p = fs::temp_directory_path() / ("gimbald-secret-" + std::to_string(::getpid()) +
                                                    "-" + std::to_string(mode));
    std::ofstream(p) << text;
    ::chmod(p.c_str(), mode);
    return p;
}

}  // namespace

TEST_CASE("read_secret_file: text, or unavailable / forbidden / bad_request") {
    const auto good = temp_file("s3cret", 0600);
    auto text = read_secret_file(good.string());
    REQUIRE(text);
    CHECK(*text == "s3cret");

    const auto open = temp_file("s3cret", 0644);
    auto refused = read_secret_file(open.string());
    REQUIRE_FALSE(refused);
    CHECK(refused.error().code == ErrorCode::forbidden);
    CHECK(refused.error().message ==
          open.string() + ": readable by group or others (mode 0644); chmod 600 it");

    auto missing = read_secret_file((good.string() + ".none"));
    REQUIRE_FALSE(missing);
    CHECK(missing.error().code == ErrorCode::unavailable);
    CHECK(missing.error().message == good.string() + ".none: missing");

    auto directory = read_secret_file(fs::temp_directory_path().string());
    REQUIRE_FALSE(directory);
    CHECK(directory.error().code == ErrorCode::bad_request);
    fs::remove(good);
    fs::remove(open);
}

TEST_CASE("read_secret_file: a FIFO or a device is refused, not waited on or read") {
    // Issue 25: a key file that is a FIFO hung --check-config and the start.
    const fs::path fifo =
        fs::temp_directory_path() / ("gimbald-secret-fifo-" + std::to_string(::getpid()));
    REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
    // Were the FIFO waited on, this writer would end the wait after 2 s with nothing to read;
    // the message below tells the two apart without hanging the test.
    std::thread unblock([&fifo] {
        std::this_thread::sleep_for(std::chrono::seconds(2));
        const int fd = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
        if (fd >= 0) ::close(fd);
    });
    auto refused = read_secret_file(fifo.string());
    unblock.join();
    fs::remove(fifo);
    REQUIRE_FALSE(refused);
    CHECK(refused.error().code == ErrorCode::bad_request);
    CHECK(refused.error().message == fifo.string() + ": not a regular file (a FIFO)");
    auto zero = read_secret_file("/dev/zero");
    REQUIRE_FALSE(zero);
    CHECK(zero.error().message == "/dev/zero: not a regular file (a character device)");
    const auto big =
        fs::temp_directory_path() / ("gimbald-secret-big-" + std::to_string(::getpid()));
    std::ofstream(big) << std::string(64 * 1024 + 1, 'a');
    ::chmod(big.c_str(), 0600);
    auto large = read_secret_file(big.string());
    fs::remove(big);
    REQUIRE_FALSE(large);
    CHECK(large.error().message == big.string() + ": larger than 64 KiB: not a secret file");
}
