// The frame-time code (sim/frame_code.hpp): layout as documented, round trips, CRC, and what
// must not decode.
#include <catch2/catch.hpp>
#include <cstring>
#include <random>
#include <string_view>

#include "sim/frame_code.hpp"

using namespace gimbal::sim;

namespace {

I420Frame grey_frame(int width = 640, int height = 360, std::uint8_t level = 120) {
    I420Frame f;
    REQUIRE(f.resize(width, height));
    std::fill(f.y.begin(), f.y.end(), level);
    std::fill(f.u.begin(), f.u.end(), std::uint8_t{100});
    std::fill(f.v.begin(), f.v.end(), std::uint8_t{140});
    return f;
}

// Whether cell k reads white, sampled at its centre pixel.
bool cell_white(const I420Frame& f, int k, int block = 16) {
    const int x = (k % 32) * block + block / 2, y = (k / 32) * block + block / 2;
    return f.luma(x, y) > 128;
}

}  // namespace

TEST_CASE("frame code: CRC-8/SMBUS check value", "[sim][frame_code]") {
    const std::string_view text = "123456789";
    std::vector<std::uint8_t> bytes(text.begin(), text.end());
    CHECK(crc8_smbus(bytes) == 0xF4);  // the catalogue's check value for CRC-8/SMBUS
    CHECK(crc8_smbus({}) == 0x00);
}

TEST_CASE("frame code: the documented layout", "[sim][frame_code]") {
    I420Frame f = grey_frame();
    const std::uint64_t t = 0x0123456789ABull;
    REQUIRE(draw_frame_code(f, t));
    const int b = 16;
    CHECK(frame_code_block_px(640, 360) == b);
    // Start and stop marks.
    CHECK(cell_white(f, 0));
    CHECK_FALSE(cell_white(f, 1));
    CHECK(cell_white(f, 2));
    CHECK_FALSE(cell_white(f, 3));
    CHECK_FALSE(cell_white(f, 60));
    CHECK(cell_white(f, 61));
    CHECK_FALSE(cell_white(f, 62));
    CHECK(cell_white(f, 63));
    // The time, most significant bit first, from cell 4; cells 36.. continue on the second row.
    for (int i = 0; i < 48; ++i) CHECK(cell_white(f, 4 + i, b) == (((t >> (47 - i)) & 1) == 1));
    // The CRC of the six bytes, big-endian.
    const std::uint8_t bytes[6] = {0x01, 0x23, 0x45, 0x67, 0x89, 0xAB};
    const std::uint8_t crc = crc8_smbus(bytes);
    for (int i = 0; i < 8; ++i) CHECK(cell_white(f, 52 + i, b) == (((crc >> (7 - i)) & 1) == 1));
    // Exact levels and neutral chroma in the cells; the rest of the frame untouched.
    CHECK(f.luma(0, 0) == 235);
    CHECK(f.luma(16, 0) == 16);
    CHECK(f.luma(15, 31) == (cell_white(f, 32) ? 235 : 16));
    CHECK(f.cb(5, 5) == 128);
    CHECK(f.cr(5, 5) == 128);
    CHECK(f.luma(512, 0) == 120);
    CHECK(f.luma(0, 32) == 120);
    CHECK(f.cb(512, 0) == 100);
}

TEST_CASE("frame code: round trips", "[sim][frame_code]") {
    std::mt19937_64 rng(3);
    std::vector<std::uint64_t> times{0, 1, frame_code_max, 1735689600000ull, 1767225599999ull};
    for (int i = 0; i < 200; ++i) times.push_back(rng() & frame_code_max);
    for (const std::uint64_t t : times) {
        I420Frame f = grey_frame();
        REQUIRE(draw_frame_code(f, t));
        const auto back = decode_frame_code(f);
        REQUIRE(back);
        CHECK(*back == t);
    }
    // Other sizes: the cells shrink to fit, down to 4 px.
    for (auto [w, h] : {std::pair{320, 180}, {1280, 720}, {128, 16}, {1920, 1080}}) {
        I420Frame f = grey_frame(w, h);
        INFO(w << "x" << h);
        REQUIRE(draw_frame_code(f, 1735689600123ull));
        CHECK(decode_frame_code(f) == 1735689600123ull);
    }
    CHECK(frame_code_block_px(320, 180) == 10);
    CHECK(frame_code_block_px(1920, 1080) == 16);
    // A strided plane (as a decoder hands it out).
    I420Frame f = grey_frame();
    REQUIRE(draw_frame_code(f, 42));
    std::vector<std::uint8_t> strided(704 * 360, 0);
    for (std::size_t y = 0; y < 360; ++y) std::memcpy(&strided[704 * y], &f.y[640 * y], 640);
    CHECK(decode_frame_code(strided, 640, 360, 704) == 42u);
}

TEST_CASE("frame code: survives noise and blur-like level shifts", "[sim][frame_code]") {
    std::mt19937_64 rng(9);
    std::uniform_int_distribution<int> noise(-35, 35);
    I420Frame f = grey_frame();
    REQUIRE(draw_frame_code(f, 1735689600777ull));
    // A compressed picture: levels pulled towards grey, plus noise.
    for (auto& p : f.y)
        p = static_cast<std::uint8_t>(std::clamp(60 + (p - 16) * 140 / 219 + noise(rng), 0, 255));
    CHECK(decode_frame_code(f) == 1735689600777ull);
}

TEST_CASE("frame code: what does not decode", "[sim][frame_code]") {
    I420Frame f = grey_frame();
    CHECK_FALSE(decode_frame_code(f));  // no code at all
    CHECK_FALSE(draw_frame_code(f, frame_code_max + 1));
    CHECK(f.luma(0, 0) == 120);  // unchanged
    // One data cell flipped: the CRC no longer matches.
    REQUIRE(draw_frame_code(f, 1735689600123ull));
    const auto flip = [&](int k) {
        for (int y = (k / 32) * 16; y < (k / 32) * 16 + 16; ++y)
            for (int x = (k % 32) * 16; x < (k % 32) * 16 + 16; ++x) {
                auto& p = f.y[static_cast<std::size_t>(y * 640 + x)];
                p = p > 128 ? 16 : 235;
            }
    };
    for (int k : {10, 55, 0, 63}) {
        flip(k);
        CHECK_FALSE(decode_frame_code(f));
        flip(k);
        CHECK(decode_frame_code(f) == 1735689600123ull);
    }
    // A cell half way between black and white is ambiguous.
    for (int y = 4; y < 12; ++y)
        for (int x = 20 * 16 + 4; x < 20 * 16 + 12; ++x)
            f.y[static_cast<std::size_t>(y * 640 + x)] = 126;
    CHECK_FALSE(decode_frame_code(f));
    // Too small for a code, and a plane shorter than its rows.
    I420Frame tiny = grey_frame(64, 16);
    CHECK(frame_code_block_px(64, 16) == 0);
    CHECK_FALSE(draw_frame_code(tiny, 1));
    CHECK_FALSE(decode_frame_code(tiny));
    std::vector<std::uint8_t> short_plane(640 * 10, 0);
    CHECK_FALSE(decode_frame_code(short_plane, 640, 360, 640));
}
