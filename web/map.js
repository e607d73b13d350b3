// The plan view: an SVG, north up, centred on the aircraft, in the local tangent plane of
// geo.js. Draws the aircraft (rotated to heading), line of sight, target, footprint, track,
// a visually tracked object's ground trail and position, optional XYZ tiles, a scale bar;
// records what it drew (lat/lon and pixels) for the test hook and as data-* attributes on
// the SVG elements.
'use strict';

(function (global) {
  const Geo = global.GimbaldGeo;
  const SVG_NS = 'http://www.w3.org/2000/svg';
  // Zoom steps in pixels per metre (1-2-5 series): 0.005 px/m shows 100+ km, 20 px/m a few tens of metres.
  const ZOOM_STEPS = [];
  for (let e = -3; e <= 1; e++) for (const f of [1, 2, 5]) ZOOM_STEPS.push(f * Math.pow(10, e));
  const FIXED = 2; // pixel coordinates are written with 2 decimals

  function el(name, attrs) {
    const node = document.createElementNS(SVG_NS, name);
    for (const k in attrs) node.setAttribute(k, attrs[k]);
    return node;
  }
  const fmt = (v) => v.toFixed(FIXED);

  class PlanView {
    constructor(svg) {
      this.svg = svg;
      this.zoomIndex = ZOOM_STEPS.indexOf(0.1);
      this.fitted = false;
      this.tilesUrl = null;
      this.tileNodes = new Map();
      this.projection = null;
      this.drawn = null;
      this.nodes = {};
      for (const id of ['tiles', 'grid', 'track', 'footprint', 'los', 'uav-output', 'target',
        'object-trail', 'object-mark', 'click-mark', 'aircraft', 'scale-bar']) {
        this.nodes[id] = svg.querySelector('#' + id);
      }
      this.resize();
    }

    get pxPerM() { return ZOOM_STEPS[this.zoomIndex]; }

    // The SVG's user units are CSS pixels: viewBox = its own size, origin top-left.
    resize() {
      const r = this.svg.getBoundingClientRect();
      this.width = Math.max(1, r.width);
      this.height = Math.max(1, r.height);
      this.svg.setAttribute('viewBox', `0 0 ${this.width} ${this.height}`);
    }

    zoom(delta) {
      this.zoomIndex = Math.min(ZOOM_STEPS.length - 1, Math.max(0, this.zoomIndex + delta));
      this.fitted = true; // the operator chose: no more automatic fit
    }

    // The largest zoom step that still shows every given ground distance (metres from the
    // aircraft) inside the view, with a margin.
    fit(distances) {
      const half = Math.min(this.width, this.height) / 2 - 30;
      const far = Math.max(200, ...distances);
      let i = 0;
      for (let k = 0; k < ZOOM_STEPS.length; k++) if (ZOOM_STEPS[k] * far <= half) i = k;
      this.zoomIndex = i;
    }

    // view: {gimbal, time_ms, aircraft:{lat,lon,heading}, target:{lat,lon}|null,
    //        footprint:[{lat,lon}x4]|null, track:[{lat,lon}], uav:{lat,lon}|null, click:{lat,lon}|null,
    //        object:{id, state, trail:[{lat,lon}], current:{lat,lon}|null}|null}
    render(view) {
      this.resize();
      const n = this.nodes;
      if (!view || !view.aircraft) {
        this.projection = null;
        this.drawn = null;
        for (const id of ['aircraft', 'target', 'los', 'footprint', 'track', 'uav-output', 'click-mark',
          'object-trail', 'object-mark']) {
          n[id].setAttribute('visibility', 'hidden');
        }
        this.drawScaleBar();
        return;
      }
      const a = view.aircraft;
      if (!this.fitted) {
        // Fit the target with room around it, and the footprint unless it reaches far beyond
        // the target (near the horizon its far edge runs out to many kilometres).
        const d = [];
        let reach = Infinity;
        if (view.target) {
          const r = Geo.groundDistance(a.lat, a.lon, view.target.lat, view.target.lon);
          d.push(1.5 * r);
          reach = 3 * r;
        }
        for (const c of view.footprint || []) d.push(Math.min(reach, Geo.groundDistance(a.lat, a.lon, c.lat, c.lon)));
        this.fit(d);
        if (view.target) this.fitted = true;
      }
      const p = Geo.makeProjection(a.lat, a.lon, this.width / 2, this.height / 2, this.pxPerM);
      this.projection = p;
      const at = (q) => Object.assign({ lat: q.lat, lon: q.lon }, p.toScreen(q.lat, q.lon));
      const drawn = { gimbal: view.gimbal, system_time_ms: view.time_ms, px_per_m: this.pxPerM,
        aircraft: Object.assign(at(a), { heading: a.heading }), target: null, footprint: null,
        uav: null, object: null };

      this.drawTiles(p, a);
      this.drawRangeRings(p);

      // Track, oldest first.
      const pts = view.track.map((q) => p.toScreen(q.lat, q.lon));
      n.track.setAttribute('points', pts.map((q) => fmt(q.x) + ',' + fmt(q.y)).join(' '));
      n.track.setAttribute('visibility', pts.length > 1 ? 'visible' : 'hidden');

      if (view.footprint && view.footprint.length === 4) {
        drawn.footprint = view.footprint.map(at);
        n.footprint.setAttribute('points', drawn.footprint.map((q) => fmt(q.x) + ',' + fmt(q.y)).join(' '));
        n.footprint.dataset.corners = JSON.stringify(drawn.footprint);
        n.footprint.setAttribute('visibility', 'visible');
      } else {
        n.footprint.removeAttribute('points');
        n.footprint.dataset.corners = 'null';
        n.footprint.setAttribute('visibility', 'hidden');
      }

      if (view.target) {
        drawn.target = at(view.target);
        this.place(n.target, drawn.target);
        n.target.setAttribute('cx', fmt(drawn.target.x));
        n.target.setAttribute('cy', fmt(drawn.target.y));
        n.los.setAttribute('x1', fmt(drawn.aircraft.x));
        n.los.setAttribute('y1', fmt(drawn.aircraft.y));
        n.los.setAttribute('x2', fmt(drawn.target.x));
        n.los.setAttribute('y2', fmt(drawn.target.y));
        n.target.setAttribute('visibility', 'visible');
        n.los.setAttribute('visibility', 'visible');
      } else {
        n.target.setAttribute('visibility', 'hidden');
        n.los.setAttribute('visibility', 'hidden');
        delete n.target.dataset.lat;
      }

      // The UAV position a gimbal reports in STATE `output` (output.uav), when it differs
      // from the position the aircraft symbol is drawn at (e.g. the vehicle feed's).
      n['uav-output'].replaceChildren();
      if (view.uav) {
        drawn.uav = at(view.uav);
        n['uav-output'].appendChild(el('rect', { x: fmt(drawn.uav.x - 5), y: fmt(drawn.uav.y - 5), width: 10, height: 10 }));
        this.place(n['uav-output'], drawn.uav);
        n['uav-output'].setAttribute('visibility', 'visible');
      } else {
        n['uav-output'].setAttribute('visibility', 'hidden');
      }

      drawn.object = this.drawObject(view.object, at);

      n['click-mark'].replaceChildren();
      if (view.click) {
        const c = p.toScreen(view.click.lat, view.click.lon);
        n['click-mark'].appendChild(el('circle', { cx: fmt(c.x), cy: fmt(c.y), r: 4 }));
        n['click-mark'].appendChild(el('path', { d: `M${fmt(c.x - 9)},${fmt(c.y)} h18 M${fmt(c.x)},${fmt(c.y - 9)} v18` }));
        n['click-mark'].setAttribute('visibility', 'visible');
      } else {
        n['click-mark'].setAttribute('visibility', 'hidden');
      }

      const heading = Number.isFinite(a.heading) ? a.heading : 0;
      n.aircraft.setAttribute('transform',
        `translate(${fmt(drawn.aircraft.x)},${fmt(drawn.aircraft.y)}) rotate(${heading.toFixed(1)})`);
      this.place(n.aircraft, drawn.aircraft);
      n.aircraft.dataset.heading = String(heading);
      n.aircraft.classList.toggle('no-heading', !Number.isFinite(a.heading));
      n.aircraft.setAttribute('visibility', 'visible');

      this.drawScaleBar();
      this.drawn = drawn;
    }

    // The visually tracked object (contract section 20): its ground trail, oldest first, and a
    // square where it is now (dashed while the track is lost: a prediction).
    drawObject(object, at) {
      const n = this.nodes;
      const trail = object ? object.trail.map(at) : [];
      n['object-trail'].setAttribute('points', trail.map((q) => fmt(q.x) + ',' + fmt(q.y)).join(' '));
      n['object-trail'].setAttribute('visibility', trail.length > 1 ? 'visible' : 'hidden');
      n['object-mark'].replaceChildren();
      const c = object && object.current ? at(object.current) : null;
      if (c) {
        n['object-mark'].appendChild(el('rect', { x: fmt(c.x - 6), y: fmt(c.y - 6), width: 12, height: 12 }));
        n['object-mark'].setAttribute('class', 'object-mark ' + (object.state === 'tracking' ? 'tracking' : 'lost'));
        this.place(n['object-mark'], c);
        n['object-mark'].setAttribute('visibility', 'visible');
      } else {
        n['object-mark'].setAttribute('visibility', 'hidden');
      }
      return object ? { id: object.id, state: object.state, trail, current: c } : null;
    }

    // data-lat/lon (the source) and data-x/y (SVG user units = CSS pixels from the SVG's corner).
    place(node, q) {
      node.dataset.lat = String(q.lat);
      node.dataset.lon = String(q.lon);
      node.dataset.x = fmt(q.x);
      node.dataset.y = fmt(q.y);
    }

    drawScaleBar() {
      const g = this.nodes['scale-bar'];
      g.replaceChildren();
      const metres = Geo.niceLength(160 / this.pxPerM);
      const len = metres * this.pxPerM;
      const x0 = 16;
      const y0 = this.height - 20;
      g.appendChild(el('rect', { class: 'scale-bg', x: x0 - 8, y: y0 - 22, width: len + 16 + 70, height: 32, rx: 4 }));
      g.appendChild(el('path', { d: `M${x0},${y0 - 6} v6 h${fmt(len)} v-6` }));
      const t = el('text', { x: fmt(x0 + len + 8), y: y0 });
      t.textContent = metres >= 1000 ? metres / 1000 + ' km' : metres + ' m';
      g.appendChild(t);
      g.dataset.metres = String(metres);
      g.dataset.pixels = fmt(len);
    }

    // Range rings around the aircraft at multiples of the scale bar's length, labelled.
    drawRangeRings(p) {
      const g = this.nodes.grid;
      g.replaceChildren();
      const step = Geo.niceLength(160 / this.pxPerM);
      const maxR = Math.hypot(this.width, this.height) / 2;
      for (let i = 1; i * step * this.pxPerM < maxR && i <= 20; i++) {
        const r = i * step * this.pxPerM;
        g.appendChild(el('circle', { cx: fmt(p.cx), cy: fmt(p.cy), r: fmt(r) }));
        const label = el('text', { x: fmt(p.cx + r * Math.SQRT1_2 + 3), y: fmt(p.cy - r * Math.SQRT1_2 - 3) });
        const m = i * step;
        label.textContent = m >= 1000 ? m / 1000 + ' km' : m + ' m';
        g.appendChild(label);
      }
      g.appendChild(el('path', { class: 'axis', d: `M${fmt(p.cx)},0 V${this.height} M0,${fmt(p.cy)} H${this.width}` }));
    }

    // XYZ tiles in Web Mercator, each drawn as an axis-aligned image between its projected
    // NW and SE corners (exact enough at the scales where tiles help).
    drawTiles(p, a) {
      const g = this.nodes.tiles;
      if (!this.tilesUrl) { if (g.firstChild) g.replaceChildren(); return; }
      const circumference = 40075016.686 * Math.cos((a.lat * Math.PI) / 180);
      let z = Math.round(Math.log2((circumference * this.pxPerM) / 256));
      z = Math.max(0, Math.min(19, z));
      const c = p.toLatLon(0, 0);
      const d = p.toLatLon(this.width, this.height);
      const t0 = Geo.tileOf(c.lat, c.lon, z);
      const t1 = Geo.tileOf(d.lat, d.lon, z);
      const wanted = new Set();
      const n = Math.pow(2, z);
      for (let ty = Math.floor(t0.y); ty <= Math.floor(t1.y) && ty < n; ty++) {
        for (let tx = Math.floor(t0.x); tx <= Math.floor(t1.x); tx++) {
          if (ty < 0) continue;
          const key = `${z}/${tx}/${ty}`;
          wanted.add(key);
          let img = this.tileNodes.get(key);
          if (!img) {
            const wx = ((tx % n) + n) % n;
            const url = this.tilesUrl.replace('{z}', z).replace('{x}', wx).replace('{y}', ty);
            img = el('image', { href: url, preserveAspectRatio: 'none' });
            this.tileNodes.set(key, img);
          }
          const nw = Geo.tileCorner(tx, ty, z);
          const se = Geo.tileCorner(tx + 1, ty + 1, z);
          const q0 = p.toScreen(nw.lat, nw.lon);
          const q1 = p.toScreen(se.lat, se.lon);
          img.setAttribute('x', fmt(q0.x));
          img.setAttribute('y', fmt(q0.y));
          img.setAttribute('width', fmt(q1.x - q0.x + 0.5));
          img.setAttribute('height', fmt(q1.y - q0.y + 0.5));
          if (img.parentNode !== g) g.appendChild(img);
        }
      }
      for (const [key, img] of this.tileNodes) {
        if (!wanted.has(key)) { img.remove(); if (!key.startsWith(z + '/')) this.tileNodes.delete(key); }
      }
    }
  }

  global.GimbaldPlanView = PlanView;
})(window);
