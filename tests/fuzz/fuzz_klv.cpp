// libFuzzer target for lib/klv (MISB ST 0601): any bytes are searched for local sets and each
// one found is decoded, shown as JSON and relayed (re-encoded from its raw items); the input
// is also decoded as one set, read as a KLV unit (check_sets, the daemon's entry point) and
// used as typed values for the encoder. Properties:
//  - decode() reads no byte past the set and reports its size when the set is complete;
//  - a set that is refused (bad checksum, too large, malformed) has nothing decoded;
//  - the JSON can always be written (strings from the wire are valid UTF-8);
//  - check_sets() keeps each set's JSON within its limit and at most max_sets sets;
//  - a good set relayed item by item encodes to a set that decodes to the same JSON;
//  - a number encoded in range decodes within one step of itself.
// Any crash, sanitizer report or broken property aborts.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "klv/checked_sets.hpp"
#include "klv/local_set.hpp"
#include "klv/mapping.hpp"

namespace klv = gimbal::klv;

namespace {

[[noreturn]] void fail(const char* what) {
    std::fprintf(stderr, "fuzz_klv: %s\n", what);
    std::abort();
}

void check_set(std::span<const std::uint8_t> set) {
    const klv::DecodeResult r = klv::decode(set);
    (void)r.json.dump();
    if (r.status == klv::DecodeStatus::too_large && set.size() <= klv::max_set_bytes &&
        r.reason.find("items") == std::string::npos)
        fail("a set within the size limit refused as too large");
    if (!r.ok()) {
        if (!r.items.empty() || !r.json.empty()) fail("a refused set has decoded items");
        return;
    }
    if (set.size() > klv::max_set_bytes) fail("a set over the size limit decoded");
    if (r.items.size() > klv::max_set_items) fail("a set over the item limit decoded");
    if (r.consumed != set.size()) fail("a found set decodes to another size");
    klv::LocalSet relay;
    for (const klv::RawItem& item : r.items)
        if (item.tag != 1) relay.add(item.tag, item.value);
    const klv::Encoded e = klv::encode(relay);
    if (!e.ok()) fail("a relayed set does not encode");
    const klv::DecodeResult again = klv::decode(e.value());
    if (!again.ok()) fail("a relayed set does not decode");
    // encode() writes only the final checksum: earlier tag 1 items are not relayed.
    const auto without_checksums = [](nlohmann::json j) {
        j.erase("checksum");
        if (j.contains("invalid")) {
            j["invalid"].erase("1");
            if (j["invalid"].empty()) j.erase("invalid");
        }
        return j;
    };
    const nlohmann::json a = without_checksums(r.json), b = without_checksums(again.json);
    if (a != b) fail("a relayed set decodes to other values");
}

void check_values(std::span<const std::uint8_t> data) {
    // Up to eight values from the input's head: one byte picks a linear or IMAPB row, eight
    // bytes are the double.
    std::vector<const klv::TagSpec*> rows;
    for (const klv::TagSpec& row : klv::st0601_tags)
        if (row.kind == klv::Kind::linear || row.kind == klv::Kind::imapb) rows.push_back(&row);
    for (std::size_t at = 0; at + 9 <= data.size() && at < 9 * 8; at += 9) {
        const klv::TagSpec& row = *rows[data[at] % rows.size()];
        double x = 0;
        std::memcpy(&x, data.data() + at + 1, 8);
        klv::LocalSet set;
        set.add(row.tag, x);
        const klv::Encoded e = klv::encode(set);
        if (!e.ok()) {
            if (!std::isnan(x)) fail("a number was refused");
            continue;
        }
        const klv::DecodeResult r = klv::decode(e.value(), klv::Digits::exact);
        if (!r.ok()) fail("an encoded number does not decode");
        if (!klv::in_range(row.tag, x)) continue;
        const nlohmann::json& v = r.json[std::string(row.name)];
        if (!v.is_number()) fail("a number in range decodes to null");
        if (std::abs(v.get<double>() - x) > klv::step(row.tag) * 1.000001 + 1e-9 * std::abs(x))
            fail("a number in range decodes more than one step away");
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::span<const std::uint8_t> input(data, size);
    const klv::FoundSets found = klv::find_sets(input);
    if (found.keep_from > size) fail("keep_from past the input");
    std::size_t last_end = 0;
    for (const klv::SetSpan s : found.sets) {
        if (s.offset < last_end || s.offset + s.size > size) fail("a set outside the input");
        last_end = s.offset + s.size;
        check_set(input.subspan(s.offset, s.size));
    }
    const klv::DecodeResult whole = klv::decode(input);
    if (whole.consumed > size) fail("consumed past the input");
    (void)whole.json.dump();
    klv::CheckLimits limits;
    limits.max_json_bytes = 256;
    limits.max_sets = 4;
    const klv::CheckedSets checked = klv::check_sets(input, limits);
    if (checked.sets.size() > limits.max_sets) fail("check_sets took more sets than allowed");
    for (const auto& s : checked.sets) {
        if (s.json.dump().size() > limits.max_json_bytes) fail("a set's JSON over its limit");
        if (s.truncated != s.json.contains("truncated")) fail("truncated not marked");
    }
    check_values(input);
    return 0;
}
