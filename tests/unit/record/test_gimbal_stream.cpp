// load_gimbal_stream: which gimbal's bytes a replay or export gets out of a recording.
#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "pcapng_builder.hpp"
#include "record/gimbal_stream.hpp"

namespace r = gimbal::record;
using gimbal::test::Builder;
using gimbal::test::Bytes;

namespace {

Bytes pdu(const std::string& dissector, Bytes bytes) {
    return Builder::exported_pdu(dissector, bytes);
}

// Two gimbals and the JSON interface; then a second section (a rotated file appended)
// listing the interfaces in another order.
Bytes two_gimbals(bool cut_last = false) {
    Builder b(false);
    b.shb()
        .idb("gimbal:main", 6, 252, 0, "orion tcp 127.0.0.1:8747")
        .idb("gimbal:nose", 6, 252, 0, "viewpro serial /dev/ttyUSB0")
        .idb("json");
    b.epb(0, 10, pdu("orion", {1, 2}), 1);
    b.epb(0, 11, pdu("orion", {9}), 2);  // a command gimbald sent: not played
    b.epb(1, 12, pdu("viewpro", {7}), 1);
    b.epb(2, 13, pdu("gimbald-json", {'{', '}'}), 1);
    b.epb(0, 14, pdu("data", {3}), 1);          // junk is part of what the gimbal sent
    b.epb(0, 15, {0x00, 0x0C, 0x00, 0x40}, 1);  // malformed tags: skipped, counted
    b.shb().idb("json").idb("gimbal:nose", 6, 252, 0, "viewpro serial /dev/ttyUSB0");
    b.idb("gimbal:main", 6, 252, 0, "orion tcp 127.0.0.1:8747");
    b.epb(2, 20, pdu("orion", {4, 5}), 1);
    b.epb(1, 21, pdu("viewpro", {8}), 1);
    if (cut_last) b.out.resize(b.out.size() - 5);
    return b.out;
}

}  // namespace

TEST_CASE("a named gimbal's inbound bytes, in order, across sections", "[record]") {
    const auto file = two_gimbals();
    r::GimbalStream s;
    std::string error;
    REQUIRE(r::load_gimbal_stream(file, "main", s, error));
    CHECK(s.gimbal.name == "main");
    CHECK(s.gimbal.protocol == "orion");
    CHECK(s.all_gimbals.size() == 2);
    REQUIRE(s.chunks.size() == 3);
    CHECK(s.chunks[0].time_us == 10);
    CHECK(s.chunks[0].bytes == Bytes{1, 2});
    CHECK(s.chunks[1].bytes == Bytes{3});
    CHECK(s.chunks[2].time_us == 20);
    CHECK(s.chunks[2].bytes == Bytes{4, 5});
    CHECK(s.bytes == 5);
    CHECK(s.outbound_pdus == 1);
    CHECK(s.bad_pdus == 1);
    CHECK(s.stop == r::Stop::end);

    REQUIRE(r::load_gimbal_stream(file, "nose", s, error));
    CHECK(s.gimbal.protocol == "viewpro");
    REQUIRE(s.chunks.size() == 2);
    CHECK(s.chunks[1].bytes == Bytes{8});
}

TEST_CASE("choosing a gimbal", "[record]") {
    r::GimbalStream s;
    std::string error;
    CHECK_FALSE(r::load_gimbal_stream(two_gimbals(), "", s, error));
    CHECK(error.find("several gimbals (main, nose)") != std::string::npos);
    CHECK_FALSE(r::load_gimbal_stream(two_gimbals(), "json", s, error));
    CHECK(error.find("no gimbal \"json\"") != std::string::npos);

    Builder one(true);
    one.shb().idb("gimbal:solo").epb(0, 5, pdu("viewpro", {1}), 1);  // protocol from the PDUs
    REQUIRE(r::load_gimbal_stream(one.out, "", s, error));
    CHECK(s.gimbal.name == "solo");
    CHECK(s.gimbal.protocol == "viewpro");

    Builder none(false);
    none.shb().idb("json");
    CHECK_FALSE(r::load_gimbal_stream(none.out, "", s, error));
    CHECK(error.find("no gimbal interface") != std::string::npos);
    CHECK_FALSE(r::load_gimbal_stream(Bytes{}, "", s, error));
    CHECK_FALSE(r::load_gimbal_stream(Bytes(64, 0x11), "", s, error));
    CHECK(error.find("not a pcapng file") != std::string::npos);
}

TEST_CASE("a cut-short recording gives what came before and says so", "[record]") {
    r::GimbalStream s;
    std::string error;
    REQUIRE(r::load_gimbal_stream(two_gimbals(true), "nose", s, error));
    CHECK(s.stop == r::Stop::truncated);
    CHECK_FALSE(s.stop_message.empty());
    REQUIRE(s.chunks.size() == 1);
    CHECK(s.chunks[0].bytes == Bytes{7});
}

TEST_CASE("rotated files read as one recording, a cut one in the middle included", "[record]") {
    namespace fs = std::filesystem;
    const fs::path dir =
        fs::temp_directory_path() / ("gimbal-stream-test-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const auto write = [&](const std::string& name, const Bytes& bytes) {
        std::ofstream(dir / name, std::ios::binary)
            .write(reinterpret_cast<const char*>(bytes.data()),
                   static_cast<std::streamsize>(bytes.size()));
        return (dir / name).string();
    };
    const std::string first = write("1.pcapng", two_gimbals(true));  // cut: its last PDU lost
    const std::string second = write("2.pcapng", two_gimbals());
    r::GimbalStream s;
    std::vector<std::string> warnings;
    std::string error;
    REQUIRE(r::load_gimbal_files({first, second}, "main", s, warnings, error));
    CHECK(s.gimbal.protocol == "orion");
    CHECK(s.chunks.size() == 6);  // 3 from each: the cut lost only a Viewpro PDU
    REQUIRE(warnings.size() >= 1);
    CHECK(warnings[0].find("1.pcapng: truncated") != std::string::npos);
    CHECK(s.stop == r::Stop::end);  // of the last file

    warnings.clear();
    CHECK_FALSE(
        r::load_gimbal_files({second, (dir / "missing").string()}, "main", s, warnings, error));
    CHECK(error.find("missing: cannot open") != std::string::npos);
    fs::remove_all(dir);
}
