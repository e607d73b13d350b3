// KML 2.2 (OGC 07-147r2): one Document; Placemarks with LineString and Polygon geometries,
// altitudeMode absolute (metres above mean sea level, so the MSL altitudes are used).
// Geometries lacking an altitude are clamped to the ground instead; the object tracks' heights
// above the ellipsoid become MSL with the undulation the gimbal reported (with_msl_heights).
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

constexpr const char* object_styles =
    "<Style id=\"object\"><LineStyle><color>ffff00ff</color><width>3</width></LineStyle>"
    "</Style>\n"
    "<Style id=\"object_lost\"><LineStyle><color>ff808080</color><width>5</width></LineStyle>"
    "</Style>\n"
    "<Style id=\"object_event\"><IconStyle><color>ffff00ff</color><scale>0.8</scale>"
    "</IconStyle></Style>\n";

std::string data(const std::string& name, const std::string& value) {
    return "<Data name=\"" + escape(name) + "\"><value>" + escape(value) + "</value></Data>";
}

// A Folder per track: its line, its stretches while lost (drawn over the line) and its marks.
std::string object_folder(const ObjectTrack& track) {
    const std::string name = "object " + std::to_string(track.id);
    std::string out = "<Folder><name>object track " + std::to_string(track.id) + "</name>" +
                      time_span(track.start_us, track.end_us) + "\n";
    std::string mode;
    const auto line = object_line(track);
    const auto ground = [](const ObjectSample* s) { return *s->ground; };
    if (line.size() >= 2) {
        const auto coords = coordinates(line, ground, mode);
        out += "<Placemark><name>" + name + "</name>" + time_span(track.start_us, track.end_us) +
               "<styleUrl>#object</styleUrl><ExtendedData>" + data("gimbal", track.gimbal) +
               data("id", std::to_string(track.id)) +
               (track.end_reason ? data("end_reason", *track.end_reason) : std::string()) +
               data("points", std::to_string(line.size())) + "</ExtendedData>" +
               line_string(coords, mode) + "</Placemark>\n";
    }
    for (const auto& stretch : lost_stretches(track)) {
        const auto coords = coordinates(stretch, ground, mode);
        out += "<Placemark><name>" + name + " lost</name>" +
               time_span(stretch.front()->time_us, stretch.back()->time_us) +
               "<styleUrl>#object_lost</styleUrl>" + line_string(coords, mode) + "</Placemark>\n";
    }
    for (const auto& mark : object_marks(track)) {
        const std::vector<Position> at{mark.at};
        const auto coords = coordinates(
            at, [](const Position& p) { return p; }, mode);
        const auto& e = *mark.event;
        out += "<Placemark><name>" + name + " " + escape(e.event) +
               (e.reason ? " (" + escape(*e.reason) + ")" : std::string()) +
               "</name><TimeStamp><when>" + iso_time(e.time_us) +
               "</when></TimeStamp><styleUrl>#object_event</styleUrl><Point><altitudeMode>" + mode +
               "</altitudeMode><coordinates>" + coords + "</coordinates></Point></Placemark>\n";
    }
    return out + "</Folder>\n";
}

}  // namespace

std::string to_kml(const Flight& flight, double footprint_every_s,
                   const std::vector<ObjectTrack>& objects) {
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
    if (!objects.empty()) out += object_styles;

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

    if (!objects.empty()) {
        out += "<Folder><name>object tracks</name>\n";
        for (const auto& object : with_msl_heights(objects, flight)) out += object_folder(object);
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
