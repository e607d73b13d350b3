// The operator console in a real browser: Debian's chromium, headless, driven by puppeteer-core.
// gimbal-sim (TCP, --rx-log) behind gimbald with `http` configured. Checks that the plan view
// draws the aircraft, target and footprint where STATE says (projection recomputed here from
// the formula in docs/console.md), that a click on the map reaches the gimbal as a geopoint at
// the clicked place, that the position control works, that laser controls are absent unless
// fire is allowed and then need arm + fire + confirm, and that the page reconnects after the
// daemon restarts, and that with a terrain section a click leaves the altitude to gimbald.
// Saves a screenshot (CONSOLE_SCREENSHOT, default ./console.png).
// Exit 0 on success, 1 on a failed check.
'use strict';
const dgram = require('dgram');
const net = require('net');
const fs = require('fs');
const os = require('os');
const path = require('path');
const http = require('http');
const { spawn, spawnSync } = require('child_process');
const puppeteer = require('puppeteer-core');

const GIMBALD = process.env.GIMBALD;
const GIMBAL_SIM = process.env.GIMBAL_SIM;
const SOURCE_DIR = process.env.GIMBAL_SOURCE_DIR || path.resolve(__dirname, '../../..');
const CHROMIUM = process.env.CHROMIUM || '/usr/bin/chromium';
const SCREENSHOT = process.env.CONSOLE_SCREENSHOT || path.join(process.cwd(), 'console.png');
const PIXEL_TOLERANCE = 1.5;
const children = [];
let failures = 0;
let workDir = null; // removed at the end unless the test failed

function check(ok, what) {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
  if (!ok) failures++;
  return ok;
}
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
async function waitFor(pred, timeoutMs, intervalMs = 100) {
  const end = Date.now() + timeoutMs;
  for (;;) {
    const v = await pred();
    if (v || Date.now() > end) return v;
    await sleep(intervalMs);
  }
}

async function freePort(kind) {
  return new Promise((resolve) => {
    if (kind === 'tcp') {
      const s = net.createServer();
      s.listen(0, '127.0.0.1', () => { const p = s.address().port; s.close(() => resolve(p)); });
    } else {
      const s = dgram.createSocket('udp4');
      s.bind(0, '127.0.0.1', () => { const p = s.address().port; s.close(() => resolve(p)); });
    }
  });
}

function start(cmd, args) {
  const child = spawn(cmd, args, { stdio: ['ignore', 'pipe', 'pipe'] });
  children.push(child);
  child.lines = [];
  let rest = '';
  child.stdout.on('data', (d) => {
    rest += d.toString();
    const lines = rest.split('\n');
    rest = lines.pop();
    child.lines.push(...lines);
  });
  child.stderrText = '';
  child.stderr.on('data', (d) => { if (child.stderrText.length < 20000) child.stderrText += d.toString(); });
  return child;
}
function stop(child) {
  return new Promise((resolve) => {
    if (child.exitCode !== null || child.signalCode !== null) { resolve(); return; }
    const t = setTimeout(() => child.kill('SIGKILL'), 5000);
    child.once('exit', () => { clearTimeout(t); resolve(); });
    child.kill('SIGTERM');
  });
}

function httpGet(port, p) {
  return new Promise((resolve) => {
    const req = http.get({ host: '127.0.0.1', port, path: p, timeout: 2000 }, (res) => {
      let body = '';
      res.on('data', (d) => { body += d; });
      res.on('end', () => resolve({ status: res.statusCode, body }));
    });
    req.on('error', () => resolve(null));
    req.on('timeout', () => { req.destroy(); resolve(null); });
  });
}

// STATEs of our own UDP subscription (20 Hz), keyed by telemetry.system_time_ms, so a drawn
// frame can be compared with the exact STATE it was drawn from.
class Reference {
  constructor(commandPort, gimbal) {
    this.port = commandPort;
    this.gimbal = gimbal;
    this.byTime = new Map();
    this.latest = null;
    this.socket = dgram.createSocket('udp4');
    this.socket.on('message', (buf) => {
      let m;
      try { m = JSON.parse(buf.toString()); } catch (e) { return; }
      if (m.type === 'state' && m.gimbal === gimbal && m.state.telemetry) {
        this.latest = m.state;
        this.byTime.set(m.state.telemetry.system_time_ms, m.state);
        if (this.byTime.size > 2000) this.byTime.delete(this.byTime.keys().next().value);
      }
    });
  }
  async open() {
    await new Promise((r) => this.socket.bind(0, '127.0.0.1', r));
    const sub = () => this.socket.send(JSON.stringify({ cmd: 'subscribe', gimbal: this.gimbal, rate_hz: 20, ttl_s: 60, events: false }), this.port, '127.0.0.1');
    sub();
    this.timer = setInterval(sub, 20000);
  }
  close() { clearInterval(this.timer); this.socket.close(); }
}

// One request on gimbald's UDP command socket; its reply (null after 2 s).
function udpRequest(port, request) {
  return new Promise((resolve) => {
    const s = dgram.createSocket('udp4');
    const t = setTimeout(() => { s.close(); resolve(null); }, 2000);
    s.on('message', (buf) => { clearTimeout(t); s.close(); resolve(JSON.parse(buf.toString())); });
    s.send(JSON.stringify(request), port, '127.0.0.1');
  });
}

// The projection of docs/console.md, written again here: local tangent plane at the aircraft,
// x = cx + east * k, y = cy - north * k.
const WGS84_A = 6378137.0;
const WGS84_F = 1 / 298.257223563;
const WGS84_E2 = WGS84_F * (2 - WGS84_F);
function projector(lat0, lon0, cx, cy, k) {
  const phi = (lat0 * Math.PI) / 180;
  const w = 1 - WGS84_E2 * Math.sin(phi) ** 2;
  const mLat = ((WGS84_A * (1 - WGS84_E2)) / w ** 1.5) * (Math.PI / 180);
  const mLon = (WGS84_A / Math.sqrt(w)) * Math.cos(phi) * (Math.PI / 180);
  return {
    screen: (lat, lon) => ({ x: cx + (lon - lon0) * mLon * k, y: cy - (lat - lat0) * mLat * k }),
    latlon: (x, y) => ({ lat: lat0 + (cy - y) / k / mLat, lon: lon0 + (x - cx) / k / mLon }),
    metres: (lat1, lon1, lat2, lon2) => Math.hypot((lon2 - lon1) * mLon, (lat2 - lat1) * mLat),
  };
}
const dist = (a, b) => Math.hypot(a.x - b.x, a.y - b.y);

// What the page drew, read from the SVG elements themselves in one synchronous pass.
async function readDrawn(page) {
  return page.evaluate(() => {
    const svg = document.getElementById('map');
    const r = svg.getBoundingClientRect();
    const centre = (id) => {
      const e = document.getElementById(id);
      if (!e || e.getAttribute('visibility') === 'hidden') return null;
      const b = e.getBoundingClientRect();
      return { x: b.left + b.width / 2 - r.left, y: b.top + b.height / 2 - r.top };
    };
    const poly = document.getElementById('footprint');
    const corners = poly.getAttribute('visibility') === 'visible'
      ? Array.from(poly.points).map((p) => ({ x: p.x, y: p.y })) : null;
    const hook = window.gimbaldConsole;
    const transform = document.getElementById('aircraft').getAttribute('transform') || '';
    const rot = /rotate\(([-0-9.]+)\)/.exec(transform);
    return {
      width: r.width, height: r.height, left: r.left, top: r.top,
      aircraft: centre('aircraft-centre'), target: centre('target'), footprint: corners,
      rotation: rot ? Number(rot[1]) : null,
      hook: hook && { drawn: hook.drawn, projection: hook.projection, stream: hook.stream },
    };
  });
}

function compareFrame(d, st, label) {
  const t = st.telemetry;
  const P = projector(t.lat, t.lon, d.width / 2, d.height / 2, d.hook.drawn.px_per_m);
  const ok = [];
  const a = P.screen(t.lat, t.lon);
  ok.push(dist(d.aircraft, a) <= PIXEL_TOLERANCE);
  const headingErr = Math.abs(((d.rotation - t.yaw + 540) % 360) - 180);
  ok.push(headingErr < 0.2);
  let worst = dist(d.aircraft, a);
  if (t.target) {
    const e = P.screen(t.target.lat, t.target.lon);
    ok.push(d.target !== null && dist(d.target, e) <= PIXEL_TOLERANCE);
    if (d.target) worst = Math.max(worst, dist(d.target, e));
  } else {
    ok.push(d.target === null);
  }
  if (t.footprint) {
    ok.push(d.footprint !== null && d.footprint.length === 4);
    if (d.footprint) {
      t.footprint.forEach((c, i) => {
        const e = P.screen(c.lat, c.lon);
        worst = Math.max(worst, dist(d.footprint[i], e));
        ok.push(dist(d.footprint[i], e) <= PIXEL_TOLERANCE);
      });
    }
  } else {
    ok.push(d.footprint === null);
  }
  return { ok: ok.every(Boolean), worst, headingErr, label };
}

async function main() {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'gimbald-console-'));
  workDir = dir;
  const rxLog = path.join(dir, 'rx.jsonl');
  // Flat ground at 100 m until the terrain phase below (gimbald then reads the simulator's
  // DEM; the gimbal's own target stays on its flat ground).
  const sim = start(GIMBAL_SIM, ['--port', '0', '--no-discovery', '--rx-log', rxLog, '--terrain-alt', '100']);
  const simLine = await waitFor(() => sim.lines.find((l) => l.startsWith('tcp: ')), 5000);
  if (!check(!!simLine, 'gimbal-sim serves TCP')) return;
  const simPort = Number(simLine.split(':').pop());
  const commandPort = await freePort('udp');
  const httpPort = await freePort('tcp');
  const config = {
    gimbals: [{ name: 'orion1', protocol: 'orion', link: { type: 'tcp', host: '127.0.0.1', port: simPort } }],
    command: { port: commandPort },
    // The checkout's console, wherever the binary was built (a copied one serves the installed).
    http: { bind: '127.0.0.1', port: httpPort, web_root: path.join(SOURCE_DIR, 'web') },
  };
  const cfgPath = path.join(dir, 'gimbald.json');
  fs.writeFileSync(cfgPath, JSON.stringify(config));
  const startDaemon = () => start(GIMBALD, ['-c', cfgPath, '--log-level', 'warn']);
  let daemon = startDaemon();
  const up = await waitFor(async () => {
    if (daemon.exitCode !== null) return true; // reported below
    const r = await httpGet(httpPort, '/api/state');
    if (!r || r.status !== 200) return false;
    const s = JSON.parse(r.body).gimbals.orion1;
    return s && s.link.connected && s.telemetry;
  }, 10000) && daemon.exitCode === null;
  if (!check(!!up, 'gimbald serves /api/state with live Orion telemetry')) {
    console.log(daemon.stderrText.slice(-2000));
    return;
  }
  const ref = new Reference(commandPort, 'orion1');
  await ref.open();

  const browser = await puppeteer.launch({
    executablePath: CHROMIUM,
    headless: true,
    args: ['--headless=new', '--no-sandbox', '--disable-gpu', '--disable-dev-shm-usage', '--no-first-run',
      '--disable-background-networking', '--disable-extensions'],
    defaultViewport: { width: 1400, height: 860 },
  });
  try {
    const page = await browser.newPage();
    const external = [];
    const pageErrors = [];
    page.on('request', (req) => {
      const u = new URL(req.url());
      if (u.protocol !== 'data:' && u.host !== `127.0.0.1:${httpPort}`) external.push(req.url());
    });
    page.on('pageerror', (e) => pageErrors.push(String(e)));
    page.on('console', (m) => { if (m.type() === 'error') pageErrors.push(m.text()); });
    await page.goto(`http://127.0.0.1:${httpPort}/`, { waitUntil: 'load', timeout: 10000 });

    const live = await waitFor(() => page.evaluate(() => {
      const h = window.gimbaldConsole;
      return h && h.stream === 'open' && h.drawn && h.drawn.aircraft ? h.drawn.gimbal : null;
    }), 10000);
    check(live === 'orion1', 'page live over /api/stream, plan view drawn for orion1');
    check(await page.$('#laser-controls button') === null && await page.$eval('#laser-controls', (e) => e.hidden),
      'laser.allow_fire false: no laser controls in the page');

    // Point the camera well below the horizon with the console's position control, so the
    // footprint exists whatever the default attitude.
    await page.$eval('#pos-tilt', (e) => { e.value = '-55'; });
    await page.$eval('#pos-pan', (e) => { e.value = '20'; });
    await page.click('#position-form button[type=submit]');
    const posReply = await waitFor(() => page.$eval('#last-command', (e) => (e.classList.contains('ok') || e.classList.contains('err') ? e.textContent : null)), 5000);
    check(posReply && posReply.includes('"ok":true'), 'position control: reply ok shown');
    const posRx = await waitFor(() => readRx(rxLog).find((l) => l.id === 1 && l.packet && l.packet.mode === 'position' && Math.abs(l.packet.target[1] - -55) < 0.01 && Math.abs(l.packet.target[0] - 20) < 0.01), 3000);
    check(!!posRx, 'gimbal received OrionCmd position pan 20 tilt -55 from the position control');
    await waitFor(() => ref.latest && ref.latest.telemetry.footprint && Math.abs(ref.latest.telemetry.tilt - -55) < 1, 5000);

    // Rate pad (pan right at 10 deg/s for 1 s) and camera zoom (x2 with the + button).
    let mark = readRx(rxLog).length;
    await page.click('[data-rate="1,0"]');
    const rateRx = await waitFor(() => readRx(rxLog).slice(mark).find((l) => l.id === 1 && l.packet && l.packet.mode === 'rate'), 3000);
    // Rates travel in coarse wire units (10 deg/s arrives as 10.03).
    check(rateRx && Math.abs(rateRx.packet.target[0] - 10) < 0.1 && Math.abs(rateRx.packet.target[1]) < 0.01 && Math.abs(rateRx.packet.impulse_time_s - 1) < 0.01,
      `rate pad: OrionCmd rate ${rateRx ? JSON.stringify(rateRx.packet) : 'not received'}`);
    mark = readRx(rxLog).length;
    await page.click('#zoom-plus');
    const zoomRx = await waitFor(() => readRx(rxLog).slice(mark).find((l) => l.id === 97), 3000);
    check(zoomRx && zoomRx.packet && zoomRx.packet.zoom === 2 && zoomRx.packet.index === 0,
      `camera zoom +: CameraState ${zoomRx ? JSON.stringify(zoomRx.packet) : 'not received'}`);

    // Drawn positions against STATE: frames whose telemetry time we also received.
    const results = [];
    let unmatched = 0;
    await waitFor(async () => {
      const d = await readDrawn(page);
      const st = d.hook && d.hook.drawn && ref.byTime.get(d.hook.drawn.system_time_ms);
      if (st && st.telemetry.footprint) {
        if (!results.some((r) => r.label === d.hook.drawn.system_time_ms)) results.push(compareFrame(d, st, d.hook.drawn.system_time_ms));
      } else {
        unmatched++;
      }
      return results.length >= 4;
    }, 10000, 230);
    check(results.length >= 4, `compared ${results.length} drawn frames with the exact STATE (${unmatched} samples had no match)`);
    for (const r of results) {
      check(r.ok, `frame t=${r.label} ms: aircraft, target and 4 footprint corners within ${PIXEL_TOLERANCE} px (worst ${r.worst.toFixed(2)} px), heading off by ${r.headingErr.toFixed(2)} deg`);
    }
    const d0 = await readDrawn(page);
    check(d0.target && dist(d0.aircraft, d0.target) > 40, `target drawn away from the aircraft (${d0.target ? dist(d0.aircraft, d0.target).toFixed(0) : '-'} px)`);
    const trackPoints = await page.$eval('#track', (e) => (e.getAttribute('points') || '').trim().split(/\s+/).length);
    check(trackPoints >= 3, `track drawn (${trackPoints} points)`);
    const scale = await page.$eval('#scale-bar', (e) => ({ m: Number(e.dataset.metres), px: Number(e.dataset.pixels) }));
    check(Math.abs(scale.m * d0.hook.drawn.px_per_m - scale.px) < 0.05 && scale.px > 40,
      `scale bar: ${scale.m} m drawn as ${scale.px} px at ${d0.hook.drawn.px_per_m} px/m`);

    // Zoom in with the console's button (a pixel must be well under the 3 m allowed) and
    // compare again: the same formula at another scale.
    for (let i = 0; i < 12 && (await readDrawn(page)).hook.drawn.px_per_m < 1; i++) {
      await page.click('#zoom-in');
    }
    let zoomed = null;
    let stZoomed = null;
    await waitFor(async () => {
      zoomed = await readDrawn(page);
      stZoomed = ref.byTime.get(zoomed.hook.drawn.system_time_ms);
      return stZoomed;
    }, 3000, 150);
    check(zoomed.hook.drawn.px_per_m >= 1, `zoomed in to ${zoomed.hook.drawn.px_per_m} px/m with the + button`);
    if (check(!!stZoomed, 'zoomed frame matched to its STATE')) {
      const r = compareFrame(zoomed, stZoomed, zoomed.hook.drawn.system_time_ms);
      check(r.ok, `zoomed frame: aircraft, target and footprint within ${PIXEL_TOLERANCE} px (worst ${r.worst.toFixed(2)} px)`);
    }

    // Click the map at a known offset from the aircraft: the gimbal must receive a geopoint
    // at the clicked place, at the target's altitude (the simulated ground is 100 m).
    const off = { x: 150, y: -90 };
    const before = readRx(rxLog).length;
    const dc = await readDrawn(page);
    await page.mouse.click(dc.left + dc.width / 2 + off.x, dc.top + dc.height / 2 + off.y);
    const click = await waitFor(() => page.evaluate(() => {
      const c = window.gimbaldConsole.lastClick;
      return c && c.reply ? c : null;
    }), 5000);
    if (check(!!click, 'map click: geopoint sent and the reply recorded')) {
      check(click.reply.ok === true, `geopoint reply ok (${JSON.stringify(click.reply).slice(0, 120)})`);
      // The browser reports whole CSS pixels: the page may see the click up to 0.5 px away.
      check(Math.abs(click.x - (dc.width / 2 + off.x)) <= 0.5 && Math.abs(click.y - (dc.height / 2 + off.y)) <= 0.5,
        `click seen by the page where the mouse clicked (${click.x.toFixed(2)}, ${click.y.toFixed(2)})`);
      // The centre the page used must be an aircraft position of STATE.
      const centreState = ref.byTime.get(click.centre.system_time_ms);
      check(centreState && centreState.telemetry.lat === click.centre.lat && centreState.telemetry.lon === click.centre.lon,
        'click projection centred on the aircraft position of a STATE');
      const P = projector(click.centre.lat, click.centre.lon, dc.width / 2, dc.height / 2, click.px_per_m);
      const expected = P.latlon(dc.width / 2 + off.x, dc.height / 2 + off.y);
      const offsetM = Math.hypot(off.x, off.y) / click.px_per_m;
      const rx = await waitFor(() => readRx(rxLog).slice(before).find((l) => l.id === 213 && l.packet), 3000);
      if (check(!!rx, 'gimbal received a GeopointCmd (213)')) {
        const err = P.metres(expected.lat, expected.lon, rx.packet.lat, rx.packet.lon);
        check(err < 3, `geopoint at the clicked place: ${err.toFixed(2)} m off (click ${offsetM.toFixed(0)} m from the aircraft)`);
        check(Math.abs(rx.packet.alt - 100) < 1, `geopoint alt = target altitude (${rx.packet.alt.toFixed(2)} m, simulated ground 100 m)`);
      }
      const mode = await waitFor(() => ref.latest && ref.latest.telemetry.mode === 'geopoint', 3000);
      check(!!mode, 'gimbal in geopoint mode');
      const ev = await waitFor(() => page.$$eval('#events li', (li) => li.map((e) => e.textContent).find((t) => t.includes('mode') && t.includes('"to":"geopoint"'))), 3000);
      check(!!ev, `mode event listed in the events panel (${ev})`);
      const shown = await page.$eval('#last-command', (e) => e.textContent);
      check(shown.includes('"cmd":"geopoint"') && shown.includes('"ok":true'), 'reply shown in the command panel');
    }
    await waitFor(() => page.$eval('#mode', (e) => e.textContent === 'geopoint'), 3000);
    const panel = await page.evaluate(() => ({
      mode: document.getElementById('mode').textContent,
      link: document.getElementById('link').textContent,
      endpoint: document.getElementById('endpoint').textContent,
      stale: document.getElementById('stale').textContent,
    }));
    check(panel.mode === 'geopoint' && panel.link === 'connected' && panel.endpoint.includes(String(simPort)) && panel.stale === 'fresh',
      `status panel: link ${panel.link}, endpoint "${panel.endpoint}", ${panel.stale}, mode ${panel.mode}`);

    await sleep(1500); // let the gimbal slew to the click for the picture
    await page.screenshot({ path: SCREENSHOT });
    check(fs.statSync(SCREENSHOT).size > 10000, `screenshot saved: ${SCREENSHOT}`);

    // The daemon goes away and comes back, now with a command token the page does not have:
    // the page reconnects by itself, and its commands are refused with a clear banner.
    await stop(daemon);
    fs.writeFileSync(cfgPath, JSON.stringify({ ...config, command: { port: commandPort, token: 'not-in-the-browser' } }));
    const down = await waitFor(() => page.$eval('#stream-status', (e) => e.textContent !== 'live'), 5000);
    check(!!down, 'stream badge leaves "live" when gimbald stops');
    const alert = await page.$eval('#map-alert', (e) => (e.hidden ? '' : e.textContent));
    check(alert.startsWith('NO LIVE DATA'), `map says it is not live: "${alert}"`);
    daemon = startDaemon();
    const back = await waitFor(() => page.evaluate(() => {
      const b = document.getElementById('stream-status').textContent;
      return b === 'live' && window.gimbaldConsole.stream === 'open';
    }), 15000, 200);
    check(!!back, 'page reconnected to the restarted gimbald');
    const rxBefore = readRx(rxLog).length;
    await page.mouse.click(dc.left + dc.width / 2 - 60, dc.top + dc.height / 2 + 40);
    const banner = await waitFor(() => page.$eval('#banner', (e) => (!e.hidden ? e.textContent : null)), 5000);
    check(banner && banner.startsWith('forbidden'), `command refused: banner "${(banner || '').slice(0, 60)}..."`);
    await sleep(300);
    check(!readRx(rxLog).slice(rxBefore).some((l) => l.id === 213), 'no geopoint reached the gimbal');

    // With terrain (contract section 15): /api/console says so, a click sends geopoint with no
    // alt and gimbald takes the ground's height there from the DEM; the footprint drawn is
    // STATE's, now on the terrain.
    const dem = path.join(dir, 'sim-dem.tif');
    const written = spawnSync(GIMBAL_SIM, ['--write-dem', dem], { encoding: 'utf8' });
    check(written.status === 0, `gimbal-sim --write-dem wrote the DEM (${(written.stderr || '').trim()})`);
    await stop(daemon);
    fs.writeFileSync(cfgPath, JSON.stringify({ ...config, terrain: { files: [dem], geoid: 'none' } }));
    daemon = startDaemon();
    const onTerrain = await waitFor(() => page.evaluate(() => {
      const h = window.gimbaldConsole;
      return h.stream === 'open' && document.getElementById('stream-status').textContent === 'live' &&
        h.drawn && h.drawn.footprint ? true : null;
    }), 15000, 200);
    check(!!onTerrain, 'page reconnected to gimbald with terrain');
    const st = await udpRequest(commandPort, { cmd: 'state', gimbal: 'orion1' });
    check(st && st.state.telemetry.footprint_surface === 'terrain', `STATE footprint_surface ${st && st.state.telemetry.footprint_surface}`);
    const rxTerrain = readRx(rxLog).length;
    await page.mouse.click(dc.left + dc.width / 2 + 80, dc.top + dc.height / 2 - 60);
    const tclick = await waitFor(() => page.evaluate(() => {
      const c = window.gimbaldConsole.lastClick;
      return c && c.reply && c.alt_from === 'terrain' ? c : null;
    }), 5000);
    if (check(!!tclick && tclick.reply.ok === true, `terrain click: geopoint ok (${tclick ? JSON.stringify(tclick.reply).slice(0, 120) : '-'})`)) {
      const shown = await page.$eval('#last-command', (e) => e.textContent);
      check(shown.includes('"cmd":"geopoint"') && !shown.includes('"alt"'), `geopoint sent without alt: ${shown.split('\n')[0]}`);
      const elevation = await udpRequest(commandPort, { cmd: 'elevation', lat: tclick.lat, lon: tclick.lon });
      const rx = await waitFor(() => readRx(rxLog).slice(rxTerrain).find((l) => l.id === 213 && l.packet), 3000);
      check(rx && elevation && elevation.ok && Math.abs(rx.packet.alt - elevation.alt) < 0.01 &&
        Math.abs(rx.packet.lat - tclick.lat) < 1e-6 && Math.abs(rx.packet.lon - tclick.lon) < 1e-6,
        `GeopointCmd at the click, alt = the terrain's ${elevation && elevation.alt} m (${rx ? rx.packet.alt : '-'})`);
    }
    check(external.length === 0, `no tiles_url: no request to anything but gimbald (${external.slice(0, 3).join(' ')})`);
    check(pageErrors.length === 0, `no script errors in the page (${pageErrors.slice(0, 3).join(' | ')})`);
    await page.close();

    await laserSequence(browser, dir);
  } finally {
    await browser.close();
    ref.close();
  }
}

// A local XYZ tile server: SVG tiles, every requested z/x/y remembered.
async function startTileServer() {
  const requested = [];
  const server = http.createServer((req, res) => {
    const m = /^\/(\d+)\/(\d+)\/(\d+)\.svg$/.exec(req.url);
    if (!m) { res.writeHead(404); res.end(); return; }
    requested.push(m.slice(1).map(Number));
    res.writeHead(200, { 'Content-Type': 'image/svg+xml' });
    res.end(`<svg xmlns="http://www.w3.org/2000/svg" width="256" height="256"><rect width="256" height="256" fill="#17251c" stroke="#2e5a3a"/></svg>`);
  });
  await new Promise((r) => server.listen(0, '127.0.0.1', r));
  return { server, requested, port: server.address().port };
}

// Web Mercator tile arithmetic, written again here: a tile's north-west corner.
function tileCorner(x, y, z) {
  const n = 2 ** z;
  return { lat: (Math.atan(Math.sinh(Math.PI * (1 - (2 * y) / n))) * 180) / Math.PI, lon: (x / n) * 360 - 180 };
}

// gimbald --sim with laser.allow_fire true and http.tiles_url: tiles come from the tile
// server, placed at their projected corners; the laser controls appear; FIRE needs the arm
// box, and one press of FIRE alone sends nothing; the confirm press fires.
async function laserSequence(browser, dir) {
  const httpPort = await freePort('tcp');
  const commandPort = await freePort('udp');
  const tiles = await startTileServer();
  const cfgPath = path.join(dir, 'laser.json');
  fs.writeFileSync(cfgPath, JSON.stringify({
    command: { port: commandPort }, laser: { allow_fire: true },
    http: { bind: '127.0.0.1', port: httpPort, web_root: path.join(SOURCE_DIR, 'web'), tiles_url: `http://127.0.0.1:${tiles.port}/{z}/{x}/{y}.svg` },
  }));
  const daemon = start(GIMBALD, ['--sim', 'orion,viewpro', '-c', cfgPath, '--log-level', 'warn']);
  const stateOf = async (name) => {
    const r = await httpGet(httpPort, '/api/state');
    if (!r || r.status !== 200) return null;
    return JSON.parse(r.body).gimbals[name] || null;
  };
  const lasersOf = async () => {
    const g = await stateOf('sim-orion');
    return g && g.lasers;
  };
  if (!check(!!(await waitFor(lasersOf, 10000)), 'laser daemon up with laser states')) return;
  const page = await browser.newPage();
  await page.goto(`http://127.0.0.1:${httpPort}/`, { waitUntil: 'load', timeout: 10000 });
  await waitFor(() => page.evaluate(() => window.gimbaldConsole && window.gimbaldConsole.drawn), 10000);
  const tile = await waitFor(() => page.evaluate(() => {
    const img = document.querySelector('#tiles image');
    const h = window.gimbaldConsole;
    if (!img || !h.drawn) return null;
    const r = document.getElementById('map').getBoundingClientRect();
    return { href: img.getAttribute('href'), x: Number(img.getAttribute('x')), y: Number(img.getAttribute('y')),
      count: document.querySelectorAll('#tiles image').length, lat0: h.projection.lat0, lon0: h.projection.lon0,
      k: h.projection.px_per_m, width: r.width, height: r.height };
  }), 5000);
  if (check(!!tile, `tiles_url: ${tile ? tile.count : 0} tiles drawn, ${tiles.requested.length} requested from the tile server`)) {
    const m = /\/(\d+)\/(\d+)\/(\d+)\.svg$/.exec(tile.href);
    const [z, x, y] = m.slice(1).map(Number);
    const P = projector(tile.lat0, tile.lon0, tile.width / 2, tile.height / 2, tile.k);
    const nw = P.screen(tileCorner(x, y, z).lat, tileCorner(x, y, z).lon);
    check(Math.abs(nw.x - tile.x) < PIXEL_TOLERANCE && Math.abs(nw.y - tile.y) < PIXEL_TOLERANCE,
      `tile ${z}/${x}/${y} drawn at its projected north-west corner (${tile.x}, ${tile.y}) vs (${nw.x.toFixed(2)}, ${nw.y.toFixed(2)})`);
    await sleep(300);
    check(tiles.requested.length > 0 && tiles.requested.some(([rz, rx, ry]) => rz === z && rx === x && ry === y),
      'the browser fetched the drawn tile from tiles_url');
  }
  tiles.server.close();
  const fire = await waitFor(() => page.$('#laser-fire-0'), 5000);
  if (!check(!!fire, 'laser.allow_fire true: laser controls shown')) { await page.close(); await stop(daemon); return; }
  check(await page.$eval('#laser-fire-0', (e) => e.disabled), 'FIRE disabled until armed');
  await page.click('#laser-arm-0');
  check(!(await page.$eval('#laser-fire-0', (e) => e.disabled)), 'arm box enables FIRE');
  await page.click('#laser-fire-0');
  await sleep(600);
  const afterOne = await page.evaluate(() => document.getElementById('last-command').textContent);
  const l1 = await lasersOf();
  check(!afterOne.includes('"cmd":"laser"') && !l1[0].active, 'one FIRE press sends nothing (confirm asked)');
  check((await page.$eval('#laser-fire-0', (e) => e.textContent)).startsWith('CONFIRM'), 'FIRE button asks to confirm');
  await page.click('#laser-fire-0');
  const firing = await waitFor(async () => { const l = await lasersOf(); return l && l[0].active; }, 3000);
  check(!!firing, 'confirm within 5 s fires laser 0 (STATE lasers[0].active)');
  await page.click('#laser-cease-0');
  const ceased = await waitFor(async () => { const l = await lasersOf(); return l && !l[0].active; }, 3000);
  check(!!ceased, 'cease stops laser 0');
  await viewproView(page, stateOf);
  await page.close();
  await stop(daemon);
}

// A Viewpro gimbal: the aircraft where output.uav says, the target at output.target (the
// simulated Viewpro hovers with a fixed gimbal, so STATE does not move), its output panel,
// and no geopoint from a map click.
async function viewproView(page, stateOf) {
  await page.select('#gimbal-select', 'sim-viewpro');
  const st = await waitFor(async () => {
    const s = await stateOf('sim-viewpro');
    return s && s.output && s.output.uav && s.output.target ? s : null;
  }, 5000);
  if (!check(!!st, 'Viewpro STATE has output.uav and output.target')) return;
  const d = await waitFor(async () => {
    const x = await readDrawn(page);
    return x.hook.drawn && x.hook.drawn.gimbal === 'sim-viewpro' ? x : null;
  }, 5000);
  if (!check(!!d, 'plan view switched to sim-viewpro')) return;
  const out = st.output;
  const P = projector(out.uav.lat, out.uav.lon, d.width / 2, d.height / 2, d.hook.drawn.px_per_m);
  const e = P.screen(out.target.lat, out.target.lon);
  check(dist(d.aircraft, P.screen(out.uav.lat, out.uav.lon)) <= PIXEL_TOLERANCE && d.target && dist(d.target, e) <= PIXEL_TOLERANCE,
    `Viewpro: aircraft at output.uav, target at output.target (${d.target ? dist(d.target, e).toFixed(2) : '-'} px)`);
  const vp = await page.$eval('#vp-uav', (x) => x.textContent);
  check(!(await page.$eval('#viewpro-panel', (x) => x.hidden)) && vp.startsWith(out.uav.lat.toFixed(6)),
    `Viewpro output panel shows the UAV (${vp})`);
  await page.mouse.click(d.left + d.width / 2 + 50, d.top + d.height / 2 + 50);
  const said = await page.$eval('#last-command', (x) => x.textContent);
  check(said.includes('Orion command') && !(await page.evaluate(() => window.gimbaldConsole.lastClick.reply)),
    'Viewpro: a map click sends no geopoint and says why');
}

function readRx(file) {
  let text = '';
  try { text = fs.readFileSync(file, 'utf8'); } catch (e) { return []; }
  return text.split('\n').filter((l) => l.trim()).map((l) => { try { return JSON.parse(l); } catch (e) { return {}; } });
}

const watchdog = setTimeout(() => { console.log('FAIL timeout'); cleanup(1); }, 110000);
function cleanup(code) {
  clearTimeout(watchdog);
  for (const c of children) if (c.exitCode === null) c.kill('SIGKILL');
  if (workDir && code === 0) fs.rmSync(workDir, { recursive: true, force: true });
  else if (workDir) console.log(`kept ${workDir} (rx log, configs)`);
  process.exit(code);
}
main().then(() => {
  console.log(failures ? `${failures} check(s) failed` : 'all console checks passed');
  cleanup(failures ? 1 : 0);
}, (e) => {
  console.log('FAIL', e && e.stack ? e.stack : e);
  cleanup(1);
});
