// KML 2.2 (OGC 07-147r2): one Document; Placemarks with LineString and Polygon geometries,
// altitudeMode absolute (metres above mean sea level, so the MSL altitudes are used).
// Geometries lacking an altitude are clamped to the ground instead.
#include "export/writers.hpp"

namespace gimbal::flight_export {

namespace {

std::string escape(const std::string& s) {
    std::string out;
    for (char c : s) {
        switch (c) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '"':
                out += "&quot;";
                break;
            default:
                out += c;
        }
    }
    return out;
}

std::string number(double v) {
    return value_text(nlohmann::json(v));
}

// "lon,lat,alt lon,lat,alt ..." and the altitude mode that fits it.
template <class Points, class Get>
std::string coordinates(const Points& points, Get get, std::string& mode) {
    bool with_alt = true;
    for (const auto& p : points) with_alt = with_alt && get(p).alt_msl.has_value();
    mode = with_alt ? "absolute" : "clampToGround";
    std::string out;
    for (const auto& p : points) {
        const Position& pos = get(p);
        if (!out.empty()) out += ' ';
        // Appended piece by piece: GCC 12's -O2 warns falsely (-Wrestrict) on "," + string.
        out += number(pos.lon);
        out += ',';
        out += number(pos.lat);
        if (with_alt) {
            out += ',';
            out += number(*pos.alt_msl);
        }
    }
    return out;
}

std::string line_string(const std::string& coords, const std::string& mode) {
    return "<LineString><tessellate>1</tessellate><altitudeMode>" + mode +
           "</altitudeMode><coordinates>" + coords + "</coordinates></LineString>";
}

std::string time_span(std::int64_t begin_us, std::int64_t end_us) {
    return "<TimeSpan><begin>" + iso_time(begin_us) + "</begin><end>" + iso_time(end_us) +
           "</end></TimeSpan>";
}

std::string extended_data(const TrackPoint& p) {
    std::string out = "<ExtendedData>";
    for (const auto& [key, value] : p.values.items()) {
        if (value.is_null()) continue;
        out += "<Data name=\"" + escape(key) + "\"><value>" + escape(value_text(value)) +
               "</value></Data>";
    }
    return out + "</ExtendedData>";
}

}  // namespace

std::string to_kml(const Flight& flight, double footprint_every_s) {
    std::string out =
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
        "<kml xmlns=\"http://www.opengis.net/kml/2.2\">\n<Document>\n"
        "<name>gimbal " +
        escape(flight.gimbal) +
        "</name>\n"
        "<Style id=\"aircraft\"><LineStyle><color>ff0000ff</color><width>3</width></LineStyle>"
        "</Style>\n"
        "<Style id=\"target\"><LineStyle><color>ff00ffff</color><width>2</width></LineStyle>"
        "</Style>\n"
        "<Style id=\"footprint\"><LineStyle><color>ff00ff00</color><width>1</width></LineStyle>"
        "<PolyStyle><color>4000ff00</color></PolyStyle></Style>\n";

    std::vector<const TrackPoint*> track;
    for (const auto& p : flight.points)
        if (p.aircraft) track.push_back(&p);
    std::string mode;
    if (track.size() >= 2) {
        const auto coords = coordinates(
            track, [](const TrackPoint* p) { return *p->aircraft; }, mode);
        out += "<Placemark><name>aircraft track</name>" +
               time_span(track.front()->time_us, track.back()->time_us) +
               "<styleUrl>#aircraft</styleUrl>" + line_string(coords, mode) + "</Placemark>\n";
    }

    const auto segments = target_segments(flight);
    if (!segments.empty()) {
        out += "<Folder><name>target track</name>\n";
        for (const auto& segment : segments) {
            if (segment.size() < 2) continue;
            const auto coords = coordinates(
                segment, [](const TrackPoint* p) { return *p->target; }, mode);
            out += "<Placemark><name>target track</name>" +
                   time_span(segment.front()->time_us, segment.back()->time_us) +
                   "<styleUrl>#target</styleUrl>" + line_string(coords, mode) + "</Placemark>\n";
        }
        out += "</Folder>\n";
    }

    const auto footprints = footprints_every(flight, footprint_every_s);
    if (!footprints.empty()) {
        out += "<Folder><name>camera footprints</name>\n";
        for (const TrackPoint* p : footprints) {
            const auto ring = counter_clockwise_ring(*p->footprint);
            const auto coords = coordinates(
                ring, [](const Position& q) { return q; }, mode);
            out += "<Placemark><name>footprint " + iso_time(p->time_us) +
                   "</name><TimeStamp><when>" + iso_time(p->time_us) +
                   "</when></TimeStamp><styleUrl>#footprint</styleUrl>" + extended_data(*p) +
                   "<Polygon><altitudeMode>" + mode +
                   "</altitudeMode><outerBoundaryIs><LinearRing><coordinates>" + coords +
                   "</coordinates></LinearRing></outerBoundaryIs></Polygon></Placemark>\n";
        }
        out += "</Folder>\n";
    }
    out += "</Document>\n</kml>\n";
    return out;
}

}  // namespace gimbal::flight_export
