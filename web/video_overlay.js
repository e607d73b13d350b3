// What the console draws over the video (an SVG the size of the shown picture): a
// crosshair, the camera's mode and field of view, a north arrow and the aircraft's heading
// relative to where the camera looks, ground points placed where gimbald's `project`
// command says they appear (image x, y in -1..1), and STATE `track`'s box with its state, id
// and confidence (contract section 20). Exposed as window.GimbaldVideoOverlay.
'use strict';

(function (global) {
  const Geo = global.GimbaldGeo;
  const SVG_NS = 'http://www.w3.org/2000/svg';

  function el(name, attrs, parent) {
    const node = document.createElementNS(SVG_NS, name);
    for (const k in attrs) node.setAttribute(k, attrs[k]);
    if (parent) parent.append(node);
    return node;
  }

  // Degrees clockwise from north, from one point to another (spherical, good enough for an arrow).
  function bearing(a, b) {
    const f1 = (a.lat * Math.PI) / 180;
    const f2 = (b.lat * Math.PI) / 180;
    const dl = ((b.lon - a.lon) * Math.PI) / 180;
    const y = Math.sin(dl) * Math.cos(f2);
    const x = Math.cos(f1) * Math.sin(f2) - Math.sin(f1) * Math.cos(f2) * Math.cos(dl);
    return ((Math.atan2(y, x) * 180) / Math.PI + 360) % 360;
  }

  // Where the camera looks, degrees from north: towards the ground at the image centre, else
  // the target, else the mount's yaw plus pan.
  function cameraAzimuth(t) {
    if (!t || !Number.isFinite(t.lat)) return null;
    for (const p of [t.ground, t.target]) {
      if (p && Number.isFinite(p.lat) && Geo.groundDistance(t.lat, t.lon, p.lat, p.lon) > 1) return bearing(t, p);
    }
    return Number.isFinite(t.yaw) && Number.isFinite(t.pan) ? (t.yaw + t.pan + 360) % 360 : null;
  }

  class VideoOverlay {
    constructor(svg) {
      this.svg = svg;
      this.width = 1;
      this.height = 1;
      this.drawn = null; // what was drawn last (test hook)
    }

    // `points`: [{name, label, x, y}] in image coordinates (-1..1), from `project`.
    render(state, points, zoom) {
      const r = this.svg.getBoundingClientRect();
      this.width = Math.max(1, r.width);
      this.height = Math.max(1, r.height);
      const W = this.width;
      const H = this.height;
      this.svg.setAttribute('viewBox', `0 0 ${W} ${H}`);
      this.svg.replaceChildren();
      const t = state && state.telemetry;
      const cx = W / 2;
      const cy = H / 2;
      const cross = el('g', { class: 'crosshair' }, this.svg);
      for (const [x1, y1, x2, y2] of [[cx - 24, cy, cx - 6, cy], [cx + 6, cy, cx + 24, cy],
        [cx, cy - 24, cx, cy - 6], [cx, cy + 6, cx, cy + 24]]) {
        el('line', { x1, y1, x2, y2 }, cross);
      }
      const drawn = { crosshair: { x: cx, y: cy }, points: [], azimuth: null, heading: null };

      const az = cameraAzimuth(t);
      if (az !== null) {
        const g = el('g', { class: 'compass', transform: `translate(${W - 42},42)` }, this.svg);
        el('circle', { r: 30 }, g);
        const north = el('g', { transform: `rotate(${(-az).toFixed(2)})` }, g);
        el('path', { class: 'north', d: 'M0,-26 L6,-8 L0,-12 L-6,-8 Z' }, north);
        el('text', { y: -30, 'text-anchor': 'middle', class: 'n' }, north).textContent = 'N';
        drawn.azimuth = az;
        if (Number.isFinite(t.yaw)) {
          const hdg = el('g', { transform: `rotate(${(t.yaw - az).toFixed(2)})` }, g);
          el('path', { class: 'heading', d: 'M0,-18 L4,-4 L0,-7 L-4,-4 Z M0,-7 L0,14' }, hdg);
          drawn.heading = t.yaw;
        }
        el('text', { x: 30, y: 46, 'text-anchor': 'end', class: 'label' }, g).textContent =
          `cam ${az.toFixed(0)}\u00b0  hdg ${Number.isFinite(t.yaw) ? t.yaw.toFixed(0) : '-'}\u00b0`;
      }

      const info = [];
      if (t) {
        info.push(`mode ${t.mode}`);
        if (Number.isFinite(t.hfov)) info.push(`hfov ${t.hfov.toFixed(1)}\u00b0`);
      }
      if (Number.isFinite(zoom)) info.push(`zoom \u00d7${zoom}`);
      const text = el('text', { x: 10, y: H - 12, class: 'info' }, this.svg);
      text.textContent = info.join('   ');
      drawn.info = text.textContent;

      for (const p of points || []) {
        if (!Number.isFinite(p.x) || !Number.isFinite(p.y) || Math.abs(p.x) > 1 || Math.abs(p.y) > 1) continue;
        const x = ((p.x + 1) / 2) * W;
        const y = ((p.y + 1) / 2) * H;
        const g = el('g', { class: 'point ' + p.name, transform: `translate(${x.toFixed(2)},${y.toFixed(2)})` }, this.svg);
        if (p.name === 'target') el('circle', { r: 9 }, g);
        else el('path', { d: 'M-7,-7 L7,7 M-7,7 L7,-7' }, g);
        el('text', { x: 11, y: -8 }, g).textContent = p.label;
        drawn.points.push({ name: p.name, x, y });
      }
      drawn.track = this.drawTrack(state && state.track, W, H);
      this.drawn = drawn;
    }

    // The visual track's box: solid while `tracking`, dashed in another colour while `lost`
    // (then it is the tracker's prediction), labelled "tracking #3 0.82". Returns what was
    // drawn in overlay pixels, or null.
    drawTrack(track, W, H) {
      const b = track && track.box;
      if (!b || ![b.x0, b.y0, b.x1, b.y1].every(Number.isFinite)) return null;
      const x0 = ((b.x0 + 1) / 2) * W;
      const y0 = ((b.y0 + 1) / 2) * H;
      const x1 = ((b.x1 + 1) / 2) * W;
      const y1 = ((b.y1 + 1) / 2) * H;
      const lost = track.state !== 'tracking';
      const g = el('g', { class: 'track-box ' + (lost ? 'lost' : 'tracking') }, this.svg);
      el('rect', { x: x0.toFixed(2), y: y0.toFixed(2), width: (x1 - x0).toFixed(2), height: (y1 - y0).toFixed(2) }, g);
      const conf = Number.isFinite(track.confidence) ? track.confidence.toFixed(2) : '-';
      const label = `${track.state} #${track.id} ${conf}`;
      // Above the box, or inside its top when the box touches the picture's top edge.
      el('text', { x: x0.toFixed(2), y: (y0 > 16 ? y0 - 5 : y0 + 14).toFixed(2) }, g).textContent = label;
      return { id: track.id, state: track.state, confidence: track.confidence, label,
        x0, y0, x1, y1, at: Date.now() };
    }
  }

  global.GimbaldVideoOverlay = VideoOverlay;
})(window);
