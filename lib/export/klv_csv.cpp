#include "export/klv_csv.hpp"

#include <map>
#include <set>

#include "export/flight.hpp"
#include "klv/local_set.hpp"
#include "klv/st0601.hpp"
#include "video/ts_demuxer.hpp"

namespace gimbal::flight_export {

using nlohmann::json;

namespace {

void add_sets(std::span<const std::uint8_t> bytes, std::int64_t time_us, bool generated,
              KlvTrack& track) {
    for (const klv::SetSpan s : klv::find_sets(bytes).sets) {
        klv::DecodeResult r = klv::decode(bytes.subspan(s.offset, s.size));
        if (r.status == klv::DecodeStatus::bad_checksum) {
            ++track.bad_checksums;
        } else if (!r.ok()) {
            ++track.malformed;
        } else {
            track.rows.push_back({time_us, generated, std::move(r.json)});
        }
    }
}

// Column order: tag number, the checksum (tag 1) after every other item, then the groups of
// unknown and invalid items.
int rank(const std::string& item) {
    if (item == "checksum") return 1000;
    if (item == "unknown") return 1001;
    if (item == "invalid") return 1002;
    for (const auto& row : klv::st0601_tags)
        if (row.name == item) return static_cast<int>(row.tag);
    return 1003;
}

std::string cell(const json& v) {
    std::string s = v.is_string() ? v.get<std::string>() : v.is_null() ? "" : value_text(v);
    if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
    std::string quoted = "\"";
    for (char c : s) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    return quoted + "\"";
}

bool spread(const std::string& item, const json& value) {
    return value.is_object() && item != "unknown" && item != "invalid";
}

}  // namespace

KlvTrack klv_track(const record::VideoStream& video) {
    KlvTrack track;
    std::int64_t now_us = 0;
    video::TsDemuxer demux(
        {{}, [&](const video::KlvUnit& unit) { add_sets(unit.data, now_us, false, track); }, {}});
    for (const auto& chunk : video.chunks) {
        now_us = chunk.time_us;
        if (chunk.generated)
            add_sets(chunk.bytes, chunk.time_us, true, track);
        else
            demux.push(chunk.bytes);
    }
    demux.flush();
    return track;
}

std::string to_klv_csv(const KlvTrack& track) {
    // Every column, in order: (rank, item, member or "").
    std::set<std::tuple<int, std::string, std::string>> columns;
    for (const auto& row : track.rows)
        for (const auto& [item, value] : row.decoded.items()) {
            if (spread(item, value))
                for (const auto& [member, inner] : value.items())
                    columns.emplace(rank(item), item, member);
            else
                columns.emplace(rank(item), item, "");
        }
    std::string out = "time,source";
    for (const auto& [r, item, member] : columns)
        out += "," + cell(json(member.empty() ? item : item + "." + member));
    out += "\r\n";
    for (const auto& row : track.rows) {
        out += iso_time(row.time_us);
        out += row.generated ? ",generated" : ",stream";
        for (const auto& [r, item, member] : columns) {
            out += ",";
            const auto it = row.decoded.find(item);
            if (it == row.decoded.end()) continue;
            if (member.empty()) {
                out += spread(item, *it) ? "" : cell(*it);
            } else if (it->is_object() && it->contains(member)) {
                out += cell((*it)[member]);
            }
        }
        out += "\r\n";
    }
    return out;
}

}  // namespace gimbal::flight_export
