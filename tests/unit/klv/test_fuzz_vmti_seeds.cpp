// The fuzz_vmti seeds (tests/fuzz/corpus/vmti, and any saved findings in
// tests/fuzz/regressions/vmti) replayed as ordinary tests with fuzz_vmti's properties: a set
// is refused with a reason, or decodes, encodes and decodes again to itself.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "klv/vmti.hpp"

using namespace gimbal::klv;

TEST_CASE("fuzz_vmti seeds and regressions replay cleanly") {
    std::size_t files = 0, decoded = 0;
    for (const char* folder : {"tests/fuzz/corpus/vmti", "tests/fuzz/regressions/vmti"}) {
        const std::filesystem::path dir = std::filesystem::path(GIMBAL_SOURCE_DIR) / folder;
        if (!std::filesystem::is_directory(dir)) continue;
        for (const auto& entry : std::filesystem::directory_iterator(dir)) {
            INFO(entry.path().string());
            std::ifstream in(entry.path(), std::ios::binary);
            const Bytes bytes((std::istreambuf_iterator<char>(in)),
                              std::istreambuf_iterator<char>());
            ++files;
            const auto set = decode_vmti(bytes);
            if (!set.ok()) {
                CHECK(set.error().message.rfind("VMTI: ", 0) == 0);
                continue;
            }
            ++decoded;
            CHECK_NOTHROW(vmti_json(*set).dump());
            const auto encoded = encode_vmti(*set);
            REQUIRE(encoded.ok());
            const auto again = decode_vmti(*encoded);
            REQUIRE(again.ok());
            CHECK(*again == *set);
        }
    }
    CHECK(files >= 5);
    CHECK(decoded >= 5);
}
