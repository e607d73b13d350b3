// ST 0601 tag 74 holds a VMTI local set (contract section 20): decode() shows it decoded
// under "vmti"; one that does not decode keeps its hex under "vmti_local_set" with the reason
// under "vmti_error"; a zero-length tag 74 is null ("unknown").
#include <catch2/catch.hpp>

#include "klv/local_set.hpp"
#include "klv/vmti.hpp"

using namespace gimbal::klv;

namespace {

DecodeResult with_tag_74(const Bytes& value) {
    LocalSet set;
    set.add(tag_of("precision_time_stamp"), std::uint64_t{1'700'000'000'000'000});
    set.add(74, value);
    const Encoded e = encode(set);
    REQUIRE(e.ok());
    return decode(e.value());
}

}  // namespace

TEST_CASE("ST 0601 tag 74 decodes as the VMTI set") {
    VmtiSet vmti;
    vmti.frame_width = 1920;
    vmti.frame_height = 1080;
    VmtiTarget t;
    t.id = 3;
    t.centroid = vmti_pixel_number(540, 960, 1920);
    t.confidence_pct = 64;
    vmti.targets.push_back(t);
    const auto bytes = encode_vmti(vmti);
    REQUIRE(bytes.ok());
    const DecodeResult r = with_tag_74(*bytes);
    REQUIRE(r.ok());
    CHECK_FALSE(r.json.contains("vmti_local_set"));
    CHECK_FALSE(r.json.contains("vmti_error"));
    const auto& j = r.json["vmti"];
    CHECK(j["version"] == vmti_version);
    CHECK(j["frame_width"] == 1920);
    REQUIRE(j["targets"].size() == 1);
    CHECK(j["targets"][0]["id"] == 3);
    CHECK(j["targets"][0]["centroid"]["row"] == 540);
    CHECK(j["targets"][0]["centroid"]["column"] == 960);
    CHECK(j["targets"][0]["confidence_level"] == 64);
}

TEST_CASE("ST 0601 tag 74 that is not a VMTI set keeps its hex and says why") {
    const DecodeResult r = with_tag_74({0x08, 0x01, 0x00});  // frame width 0
    REQUIRE(r.ok());
    CHECK_FALSE(r.json.contains("vmti"));
    CHECK(r.json["vmti_local_set"] == "080100");
    CHECK(r.json["vmti_error"] == "VMTI: tag 8 is 0");
}

TEST_CASE("ST 0601 tag 74 of zero length is null") {
    const DecodeResult r = with_tag_74({});
    REQUIRE(r.ok());
    CHECK(r.json["vmti"].is_null());
}
