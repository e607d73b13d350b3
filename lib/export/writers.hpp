// The export formats of gimbal-export (docs/replay-export.md). Pure: a Flight (and the
// object tracks of its gimbal's visual tracking) in, text out.
#pragma once

#include <string>
#include <vector>

#include "export/flight.hpp"
#include "export/object_track.hpp"

namespace gimbal::flight_export {

// RFC 7946 FeatureCollection: aircraft track (LineString), target track (one LineString per
// run of ranged points), the object tracks (a LineString per track, one per stretch while
// lost, a Point per lost, re-acquired and end), footprints (Polygon, every
// footprint_every_s seconds).
std::string to_geojson(const Flight& flight, double footprint_every_s,
                       const std::vector<ObjectTrack>& objects = {});
// KML 2.2 Document of Placemarks with LineString/Polygon/Point, altitudeMode absolute (MSL);
// the object tracks in a Folder of their own.
std::string to_kml(const Flight& flight, double footprint_every_s,
                   const std::vector<ObjectTrack>& objects = {});
// Header "time,<value_columns()>", then one row per telemetry packet.
std::string to_csv(const Flight& flight);
// Header object_columns(), then one row per record of every object track.
std::string to_track_csv(const std::vector<ObjectTrack>& objects);

}  // namespace gimbal::flight_export
