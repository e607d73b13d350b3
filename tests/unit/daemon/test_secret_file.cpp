// Secret files answer with the result type: the text, or a coded error naming the file.
#include <sys/stat.h>
#include <unistd.h>
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>

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
