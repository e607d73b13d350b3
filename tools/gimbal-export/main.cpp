// gimbal-export: aircraft track, target track, camera footprints and the visually tracked
// object's track from a gimbald recording, as GeoJSON, KML or CSV. See `gimbal-export --help`
// and docs/replay-export.md.
#include <CLI/CLI.hpp>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "export/klv_csv.hpp"
#include "export/writers.hpp"
#include "record/gimbal_stream.hpp"
#include "record/track_stream.hpp"
#include "record/video_stream.hpp"

namespace {

constexpr const char* description = R"(NAME
       gimbal-export - aircraft track, target track, camera footprints and the
       visually tracked object's track from a gimbald recording, for QGIS,
       Google Earth or a spreadsheet

SYNOPSIS
       gimbal-export FILE... --format geojson|kml|csv|track-csv|klv-csv
                     [--gimbal NAME] [--footprint-every S] [-o OUT]

DESCRIPTION
       Reads a pcapng recording written by gimbald (docs/recording.md),
       decodes what one gimbal sent - its telemetry frames, with the decoder of
       its protocol, the same codec and state code gimbald uses - and, when the
       gimbal had visual tracking (interface track:NAME), the records of its
       tracks: the events and STATE track after every box gimbald handled.
       It writes one of:

       geojson    an RFC 7946 FeatureCollection: the aircraft track
                  (LineString), the target track (a LineString per run of
                  ranged points), the object tracks, and camera footprints
                  (Polygon, exterior ring counter-clockwise) every S seconds,
                  each with the telemetry values as properties. Positions are
                  [lon, lat, alt], alt above the WGS84 ellipsoid (a gimbal that
                  reports only MSL heights has positions [lon, lat] and alt_msl
                  as a property). An object track is a LineString (kind
                  object_track) through every ground position the tracker's
                  filter had, with properties id, gimbal, start, end,
                  end_reason (stopped, overridden, timeout, no_video; null
                  when the recording ends first), points and lost_points; a
                  LineString (kind object_track_lost) over each stretch while
                  the object was lost, its positions predicted; and a Point
                  (kind object_event) where it was lost, re-acquired and ended.
       kml        a KML 2.2 Document with the same Placemarks (LineString,
                  Polygon, Point), altitudeMode absolute with heights above
                  mean sea level (alt minus the reported geoid undulation when
                  the gimbal reports heights above the ellipsoid; the object's
                  heights with the undulation reported for the aircraft). The
                  object tracks are in a Folder "object tracks", one Folder
                  per track.
       csv        a header line, then one row per telemetry packet: time (the
                  receive time, ISO-8601 UTC), gimbal_time, system_time_ms,
                  lat, lon, alt, alt_msl, roll, pitch, yaw (aircraft), pan,
                  tilt, hfov, vfov, mode, range_source, target_lat,
                  target_lon, target_alt, target_alt_msl, zoom, lrf_m; empty
                  where the packet has no value.
       track-csv  the object tracks as a table: a header line, then one row
                  per track record in recorded order: time (when gimbald
                  handled it, ISO-8601 UTC), gimbal, id, event (empty for a
                  box; track_start, track_lost, track_reacquired, track_end),
                  state (tracking, lost; ended on track_end), lat, lon, alt
                  (where the filter had the object, alt above the WGS84
                  ellipsoid; empty before the first located box),
                  velocity_north, velocity_east, speed (m/s), course
                  (degrees), confidence, centre_x, centre_y (the box's centre
                  in image coordinates, -1..1), reason (on track_end). An
                  event row has no position. A recording without the gimbal's
                  track interface is exit 1.
       klv-csv    the KLV track of the gimbal's recorded video (interface
                  video:NAME, contract section 17): a header line, then one
                  row per MISB ST 0601 set - the sets found in the recorded
                  MPEG-TS (source "stream", checksum verified; bad ones are
                  skipped and counted) and those gimbald generated (source
                  "generated") - with time (when gimbald received or made it,
                  ISO-8601 UTC), source, and every decoded item as a column
                  (names and units of docs/video.md; flags as item.flag
                  columns).

       Units are those of gimbald's STATE (degrees, metres). Camera footprints
       are the image corners projected onto the ground at the target's altitude
       (only for gimbals that report a field of view); a footprint is drawn
       for the first packet that has one and then every --footprint-every
       seconds of receive time. An object track runs from its track_start to
       its track_end; gimbald numbers tracks from 1 again when it restarts, so
       one id may name several tracks of a recording. Several FILEs are read
       as one recording, in the order given (gimbald rotates files). A file
       cut short by a crash is read up to its last complete block, with a
       warning.
)";

constexpr const char* footer = R"(OUTPUT
       The export goes to OUT (or standard output); a summary line goes to
       standard error:
           gimbal-export: gimbal main (orion): 300 telemetry packets, 30 footprints
           gimbal-export: gimbal main (orion): 300 telemetry packets, 30 footprints,
               2 object tracks (412 positions)
           gimbal-export: visual track of gimbal main: 2 tracks, 431 records
               (412 positions)
           gimbal-export: video of gimbal main: 450 KLV sets (450 stream, 0 generated)

EXIT STATUS
       0 written; 1 bad command line, unreadable file, not a recording, no such
       gimbal (no track of it for track-csv, no video of it for klv-csv), or
       OUT cannot be written.

EXAMPLES
       gimbal-export flight.pcapng --format geojson -o flight.geojson
       gimbal-export flight.pcapng --format kml --footprint-every 2 -o flight.kml
       gimbal-export flight.pcapng --gimbal nose --format csv > nose.csv
       gimbal-export flight.pcapng --format track-csv -o object.csv
       gimbal-export flight.pcapng --format klv-csv -o klv.csv
)";

// Writes `text` to `output` (standard output when empty); false when it cannot.
bool write_output(const std::string& output, const std::string& text) {
    if (output.empty()) {
        std::cout << text << std::flush;
        return true;
    }
    std::ofstream out(output, std::ios::binary | std::ios::trunc);
    out << text;
    out.close();
    if (!out) {
        std::cerr << "gimbal-export: cannot write " << output << std::endl;
        return false;
    }
    return true;
}

int export_klv(const std::vector<std::string>& files, const std::string& gimbal,
               const std::string& output) {
    namespace fe = gimbal::flight_export;
    std::string error;
    std::vector<std::string> warnings;
    gimbal::record::VideoStream video;
    if (!gimbal::record::load_video_files(files, gimbal, video, warnings, error)) {
        std::cerr << "gimbal-export: " << error << std::endl;
        return 1;
    }
    for (const auto& w : warnings)
        std::cerr << "gimbal-export: warning: " << w << "; exporting what came before" << std::endl;
    const fe::KlvTrack track = fe::klv_track(video);
    if (!write_output(output, fe::to_klv_csv(track))) return 1;
    std::size_t generated = 0;
    for (const auto& row : track.rows) generated += row.generated ? 1 : 0;
    std::cerr << "gimbal-export: video of gimbal " << video.gimbal << ": " << track.rows.size()
              << " KLV sets (" << track.rows.size() - generated << " stream, " << generated
              << " generated)"
              << (track.bad_checksums
                      ? ", " + std::to_string(track.bad_checksums) + " with a bad checksum skipped"
                      : std::string())
              << std::endl;
    return 0;
}

// The object tracks of the gimbal's visual tracking (none when it had none).
bool load_objects(const std::vector<std::string>& files, const std::string& gimbal,
                  gimbal::record::TrackStream& stream,
                  std::vector<gimbal::flight_export::ObjectTrack>& objects) {
    std::string error;
    if (!gimbal::record::load_track_files(files, gimbal, stream, error)) {
        std::cerr << "gimbal-export: " << error << std::endl;
        return false;
    }
    objects = gimbal::flight_export::object_tracks(stream);
    return true;
}

std::size_t positions(const std::vector<gimbal::flight_export::ObjectTrack>& objects) {
    std::size_t n = 0;
    for (const auto& track : objects) n += gimbal::flight_export::object_line(track).size();
    return n;
}

std::string unreadable(const gimbal::record::TrackStream& stream) {
    return stream.unreadable
               ? ", " + std::to_string(stream.unreadable) + " unreadable records skipped"
               : std::string();
}

int export_track_csv(const gimbal::record::TrackStream& stream,
                     const std::vector<gimbal::flight_export::ObjectTrack>& objects,
                     const std::string& output) {
    if (!stream.found) {
        std::cerr << "gimbal-export: the recording has no visual track of gimbal " << stream.gimbal
                  << " (interface track:" << stream.gimbal
                  << "; its video needs a tracking section)" << std::endl;
        return 1;
    }
    if (!write_output(output, gimbal::flight_export::to_track_csv(objects))) return 1;
    std::cerr << "gimbal-export: visual track of gimbal " << stream.gimbal << ": " << objects.size()
              << " tracks, " << stream.records.size() << " records (" << positions(objects)
              << " positions)" << unreadable(stream) << std::endl;
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    namespace fe = gimbal::flight_export;
    std::vector<std::string> files;
    std::string format;
    std::string gimbal;
    std::string output;
    double footprint_every_s = 10.0;
    bool version = false;

    CLI::App app{description, "gimbal-export"};
    app.footer(footer);
    app.get_formatter()->column_width(30);
    app.add_option("FILE", files, "Recording (pcapng) to read; several: in this order")
        ->type_name("");
    app.add_option("--format", format, "Output format: geojson, kml, csv, track-csv or klv-csv")
        ->type_name("FORMAT")
        ->check(CLI::IsMember({"geojson", "kml", "csv", "track-csv", "klv-csv"}).description(""));
    app.add_option("--gimbal", gimbal,
                   "Gimbal to export (its interface gimbal:NAME); needed when the recording "
                   "holds several")
        ->type_name("NAME");
    app.add_option("--footprint-every", footprint_every_s,
                   "Seconds between camera footprints; 0 = every packet")
        ->type_name("S")
        ->check(CLI::NonNegativeNumber.description(""))
        ->capture_default_str();
    app.add_option("-o,--output", output, "Write to OUT instead of standard output")
        ->type_name("OUT");
    app.add_flag("--version", version, "Print the version and exit");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e) == 0 ? 0 : 1;
    }
    if (version) {
        std::cout << "gimbal-export " << GIMBALD_VERSION << "\n";
        return 0;
    }
    if (files.empty() || format.empty()) {
        std::cerr << "gimbal-export: FILE and --format are required\n"
                     "Run with --help for more information.\n";
        return 1;
    }

    if (format == "klv-csv") return export_klv(files, gimbal, output);

    std::string error;
    std::vector<std::string> warnings;
    gimbal::record::GimbalStream stream;
    fe::Flight flight;
    if (!gimbal::record::load_gimbal_files(files, gimbal, stream, warnings, error)) {
        std::cerr << "gimbal-export: " << error << std::endl;
        return 1;
    }
    if (!fe::build_flight(stream, flight, error)) {
        std::cerr << "gimbal-export: " << error << std::endl;
        return 1;
    }
    for (const auto& w : warnings)
        std::cerr << "gimbal-export: warning: " << w << "; exporting what came before" << std::endl;
    gimbal::record::TrackStream track_stream;
    std::vector<fe::ObjectTrack> objects;
    if (format != "csv" && !load_objects(files, flight.gimbal, track_stream, objects)) return 1;
    if (format == "track-csv") return export_track_csv(track_stream, objects, output);

    const std::string text = format == "geojson"
                                 ? fe::to_geojson(flight, footprint_every_s, objects)
                             : format == "kml" ? fe::to_kml(flight, footprint_every_s, objects)
                                               : fe::to_csv(flight);
    if (!write_output(output, text)) return 1;
    std::cerr << "gimbal-export: gimbal " << flight.gimbal << " (" << flight.protocol
              << "): " << flight.points.size() << " telemetry packets, "
              << fe::footprints_every(flight, footprint_every_s).size() << " footprints"
              << (flight.decode_errors
                      ? ", " + std::to_string(flight.decode_errors) + " frames did not decode"
                      : std::string());
    if (track_stream.found)
        std::cerr << ", " << objects.size() << " object tracks (" << positions(objects)
                  << " positions)" << unreadable(track_stream);
    std::cerr << std::endl;
    return 0;
}
