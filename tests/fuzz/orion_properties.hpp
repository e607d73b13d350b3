// The properties the Orion fuzz targets check, as plain functions so that the unit tests can
// replay the corpus and every saved crash through exactly the same checks. Each returns an
// empty string when the property holds, else what broke. Every packet type is reached through
// dispatch()/for_each_packet(), so packets declared later are covered without changes here.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include "protocols/orion/codec/framer.hpp"
#include "protocols/orion/codec/framing.hpp"
#include "protocols/orion/codec/json.hpp"
#include "protocols/orion/codec/packets.hpp"

namespace gimbal::fuzz {

using Bytes = std::vector<std::uint8_t>;
using nlohmann::json;

// --- JSON comparison ---------------------------------------------------------------------

enum class Numbers {
    exact,       // equal doubles
    close,       // within 1e-12 relative (degrees <-> radians and back)
    saturation,  // also: the most negative raw value of a signed field became the next one
};

inline bool numbers_match(double a, double b, Numbers mode) {
    if (a == b) return true;
    if (mode == Numbers::exact) return false;
    if (std::fabs(a - b) <= 1e-12 * std::max(std::fabs(a), std::fabs(b))) return true;
    if (mode != Numbers::saturation) return false;
    // The encoder saturates signed fields at -(2^(n-1) - 1), so a decoded -2^(n-1) comes
    // back one step smaller: a / b is 2^(n-1) / (2^(n-1) - 1) for I8, I16, I24, I32.
    if (a < 0 && b < 0 && b > a)
        for (const int bits : {8, 16, 24, 32}) {
            const double top = std::ldexp(1.0, bits - 1);
            if (std::fabs(a / b - top / (top - 1)) <= 1e-3 / top) return true;  // one step
        }
    // F16:9 patterns with the all-ones exponent decode (as in ProtoGen) to values above the
    // largest finite one, which is where the encoder saturates.
    const double f16_largest = orion::small_to_float(0x7DFF, 16, 9);
    if (std::fabs(b) == f16_largest && std::fabs(a) > f16_largest && (a < 0) == (b < 0))
        return true;
    return false;
}

// Empty when a and b have the same shape and values. With `defaults` (a default packet's
// JSON) and `requantized` (the same after a trip over the wire): a field that held its
// default in a and the wire's nearest value to it in b matches too - an absent optional
// field takes the ICD default, which the wire may not be able to represent exactly.
inline std::string json_diff(const json& a, const json& b, Numbers mode,
                             const std::string& where = "", const json* defaults = nullptr,
                             const json* requantized = nullptr) {
    if (a.is_number() && b.is_number()) {
        if (numbers_match(a.get<double>(), b.get<double>(), mode)) return {};
        if (defaults && requantized && defaults->is_number() && requantized->is_number() &&
            a == *defaults && b == *requantized)
            return {};
        return where + ": " + a.dump() + " != " + b.dump();
    }
    if (a.type() != b.type()) return where + ": " + a.dump() + " != " + b.dump();
    auto child = [](const json* parent, const auto& key) -> const json* {
        if (!parent) return nullptr;
        if constexpr (std::is_convertible_v<decltype(key), std::string>) {
            return parent->is_object() && parent->contains(key) ? &parent->at(key) : nullptr;
        } else {
            return parent->is_array() && key < parent->size() ? &(*parent)[key] : nullptr;
        }
    };
    if (a.is_object()) {
        if (a.size() != b.size()) return where + ": key count " + a.dump() + " != " + b.dump();
        for (const auto& item : a.items()) {
            const std::string& key = item.key();
            if (!b.contains(key)) return where + "." + key + ": missing";
            auto d = json_diff(item.value(), b.at(key), mode, where + "." + key,
                               child(defaults, key), child(requantized, key));
            if (!d.empty()) return d;
        }
        return {};
    }
    if (a.is_array()) {
        if (a.size() != b.size()) return where + ": array size " + a.dump() + " != " + b.dump();
        for (std::size_t i = 0; i < a.size(); ++i) {
            auto d = json_diff(a[i], b[i], mode, where + "[" + std::to_string(i) + "]",
                               child(defaults, i), child(requantized, i));
            if (!d.empty()) return d;
        }
        return {};
    }
    return a == b ? std::string{} : where + ": " + a.dump() + " != " + b.dump();
}

inline bool contains_null(const json& j) {
    if (j.is_null()) return true;
    if (j.is_structured())
        for (const auto& item : j) {
            if (contains_null(item)) return true;
        }
    return false;
}

inline Bytes bytes_of(const orion::Payload& p) {
    return Bytes(p.bytes.begin(), p.bytes.begin() + static_cast<long>(p.size));
}

// --- codec properties -----------------------------------------------------------------------

// A packet read from JSON goes to the wire and back without moving: JSON -> packet ->
// JSON is stable, and the JSON of the decoded wire bytes matches.
template <class P>
std::string check_json_to_wire(const P& packet, const json& source) {
    const std::string name(P::name);
    orion::Payload wire;
    if (!orion::encode(packet, wire))
        return name + ": accepted from JSON but does not encode: " + source.dump();
    if (wire.size < P::min_length || wire.size > P::max_length)
        return name + ": encodes to " + std::to_string(wire.size) + " bytes, outside " +
               std::to_string(P::min_length) + ".." + std::to_string(P::max_length);
    const auto back = orion::decode<P>(wire.view());
    if (!back) return name + ": own encoding does not decode: " + orion::to_string(back.error);
    // The wire quantises and JSON shows strings as printable ASCII, so compare after one more
    // trip: JSON -> packet -> wire -> packet -> JSON must then reproduce its input, and
    // the wire bytes must not change any more.
    const json once = orion::to_json(back.value);
    P again{};
    orion::JsonError error;
    if (!orion::from_json(once, again, error)) {
        if (contains_null(once)) return {};  // a non-finite float has no JSON number
        return name + ": its own JSON is rejected (" + std::string(to_string(error.code)) + ": " +
               error.message + "): " + once.dump();
    }
    const orion::Payload wire_again = orion::encode(again);
    const auto twice = orion::decode<P>(wire_again.view());
    if (!twice) return name + ": re-encoded JSON does not decode";
    const json twice_json = orion::to_json(twice.value);
    if (auto d = json_diff(once, twice_json, Numbers::close, name); !d.empty())
        return "JSON -> wire -> JSON moved " + d;
    P third{};
    if (!orion::from_json(twice_json, third, error))
        return name + ": JSON accepted once is rejected the second time: " + twice_json.dump();
    if (bytes_of(orion::encode(third)) != bytes_of(wire_again))
        return name + ": JSON -> wire is not stable: " + twice_json.dump();
    return {};
}

// Contract section 1: the JSON clients get (Digits::shortest) has fewer digits but must still
// read back to exactly the same wire bytes as the exact JSON does.
template <class P>
std::string check_shortest_json(const P& packet) {
    const json lean = orion::to_json(packet, orion::Digits::shortest);
    P back{};
    orion::JsonError error;
    if (!orion::from_json(lean, back, error)) {
        if (contains_null(lean)) return {};  // a non-finite float has no JSON number
        return std::string(P::name) + ": its shortest JSON is rejected (" +
               std::string(to_string(error.code)) + ": " + error.message + "): " + lean.dump();
    }
    // Compared with what the exact JSON reads back to: strings shown as printable ASCII are
    // a normalisation both share.
    P exact{};
    if (!orion::from_json(orion::to_json(packet), exact, error)) return {};
    if (bytes_of(orion::encode(back)) != bytes_of(orion::encode(exact)))
        return std::string(P::name) + ": its shortest JSON encodes to other bytes: " + lean.dump();
    return {};
}

// Decode `data` as P; when it decodes, re-encode and decode again: nothing but the documented
// normalisations may change, and after one trip nothing changes at all.
template <class P>
std::string check_decode_as(std::span<const std::uint8_t> data) {
    const std::string name(P::name);
    const auto first = orion::decode<P>(data);
    if (!first) {
        if (data.size() >= P::max_length)
            return name + ": " + std::to_string(data.size()) +
                   " bytes (at least max_length) do not decode: " + orion::to_string(first.error);
        return {};
    }
    if (data.size() < P::min_length)
        return name + ": decodes from " + std::to_string(data.size()) +
               " bytes, below min_length " + std::to_string(P::min_length);
    orion::Payload wire;
    if (!orion::encode(first.value, wire)) return name + ": decoded packet does not re-encode";
    if (wire.size < P::min_length || wire.size > P::max_length)
        return name + ": re-encodes to " + std::to_string(wire.size) + " bytes, outside " +
               std::to_string(P::min_length) + ".." + std::to_string(P::max_length);
    const auto second = orion::decode<P>(wire.view());
    if (!second)
        return name + ": re-encoded bytes do not decode: " + orion::to_string(second.error);
    const json j1 = orion::to_json(first.value);
    const json j2 = orion::to_json(second.value);
    const json defaults = orion::to_json(P{});
    const json requantized = orion::to_json(orion::decode<P>(orion::encode(P{}).view()).value);
    if (auto d = json_diff(j1, j2, Numbers::saturation, name, &defaults, &requantized); !d.empty())
        return "decode -> encode -> decode changed " + d;
    // Fixpoint: our own encoding round-trips exactly.
    const orion::Payload wire2 = orion::encode(second.value);
    if (bytes_of(wire2) != bytes_of(wire)) return name + ": encode(decode(encode(x))) differs";
    if (auto lean = check_shortest_json(second.value); !lean.empty()) return lean;
    return check_json_to_wire(second.value, j2);
}

// fuzz_orion_decode: the first byte selects the packet id, the rest is its data.
inline std::string check_decode(std::span<const std::uint8_t> input) {
    if (input.empty()) return {};
    const std::uint8_t id = input[0];
    auto data = input.subspan(1);
    if (data.size() > orion::max_data_length) data = data.first(orion::max_data_length);
    std::string failure;
    orion::dispatch(id, [&]<class P>() { failure = check_decode_as<P>(data); });
    return failure;
}

// The number of packet types, and a call of f.template operator()<P>() for the index-th.
inline std::size_t packet_type_count() {
    std::size_t n = 0;
    orion::for_each_packet([&]<class P>() { ++n; });
    return n;
}

template <class F>
void with_packet_type(std::size_t index, F&& f) {
    std::size_t i = 0;
    orion::for_each_packet([&]<class P>() {
        if (i++ == index) f.template operator()<P>();
    });
}

// fuzz_orion_json: the first byte selects a packet type, the rest is parsed as JSON and read
// into that packet. Never crashes; what it accepts must encode and survive the wire.
inline std::string check_json(std::span<const std::uint8_t> input) {
    if (input.empty()) return {};
    const std::size_t index = input[0] % packet_type_count();
    const auto text = input.subspan(1);
    const json j = json::parse(text.begin(), text.end(), nullptr, false);
    if (j.is_discarded()) return {};
    std::string failure;
    with_packet_type(index, [&]<class P>() {
        P packet{};
        orion::JsonError error;
        if (!orion::from_json(j, packet, error)) {
            if (error.code != "bad_request" && error.code != "out_of_range")
                failure = std::string(P::name) + ": unknown error code '" +
                          std::string(to_string(error.code)) + "'";
            else if (error.message.empty())
                failure = std::string(P::name) + ": error without a message";
            return;
        }
        failure = check_json_to_wire(packet, j);
    });
    return failure;
}

// --- framer properties -------------------------------------------------------------------------

struct FramerRun {
    std::vector<orion::Frame> frames;
    orion::FramerStats stats;
    std::size_t pending = 0;
    std::uint64_t frame_bytes = 0;
    std::string failure;
};

// Pushes `stream` in chunks whose sizes cycle through `chunks` (0 means 1).
inline FramerRun run_framer(std::span<const std::uint8_t> stream,
                            std::span<const std::uint8_t> chunks) {
    FramerRun run;
    orion::Framer framer;
    std::size_t at = 0;
    for (std::size_t k = 0; at < stream.size(); ++k) {
        const std::size_t want = chunks.empty() ? stream.size() : 1u + chunks[k % chunks.size()];
        const std::size_t n = std::min(want, stream.size() - at);
        framer.push(stream.subspan(at, n), [&](const orion::Frame& f) {
            run.frames.push_back(f);
            run.frame_bytes += orion::header_size + f.payload.size + orion::checksum_size;
        });
        at += n;
        const auto& s = framer.stats();
        if (run.failure.empty() &&
            s.bytes != run.frame_bytes + s.dropped_bytes + framer.pending_bytes())
            run.failure = "bytes != delivered + dropped + pending after a push";
        if (run.failure.empty() && framer.pending_bytes() >= orion::max_frame_size)
            run.failure = "more pending than one unfinished frame";
    }
    run.stats = framer.stats();
    run.pending = framer.pending_bytes();
    framer.reset();
    if (run.failure.empty() &&
        framer.stats().bytes != run.frame_bytes + framer.stats().dropped_bytes)
        run.failure = "after reset(), bytes != delivered + dropped";
    return run;
}

inline bool same_frame(const orion::Frame& a, const orion::Frame& b) {
    return a.id == b.id && std::ranges::equal(a.data(), b.data());
}

// fuzz_orion_framer: the first byte says how many of the next bytes are chunk sizes; the
// rest is the stream. The result must not depend on how the stream was chunked.
inline std::string check_framer(std::span<const std::uint8_t> input) {
    if (input.empty()) return {};
    const std::size_t n_chunks = std::min<std::size_t>(input[0] % 16, input.size() - 1);
    const auto chunks = input.subspan(1, n_chunks);
    const auto stream = input.subspan(1 + n_chunks);

    const FramerRun chunked = run_framer(stream, chunks);
    if (!chunked.failure.empty()) return chunked.failure;
    const FramerRun whole = run_framer(stream, {});
    if (!whole.failure.empty()) return whole.failure;

    if (chunked.frames.size() != whole.frames.size())
        return "chunking changed the number of frames";
    for (std::size_t i = 0; i < whole.frames.size(); ++i)
        if (!same_frame(chunked.frames[i], whole.frames[i])) return "chunking changed a frame";
    const auto& a = chunked.stats;
    const auto& b = whole.stats;
    if (a.packets != b.packets || a.dropped_bytes != b.dropped_bytes ||
        a.bad_checksums != b.bad_checksums || a.oversize != b.oversize ||
        chunked.pending != whole.pending)
        return "chunking changed the counters";
    if (a.packets != whole.frames.size()) return "packets counter != frames delivered";

    // Every frame is in the stream, in order, and re-frames to exactly one valid frame.
    auto from = stream.begin();
    for (const orion::Frame& f : whole.frames) {
        if (f.payload.size > orion::max_data_length) return "frame longer than 140 bytes";
        const Bytes wire = orion::frame_bytes(f.id, f.data());
        const auto found = std::search(from, stream.end(), wire.begin(), wire.end());
        if (found == stream.end()) return "delivered a frame that is not in the stream";
        from = found + static_cast<long>(wire.size());
        orion::Framer again;
        const auto out = again.push(wire);
        if (out.size() != 1 || !same_frame(out[0], f) || again.stats().dropped_bytes != 0)
            return "a delivered frame does not re-frame to itself";
    }
    return {};
}

}  // namespace gimbal::fuzz
