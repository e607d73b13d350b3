// The ground trail of each gimbal's visually tracked object (contract section 20), from
// STATE `track` as it comes: what the plan view draws. Exposed as window.GimbaldObjectTrails.
'use strict';

(function (global) {
  // Ground points kept per trail.
  const MAX_POINTS = 300;

  class ObjectTrails {
    constructor() {
      this.trails = {}; // gimbal name -> {id, trail: [{lat, lon}]}
    }

    // STATE `track` (or null) of a gimbal: a new id starts a new trail.
    take(name, track) {
      if (!track) return;
      let o = this.trails[name];
      if (!o || o.id !== track.id) o = this.trails[name] = { id: track.id, trail: [] };
      const g = track.ground;
      // Only where the tracker saw it: while lost, `ground` is the filter's prediction.
      if (track.state !== 'tracking' || !g || !Number.isFinite(g.lat)) return;
      const last = o.trail[o.trail.length - 1];
      if (!last || last.lat !== g.lat || last.lon !== g.lon) o.trail.push({ lat: g.lat, lon: g.lon });
      if (o.trail.length > MAX_POINTS) o.trail.shift();
    }

    // For the plan view: the trail, and where the object is now while its track runs (after
    // it ends the trail stays until the next track starts); null before any track.
    view(name, track) {
      const o = this.trails[name];
      if (!o) return null;
      const running = !!track && track.id === o.id;
      const g = running && track.ground;
      return { id: o.id, state: running ? track.state : 'ended', trail: o.trail,
        current: g && Number.isFinite(g.lat) ? { lat: g.lat, lon: g.lon } : null };
    }
  }

  global.GimbaldObjectTrails = ObjectTrails;
})(window);
