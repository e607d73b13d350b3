#include "record/track_stream.hpp"

#include "record/interface_scan.hpp"

namespace gimbal::record {

bool load_track_stream(std::span<const std::uint8_t> file, const std::string& gimbal,
                       TrackStream& out, std::string& error) {
    out.gimbal = gimbal;
    const std::string wanted = std::string(track_prefix) + gimbal;
    const bool scanned = scan_interfaces(
        file, [&](const RecordedInterface& itf) { out.found = out.found || itf.name == wanted; },
        error);
    if (!scanned) return false;
    PcapngReader reader(file);
    RecordedPacket p;
    while (reader.next(p)) {
        if (reader.interfaces()[p.interface_id].name != wanted) continue;
        auto record = p.pdu_error.empty() ? read_track_record(p.pdu, p.timestamp_us) : std::nullopt;
        if (record)
            out.records.push_back(std::move(*record));
        else
            ++out.unreadable;
    }
    return true;
}

bool load_track_files(const std::vector<std::string>& paths, const std::string& gimbal,
                      TrackStream& out, std::string& error) {
    out = TrackStream{};
    for (const auto& path : paths) {
        std::vector<std::uint8_t> bytes;
        std::string why;
        if (!read_file(path, bytes, why) || !load_track_stream(bytes, gimbal, out, why)) {
            error = path + ": " + why;
            return false;
        }
    }
    return true;
}

}  // namespace gimbal::record
