// Plan-view geometry of the operator console: a local tangent plane around the aircraft
// (metres east and north) and its mapping to screen pixels, plus the Web Mercator tile
// arithmetic for optional background tiles. Pure functions; docs/console.md states the same
// formulas so a test can recompute every drawn position from STATE.
'use strict';

(function (global) {
  const WGS84_A = 6378137.0;
  const WGS84_F = 1 / 298.257223563;
  const WGS84_E2 = WGS84_F * (2 - WGS84_F);
  const DEG = Math.PI / 180;

  // Metres per degree of latitude (meridian radius M) and of longitude (N cos lat) at lat0.
  function metresPerDegree(lat0) {
    const s = Math.sin(lat0 * DEG);
    const w = 1 - WGS84_E2 * s * s;
    const meridian = (WGS84_A * (1 - WGS84_E2)) / Math.pow(w, 1.5);
    const normal = WGS84_A / Math.sqrt(w);
    return { lat: meridian * DEG, lon: normal * Math.cos(lat0 * DEG) * DEG };
  }

  // Longitude difference folded into -180..180 so a view across the antimeridian works.
  function lonDelta(lon, lon0) {
    let d = lon - lon0;
    while (d > 180) d -= 360;
    while (d < -180) d += 360;
    return d;
  }

  // A projection centred on (lat0, lon0) drawn at (cx, cy) with pxPerM pixels per metre,
  // north up: x grows east, y grows south (screen convention).
  function makeProjection(lat0, lon0, cx, cy, pxPerM) {
    const m = metresPerDegree(lat0);
    return {
      lat0, lon0, cx, cy, px_per_m: pxPerM, m_per_deg_lat: m.lat, m_per_deg_lon: m.lon,
      toLocal(lat, lon) {
        return { east: lonDelta(lon, lon0) * m.lon, north: (lat - lat0) * m.lat };
      },
      toScreen(lat, lon) {
        const p = this.toLocal(lat, lon);
        return { x: cx + p.east * pxPerM, y: cy - p.north * pxPerM };
      },
      toLatLon(x, y) {
        const east = (x - cx) / pxPerM;
        const north = (cy - y) / pxPerM;
        let lon = lon0 + east / m.lon;
        if (lon > 180) lon -= 360;
        if (lon < -180) lon += 360;
        return { lat: lat0 + north / m.lat, lon };
      },
    };
  }

  // Horizontal distance in metres between two points (local plane; fine over tens of km).
  function groundDistance(lat1, lon1, lat2, lon2) {
    const m = metresPerDegree((lat1 + lat2) / 2);
    return Math.hypot(lonDelta(lon2, lon1) * m.lon, (lat2 - lat1) * m.lat);
  }

  // A 1-2-5 "nice" length not longer than maxMetres, for the scale bar.
  function niceLength(maxMetres) {
    const p = Math.pow(10, Math.floor(Math.log10(maxMetres)));
    for (const f of [5, 2, 1]) if (f * p <= maxMetres) return f * p;
    return p;
  }

  // Web Mercator (XYZ tiles): tile column/row of a point at zoom z, and a tile's NW corner.
  function tileOf(lat, lon, z) {
    const n = Math.pow(2, z);
    const x = ((lon + 180) / 360) * n;
    const r = lat * DEG;
    const y = ((1 - Math.log(Math.tan(r) + 1 / Math.cos(r)) / Math.PI) / 2) * n;
    return { x, y };
  }
  function tileCorner(x, y, z) {
    const n = Math.pow(2, z);
    const lon = (x / n) * 360 - 180;
    const lat = Math.atan(Math.sinh(Math.PI * (1 - (2 * y) / n))) / DEG;
    return { lat, lon };
  }

  global.GimbaldGeo = {
    metresPerDegree, lonDelta, makeProjection, groundDistance, niceLength, tileOf, tileCorner,
  };
})(window);
