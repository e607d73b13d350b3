// The video panel's fallback where WebCodecs is missing (a page loaded over plain HTTP from
// another machine is not a secure context, and browsers then hide VideoDecoder): Media
// Source Extensions, which every browser offers anywhere. The H.264 access units of
// /api/video are wrapped here into fragmented MP4 (ISO/IEC 14496-12 boxes, the avcC record
// of 14496-15 5.3.3.1 from the stream's own SPS and PPS): an init segment, then one
// moof+mdat fragment per access unit. A muted <video> element plays them at the live edge;
// each new frame is handed to onFrame to be drawn on the panel's canvas.
// H.264 only (an H.265 stream needs WebCodecs). Exposed as window.GimbaldMsePlayer.
'use strict';

(function (global) {
  const TIMESCALE = 90000;
  const MAX_QUEUE = 30; // fragments waiting for the SourceBuffer before we skip to a key frame
  const LIVE_SLACK_S = 0.3; // further behind the buffered end than this: jump to it

  const ascii = (s) => Array.from(s, (c) => c.charCodeAt(0));
  const u16 = (v) => [(v >>> 8) & 255, v & 255];
  const u32 = (v) => [(v >>> 24) & 255, (v >>> 16) & 255, (v >>> 8) & 255, v & 255];
  const u64 = (v) => u32(Math.floor(v / 2 ** 32)).concat(u32(v >>> 0));
  const zeros = (n) => new Array(n).fill(0);
  const MATRIX = [].concat(u32(0x10000), u32(0), u32(0), u32(0), u32(0x10000), u32(0), u32(0), u32(0), u32(0x40000000));

  // A box: 32-bit size, 4-character type, then the parts (arrays of bytes or Uint8Arrays).
  function box(type, ...parts) {
    const size = 8 + parts.reduce((n, p) => n + p.length, 0);
    const out = new Uint8Array(size);
    out.set(u32(size), 0);
    out.set(ascii(type), 4);
    let at = 8;
    for (const p of parts) { out.set(p, at); at += p.length; }
    return out;
  }
  const fullBox = (type, version, flags, ...parts) => box(type, [version].concat(u32(flags).slice(1)), ...parts);

  // The NAL units of an Annex B access unit, without start codes.
  function nalUnits(bytes) {
    const out = [];
    let start = -1;
    for (let i = 0; i + 2 < bytes.length; i++) {
      if (bytes[i] === 0 && bytes[i + 1] === 0 && bytes[i + 2] === 1) {
        if (start >= 0) {
          let end = i;
          while (end > start && bytes[end - 1] === 0) end--;
          out.push(bytes.subarray(start, end));
        }
        start = i + 3;
        i += 2;
      }
    }
    if (start >= 0 && start < bytes.length) out.push(bytes.subarray(start));
    return out;
  }

  function initSegment(sps, pps, width, height) {
    const avcC = box('avcC', [1, sps[1], sps[2], sps[3], 0xff, 0xe1], u16(sps.length), sps, [1], u16(pps.length), pps);
    const avc1 = box('avc1', zeros(6), u16(1), zeros(16), u16(width), u16(height), u32(0x480000), u32(0x480000),
      u32(0), u16(1), zeros(32), u16(0x18), u16(0xffff), avcC);
    const stbl = box('stbl', fullBox('stsd', 0, 0, u32(1), avc1), fullBox('stts', 0, 0, u32(0)),
      fullBox('stsc', 0, 0, u32(0)), fullBox('stsz', 0, 0, u32(0), u32(0)), fullBox('stco', 0, 0, u32(0)));
    const minf = box('minf', fullBox('vmhd', 0, 1, zeros(8)),
      box('dinf', fullBox('dref', 0, 0, u32(1), fullBox('url ', 0, 1))), stbl);
    const mdia = box('mdia', fullBox('mdhd', 0, 0, u32(0), u32(0), u32(TIMESCALE), u32(0), u16(0x55c4), u16(0)),
      fullBox('hdlr', 0, 0, u32(0), ascii('vide'), zeros(12), ascii('video'), [0]), minf);
    const trak = box('trak', fullBox('tkhd', 0, 3, u32(0), u32(0), u32(1), u32(0), u32(0), zeros(8), u16(0), u16(0),
      u16(0), u16(0), MATRIX, u32(width * 65536), u32(height * 65536)), mdia);
    const mvhd = fullBox('mvhd', 0, 0, u32(0), u32(0), u32(1000), u32(0), u32(0x10000), u16(0x100), zeros(10),
      MATRIX, zeros(24), u32(2));
    const mvex = box('mvex', fullBox('trex', 0, 0, u32(1), u32(1), u32(0), u32(0), u32(0)));
    const ftyp = box('ftyp', ascii('isom'), u32(0x200), ascii('isom'), ascii('iso6'), ascii('avc1'), ascii('mp41'));
    const moov = box('moov', mvhd, trak, mvex);
    const out = new Uint8Array(ftyp.length + moov.length);
    out.set(ftyp, 0);
    out.set(moov, ftyp.length);
    return out;
  }

  // One fragment: a moof with one sample (its data offset points past the moof into the
  // mdat's payload), then the mdat.
  function fragment(sequence, decodeTime, duration, sample, key) {
    const flags = key ? 0x02000000 : 0x01010000; // sample_depends_on 2 (I) / 1 and non-sync
    const build = (offset) => box('moof', fullBox('mfhd', 0, 0, u32(sequence)),
      box('traf', fullBox('tfhd', 0, 0x020000, u32(1)), fullBox('tfdt', 1, 0, u64(decodeTime)),
        fullBox('trun', 0, 0x000701, u32(1), u32(offset), u32(duration), u32(sample.length), u32(flags))));
    const moof = build(0);
    const final = build(moof.length + 8);
    const mdat = box('mdat', sample);
    const out = new Uint8Array(final.length + mdat.length);
    out.set(final, 0);
    out.set(mdat, final.length);
    return out;
  }

  class MsePlayer {
    static supported(codec) {
      return typeof global.MediaSource === 'function' &&
        global.MediaSource.isTypeSupported(`video/mp4; codecs="${codec}"`);
    }

    // `video`: a muted <video> element; `onFrame()`: a new frame is showing in it.
    constructor(video, onFrame) {
      this.video = video;
      this.onFrame = onFrame;
      this.config = null;
      this.source = null;
      this.buffer = null;
      this.queue = [];
      this.sequence = 0;
      this.firstUs = null;
      this.lastUs = null;
      this.duration = TIMESCALE / 15;
      this.needKey = true;
      this.skipped = 0;
      this.closed = false;
      this.watchFrames();
    }

    // A new configuration: a fresh MediaSource (the init segment waits for a key frame's SPS/PPS).
    configure(config) {
      this.reset();
      this.config = config;
      this.source = new global.MediaSource();
      this.video.src = URL.createObjectURL(this.source);
      this.source.addEventListener('sourceopen', () => {
        if (!this.source || this.source.readyState !== 'open') return;
        this.buffer = this.source.addSourceBuffer(`video/mp4; codecs="${config.codec}"`);
        this.buffer.mode = 'segments';
        this.buffer.addEventListener('updateend', () => this.pump());
        this.pump();
      }, { once: true });
    }

    reset() {
      this.queue = [];
      this.buffer = null;
      if (this.source && this.video.src) URL.revokeObjectURL(this.video.src);
      this.source = null;
      this.video.removeAttribute('src');
      this.sequence = 0;
      this.firstUs = null;
      this.lastUs = null;
      this.needKey = true;
      this.initialised = false;
    }

    close() {
      this.closed = true;
      this.reset();
    }

    push(timestampUs, key, annexB) {
      if (!this.config) return;
      if (this.needKey && !key) { this.skipped++; return; }
      if (!key && this.queue.length > MAX_QUEUE) {
        this.queue = this.queue.filter((q) => q.init);
        this.needKey = true;
        this.skipped++;
        return;
      }
      const nals = nalUnits(annexB);
      const parts = [];
      let sps = null;
      let pps = null;
      for (const n of nals) {
        const type = n[0] & 0x1f;
        if (type === 7) sps = sps || n;
        if (type === 8) pps = pps || n;
        if (type === 9) continue; // access unit delimiter: not part of an MP4 sample
        parts.push(u32(n.length), n);
      }
      if (key && !this.initialised) {
        if (!sps || !pps) return;
        this.queue.push({ init: true, bytes: initSegment(sps, pps, this.config.width, this.config.height) });
        this.initialised = true;
      }
      this.needKey = false;
      const size = parts.reduce((n, p) => n + p.length, 0);
      const sample = new Uint8Array(size);
      let at = 0;
      for (const p of parts) { sample.set(p, at); at += p.length; }
      if (this.firstUs === null) this.firstUs = timestampUs;
      if (this.lastUs !== null && timestampUs > this.lastUs) this.duration = Math.round(((timestampUs - this.lastUs) * 9) / 100);
      this.lastUs = timestampUs;
      const decodeTime = Math.max(0, Math.round(((timestampUs - this.firstUs) * 9) / 100));
      this.queue.push({ bytes: fragment(++this.sequence, decodeTime, this.duration, sample, key) });
      this.pump();
    }

    pump() {
      if (!this.buffer || this.buffer.updating) return;
      const v = this.video;
      const held = v.buffered;
      // Keep only the last few seconds in the SourceBuffer (removal ends in updateend too).
      if (held.length && v.currentTime - held.start(0) > 10) {
        this.buffer.remove(held.start(0), v.currentTime - 5);
        return;
      }
      if (!this.queue.length) return;
      try {
        this.buffer.appendBuffer(this.queue.shift().bytes);
      } catch (e) {
        // QuotaExceeded or a closed source: start again at the next key frame.
        this.configure(this.config);
        return;
      }
      const b = this.video.buffered;
      if (b.length) {
        const end = b.end(b.length - 1);
        if (end - this.video.currentTime > LIVE_SLACK_S) this.video.currentTime = Math.max(b.start(b.length - 1), end - 0.05);
      }
      if (this.video.paused) this.video.play().catch(() => {});
    }

    // A new frame on screen: requestVideoFrameCallback where there is one, else polling.
    watchFrames() {
      const v = this.video;
      if (typeof v.requestVideoFrameCallback === 'function') {
        const tick = () => { if (this.closed) return; this.onFrame(); v.requestVideoFrameCallback(tick); };
        v.requestVideoFrameCallback(tick);
        return;
      }
      let last = -1;
      const poll = () => {
        if (this.closed) return;
        if (v.currentTime !== last && v.readyState >= 2) { last = v.currentTime; this.onFrame(); }
        global.requestAnimationFrame(poll);
      };
      global.requestAnimationFrame(poll);
    }
  }

  global.GimbaldMsePlayer = MsePlayer;
})(window);
