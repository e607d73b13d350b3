// The fuzz_klv seeds and saved findings (tests/fuzz/corpus/klv, tests/fuzz/regressions/klv)
// replayed as ordinary tests: each file's sets decode without reading past the set, and a
// well-formed set relayed item by item decodes to the same values.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "klv/local_set.hpp"

using namespace gimbal::klv;

TEST_CASE("fuzz_klv seeds and regressions replay cleanly") {
    std::size_t files = 0;
    for (const char* folder : {"tests/fuzz/corpus/klv", "tests/fuzz/regressions/klv"}) {
        const std::filesystem::path dir = std::filesystem::path(GIMBAL_SOURCE_DIR) / folder;
        REQUIRE(std::filesystem::is_directory(dir));
        for (const auto& entry : std::filesystem::directory_iterator(dir)) {
            INFO(entry.path().string());
            std::ifstream in(entry.path(), std::ios::binary);
            const Bytes bytes((std::istreambuf_iterator<char>(in)),
                              std::istreambuf_iterator<char>());
            ++files;
            const FoundSets found = find_sets(bytes);
            CHECK(found.keep_from <= bytes.size());
            for (const SetSpan s : found.sets) {
                const DecodeResult r = decode(std::span(bytes).subspan(s.offset, s.size));
                CHECK_NOTHROW(r.json.dump());
                if (!r.ok()) {
                    CHECK(r.items.empty());  // refused: nothing decoded
                    CHECK(r.json.empty());
                    continue;
                }
                CHECK(r.consumed == s.size);
                LocalSet relay;
                for (const RawItem& item : r.items)
                    if (item.tag != 1) relay.add(item.tag, item.value);
                const Encoded e = encode(relay);
                REQUIRE(e.ok());
                const DecodeResult again = decode(e.value());
                REQUIRE(again.ok());
                nlohmann::json a = r.json, b = again.json;
                for (nlohmann::json* j : {&a, &b}) {
                    j->erase("checksum");
                    if (j->contains("invalid")) {
                        (*j)["invalid"].erase("1");
                        if ((*j)["invalid"].empty()) j->erase("invalid");
                    }
                }
                CHECK(a == b);
            }
        }
    }
    CHECK(files >= 6);
}
