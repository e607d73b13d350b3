// Drag a box on the video to start a visual track (contract section 20): mousedown, move
// more than a few pixels, mouseup. Draws the rubber band (a div over the picture) while
// dragging and hands the box in image coordinates to `onBox`; the click that follows the
// drag's mouseup is swallowed so it is not also a click-to-point. Exposed as
// window.GimbaldTrackBox.
'use strict';

(function (global) {
  // Less movement than this is a click, not a drag (hand jitter on a press).
  const DRAG_PX = 5;
  const clamp = (v) => Math.max(-1, Math.min(1, v));

  class TrackBox {
    // target: the picture's element; band: an absolutely placed element in the same box as
    // the picture; opts.toImage(clientX, clientY) -> {x, y} (the console's conversion);
    // opts.enabled() -> whether tracking is offered; opts.onBox({x0, y0, x1, y1}).
    constructor(target, band, opts) {
      this.target = target;
      this.band = band;
      this.opts = opts;
      this.start = null; // {x, y} client pixels of the mousedown
      this.dragging = false;
      this.swallow = false;
      target.addEventListener('mousedown', (ev) => this.down(ev));
      // On window: the drag may end outside the picture.
      window.addEventListener('mousemove', (ev) => this.move(ev));
      window.addEventListener('mouseup', (ev) => this.up(ev));
    }

    down(ev) {
      // No preventDefault: the press still takes focus off an input, so the keys work after it.
      if (ev.button !== 0 || !this.opts.enabled()) return;
      this.start = { x: ev.clientX, y: ev.clientY };
      this.dragging = false;
    }

    move(ev) {
      if (!this.start) return;
      // Released outside the window: no mouseup came.
      if ((ev.buttons & 1) === 0) { this.cancel(); return; }
      if (!this.dragging && Math.hypot(ev.clientX - this.start.x, ev.clientY - this.start.y) < DRAG_PX) return;
      this.dragging = true;
      const r = this.target.getBoundingClientRect();
      // The band stays on the picture even when the pointer leaves it.
      const x = (v) => Math.max(0, Math.min(r.width, v - r.left));
      const y = (v) => Math.max(0, Math.min(r.height, v - r.top));
      const [ax, bx] = [x(this.start.x), x(ev.clientX)].sort((a, b) => a - b);
      const [ay, by] = [y(this.start.y), y(ev.clientY)].sort((a, b) => a - b);
      Object.assign(this.band.style, { left: ax + 'px', top: ay + 'px', width: bx - ax + 'px', height: by - ay + 'px' });
      this.band.hidden = false;
    }

    up(ev) {
      if (!this.start) return;
      const start = this.start;
      const dragged = this.dragging;
      this.cancel();
      if (!dragged) return;
      // The browser's click follows this mouseup in the same task; a later click is not ours.
      this.swallow = true;
      setTimeout(() => { this.swallow = false; }, 0);
      const a = this.opts.toImage(start.x, start.y);
      const b = this.opts.toImage(ev.clientX, ev.clientY);
      const box = { x0: clamp(Math.min(a.x, b.x)), y0: clamp(Math.min(a.y, b.y)),
        x1: clamp(Math.max(a.x, b.x)), y1: clamp(Math.max(a.y, b.y)) };
      // Dragged wholly off the picture's edge: nothing left to track.
      if (box.x1 <= box.x0 || box.y1 <= box.y0) return;
      this.opts.onBox(box);
    }

    // Ends a drag without a track (Esc, mouseup); true when one was in progress.
    cancel() {
      const was = !!this.start;
      this.start = null;
      this.dragging = false;
      this.band.hidden = true;
      return was;
    }

    // For the picture's click handler: true for the click that ends a drag.
    swallowClick() {
      const s = this.swallow;
      this.swallow = false;
      return s;
    }
  }

  global.GimbaldTrackBox = TrackBox;
})(window);
