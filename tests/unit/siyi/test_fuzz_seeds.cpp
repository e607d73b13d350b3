// The fuzz_siyi seeds (tests/fuzz/corpus/siyi, and tests/fuzz/regressions/siyi once it has
// findings) replayed as ordinary tests: every frame in them decodes as its seed says, and the
// simulated gimbal answers the controller's session with whole, decodable frames.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "protocols/siyi/codec/json.hpp"
#include "sim_rig.hpp"
#include "vectors.hpp"

using namespace gimbal::siyi;
using namespace siyi_test;

namespace {

Bytes read_file(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return Bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

}  // namespace

TEST_CASE("fuzz_siyi seeds and regressions replay cleanly", "[siyi][fuzz]") {
    std::size_t files = 0, frames = 0;
    for (const char* folder : {"tests/fuzz/corpus/siyi", "tests/fuzz/regressions/siyi"}) {
        const std::filesystem::path dir = std::filesystem::path(GIMBAL_SOURCE_DIR) / folder;
        if (!std::filesystem::is_directory(dir)) continue;
        for (const auto& entry : std::filesystem::directory_iterator(dir)) {
            INFO(entry.path().string());
            const Bytes bytes = read_file(entry.path());
            ++files;
            Framer framer;
            std::uint64_t delivered = 0;
            framer.push(bytes, [&](const Frame& f) {
                ++frames;
                delivered += f.wire_size();
                const auto d = f.is_ack() ? frame_to_json(f, Direction::from_gimbal)
                                          : frame_to_json(f, Direction::to_gimbal);
                CHECK_NOTHROW(d.dump());
                // The seeds are the SDK's examples and well-formed replies and requests,
                // except the MK15's datalink command.
                if (f.cmd != 0x40) CHECK_FALSE(d.contains("error"));
            });
            const auto& s = framer.stats();
            CHECK(s.bytes == delivered + s.dropped_bytes + framer.pending_bytes());
            // Only the session seed has junk, one false start of it a whole false frame.
            CHECK(s.bad_checksums <= 1);

            Rig rig;
            rig.send_bytes(bytes);
            rig.run(1.0);
            Framer check;
            (void)check.push(rig.raw);
            CHECK(check.stats().dropped_bytes == 0);
            CHECK(check.pending_bytes() == 0);
        }
    }
    CHECK(files >= 15);
    CHECK(frames >= 30);
}

TEST_CASE("the controller session seed drives the simulated gimbal", "[siyi][fuzz]") {
    const Bytes session = read_file(std::filesystem::path(GIMBAL_SOURCE_DIR) /
                                    "tests/fuzz/corpus/siyi/session_with_junk.bin");
    Rig rig;
    rig.send_bytes(session);
    rig.run(2.0);
    CHECK(rig.last<HardwareId>().id.substr(0, 2) == "7A");
    CHECK(rig.all<GimbalAttitude>().size() > 20);  // the 20 Hz stream it asks for
    CHECK(rig.last<FunctionFeedback>().info == FeedbackInfo::record_started);
    CHECK(rig.sim.recording());
    CHECK(rig.sim.stats().unknown == 0);
    CHECK(rig.sim.stats().too_short == 0);
    CHECK(rig.sim.framer_stats().dropped_bytes == 7);  // the junk: 55 12, and 55 66 01 20 00
}
