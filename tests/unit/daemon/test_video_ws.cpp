// The video WebSocket's pure parts (contract section 18, docs/http.md): which gimbal a
// /api/video path names, and the binary message of one access unit.
#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "http/http_api.hpp"
#include "http/video_feeds.hpp"

using gimbald::http::video_frame_message;
using gimbald::http::video_gimbal;

TEST_CASE("Video WebSocket: the gimbal named by the path", "[http][video]") {
    CHECK(video_gimbal("/api/video/main") == "main");
    CHECK(video_gimbal("/api/video/sim-orion") == "sim-orion");
    CHECK(video_gimbal("/api/video/a%2Db") == "a-b");
    CHECK_FALSE(video_gimbal("/api/video/"));
    CHECK_FALSE(video_gimbal("/api/video"));
    CHECK_FALSE(video_gimbal("/api/video/a/b"));
    CHECK_FALSE(video_gimbal("/api/video/a%2Fb"));
    CHECK_FALSE(video_gimbal("/api/video/%zz"));
    CHECK_FALSE(video_gimbal("/api/stream"));
}

TEST_CASE("Video WebSocket: timestamp in microseconds, key flag, the access unit",
          "[http][video]") {
    const std::vector<std::uint8_t> au = {0, 0, 0, 1, 0x65, 0x88, 0x80};
    gimbal::video::AccessUnit unit;
    unit.pts = 90'000ull * 3600 + 3;  // one hour and 3 ticks: 3'600'000'033 us
    unit.key_frame = true;
    unit.data = au;
    const std::string m = video_frame_message(unit);
    REQUIRE(m.size() == 9 + au.size());
    std::uint64_t us = 0;
    for (int i = 0; i < 8; ++i)
        us = (us << 8) | static_cast<std::uint8_t>(m[static_cast<std::size_t>(i)]);
    CHECK(us == 3'600'000'033ull);
    CHECK(m[8] == 1);
    CHECK(std::string(m.begin() + 9, m.end()) == std::string(au.begin(), au.end()));

    unit.key_frame = false;
    unit.pts.reset();
    unit.dts = (std::uint64_t{1} << 33) - 1;  // the largest 33-bit value: no overflow
    const std::string d = video_frame_message(unit);
    us = 0;
    for (int i = 0; i < 8; ++i)
        us = (us << 8) | static_cast<std::uint8_t>(d[static_cast<std::size_t>(i)]);
    CHECK(us == ((std::uint64_t{1} << 33) - 1) * 100 / 9);
    CHECK(d[8] == 0);

    unit.dts.reset();
    CHECK(video_frame_message(unit).substr(0, 9) == std::string(9, '\0'));
}
