#include "record/gimbal_stream.hpp"

#include <algorithm>

#include "protocols/registry.hpp"
#include "record/interface_scan.hpp"

namespace gimbal::record {

namespace {

constexpr std::string_view gimbal_prefix = "gimbal:";

GimbalInterfaceInfo describe(const RecordedInterface& itf) {
    GimbalInterfaceInfo info;
    info.name = itf.name.substr(gimbal_prefix.size());
    info.description = itf.description;
    const std::string first_word = itf.description.substr(0, itf.description.find(' '));
    if (protocols::find(first_word)) info.protocol = first_word;
    return info;
}

bool is_gimbal(const RecordedInterface& itf) {
    return itf.name.starts_with(gimbal_prefix) && itf.name.size() > gimbal_prefix.size();
}

std::string names(const std::vector<GimbalInterfaceInfo>& gimbals) {
    std::string s;
    for (const auto& g : gimbals) s += (s.empty() ? "" : ", ") + g.name;
    return s;
}

}  // namespace

bool load_gimbal_stream(std::span<const std::uint8_t> file, const std::string& name,
                        GimbalStream& out, std::string& error) {
    out = GimbalStream{};
    // First pass: which gimbals exist.
    const bool scanned = scan_interfaces(
        file,
        [&](const RecordedInterface& itf) {
            if (!is_gimbal(itf)) return;
            auto info = describe(itf);
            const bool known = std::any_of(out.all_gimbals.begin(), out.all_gimbals.end(),
                                           [&](const auto& g) { return g.name == info.name; });
            if (!known) out.all_gimbals.push_back(std::move(info));
        },
        error);
    if (!scanned) return false;
    if (out.all_gimbals.empty()) {
        error = "the recording has no gimbal interface (if_name \"gimbal:<name>\")";
        return false;
    }
    if (name.empty()) {
        if (out.all_gimbals.size() > 1) {
            error = "the recording holds several gimbals (" + names(out.all_gimbals) +
                    "): choose one with --gimbal";
            return false;
        }
        out.gimbal = out.all_gimbals.front();
    } else {
        const auto it = std::find_if(out.all_gimbals.begin(), out.all_gimbals.end(),
                                     [&](const auto& g) { return g.name == name; });
        if (it == out.all_gimbals.end()) {
            error = "no gimbal \"" + name +
                    "\" in the recording (it has: " + names(out.all_gimbals) + ")";
            return false;
        }
        out.gimbal = *it;
    }

    PcapngReader reader(file);
    RecordedPacket p;
    const std::string wanted = std::string(gimbal_prefix) + out.gimbal.name;
    while (reader.next(p)) {
        if (reader.interfaces()[p.interface_id].name != wanted) continue;
        if (p.direction == RecordedDirection::outbound) {
            ++out.outbound_pdus;
            continue;
        }
        if (p.direction != RecordedDirection::inbound) continue;
        if (!p.pdu_error.empty()) {
            ++out.bad_pdus;
            continue;
        }
        if (out.gimbal.protocol.empty())
            if (const auto* protocol = protocols::find_by_dissector(p.dissector))
                out.gimbal.protocol = protocol->name;
        out.bytes += p.pdu.size();
        out.chunks.push_back({p.timestamp_us, {p.pdu.begin(), p.pdu.end()}});
    }
    out.stop = reader.stop();
    out.stop_message = reader.stop_message();
    return true;
}

bool load_gimbal_files(const std::vector<std::string>& paths, const std::string& name,
                       GimbalStream& out, std::vector<std::string>& warnings, std::string& error) {
    out = GimbalStream{};
    std::string wanted = name;
    for (const auto& path : paths) {
        std::vector<std::uint8_t> bytes;
        GimbalStream part;
        if (!read_file(path, bytes, error) || !load_gimbal_stream(bytes, wanted, part, error)) {
            error = path + ": " + error;
            return false;
        }
        if (part.stop != Stop::end)
            warnings.push_back(path + ": " + to_string(part.stop) + " (" + part.stop_message + ")");
        if (part.bad_pdus > 0)
            warnings.push_back(path + ": " + std::to_string(part.bad_pdus) +
                               " packets with malformed exported-PDU tags skipped");
        if (out.gimbal.name.empty()) {
            out.gimbal = part.gimbal;
            out.all_gimbals = part.all_gimbals;
            wanted = part.gimbal.name;  // the later files must hold the same gimbal
        } else if (out.gimbal.protocol.empty()) {
            out.gimbal.protocol = part.gimbal.protocol;
        }
        out.bytes += part.bytes;
        out.outbound_pdus += part.outbound_pdus;
        out.bad_pdus += part.bad_pdus;
        out.stop = part.stop;
        out.stop_message = part.stop_message;
        for (auto& chunk : part.chunks) out.chunks.push_back(std::move(chunk));
    }
    return true;
}

}  // namespace gimbal::record
