// Replays the fuzz targets' seed corpora and every saved crash input through the same checks
// the fuzzers run (tests/fuzz/orion_properties.hpp), plus a seeded random sweep of them, so a
// fixed fuzz finding stays fixed without clang or libFuzzer.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include "../../fuzz/orion_properties.hpp"

namespace fs = std::filesystem;
using gimbal::fuzz::Bytes;

namespace {

const fs::path fuzz_dir = fs::path(__FILE__).parent_path() / ".." / ".." / "fuzz";

Bytes read_file(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Every file of tests/fuzz/corpus/<target> and tests/fuzz/regressions/<target>.
std::vector<fs::path> inputs(const std::string& target) {
    std::vector<fs::path> files;
    for (const char* kind : {"corpus", "regressions"}) {
        const fs::path dir = fuzz_dir / kind / target;
        if (!fs::is_directory(dir)) continue;
        for (const auto& entry : fs::directory_iterator(dir))
            if (entry.is_regular_file()) files.push_back(entry.path());
    }
    return files;
}

template <class Check>
void replay(const std::string& target, Check check) {
    const auto files = inputs(target);
    CHECK_FALSE(files.empty());
    for (const fs::path& file : files) {
        CAPTURE(file.filename().string());
        CHECK(check(read_file(file)) == "");
    }
}

}  // namespace

TEST_CASE("fuzz corpus and crash inputs: framer", "[orion][fuzz]") {
    replay("orion_framer", [](const Bytes& b) { return gimbal::fuzz::check_framer(b); });
}

TEST_CASE("fuzz corpus and crash inputs: decode", "[orion][fuzz]") {
    replay("orion_decode", [](const Bytes& b) { return gimbal::fuzz::check_decode(b); });
}

TEST_CASE("fuzz corpus and crash inputs: json", "[orion][fuzz]") {
    replay("orion_json", [](const Bytes& b) { return gimbal::fuzz::check_json(b); });
}

TEST_CASE("every packet type decodes random data and round-trips", "[orion][fuzz]") {
    std::mt19937 rng(99);
    for (int id = 0; id < 256; ++id) {
        for (int round = 0; round < 200; ++round) {
            Bytes input{static_cast<std::uint8_t>(id)};
            const std::size_t n = rng() % (gimbal::orion::max_data_length + 1);
            for (std::size_t i = 0; i < n; ++i) input.push_back(static_cast<std::uint8_t>(rng()));
            CAPTURE(id, n);
            const std::string failure = gimbal::fuzz::check_decode(input);
            CHECK(failure == "");
            if (!failure.empty()) break;  // one report per packet type is enough
        }
    }
}

TEST_CASE("every packet type's own JSON reads back and round-trips", "[orion][fuzz]") {
    std::mt19937 rng(100);
    gimbal::orion::for_each_packet([&]<class P>() {
        for (int round = 0; round < 50; ++round) {
            Bytes data(P::max_length);
            for (auto& b : data) b = static_cast<std::uint8_t>(rng());
            const auto decoded = gimbal::orion::decode<P>(data);
            REQUIRE(decoded.ok);
            CAPTURE(P::name);
            CHECK(gimbal::fuzz::check_json_to_wire(decoded.value,
                                                   gimbal::orion::to_json(decoded.value)) == "");
        }
    });
}

TEST_CASE("every packet declaration agrees with its minimum and maximum length", "[orion][fuzz]") {
    gimbal::orion::for_each_packet([&]<class P>() {
        CAPTURE(P::name);
        // The minimum is what a decode needs (zeros: every count and condition is zero)...
        const Bytes zeros(P::max_length, 0);
        CHECK(gimbal::orion::decode<P>(std::span(zeros).first(P::min_length)).ok);
        if (P::min_length > 0)
            CHECK_FALSE(gimbal::orion::decode<P>(std::span(zeros).first(P::min_length - 1)).ok);
        // ...and a default packet encodes within the limits.
        const gimbal::orion::Payload p = gimbal::orion::encode(P{});
        CHECK(p.size >= P::min_length);
        CHECK(p.size <= P::max_length);
        CHECK(P::max_length <= gimbal::orion::max_data_length);
    });
}

TEST_CASE("random streams keep the framer's invariants", "[orion][fuzz][framer]") {
    std::mt19937 rng(101);
    Bytes frames;
    for (int i = 0; i < 50; ++i) {
        Bytes data(rng() % 40);
        for (auto& b : data) b = static_cast<std::uint8_t>(rng());
        gimbal::orion::append_frame(static_cast<std::uint8_t>(rng()), data, frames);
    }
    for (int round = 0; round < 300; ++round) {
        Bytes input{static_cast<std::uint8_t>(rng() % 16)};
        for (int i = 0; i < 15; ++i) input.push_back(static_cast<std::uint8_t>(rng() % 200));
        // Valid frames with random damage: flipped bytes, inserted syncs, cut-outs.
        Bytes stream = frames;
        for (int hits = 0; hits < 20; ++hits) {
            const std::size_t at = rng() % stream.size();
            switch (rng() % 3) {
                case 0:
                    stream[at] = static_cast<std::uint8_t>(rng());
                    break;
                case 1:
                    stream.insert(stream.begin() + static_cast<long>(at), {0xD0, 0x0D});
                    break;
                default:
                    stream.erase(stream.begin() + static_cast<long>(at));
                    break;
            }
        }
        input.insert(input.end(), stream.begin(), stream.end());
        CHECK(gimbal::fuzz::check_framer(input) == "");
    }
}
