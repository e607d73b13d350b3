// The export formats of gimbal-export (docs/replay-export.md). Pure: a Flight in, text out.
#pragma once

#include <string>

#include "export/flight.hpp"

namespace gimbal::flight_export {

// RFC 7946 FeatureCollection: aircraft track (LineString), target track (one LineString per
// run of ranged points), footprints (Polygon, every footprint_every_s seconds).
std::string to_geojson(const Flight& flight, double footprint_every_s);
// KML 2.2 Document of Placemarks with LineString/Polygon, altitudeMode absolute (MSL).
std::string to_kml(const Flight& flight, double footprint_every_s);
// Header "time,<value_columns()>", then one row per telemetry packet.
std::string to_csv(const Flight& flight);

}  // namespace gimbal::flight_export
