#include "klv/checked_sets.hpp"

#include <algorithm>
#include <string>
#include <utility>

#include "klv/local_set.hpp"

namespace gimbal::klv {

CheckedSets check_sets(std::span<const std::uint8_t> unit, const CheckLimits& limits) {
    CheckedSets out;
    for (const SetSpan s : find_sets(unit).sets) {
        if (out.sets.size() >= limits.max_sets) {
            ++out.refused;
            continue;
        }
        const auto bytes = unit.subspan(s.offset, s.size);
        DecodeResult r = decode(bytes);
        if (r.status == DecodeStatus::bad_checksum) {
            ++out.bad_checksums;
            continue;
        }
        if (!r.ok()) {
            ++out.refused;
            continue;
        }
        CheckedSet set{{bytes.begin(), bytes.end()}, std::move(r.json), false};
        set.truncated = fit_json(set.json, limits.max_json_bytes);
        out.sets.push_back(std::move(set));
    }
    return out;
}

namespace {

// What one member adds to a compact object: "key":value and a comma.
std::size_t member_size(const std::string& key, const nlohmann::json& value) {
    return key.size() + 4 + value.dump().size();
}

}  // namespace

bool fit_json(nlohmann::json& decoded, std::size_t max_bytes) {
    if (!decoded.is_object()) return false;
    std::size_t size = decoded.dump().size();
    if (size <= max_bytes) return false;
    for (const char* group : {"unknown", "invalid"}) {
        if (const auto it = decoded.find(group); it != decoded.end()) {
            size -= std::min(size, member_size(it.key(), *it));
            decoded.erase(it);
        }
    }
    decoded["truncated"] = true;
    size += member_size("truncated", true);
    if (size > max_bytes) {
        std::vector<std::pair<std::size_t, std::string>> members;
        for (const auto& [key, value] : decoded.items())
            if (key != "truncated") members.emplace_back(member_size(key, value), key);
        // Largest first; equal sizes by name, so the result does not depend on the order.
        std::sort(members.begin(), members.end(), [](const auto& a, const auto& b) {
            return a.first > b.first || (a.first == b.first && a.second < b.second);
        });
        for (const auto& [bytes, key] : members) {
            if (size <= max_bytes) break;
            decoded.erase(key);
            size -= std::min(size, bytes);
        }
    }
    return true;
}

}  // namespace gimbal::klv
