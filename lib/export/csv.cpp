// RFC 4180 CSV: a header, then one row per telemetry packet (csv) or per record of the object
// tracks (track-csv); empty cells for values a row does not carry.
#include <cmath>
#include <optional>

#include "export/writers.hpp"

namespace gimbal::flight_export {

namespace {

std::string cell(const nlohmann::json& v) {
    const auto s = value_text(v);
    if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
    std::string quoted = "\"";
    for (char c : s) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    return quoted + "\"";
}

std::string row(const std::vector<nlohmann::json>& cells) {
    std::string out;
    for (std::size_t i = 0; i < cells.size(); ++i) {
        if (i > 0) out += ',';
        out += cell(cells[i]);
    }
    return out + "\r\n";
}

// A number's cell: empty when there is none or it is not finite (STATE's null read back).
nlohmann::json number(std::optional<double> v) {
    return v && std::isfinite(*v) ? nlohmann::json(*v) : nlohmann::json(nullptr);
}

// A member of an optional part, when the part is there.
template <class Part>
std::optional<double> member(const std::optional<Part>& part, double Part::*m) {
    return part ? std::optional<double>((*part).*m) : std::nullopt;
}

// One track record's cells, in object_columns() order.
std::vector<nlohmann::json> object_cells(const ObjectTrack& track, const ObjectSample& s) {
    using V = state::TrackVelocity;
    using C = state::TrackCentre;
    return {iso_time(s.time_us),
            track.gimbal,
            track.id,
            s.event,
            s.state,
            number(member(s.ground, &Position::lat)),
            number(member(s.ground, &Position::lon)),
            number(s.ground ? s.ground->alt : std::nullopt),
            number(member(s.velocity, &V::north)),
            number(member(s.velocity, &V::east)),
            number(member(s.velocity, &V::speed)),
            number(member(s.velocity, &V::course)),
            number(s.confidence),
            number(member(s.centre, &C::x)),
            number(member(s.centre, &C::y)),
            s.reason ? nlohmann::json(*s.reason) : nlohmann::json(nullptr)};
}

}  // namespace

std::string to_track_csv(const std::vector<ObjectTrack>& objects) {
    const auto& columns = object_columns();
    std::string out = row({columns.begin(), columns.end()});
    for (const auto& track : objects)
        for (const auto& s : track.samples) out += row(object_cells(track, s));
    return out;
}

std::string to_csv(const Flight& flight) {
    std::string out = "time";
    for (const auto& column : value_columns()) out += "," + column;
    out += "\r\n";
    for (const auto& p : flight.points) {
        out += iso_time(p.time_us);
        for (const auto& column : value_columns()) {
            out += ",";
            const auto it = p.values.find(column);
            if (it != p.values.end()) out += cell(*it);
        }
        out += "\r\n";
    }
    return out;
}

}  // namespace gimbal::flight_export
