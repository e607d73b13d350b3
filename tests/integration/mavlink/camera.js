// The MAVLink camera component (contract section 16), driven the way QGroundControl's camera
// manager drives a camera (src/Camera: discovery by a MAV_TYPE_CAMERA HEARTBEAT, then
// REQUEST_MESSAGE alternating with the deprecated request commands for CAMERA_INFORMATION,
// CAMERA_SETTINGS, STORAGE_INFORMATION, CAMERA_CAPTURE_STATUS, VIDEO_STREAM_INFORMATION and
// VIDEO_STREAM_STATUS; click-to-track as MAV_CMD_CAMERA_TRACK_POINT followed by
// SET_MESSAGE_INTERVAL for CAMERA_TRACKING_IMAGE_STATUS). node-mavlink is the ground station
// (an implementation we did not write); the camera is `gimbald --sim` with a `video` section
// (the simulated Orion's rendered picture) and a terrain model gimbal-sim wrote, so `locate`
// and the simulator agree on the ground. The stream URI is opened with ffprobe. Prints the
// settling figures. Exit 0 on success, 1 on a failed check.
'use strict';
const dgram = require('dgram');
const fs = require('fs');
const os = require('os');
const path = require('path');
const { spawn, spawnSync } = require('child_process');
const {
  MavLinkProtocolV2, MavLinkPacketSplitter, MavLinkPacketParser, minimal, common,
} = require('node-mavlink');

const REGISTRY = { ...minimal.REGISTRY, ...common.REGISTRY };
const GIMBALD = process.env.GIMBALD;
const GIMBAL_SIM = process.env.GIMBAL_SIM;
const RESULT = { ACCEPTED: 0, DENIED: 2, UNSUPPORTED: 3 };
const CMD = {
  SET_MESSAGE_INTERVAL: 511, REQUEST_MESSAGE: 512, REQUEST_CAMERA_INFORMATION: 521,
  REQUEST_CAMERA_SETTINGS: 522, REQUEST_STORAGE_INFORMATION: 525, REQUEST_CAMERA_CAPTURE_STATUS: 527,
  SET_CAMERA_ZOOM: 531, IMAGE_START_CAPTURE: 2000, TRACK_POINT: 2004, TRACK_RECTANGLE: 2005,
  STOP_TRACKING: 2010, VIDEO_START_CAPTURE: 2500, VIDEO_START_STREAMING: 2502,
  VIDEO_STOP_STREAMING: 2503, REQUEST_VIDEO_STREAM_INFORMATION: 2504, REQUEST_VIDEO_STREAM_STATUS: 2505,
};
const MSG = {
  CAMERA_INFORMATION: 259, CAMERA_SETTINGS: 260, STORAGE_INFORMATION: 261, CAMERA_CAPTURE_STATUS: 262,
  VIDEO_STREAM_INFORMATION: 269, VIDEO_STREAM_STATUS: 270, CAMERA_TRACKING_IMAGE_STATUS: 275,
  CAMERA_TRACKING_GEO_STATUS: 276,
};
const MAV_TYPE_CAMERA = 30;
const CAP = { BASIC_ZOOM: 64, VIDEO_STREAM: 256, TRACKING_POINT: 512, TRACKING_GEO_STATUS: 2048 };
const children = [];
let failures = 0;

function check(ok, what) {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
  if (!ok) failures++;
}
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

async function freePort() {
  return new Promise((resolve) => {
    const s = dgram.createSocket('udp4');
    s.bind(0, '127.0.0.1', () => { const p = s.address().port; s.close(() => resolve(p)); });
  });
}

function startGimbald(args, logs) {
  const child = spawn(GIMBALD, args, { stdio: ['ignore', 'pipe', 'pipe'] });
  children.push(child);
  let rest = '';
  child.stdout.on('data', (d) => {
    rest += d.toString();
    const lines = rest.split('\n'); rest = lines.pop();
    for (const l of lines) { try { logs.push(JSON.parse(l)); } catch (e) { /* text */ } }
  });
  child.stderr.on('data', (d) => process.stderr.write(d));
  return child;
}

// A program's standard output, run without blocking this loop: a spawnSync (ffprobe, seconds)
// left the ground station's socket unread, it dropped datagrams, and the next command's ACK
// was lost (TRACK_POINT failed 3 runs in 4 on a loaded machine).
function output(program, args, timeoutMs) {
  return new Promise((resolve) => {
    const child = spawn(program, args, { stdio: ['ignore', 'pipe', 'ignore'] });
    let out = '';
    child.stdout.on('data', (d) => { out += d.toString(); });
    const timer = setTimeout(() => child.kill('SIGKILL'), timeoutMs);
    child.on('close', () => { clearTimeout(timer); resolve(out); });
  });
}

// One request on gimbald's JSON command socket.
function request(port, req) {
  return new Promise((resolve) => {
    const s = dgram.createSocket('udp4');
    const timer = setTimeout(() => { s.close(); resolve(null); }, 3000);
    s.on('message', (b) => { clearTimeout(timer); s.close(); resolve(JSON.parse(b.toString())); });
    s.send(JSON.stringify(req), port, '127.0.0.1');
  });
}

// Metres between two points (spherical earth: enough at a few hundred metres).
function distance(a, b) {
  const r = 6371000; const rad = Math.PI / 180;
  const dn = (b.lat - a.lat) * rad * r;
  const de = (b.lon - a.lon) * rad * r * Math.cos(a.lat * rad);
  const du = (b.alt !== undefined && a.alt !== undefined) ? b.alt - a.alt : 0;
  return Math.hypot(dn, de, du);
}

// The ground station: node-mavlink on its own UDP socket.
class Gcs {
  constructor(target) {
    this.target = target;
    this.protocol = new MavLinkProtocolV2(255, 190);
    this.seq = 0;
    this.messages = [];
    this.socket = dgram.createSocket('udp4');
    const splitter = new MavLinkPacketSplitter();
    const parser = new MavLinkPacketParser();
    splitter.pipe(parser);
    parser.on('data', (packet) => {
      const clazz = REGISTRY[packet.header.msgid];
      if (!clazz) return;
      this.messages.push({ at: Date.now(), compid: packet.header.compid, sysid: packet.header.sysid,
        msgid: packet.header.msgid, name: clazz.MSG_NAME, data: packet.protocol.data(packet.payload, clazz) });
    });
    this.socket.on('message', (buf) => splitter.write(buf));
  }
  bind() { return new Promise((r) => this.socket.bind(0, '127.0.0.1', r)); }
  send(msg) {
    const buf = this.protocol.serialize(msg, this.seq++ & 255);
    return new Promise((r) => this.socket.send(buf, this.target, '127.0.0.1', () => r()));
  }
  async waitFor(pred, timeoutMs = 3000, since = 0) {
    const end = Date.now() + timeoutMs;
    for (;;) {
      const m = this.messages.find((x) => x.at >= since && pred(x));
      if (m) return m;
      if (Date.now() > end) return null;
      await sleep(20);
    }
  }
  // COMMAND_LONG to (1, compid): the ACK (from which component) and the messages that came
  // from that component with `msgid` within 600 ms.
  async command(compid, command, params, msgid = null) {
    const msg = new common.CommandLong();
    const p = [...params, 0, 0, 0, 0, 0, 0, 0].slice(0, 7);
    [msg._param1, msg._param2, msg._param3, msg._param4, msg._param5, msg._param6, msg._param7] = p;
    msg.command = command; msg.targetSystem = 1; msg.targetComponent = compid; msg.confirmation = 0;
    const since = Date.now();
    await this.send(msg);
    const ack = await this.waitFor((x) => x.name === 'COMMAND_ACK' && x.data.command === command, 3000, since);
    if (msgid !== null) await sleep(600);
    const replies = msgid === null ? []
      : this.messages.filter((x) => x.at >= since && x.msgid === msgid && x.compid === compid);
    if (!ack) return { result: null, replies };
    return { result: ack.data.result, from: ack.compid, replies };
  }
}

const text = (bytes) => (typeof bytes === 'string' ? bytes : Buffer.from(bytes).toString('latin1')).replace(/\0.*$/s, '');

async function qgcDiscovery(gcs) {
  // QGroundControl: a HEARTBEAT with MAV_TYPE_CAMERA is a camera.
  const hb = await gcs.waitFor((x) => x.name === 'HEARTBEAT' && x.data.type === MAV_TYPE_CAMERA, 5000);
  check(hb !== null && hb.compid === 100 && hb.data.autopilot === 8,
    `HEARTBEAT MAV_TYPE_CAMERA from component ${hb && hb.compid} (want 100, MAV_AUTOPILOT_INVALID)`);
  const cam = hb ? hb.compid : 100;
  // Discovery: REQUEST_MESSAGE, then the deprecated command on a retry.
  const info = await gcs.command(cam, CMD.REQUEST_MESSAGE, [MSG.CAMERA_INFORMATION], MSG.CAMERA_INFORMATION);
  check(info.result === RESULT.ACCEPTED && info.from === cam && info.replies.length === 1,
    `REQUEST_MESSAGE CAMERA_INFORMATION: ${info.result} from ${info.from}, ${info.replies.length} reply`);
  const legacy = await gcs.command(cam, CMD.REQUEST_CAMERA_INFORMATION, [1], MSG.CAMERA_INFORMATION);
  check(legacy.result === RESULT.ACCEPTED && legacy.replies.length === 1,
    `MAV_CMD_REQUEST_CAMERA_INFORMATION: ${legacy.result}, ${legacy.replies.length} reply`);
  if (info.replies.length) {
    const d = info.replies[0].data;
    const want = CAP.BASIC_ZOOM | CAP.VIDEO_STREAM | CAP.TRACKING_POINT | CAP.TRACKING_GEO_STATUS;
    check(d.flags === want, `CAMERA_INFORMATION flags ${d.flags} (want ${want})`);
    check(text(d.vendorName) === 'Trillium' && text(d.modelName) === 'Orion',
      `vendor/model "${text(d.vendorName)}"/"${text(d.modelName)}"`);
    check(d.gimbalDeviceId === 1 && d.cameraDeviceId === 0,
      `gimbal_device_id ${d.gimbalDeviceId}, camera_device_id ${d.cameraDeviceId}`);
  }
  // What QGroundControl's VehicleCameraControl asks for next (REQUEST_MESSAGE and legacy).
  for (const [name, id, legacyCmd, legacyParams] of [
    ['CAMERA_SETTINGS', MSG.CAMERA_SETTINGS, CMD.REQUEST_CAMERA_SETTINGS, [1]],
    ['STORAGE_INFORMATION', MSG.STORAGE_INFORMATION, CMD.REQUEST_STORAGE_INFORMATION, [0, 1]],
    ['CAMERA_CAPTURE_STATUS', MSG.CAMERA_CAPTURE_STATUS, CMD.REQUEST_CAMERA_CAPTURE_STATUS, [1]],
    ['VIDEO_STREAM_STATUS', MSG.VIDEO_STREAM_STATUS, CMD.REQUEST_VIDEO_STREAM_STATUS, [1]],
  ]) {
    const a = await gcs.command(cam, CMD.REQUEST_MESSAGE, [id, name === 'VIDEO_STREAM_STATUS' ? 1 : 0], id);
    const b = await gcs.command(cam, legacyCmd, legacyParams, id);
    check(a.result === RESULT.ACCEPTED && a.replies.length === 1 && b.result === RESULT.ACCEPTED && b.replies.length === 1,
      `${name}: REQUEST_MESSAGE ${a.result} (${a.replies.length}), legacy ${b.result} (${b.replies.length})`);
    if (name === 'CAMERA_SETTINGS' && a.replies.length) check(a.replies[0].data.modeId === 1, 'CAMERA_SETTINGS mode VIDEO');
    if (name === 'STORAGE_INFORMATION' && a.replies.length)
      check(a.replies[0].data.status === 3 && a.replies[0].data.storageCount === 0, 'STORAGE_INFORMATION: NOT_SUPPORTED, no storage');
    if (name === 'VIDEO_STREAM_STATUS' && a.replies.length)
      check((a.replies[0].data.flags & 1) === 1 && a.replies[0].data.resolutionH > 0,
        `VIDEO_STREAM_STATUS running, ${a.replies[0].data.resolutionH}x${a.replies[0].data.resolutionV} @ ${a.replies[0].data.framerate.toFixed(1)} fps`);
  }
  const streams = await gcs.command(cam, CMD.REQUEST_MESSAGE, [MSG.VIDEO_STREAM_INFORMATION, 0], MSG.VIDEO_STREAM_INFORMATION);
  const legacyStreams = await gcs.command(cam, CMD.REQUEST_VIDEO_STREAM_INFORMATION, [1], MSG.VIDEO_STREAM_INFORMATION);
  check(streams.result === RESULT.ACCEPTED && streams.replies.length === 1 && legacyStreams.replies.length === 1,
    `VIDEO_STREAM_INFORMATION: ${streams.result}, ${streams.replies.length} stream(s); legacy ${legacyStreams.replies.length}`);
  return { cam, stream: streams.replies.length ? streams.replies[0].data : null };
}

// What QGroundControl's VideoManager makes of an MPEG-TS stream's URI: a port to listen on.
function playableUrl(uri) {
  if (/^\d+$/.test(uri)) return `udp://0.0.0.0:${uri}`;
  return uri.replace(/^mpegts:\/\//, 'udp://');
}

// MAVSDK's Camera plugin asks every component it hears for CAMERA_INFORMATION and lists each
// one that answers: the gimbal manager must not (contract v4), or one gimbal is two cameras.
async function oneCameraPerGimbal(gcs, cam) {
  const manager = await gcs.command(154, CMD.REQUEST_MESSAGE, [MSG.CAMERA_INFORMATION], MSG.CAMERA_INFORMATION);
  check(manager.result === RESULT.DENIED && manager.from === 154 && manager.replies.length === 0,
    `REQUEST_MESSAGE CAMERA_INFORMATION to the gimbal manager 154: ${manager.result} (want DENIED), ${manager.replies.length} CAMERA_INFORMATION`);
  const since = Date.now();
  await gcs.command(cam, CMD.REQUEST_MESSAGE, [MSG.CAMERA_INFORMATION], MSG.CAMERA_INFORMATION);
  const answering = new Set(gcs.messages.filter((x) => x.at >= since && x.msgid === MSG.CAMERA_INFORMATION).map((x) => x.compid));
  check(answering.size === 1 && answering.has(cam), `components answering CAMERA_INFORMATION: [${[...answering]}] (want [${cam}])`);
}

async function clickToTrack(gcs, cam, commandPort, logs) {
  // The ground point at MAVLink (0.7, 0.4), i.e. the contract's x 0.4, y -0.2, before the click.
  const before = await request(commandPort, { cmd: 'locate', gimbal: 'sim', x: 0.4, y: -0.2 });
  check(before && before.ok, `locate 0.4,-0.2 before the click: ${JSON.stringify(before)}`);
  if (!before || !before.ok) return;
  const t0 = Date.now();
  const track = await gcs.command(cam, CMD.TRACK_POINT, [0.7, 0.4, 0.02]);
  check(track.result === RESULT.ACCEPTED && track.from === cam, `TRACK_POINT (0.7, 0.4): ${track.result} from ${track.from}`);
  const interval = await gcs.command(cam, CMD.SET_MESSAGE_INTERVAL, [MSG.CAMERA_TRACKING_IMAGE_STATUS, 500000]);
  check(interval.result === RESULT.ACCEPTED, `SET_MESSAGE_INTERVAL CAMERA_TRACKING_IMAGE_STATUS 2 Hz: ${interval.result}`);
  const geo = await gcs.waitFor((x) => x.msgid === MSG.CAMERA_TRACKING_GEO_STATUS && x.compid === cam && x.data.trackingStatus === 1, 3000, t0);
  check(geo !== null, 'CAMERA_TRACKING_GEO_STATUS ACTIVE');
  if (!geo) return;
  const held = { lat: geo.data.lat / 1e7, lon: geo.data.lon / 1e7 };
  const located = { lat: before.lat, lon: before.lon };
  const offset = distance(located, held);
  console.log(`     held point ${held.lat.toFixed(6)}, ${held.lon.toFixed(6)} (${offset.toFixed(1)} m from the locate before the click, range ${before.range_m} m)`);
  check(offset < 0.01 * before.range_m + 5, 'the held point is the ground point locate gave for that image position');
  check(Number.isFinite(geo.data.dist) && Math.abs(geo.data.dist - before.range_m) < 0.05 * before.range_m,
    `GEO_STATUS dist ${geo.data.dist.toFixed(0)} m ~ range ${before.range_m} m`);
  // The image centre settles on the held point.
  let settled = null; let last = null; const trace = [];
  while (Date.now() - t0 < 20000) {
    const c = await request(commandPort, { cmd: 'locate', gimbal: 'sim', x: 0, y: 0 });
    if (c && c.ok) {
      last = distance(held, { lat: c.lat, lon: c.lon });
      trace.push(`${((Date.now() - t0) / 1000).toFixed(1)}s:${last.toFixed(1)}m`);
      if (last < 0.005 * before.range_m + 2) {
        if (settled === null) settled = Date.now() - t0;
        if (Date.now() - t0 - settled > 1500) break;  // and stays there
      } else {
        settled = null;
      }
    }
    await sleep(200);
  }
  console.log(`     image centre to held point: ${trace.filter((_, i) => i % 5 === 0).join(' ')}`);
  check(settled !== null, `the image centre (locate 0,0) settled on the held point within ${settled === null ? '-' : (settled / 1000).toFixed(1)} s; last ${last && last.toFixed(1)} m`);
  const image = await gcs.waitFor((x) => x.msgid === MSG.CAMERA_TRACKING_IMAGE_STATUS && x.compid === cam, 2000, Date.now());
  check(image !== null && image.data.trackingMode === 1 && Math.abs(image.data.pointX - 0.5) < 0.02 && Math.abs(image.data.pointY - 0.5) < 0.02,
    `CAMERA_TRACKING_IMAGE_STATUS point ${image && image.data.pointX.toFixed(3)}, ${image && image.data.pointY.toFixed(3)} (the centre)`);
  // 1 Hz while held.
  const since = Date.now();
  await sleep(3100);
  const n = gcs.messages.filter((x) => x.at >= since && x.msgid === MSG.CAMERA_TRACKING_GEO_STATUS && x.data.trackingStatus === 1).length;
  check(n >= 2 && n <= 4, `CAMERA_TRACKING_GEO_STATUS ${n} in 3.1 s (1 Hz)`);
  const st = await request(commandPort, { cmd: 'state', gimbal: 'sim', keys: ['mavlink'] });
  const tracking = st && st.ok && st.state.mavlink.camera ? st.state.mavlink.camera.tracking : null;
  check(tracking && distance(tracking, held) < 1, `STATE mavlink.camera.tracking ${JSON.stringify(tracking)}`);
  const mode = await request(commandPort, { cmd: 'state', gimbal: 'sim', keys: ['telemetry'] });
  check(mode && mode.ok && mode.state.telemetry.mode === 'geopoint', `the Orion is in ${mode && mode.ok && mode.state.telemetry.mode} mode`);
  const cmdLine = logs.find((l) => l.event === 'command' && l.cmd === 'point' && l.transport === 'mavlink');
  check(cmdLine !== undefined, `a command line for point from MAVLink: ${JSON.stringify(cmdLine)}`);

  const stopAt = Date.now();
  const stop = await gcs.command(cam, CMD.STOP_TRACKING, [0]);
  check(stop.result === RESULT.ACCEPTED, `STOP_TRACKING: ${stop.result}`);
  const idle = await gcs.waitFor((x) => x.msgid === MSG.CAMERA_TRACKING_GEO_STATUS && x.data.trackingStatus === 0, 2000, stopAt);
  check(idle !== null, 'CAMERA_TRACKING_GEO_STATUS IDLE after STOP_TRACKING');
  await sleep(1500);
  const more = gcs.messages.filter((x) => x.at >= stopAt + 300 && x.msgid === MSG.CAMERA_TRACKING_GEO_STATUS && x.data.trackingStatus === 1).length;
  check(more === 0, `no ACTIVE status after the stop (${more})`);
}

// Another steering ends click-to-track: the gimbal manager's PITCHYAW at once, a JSON command
// once the gimbal reports it left geopoint mode.
async function otherSteeringEndsTracking(gcs, cam, commandPort) {
  const idleAfter = async (since, ms) => gcs.waitFor((x) => x.msgid === MSG.CAMERA_TRACKING_GEO_STATUS && x.compid === cam && x.data.trackingStatus === 0, ms, since);
  const activeAfter = async (since) => gcs.waitFor((x) => x.msgid === MSG.CAMERA_TRACKING_GEO_STATUS && x.compid === cam && x.data.trackingStatus === 1, 3000, since);
  let t = Date.now();
  check((await gcs.command(cam, CMD.TRACK_POINT, [0.3, 0.6, 0])).result === RESULT.ACCEPTED && await activeAfter(t) !== null, 'TRACK_POINT (0.3, 0.6): tracking');
  t = Date.now();
  const py = await gcs.command(154, 1000, [-20, 10, NaN, NaN, 0, 0, 1]);
  const idle = await idleAfter(t, 1500);
  check(py.result === RESULT.ACCEPTED && idle !== null, `GIMBAL_MANAGER_PITCHYAW ends tracking (${py.result}, IDLE after ${idle ? idle.at - t : '-'} ms)`);
  t = Date.now();
  check((await gcs.command(cam, CMD.TRACK_POINT, [0.5, 0.7, 0])).result === RESULT.ACCEPTED && await activeAfter(t) !== null, 'TRACK_POINT (0.5, 0.7): tracking');
  await sleep(1000);
  const rate = await request(commandPort, { cmd: 'rate', gimbal: 'sim', pan: 2, tilt: 0 });
  check(rate && rate.ok, `JSON rate: ${JSON.stringify(rate)}`);
  const ended = await idleAfter(t, 6000);
  check(ended !== null, `a JSON rate command ends tracking (IDLE ${ended ? ((ended.at - t) / 1000).toFixed(1) : '-'} s after the click)`);
  await request(commandPort, { cmd: 'rate', gimbal: 'sim', pan: 0, tilt: 0 });
}

async function refusals(gcs, cam) {
  const cases = [
    ['TRACK_POINT outside the image', CMD.TRACK_POINT, [1.5, 0.5, 0], RESULT.DENIED],
    ['TRACK_POINT for another camera', CMD.TRACK_POINT, [0.5, 0.5, 0, 101], RESULT.DENIED],
    ['TRACK_RECTANGLE', CMD.TRACK_RECTANGLE, [0.4, 0.4, 0.6, 0.6], RESULT.UNSUPPORTED],
    ['IMAGE_START_CAPTURE (no photos)', CMD.IMAGE_START_CAPTURE, [0, 0, 1], RESULT.UNSUPPORTED],
    ['VIDEO_START_CAPTURE (no recording over MAVLink)', CMD.VIDEO_START_CAPTURE, [0, 0], RESULT.UNSUPPORTED],
    ['VIDEO_STOP_STREAMING (always relayed)', CMD.VIDEO_STOP_STREAMING, [1], RESULT.UNSUPPORTED],
    ['VIDEO_START_STREAMING stream 1', CMD.VIDEO_START_STREAMING, [1], RESULT.ACCEPTED],
    ['REQUEST_MESSAGE VIDEO_STREAM_INFORMATION stream 2', CMD.REQUEST_MESSAGE, [MSG.VIDEO_STREAM_INFORMATION, 2], RESULT.DENIED],
    ['SET_MESSAGE_INTERVAL of another message', CMD.SET_MESSAGE_INTERVAL, [33, 100000], RESULT.UNSUPPORTED],
    ['SET_CAMERA_ZOOM range 50 %', CMD.SET_CAMERA_ZOOM, [2, 50], RESULT.ACCEPTED],
  ];
  for (const [what, command, params, want] of cases) {
    const r = await gcs.command(cam, command, params);
    check(r.result === want && r.from === cam, `${what}: ${r.result} from ${r.from} (want ${want})`);
  }
}

async function reportOnly(dir) {
  // mavlink.commands false (contract section 14): the camera reports, every command is DENIED.
  const commandPort = await freePort();
  const vehiclePort = await freePort();
  const cfg = path.join(dir, 'report-only.json');
  fs.writeFileSync(cfg, JSON.stringify({
    command: { port: commandPort },
    vehicle: { source: { type: 'udp', bind: '127.0.0.1', port: vehiclePort } },
    mavlink: { gimbal_manager: true, system_id: 1, commands: false },
  }));
  const child = startGimbald(['--sim', '-c', cfg], []);
  const gcs = new Gcs(vehiclePort);
  await gcs.bind();
  const hb = new minimal.Heartbeat();
  Object.assign(hb, { type: 6, autopilot: 8, baseMode: 0, customMode: 0, systemStatus: 4, mavlinkVersion: 3 });
  await gcs.send(hb);
  const beating = setInterval(() => gcs.send(hb), 500);  // heard once gimbald is up
  const beat = await gcs.waitFor((x) => x.name === 'HEARTBEAT' && x.data.type === MAV_TYPE_CAMERA, 8000);
  check(beat !== null, 'report-only: the camera still beats');
  const r = await gcs.command(100, CMD.REQUEST_MESSAGE, [MSG.CAMERA_INFORMATION], MSG.CAMERA_INFORMATION);
  check(r.result === RESULT.DENIED && r.replies.length === 0, `report-only: REQUEST_MESSAGE DENIED (${r.result}), nothing sent`);
  const t = await gcs.command(100, CMD.TRACK_POINT, [0.5, 0.5, 0]);
  check(t.result === RESULT.DENIED, `report-only: TRACK_POINT DENIED (${t.result})`);
  clearInterval(beating);
  gcs.socket.close();
  child.kill('SIGTERM');
}

async function signedOnly(dir) {
  // Signing (contract section 14): with mavlink.signing_key_file the camera, like the gimbal
  // managers, ignores unsigned commands and answers signed ones.
  const key = Buffer.alloc(32);
  for (let i = 0; i < 32; i++) key[i] = (i * 7 + 3) & 255;
  const keyFile = path.join(dir, 'mavlink.key');
  fs.writeFileSync(keyFile, key.toString('hex'), { mode: 0o600 });
  const commandPort = await freePort();
  const vehiclePort = await freePort();
  const cfg = path.join(dir, 'signed.json');
  fs.writeFileSync(cfg, JSON.stringify({
    command: { port: commandPort },
    vehicle: { source: { type: 'udp', bind: '127.0.0.1', port: vehiclePort } },
    mavlink: { gimbal_manager: true, system_id: 1, signing_key_file: keyFile,
      signing_state_file: path.join(dir, 'signing-state.json') },
  }));
  const child = startGimbald(['--sim', '-c', cfg], []);
  const gcs = new Gcs(vehiclePort);
  await gcs.bind();
  const hb = new minimal.Heartbeat();
  Object.assign(hb, { type: 6, autopilot: 8, baseMode: 0, customMode: 0, systemStatus: 4, mavlinkVersion: 3 });
  const beating = setInterval(() => gcs.send(hb), 500);
  await gcs.waitFor((x) => x.name === 'HEARTBEAT' && x.data.type === MAV_TYPE_CAMERA, 8000);
  const unsigned = await gcs.command(100, CMD.REQUEST_MESSAGE, [MSG.CAMERA_INFORMATION], MSG.CAMERA_INFORMATION);
  check(unsigned.result === null && unsigned.replies.length === 0, `signing on: an unsigned REQUEST_MESSAGE is ignored (${unsigned.result})`);
  const msg = new common.CommandLong();
  [msg._param1, msg._param2, msg._param3, msg._param4, msg._param5, msg._param6, msg._param7] = [MSG.CAMERA_INFORMATION, 0, 0, 0, 0, 0, 0];
  msg.command = CMD.REQUEST_MESSAGE; msg.targetSystem = 1; msg.targetComponent = 100; msg.confirmation = 0;
  const since = Date.now();
  // MAVLINK_IFLAG_SIGNED is in the header the checksum covers: set before serializing.
  const signing = new MavLinkProtocolV2(255, 190, 1);
  const signed = signing.sign(signing.serialize(msg, gcs.seq++ & 255), 1, key);
  await new Promise((r) => gcs.socket.send(signed, vehiclePort, '127.0.0.1', () => r()));
  const ack = await gcs.waitFor((x) => x.name === 'COMMAND_ACK' && x.compid === 100, 3000, since);
  const info = await gcs.waitFor((x) => x.msgid === MSG.CAMERA_INFORMATION && x.compid === 100, 1000, since);
  check(ack !== null && ack.data.result === RESULT.ACCEPTED && info !== null,
    `signing on: a signed REQUEST_MESSAGE is answered (${ack && ack.data.result})`);
  clearInterval(beating);
  gcs.socket.close();
  child.kill('SIGTERM');
}

async function main() {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'gimbald-camera-'));
  const overall = setTimeout(() => { console.log('FAIL timeout'); cleanup(); process.exit(1); }, 140000);
  try {
    const dem = path.join(dir, 'sim-dem.tif');
    const w = spawnSync(GIMBAL_SIM, ['--write-dem', dem], { encoding: 'utf8' });
    if (w.status !== 0) throw new Error(`gimbal-sim --write-dem: ${w.stderr}`);
    const commandPort = await freePort();
    const vehiclePort = await freePort();
    const videoIn = await freePort();
    const videoOut = await freePort();
    const cfgPath = path.join(dir, 'gimbald.json');
    fs.writeFileSync(cfgPath, JSON.stringify({
      gimbals: [{ name: 'sim', protocol: 'orion',
        video: { input: `udp://127.0.0.1:${videoIn}`, outputs: [`udp://127.0.0.1:${videoOut}`] } }],
      command: { port: commandPort },
      vehicle: { source: { type: 'udp', bind: '127.0.0.1', port: vehiclePort } },
      mavlink: { gimbal_manager: true, system_id: 1 },
      terrain: { files: [dem], geoid: 'none', cache_mb: 16 },
    }));
    const logs = [];
    startGimbald(['--sim', '-c', cfgPath], logs);
    const gcs = new Gcs(vehiclePort);
    await gcs.bind();
    const hb = new minimal.Heartbeat();
    Object.assign(hb, { type: 6, autopilot: 8, baseMode: 0, customMode: 0, systemStatus: 4, mavlinkVersion: 3 });
    await gcs.send(hb);
    const beating = setInterval(() => gcs.send(hb), 1000);
    // The video and the telemetry first (STATE video.connected).
    for (let i = 0; i < 60; i++) {
      const s = await request(commandPort, { cmd: 'state', gimbal: 'sim', keys: ['video', 'telemetry'] });
      if (s && s.ok && s.state.video && s.state.video.connected && s.state.video.width && s.state.telemetry) break;
      await sleep(250);
    }

    const { cam, stream } = await qgcDiscovery(gcs);
    await oneCameraPerGimbal(gcs, cam);
    if (stream) {
      const uri = text(stream.uri);
      check(stream.type === 3 && uri === String(videoOut) && stream.streamId === 1 && stream.count === 1 && stream.encoding === 1,
        `VIDEO_STREAM_INFORMATION: type ${stream.type} (MPEG_TS), uri "${uri}", encoding ${stream.encoding}, ${stream.resolutionH}x${stream.resolutionV}, name "${text(stream.name)}"`);
      const url = playableUrl(uri);
      const probe = await output('ffprobe', ['-v', 'quiet', '-analyzeduration', '3000000', '-probesize', '2000000',
        '-show_entries', 'stream=codec_type,codec_name,width,height', '-of', 'json', url], 30000);
      const found = JSON.parse(probe || '{}').streams || [];
      const video = found.find((s) => s.codec_type === 'video');
      check(video && video.codec_name === 'h264' && video.width === stream.resolutionH,
        `ffprobe ${url}: ${JSON.stringify(found)}`);
    }
    await clickToTrack(gcs, cam, commandPort, logs);
    await otherSteeringEndsTracking(gcs, cam, commandPort);
    await refusals(gcs, cam);
    clearInterval(beating);
    gcs.socket.close();
    cleanup();
    await sleep(300);
    await reportOnly(dir);
    await signedOnly(dir);
  } catch (e) {
    console.log(`FAIL exception: ${e.stack}`);
    failures++;
  }
  clearTimeout(overall);
  cleanup();
  await sleep(300);
  fs.rmSync(dir, { recursive: true, force: true });
  console.log(failures === 0 ? 'all checks passed' : `${failures} check(s) failed`);
  process.exit(failures === 0 ? 0 : 1);
}
function cleanup() { for (const c of children) if (c.exitCode === null) c.kill('SIGTERM'); }
process.on('SIGINT', () => { cleanup(); process.exit(1); });
main();
