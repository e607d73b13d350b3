// The video panel: follows GET /api/video/{gimbal} (docs/http.md "Video"), decodes the H.264
// access units in the browser with WebCodecs' VideoDecoder (Annex B, parameter sets in-band:
// no description) - or, where the browser has no VideoDecoder, with Media Source Extensions
// (mse_player.js; `?video=mse` in the page's URL forces it) - and draws each frame on a
// canvas at the video's own size, scaled by CSS to fit the pane. Falling behind, it drops frames up to the next key frame. Reconnects by
// itself. Optionally reads the simulator's time code from each drawn frame (glass-to-glass
// latency, docs/simulator.md "Time code"). Exposed as window.GimbaldVideoPanel.
'use strict';

(function (global) {
  const MAX_DECODE_QUEUE = 8; // frames waiting in the decoder before we skip to a key frame
  const LATENCY_SAMPLES = 2000;

  // ---- the simulator's time code (docs/simulator.md): 64 cells of B px in two rows -------
  function crc8(bytes) {
    let c = 0;
    for (const b of bytes) {
      c ^= b;
      for (let i = 0; i < 8; i++) c = c & 0x80 ? ((c << 1) ^ 0x07) & 0xff : (c << 1) & 0xff;
    }
    return c;
  }
  // Unix milliseconds from the top-left of a canvas drawn at the frame's own size, or null.
  function readTimeCode(ctx, width, height) {
    let B = 16;
    if (width < 512 || height < 32) {
      B = Math.floor(Math.min(width / 32, height / 2) / 2) * 2;
      if (B < 4) return null;
    }
    const img = ctx.getImageData(0, 0, 32 * B, 2 * B).data;
    const stride = 32 * B * 4;
    const luma = [];
    for (let k = 0; k < 64; k++) {
      const x0 = (k % 32) * B + B / 4;
      const y0 = Math.floor(k / 32) * B + B / 4;
      let sum = 0;
      for (let y = y0; y < y0 + B / 2; y++) {
        for (let x = x0; x < x0 + B / 2; x++) {
          const i = y * stride + x * 4;
          sum += 0.299 * img[i] + 0.587 * img[i + 1] + 0.114 * img[i + 2];
        }
      }
      luma.push(sum / ((B / 2) * (B / 2)));
    }
    const white = (luma[0] + luma[2] + luma[61] + luma[63]) / 4;
    const black = (luma[1] + luma[3] + luma[60] + luma[62]) / 4;
    if (white - black < 60) return null;
    const mid = (white + black) / 2;
    const margin = (white - black) / 4;
    const bits = [];
    for (const v of luma) {
      if (Math.abs(v - mid) < margin) return null;
      bits.push(v > mid ? 1 : 0);
    }
    const marks = [1, 0, 1, 0];
    const stops = [0, 1, 0, 1];
    for (let i = 0; i < 4; i++) if (bits[i] !== marks[i] || bits[60 + i] !== stops[i]) return null;
    const bytes = [];
    for (let b = 0; b < 6; b++) {
      let v = 0;
      for (let i = 0; i < 8; i++) v = (v << 1) | bits[4 + b * 8 + i];
      bytes.push(v);
    }
    let crc = 0;
    for (let i = 0; i < 8; i++) crc = (crc << 1) | bits[52 + i];
    if (crc8(bytes) !== crc) return null;
    return bytes.reduce((t, v) => t * 256 + v, 0);
  }

  class VideoPanel {
    // `canvas`: where frames are drawn; `onStatus(text, kind)`: what to show the operator.
    constructor(canvas, onStatus) {
      this.canvas = canvas;
      this.ctx = canvas.getContext('2d', { willReadFrequently: true });
      this.onStatus = onStatus || (() => {});
      this.onFrame = null; // called after each drawn frame
      this.gimbal = null;
      this.socket = null;
      this.decoder = null;
      this.config = null;
      this.needKey = true;
      this.retryDelay = 500;
      this.retryTimer = null;
      this.measure = false; // read the time code of every drawn frame
      this.latencies = [];
      this.stats = { messages: 0, decoded: 0, drawn: 0, skipped: 0, errors: 0, reconnects: 0,
        lastDrawnAt: 0, lastTimestamp: null, lastCode: null, state: 'idle' };
      const forced = new URLSearchParams(location.search).get('video');
      const webcodecs = typeof global.VideoDecoder === 'function' && forced !== 'mse';
      this.mode = webcodecs ? 'webcodecs' : typeof global.MediaSource === 'function' ? 'mse' : null;
      this.supported = this.mode !== null;
      this.mse = null;
      if (this.mode === 'mse') {
        const video = document.createElement('video');
        video.muted = true;
        video.playsInline = true;
        video.className = 'mse-video';
        canvas.parentNode.append(video);
        this.mse = new global.GimbaldMsePlayer(video, () => {
          if (video.videoWidth > 0) this.drawSource(video, video.videoWidth, video.videoHeight);
        });
      }
    }

    // Follows `gimbal`'s video (null: none).
    show(gimbal) {
      if (gimbal === this.gimbal) return;
      this.stop();
      this.gimbal = gimbal;
      if (!gimbal) return;
      if (!this.supported) {
        this.status('this browser has neither WebCodecs nor Media Source Extensions: no video', 'bad');
        return;
      }
      this.connect();
    }

    stop() {
      clearTimeout(this.retryTimer);
      this.retryTimer = null;
      if (this.socket) {
        const s = this.socket;
        this.socket = null;
        s.onclose = s.onmessage = s.onerror = null;
        s.close();
      }
      this.closeDecoder();
      this.config = null;
      this.stats.state = 'idle';
    }

    status(text, kind) {
      this.stats.state = kind === 'good' ? 'live' : kind === 'warn' ? 'connecting' : 'down';
      this.onStatus(text, kind);
    }

    connect() {
      const url = new URL('api/video/' + encodeURIComponent(this.gimbal), location.href);
      url.protocol = location.protocol === 'https:' ? 'wss:' : 'ws:';
      const socket = new WebSocket(url);
      socket.binaryType = 'arraybuffer';
      this.socket = socket;
      this.status('connecting to the video', 'warn');
      socket.onopen = () => { this.retryDelay = 500; };
      socket.onmessage = (ev) => {
        this.stats.messages++;
        if (typeof ev.data === 'string') this.takeConfig(ev.data);
        else this.takeFrame(ev.data);
      };
      socket.onclose = () => {
        if (this.socket !== socket) return;
        this.socket = null;
        this.closeDecoder();
        this.config = null;
        this.status('no video - reconnecting', 'bad');
        this.stats.reconnects++;
        this.retryTimer = setTimeout(() => this.connect(), this.retryDelay);
        this.retryDelay = Math.min(5000, this.retryDelay * 2);
      };
      socket.onerror = () => { /* onclose follows */ };
    }

    takeConfig(text) {
      let c;
      try { c = JSON.parse(text); } catch (e) { return; }
      if (c.type !== 'config') return;
      const same = this.config && this.config.codec === c.codec && this.config.width === c.width &&
        this.config.height === c.height;
      this.config = c;
      if (this.mode === 'mse') {
        if (!global.GimbaldMsePlayer.supported(c.codec)) {
          this.status(`${c.codec}: not playable with Media Source Extensions here (no WebCodecs: ` +
            'load the page from http://localhost, http://127.0.0.1 or over HTTPS)', 'bad');
          return;
        }
        if (!same || !this.mse.config) this.mse.configure(c);
        this.status(`${c.codec} ${c.width}\u00d7${c.height} (MSE)`, 'good');
        return;
      }
      if (same && this.decoder && this.decoder.state === 'configured') return;
      this.closeDecoder();
      this.openDecoder();
    }

    openDecoder() {
      const c = this.config;
      this.decoder = new global.VideoDecoder({
        output: (frame) => this.draw(frame),
        error: (e) => {
          this.stats.errors++;
          this.status('video decoder error: ' + e.message, 'bad');
          this.decoder = null;
          this.needKey = true;
        },
      });
      // Annex B with SPS/PPS in-band: no `description`.
      this.decoder.configure({ codec: c.codec, codedWidth: c.width, codedHeight: c.height,
        optimizeForLatency: true, hardwareAcceleration: 'no-preference' });
      this.needKey = true;
      if (this.canvas.width !== c.width || this.canvas.height !== c.height) {
        this.canvas.width = c.width;
        this.canvas.height = c.height;
      }
      this.status(`${c.codec} ${c.width}\u00d7${c.height}`, 'good');
    }

    closeDecoder() {
      if (this.mse) { this.mse.reset(); this.mse.config = null; }
      if (this.decoder && this.decoder.state !== 'closed') {
        try { this.decoder.close(); } catch (e) { /* already closed */ }
      }
      this.decoder = null;
    }

    takeFrame(buffer) {
      if (buffer.byteLength < 10) return;
      const view = new DataView(buffer);
      const timestamp = Number(view.getBigUint64(0));
      const key = (view.getUint8(8) & 1) === 1;
      if (this.mse) {
        this.mse.push(timestamp, key, new Uint8Array(buffer, 9));
        this.stats.skipped = this.mse.skipped;
        return;
      }
      if (!this.decoder && this.config && key) this.openDecoder();
      if (!this.decoder || this.decoder.state !== 'configured') return;
      // Behind (a slow machine, a hidden tab): skip to the next key frame rather than lag.
      if (!key && (this.needKey || this.decoder.decodeQueueSize > MAX_DECODE_QUEUE)) {
        this.needKey = true;
        this.stats.skipped++;
        return;
      }
      this.needKey = false;
      this.decoder.decode(new global.EncodedVideoChunk({
        type: key ? 'key' : 'delta', timestamp, data: new Uint8Array(buffer, 9),
      }));
    }

    draw(frame) {
      this.stats.lastTimestamp = frame.timestamp;
      this.drawSource(frame, frame.displayWidth, frame.displayHeight);
      frame.close();
    }

    // A decoded picture (a VideoFrame, or the MSE player's <video>) onto the canvas.
    drawSource(source, w, h) {
      this.stats.decoded++;
      if (this.canvas.width !== w || this.canvas.height !== h) {
        this.canvas.width = w;
        this.canvas.height = h;
      }
      this.ctx.drawImage(source, 0, 0, w, h);
      const now = Date.now();
      this.stats.drawn++;
      this.stats.lastDrawnAt = now;
      if (this.measure) {
        const code = readTimeCode(this.ctx, w, h);
        this.stats.lastCode = code;
        if (code !== null) {
          this.latencies.push(now - code);
          if (this.latencies.length > LATENCY_SAMPLES) this.latencies.shift();
        }
      }
      if (this.onFrame) this.onFrame();
    }

    get width() { return this.canvas.width; }
    get height() { return this.canvas.height; }
  }

  global.GimbaldVideoPanel = VideoPanel;
  global.GimbaldTimeCode = { read: readTimeCode, crc8 };
})(window);
