#include "protocols/registry.hpp"

#include <algorithm>

#include "protocols/mavlink_device/mavlink_device_entry.hpp"
#include "protocols/orion/orion_entry.hpp"
#include "protocols/siyi/siyi_entry.hpp"
#include "protocols/viewpro/viewpro_entry.hpp"
#include "state/messages.hpp"

namespace gimbal::protocols {

const Entry& entry(ProtocolId id) {
    switch (id) {
        case ProtocolId::orion:
            return orion_entry();
        case ProtocolId::viewpro:
            return viewpro_entry();
        case ProtocolId::mavlink:
            return mavlink_device_entry();
        case ProtocolId::siyi:
            return siyi_entry();
    }
    __builtin_unreachable();  // every enumerator returns above; -Wswitch names a missing one
}

std::string_view to_string(ProtocolId id) {
    return entry(id).name;
}

std::optional<ProtocolId> parse_protocol(std::string_view name) {
    for (const ProtocolId id : all_protocol_ids)
        if (entry(id).name == name) return id;
    return std::nullopt;
}

bool Entry::plans(std::string_view cmd) const {
    return std::any_of(commands.begin(), commands.end(),
                       [&](const PlannedCommand& c) { return c.name == cmd; });
}

std::vector<const Entry*> entries() {
    std::vector<const Entry*> out;
    for (const ProtocolId id : all_protocol_ids) out.push_back(&entry(id));
    return out;
}

const Entry* find(std::string_view name) {
    for (const ProtocolId id : all_protocol_ids)
        if (entry(id).name == name) return &entry(id);
    return nullptr;
}

const Entry* find_by_dissector(std::string_view dissector) {
    for (const ProtocolId id : all_protocol_ids)
        if (entry(id).dissector == dissector) return &entry(id);
    return nullptr;
}

std::vector<std::string> names() {
    std::vector<std::string> out;
    for (const ProtocolId id : all_protocol_ids) out.emplace_back(entry(id).name);
    return out;
}

std::string names_text() {
    std::string out;
    for (const auto& name : names()) out += (out.empty() ? "" : ", ") + name;
    return out;
}

bool is_state_key(std::string_view key) {
    if (state::is_shared_state_key(key)) return true;
    for (const ProtocolId id : all_protocol_ids) {
        const auto& keys = entry(id).state_keys;
        if (std::find(keys.begin(), keys.end(), key) != keys.end()) return true;
    }
    return false;
}

std::vector<const Entry*> planners_of(std::string_view cmd) {
    std::vector<const Entry*> out;
    for (const ProtocolId id : all_protocol_ids)
        if (entry(id).plans(cmd)) out.push_back(&entry(id));
    return out;
}

}  // namespace gimbal::protocols
