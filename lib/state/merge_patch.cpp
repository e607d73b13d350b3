#include "state/merge_patch.hpp"

#include <algorithm>
#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace gimbal::state {

namespace {

using nlohmann::json;

constexpr std::string_view age_key = "age_s";

bool same_object(const json& a, const json& b) {
    for (auto it = a.begin(); it != a.end(); ++it) {
        if (it.key() == age_key) continue;
        const auto other = b.find(it.key());
        if (other == b.end() ? !it->is_null() : !same_ignoring_age(*it, *other)) return false;
    }
    for (auto it = b.begin(); it != b.end(); ++it)
        if (it.key() != age_key && !it->is_null() && !a.contains(it.key())) return false;
    return true;
}

// Fills `out` with the patch from object `from` to object `to`; false when nothing but
// age_s differs.
bool diff_objects(const json& from, const json& to, json& out) {
    out = json::object();
    for (auto it = to.begin(); it != to.end(); ++it) {
        if (it.key() == age_key) continue;
        const auto before = from.find(it.key());
        if (before == from.end() || before->is_null()) {
            if (!it->is_null()) out[it.key()] = *it;
        } else if (before->is_object() && it->is_object()) {
            json sub;
            if (diff_objects(*before, *it, sub)) out[it.key()] = std::move(sub);
        } else if (!same_ignoring_age(*before, *it)) {
            out[it.key()] = *it;  // a new value, an array whole, or null
        }
    }
    for (auto it = from.begin(); it != from.end(); ++it)
        if (it.key() != age_key && !it->is_null() && !to.contains(it.key()))
            out[it.key()] = nullptr;
    if (out.empty()) return false;
    // The object changed: its age goes along, so the receiver's age_s is of this value.
    const auto age = to.find(age_key);
    const auto old_age = from.find(age_key);
    if (age != to.end()) {
        if (old_age == from.end() || *old_age != *age) out[std::string(age_key)] = *age;
    } else if (old_age != from.end() && !old_age->is_null()) {
        out[std::string(age_key)] = nullptr;
    }
    return true;
}

}  // namespace

void merge_patch_apply(json& target, const json& patch) {
    if (!patch.is_object()) {
        target = patch;
        return;
    }
    if (!target.is_object()) target = json::object();
    for (auto it = patch.begin(); it != patch.end(); ++it) {
        if (it->is_null()) {
            target.erase(it.key());
        } else {
            merge_patch_apply(target[it.key()], *it);
        }
    }
}

json merge_patch_diff(const json& from, const json& to) {
    if (!from.is_object() || !to.is_object()) return to;
    json out;
    diff_objects(from, to, out);
    return out;
}

std::vector<json> split_patch(const json& patch, std::size_t budget) {
    if (!patch.is_object() || patch.size() < 2) return {patch};
    // Each member as it adds to a part's text: "key":value and a comma.
    std::vector<std::pair<std::size_t, std::string>> members;
    for (auto it = patch.begin(); it != patch.end(); ++it)
        members.emplace_back(json(it.key()).dump().size() + 2 +
                                 it->dump(-1, ' ', false, json::error_handler_t::replace).size(),
                             it.key());
    std::sort(members.begin(), members.end(), std::greater<>());
    std::vector<json> parts;
    std::vector<std::size_t> used;  // bytes of each part, {} included
    for (const auto& [size, key] : members) {
        std::size_t i = 0;
        while (i < parts.size() && used[i] + size > budget) ++i;
        if (i == parts.size()) {
            parts.push_back(json::object());
            used.push_back(2);
        }
        parts[i][key] = patch[key];
        used[i] += size;
    }
    return parts;
}

bool same_ignoring_age(const json& a, const json& b) {
    if (a.is_object() && b.is_object()) return same_object(a, b);
    if (a.is_array() && b.is_array()) {
        if (a.size() != b.size()) return false;
        for (std::size_t i = 0; i < a.size(); ++i)
            if (!same_ignoring_age(a[i], b[i])) return false;
        return true;
    }
    return a == b;
}

}  // namespace gimbal::state
