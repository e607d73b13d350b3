#include "record/video_stream.hpp"

#include <algorithm>

#include "record/interface_scan.hpp"

namespace gimbal::record {

namespace {

bool is_video(const RecordedInterface& itf) {
    return itf.name.starts_with(video_prefix) && itf.name.size() > video_prefix.size();
}

std::string joined(const std::vector<std::string>& names) {
    std::string s;
    for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
    return s;
}

}  // namespace

bool load_video_stream(std::span<const std::uint8_t> file, const std::string& name,
                       VideoStream& out, std::string& error) {
    out = VideoStream{};
    const bool scanned = scan_interfaces(
        file,
        [&](const RecordedInterface& itf) {
            if (!is_video(itf)) return;
            std::string gimbal = itf.name.substr(video_prefix.size());
            if (std::find(out.all_gimbals.begin(), out.all_gimbals.end(), gimbal) ==
                out.all_gimbals.end())
                out.all_gimbals.push_back(std::move(gimbal));
        },
        error);
    if (!scanned) return false;
    if (out.all_gimbals.empty()) {
        error = "the recording has no video interface (if_name \"video:<gimbal>\")";
        return false;
    }
    if (name.empty()) {
        if (out.all_gimbals.size() > 1) {
            error = "the recording holds video of several gimbals (" + joined(out.all_gimbals) +
                    "): choose one with --gimbal";
            return false;
        }
        out.gimbal = out.all_gimbals.front();
    } else if (std::find(out.all_gimbals.begin(), out.all_gimbals.end(), name) ==
               out.all_gimbals.end()) {
        error = "no video of gimbal \"" + name +
                "\" in the recording (it has video of: " + joined(out.all_gimbals) + ")";
        return false;
    } else {
        out.gimbal = name;
    }

    PcapngReader reader(file);
    RecordedPacket p;
    const std::string wanted = std::string(video_prefix) + out.gimbal;
    while (reader.next(p)) {
        const auto& itf = reader.interfaces()[p.interface_id];
        if (itf.name != wanted || !p.pdu_error.empty()) continue;
        if (out.description.empty()) out.description = itf.description;
        const bool generated = p.direction == RecordedDirection::outbound;
        if (generated)
            ++out.generated_sets;
        else
            out.ts_bytes += p.pdu.size();
        out.chunks.push_back({p.timestamp_us, generated, {p.pdu.begin(), p.pdu.end()}});
    }
    out.stop = reader.stop();
    out.stop_message = reader.stop_message();
    return true;
}

bool load_video_files(const std::vector<std::string>& paths, const std::string& name,
                      VideoStream& out, std::vector<std::string>& warnings, std::string& error) {
    out = VideoStream{};
    std::string wanted = name;
    std::string first_error;
    bool any = false;
    for (const auto& path : paths) {
        std::vector<std::uint8_t> bytes;
        VideoStream part;
        std::string why;
        if (!read_file(path, bytes, why)) {
            error = path + ": " + why;
            return false;
        }
        if (!load_video_stream(bytes, wanted, part, why)) {
            if (first_error.empty()) first_error = path + ": " + why;
            continue;  // a rotated file may hold no video (yet)
        }
        any = true;
        if (part.stop != Stop::end)
            warnings.push_back(path + ": " + to_string(part.stop) + " (" + part.stop_message + ")");
        if (out.gimbal.empty()) {
            out.gimbal = part.gimbal;
            out.description = part.description;
            out.all_gimbals = part.all_gimbals;
            wanted = part.gimbal;
        }
        out.ts_bytes += part.ts_bytes;
        out.generated_sets += part.generated_sets;
        out.stop = part.stop;
        out.stop_message = part.stop_message;
        for (auto& chunk : part.chunks) out.chunks.push_back(std::move(chunk));
    }
    if (!any) {
        error = first_error;
        return false;
    }
    return true;
}

}  // namespace gimbal::record
