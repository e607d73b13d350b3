// RFC 4180 CSV: a header, then one row per telemetry packet; empty cells for values the
// packet does not carry.
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

}  // namespace

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
