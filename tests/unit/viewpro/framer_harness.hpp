// Shared by the framer tests: a framer with everything it delivered, and streams of frames
// with junk between them. Not a test file itself.
#pragma once

#include <catch2/catch.hpp>
#include <optional>
#include <random>
#include <span>
#include <vector>

#include "vectors.hpp"

namespace viewpro_test {

template <class Framer>
struct FramerHarness {
    Framer framer;
    std::vector<Bytes> got;  // the bytes of each delivered frame
    std::uint64_t delivered_bytes = 0;

    void push(std::span<const std::uint8_t> bytes) {
        framer.push(bytes, [&](const auto& f) {
            got.emplace_back(f.bytes.begin(), f.bytes.begin() + static_cast<long>(f.size));
            delivered_bytes += f.size;
        });
    }
    void push(const Bytes& bytes) { push(std::span<const std::uint8_t>(bytes)); }
    void push_in_chunks(const Bytes& stream, std::size_t chunk) {
        for (std::size_t at = 0; at < stream.size(); at += chunk)
            push(std::span(stream).subspan(at, std::min(chunk, stream.size() - at)));
    }

    // Every byte pushed is in a delivered frame, dropped, or waiting.
    bool counters_consistent() const {
        const auto& s = framer.stats();
        return s.bytes == delivered_bytes + s.dropped_bytes + framer.pending_bytes() &&
               s.frames == got.size();
    }
};

// Frames split at every offset come out whole, once, with nothing dropped.
template <class Framer>
void check_split_at_every_offset(const std::vector<Bytes>& frames) {
    for (const Bytes& frame : frames) {
        for (std::size_t cut = 0; cut <= frame.size(); ++cut) {
            CAPTURE(frame.size(), cut);
            FramerHarness<Framer> h;
            h.push(std::span(frame).first(cut));
            CHECK(h.got.empty() == (cut < frame.size()));
            h.push(std::span(frame).subspan(cut));
            REQUIRE(h.got.size() == 1);
            CHECK(h.got[0] == frame);
            CHECK(h.framer.stats().dropped_bytes == 0);
            CHECK(h.framer.pending_bytes() == 0);
            CHECK(h.counters_consistent());
        }
    }
}

// A stream of all frames cut into three pieces at every pair of offsets.
template <class Framer>
void check_stream_split_everywhere(const std::vector<Bytes>& frames) {
    const Bytes stream = concat(frames);
    for (std::size_t cut = 0; cut <= stream.size(); ++cut) {
        for (std::size_t cut2 = cut; cut2 <= stream.size(); cut2 += 1 + cut2 % 7) {
            FramerHarness<Framer> h;
            h.push(std::span(stream).first(cut));
            h.push(std::span(stream).subspan(cut, cut2 - cut));
            h.push(std::span(stream).subspan(cut2));
            REQUIRE(h.got == frames);
            REQUIRE(h.framer.stats().dropped_bytes == 0);
            REQUIRE(h.counters_consistent());
        }
    }
}

// Random junk (rich in `special` bytes, so false starts and cut-off frames are common)
// between randomly chosen frames; junk that happens to hold a valid frame has its start byte
// cleared, since that would be a real frame. Checks every frame comes out in order and every
// junk byte is counted as dropped.
template <class Framer, class IsValidFrameAt>
void check_frames_between_junk(const std::vector<Bytes>& frames, const Bytes& special,
                               IsValidFrameAt valid_frame_at, std::uint32_t seed) {
    std::mt19937 rng(seed);
    auto junk_byte = [&]() -> std::uint8_t {
        return rng() % 2 ? special[rng() % special.size()] : static_cast<std::uint8_t>(rng());
    };
    Bytes stream;
    std::vector<Bytes> want;
    std::vector<std::pair<std::size_t, std::size_t>> junk_ranges;
    std::uint64_t junk_total = 0;
    for (int n = 0; n < 3000; ++n) {
        const std::size_t junk_len = rng() % 24;
        junk_ranges.emplace_back(stream.size(), stream.size() + junk_len);
        for (std::size_t i = 0; i < junk_len; ++i) stream.push_back(junk_byte());
        junk_total += junk_len;
        const Bytes& f = frames[rng() % frames.size()];
        stream.insert(stream.end(), f.begin(), f.end());
        want.push_back(f);
    }
    // A clean tail longer than any frame lets every false start resolve.
    while (stream.size() - junk_ranges.back().second < 200) {
        stream.insert(stream.end(), frames[0].begin(), frames[0].end());
        want.push_back(frames[0]);
    }
    for (bool clean = false; !clean;) {
        clean = true;
        for (const auto& [begin, end] : junk_ranges)
            for (std::size_t i = begin; i < end; ++i)
                if (valid_frame_at(stream, i)) {
                    stream[i] = 0x00;
                    clean = false;
                }
    }

    FramerHarness<Framer> h;
    for (std::size_t at = 0; at < stream.size();) {
        const std::size_t n = std::min<std::size_t>(stream.size() - at, 1 + rng() % 200);
        h.push(std::span(stream).subspan(at, n));
        at += n;
        REQUIRE(h.counters_consistent());
    }
    REQUIRE(h.got.size() == want.size());
    CHECK(h.got == want);
    CHECK(h.framer.stats().dropped_bytes == junk_total);
    CHECK(h.framer.stats().frames == want.size());
    CHECK(h.framer.stats().bad_checksums > 0);  // the junk did contain false starts
    CHECK(h.framer.pending_bytes() == 0);
}

}  // namespace viewpro_test
