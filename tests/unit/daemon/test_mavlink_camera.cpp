// The streams a camera component announces (contract section 16): the MPEG-TS outputs of the
// gimbal's `video` section.
#include <catch2/catch.hpp>

#include "mavlink_camera.hpp"

using gimbald::camera_streams;

TEST_CASE("camera streams: one per udp output, a port or a multicast group") {
    gimbald::video::VideoConfig video;
    video.input = "udp://0.0.0.0:15004";
    video.outputs = {"udp://127.0.0.1:15010", "klv-udp://127.0.0.1:15011",
                     "udp://239.1.2.3:5600?ttl=4", "udp://[ff02::1]:5601"};
    const auto streams = camera_streams("main", video);
    REQUIRE(streams.size() == 3);
    CHECK(streams[0].name == "main");
    CHECK(streams[0].uri == "15010");  // common.xml: MPEG_TS "URI gives the port number"
    CHECK(streams[0].type == gimbal::mavlink::video_stream::type_mpeg_ts);
    CHECK(streams[1].name == "main 2");
    CHECK(streams[1].uri == "mpegts://239.1.2.3:5600");
    CHECK(streams[2].uri == "mpegts://[ff02::1]:5601");
    video.outputs = {"klv-udp://127.0.0.1:15011"};
    CHECK(camera_streams("main", video).empty());
}
