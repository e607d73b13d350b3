// JSON Merge Patch (RFC 7396), and the patch between two STATE objects that delta streams
// send (contract section 14): only the members whose value changed, at any depth; arrays
// replaced whole; a member that became null (or went away) sent as null. `age_s` members do
// not count as a change and ride along only inside objects that carry other changes.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <vector>

namespace gimbal::state {

// Applies `patch` to `target` as RFC 7396 section 2 defines it: an object patch merges
// member by member (null removes the member), anything else replaces the target.
void merge_patch_apply(nlohmann::json& target, const nlohmann::json& patch);

// The merge patch that takes `from` to `to` (both usually objects). Applying it to `from`
// gives `to` up to two things: members that are null in `to` are missing (a receiver treats
// a missing member as null), and an `age_s` is only brought up to date in an object where
// something else changed too. An empty object means "nothing changed". When either side is
// not an object, the patch is `to` itself.
nlohmann::json merge_patch_diff(const nlohmann::json& from, const nlohmann::json& to);

// `patch` (an object) cut into patches of whole top-level members, each at most `budget`
// bytes of compact JSON text where a member allows (one larger than that goes alone).
// Applied in order they do what `patch` does: the members are disjoint. Largest members
// first, each into the first part it fits (first-fit decreasing); one part when it all fits.
std::vector<nlohmann::json> split_patch(const nlohmann::json& patch, std::size_t budget);

// True when `a` and `b` are equal once every `age_s` member, at any depth, is left out and a
// missing object member is taken as null.
bool same_ignoring_age(const nlohmann::json& a, const nlohmann::json& b);

}  // namespace gimbal::state
