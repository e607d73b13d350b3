// Drives the real gimbald (with the real gimbal-sim behind it) from node-mavlink, a MAVLink
// implementation we did not write: the sequence QGroundControl plays against a gimbal manager
// (contract section 8), a second GCS refused while the first holds control, a gimbal whose link
// is down, bad input, and MAVLink 2 signing. Exit 0 on success, 1 on a failed check.
'use strict';
const dgram = require('dgram');
const net = require('net');
const fs = require('fs');
const os = require('os');
const path = require('path');
const { spawn } = require('child_process');
const {
  MavLinkProtocolV2, MavLinkPacketSplitter, MavLinkPacketParser, minimal, common,
} = require('node-mavlink');

const REGISTRY = { ...minimal.REGISTRY, ...common.REGISTRY };
const GIMBALD = process.env.GIMBALD;
const GIMBAL_SIM = process.env.GIMBAL_SIM;
const MAV_RESULT = { ACCEPTED: 0, TEMPORARILY_REJECTED: 1, DENIED: 2, UNSUPPORTED: 3, FAILED: 4 };
const resultName = (r) => (r === null ? 'no COMMAND_ACK' : Object.keys(MAV_RESULT).find((k) => MAV_RESULT[k] === r) || String(r));
const CMD = { ROI_LOCATION: 195, ROI_NONE: 197, REQUEST_MESSAGE: 512, ZOOM: 531, PITCHYAW: 1000, CONFIGURE: 1001 };
const children = [];
let failures = 0;

function check(ok, what) {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
  if (!ok) failures++;
}
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

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

// A MAVLink peer on its own UDP socket: sends with node-mavlink, keeps every decoded message.
class Peer {
  constructor(sysid, compid, target, key = null) {
    this.sysid = sysid; this.compid = compid; this.target = target; this.key = key;
    this.protocol = new MavLinkProtocolV2(sysid, compid, key ? MavLinkProtocolV2.IFLAG_SIGNED : 0);
    this.seq = 0; this.ts = Date.now();
    this.messages = [];
    this.socket = dgram.createSocket('udp4');
    this.splitter = new MavLinkPacketSplitter();
    const parser = new MavLinkPacketParser();
    this.splitter.pipe(parser);
    parser.on('data', (packet) => {
      const clazz = REGISTRY[packet.header.msgid];
      if (!clazz) return;
      const data = packet.protocol.data(packet.payload, clazz);
      this.messages.push({ at: Date.now(), packet, name: clazz.MSG_NAME, data });
    });
    this.socket.on('message', (buf) => this.splitter.write(buf));
  }
  bind() { return new Promise((r) => this.socket.bind(0, '127.0.0.1', r)); }
  // Serial instead of UDP: every peer writes to and reads from the same pseudo-terminal.
  useSerial(serial) {
    this.socket.close();
    this.serial = serial;
    serial.readers.push((buf) => this.splitter.write(buf));
  }
  send(msg, { sign = this.key !== null } = {}) {
    const protocol = sign ? this.protocol : new MavLinkProtocolV2(this.sysid, this.compid);
    let buf = protocol.serialize(msg, this.seq++ & 255);
    if (sign) { this.ts = Math.max(this.ts + 1, Date.now()); buf = protocol.sign(buf, 0, this.key, this.ts); }
    return this.sendRaw(buf);
  }
  sendRaw(buf) {
    if (this.serial) return this.serial.write(buf);
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
  heartbeat() {
    const hb = new minimal.Heartbeat();
    hb.type = 6; hb.autopilot = 8; hb.baseMode = 0; hb.customMode = 0; hb.systemStatus = 4; hb.mavlinkVersion = 3;
    return this.send(hb);
  }
  async command(command, params, { targetSystem = 1, targetComponent = 154, sign, asInt = null } = {}) {
    let msg;
    if (asInt) {
      // node-mavlink names the parameter fields _param1.._param7 (x, y, z are _param5.._param7).
      msg = new common.CommandInt();
      [msg._param1, msg._param2, msg._param3, msg._param4] = params;
      msg._param5 = asInt.x; msg._param6 = asInt.y; msg._param7 = asInt.z; msg.frame = asInt.frame;
      msg.current = 0; msg.autocontinue = 0;
    } else {
      msg = new common.CommandLong();
      [msg._param1, msg._param2, msg._param3, msg._param4, msg._param5, msg._param6, msg._param7] = params;
      msg.confirmation = 0;
    }
    msg.command = command; msg.targetSystem = targetSystem; msg.targetComponent = targetComponent;
    const since = Date.now();
    await this.send(msg, sign === undefined ? {} : { sign });
    const ack = await this.waitFor((x) => x.name === 'COMMAND_ACK' && x.data.command === command, 3000, since);
    return ack ? ack.data.result : null;
  }
  // As a GCS sends a command (the MAVLink command protocol): again when no ACK came or the
  // answer was TEMPORARILY_REJECTED (a busy link, telemetry late on a loaded machine), at
  // most `attempts` times. The last result.
  async commandRetried(command, params, options = {}, attempts = 3) {
    let result = null;
    for (let i = 0; i < attempts; i++) {
      result = await this.command(command, params, options);
      if (result !== null && result !== MAV_RESULT.TEMPORARILY_REJECTED) return result;
      await sleep(500);
    }
    return result;
  }
  close() { if (!this.serial) this.socket.close(); }
}

// The JSON command socket, for STATE.
async function jsonRequest(port, request) {
  const s = dgram.createSocket('udp4');
  return new Promise((resolve) => {
    const timer = setTimeout(() => { s.close(); resolve(null); }, 2000);
    s.on('message', (buf) => { clearTimeout(timer); s.close(); resolve(JSON.parse(buf.toString())); });
    s.send(JSON.stringify(request), port, '127.0.0.1');
  });
}

function startProcess(cmd, args, logLines) {
  const child = spawn(cmd, args, { stdio: ['ignore', 'pipe', 'pipe'] });
  children.push(child);
  let rest = '';
  child.stdout.on('data', (d) => {
    rest += d.toString();
    const lines = rest.split('\n'); rest = lines.pop();
    for (const l of lines) { try { logLines.push(JSON.parse(l)); } catch (e) { /* text */ } }
  });
  child.stderr.on('data', (d) => process.stderr.write(d));
  return child;
}

// Hamilton product and quaternion -> (yaw, pitch) in degrees, as lib/geo does.
function qmul(a, b) {
  return [a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
    a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
    a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
    a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]];
}
function fromEuler(yawDeg, pitchDeg) {
  const y = yawDeg * Math.PI / 360; const p = pitchDeg * Math.PI / 360;
  return [Math.cos(y) * Math.cos(p), -Math.sin(y) * Math.sin(p), Math.cos(y) * Math.sin(p), Math.sin(y) * Math.cos(p)];
}
function yawPitch(q) {
  const [w, x, y, z] = q;
  const yaw = Math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z)) * 180 / Math.PI;
  const pitch = Math.asin(Math.max(-1, Math.min(1, 2 * (w * y - z * x)))) * 180 / Math.PI;
  return { yaw, pitch };
}
const angleDiff = (a, b) => Math.abs(((a - b + 540) % 360) - 180);

async function startDaemon(dir, { signingKeyFile = null, serialDevice = null } = {}) {
  const simPort = await freePort('tcp');
  const deadPort = await freePort('tcp');
  const commandPort = await freePort('udp');
  const vehiclePort = await freePort('udp');
  const sim = startProcess(GIMBAL_SIM, ['--port', String(simPort)], []);
  await sleep(300);
  const config = {
    gimbals: [
      { name: 'main', protocol: 'orion', link: { type: 'tcp', host: '127.0.0.1', port: simPort } },
      { name: 'dead', protocol: 'orion', link: { type: 'tcp', host: '127.0.0.1', port: deadPort } },
    ],
    command: { port: commandPort },
    vehicle: { source: serialDevice ? { type: 'serial', device: serialDevice, baud: 115200 }
      : { type: 'udp', bind: '127.0.0.1', port: vehiclePort } },
    mavlink: { gimbal_manager: true, component_id: 154, targets: [], signing_key_file: signingKeyFile },
  };
  const cfgPath = path.join(dir, `gimbald-${vehiclePort}.json`);
  fs.writeFileSync(cfgPath, JSON.stringify(config));
  const logs = [];
  const daemon = startProcess(GIMBALD, ['-c', cfgPath, '--log-level', 'debug'], logs);
  // Ready when the JSON socket answers and the Orion link is up.
  for (let i = 0; i < 100; i++) {
    const r = await jsonRequest(commandPort, { cmd: 'state', gimbal: 'main' });
    if (r && r.ok && r.state.link.connected && r.state.telemetry) break;
    await sleep(100);
  }
  return { sim, daemon, logs, commandPort, vehiclePort };
}

// The autopilot: system 1, heartbeat, position (home 400 m MSL) and attitude.
function startAutopilot(port, key) {
  const ap = new Peer(1, 1, port, key);
  const tick = async () => {
    const hb = new minimal.Heartbeat();
    hb.type = 2; hb.autopilot = 3; hb.baseMode = 0; hb.customMode = 0; hb.systemStatus = 4; hb.mavlinkVersion = 3;
    await ap.send(hb, { sign: false });
    const pos = new common.GlobalPositionInt();
    pos.timeBootMs = 1; pos.lat = 457089827; pos.lon = -1214993263; pos.alt = 500000; pos.relativeAlt = 100000;
    pos.vx = 0; pos.vy = 0; pos.vz = 0; pos.hdg = 9000;
    await ap.send(pos, { sign: false });
  };
  ap.timer = setInterval(tick, 200);
  return ap;
}

async function mainSequence(dir) {
  const d = await startDaemon(dir);
  const ap = startAutopilot(d.vehiclePort);
  await ap.bind();
  const gcs = new Peer(255, 190, d.vehiclePort);
  await gcs.bind();
  const gcs2 = new Peer(254, 190, d.vehiclePort);
  await gcs2.bind();
  await gcs.heartbeat(); await gcs2.heartbeat();

  const hb = await gcs.waitFor((x) => x.name === 'HEARTBEAT' && x.packet.header.sysid === 1 && x.packet.header.compid === 154, 3000);
  check(hb && hb.data.type === 26 && hb.data.autopilot === 8, 'HEARTBEAT from 1/154: MAV_TYPE_GIMBAL, MAV_AUTOPILOT_INVALID');
  check(await ap.waitFor((x) => x.name === 'GIMBAL_MANAGER_STATUS', 2000) !== null, 'the autopilot (another peer) gets the streams too');

  const t0 = Date.now();
  check(await gcs.command(CMD.REQUEST_MESSAGE, [280, 0, 0, 0, 0, 0, 0]) === MAV_RESULT.ACCEPTED, 'REQUEST_MESSAGE GIMBAL_MANAGER_INFORMATION: ACCEPTED');
  const info = await gcs.waitFor((x) => x.name === 'GIMBAL_MANAGER_INFORMATION' && x.data.gimbalDeviceId === 1, 2000, t0);
  check(info && Math.abs(info.data.pitchMin * 180 / Math.PI + 120) < 1 && (info.data.capFlags & 131072) !== 0,
    'GIMBAL_MANAGER_INFORMATION: Orion limits from LIMITS, can point to a location');

  check(await gcs.command(CMD.CONFIGURE, [-2, -2, -1, -1, 0, 0, 0]) === MAV_RESULT.ACCEPTED, 'DO_GIMBAL_MANAGER_CONFIGURE -2: ACCEPTED (take control)');
  const t1 = Date.now();
  const st = await gcs.waitFor((x) => x.name === 'GIMBAL_MANAGER_STATUS' && x.data.gimbalDeviceId === 1, 2000, t1 + 10);
  check(st && st.data.primaryControlSysid === 255 && st.data.primaryControlCompid === 190, 'GIMBAL_MANAGER_STATUS: primary control 255/190');

  check(await gcs.command(CMD.PITCHYAW, [-30, 45, NaN, NaN, 0, 0, 1]) === MAV_RESULT.ACCEPTED, 'DO_GIMBAL_MANAGER_PITCHYAW angles: ACCEPTED');
  let state = null;
  for (let i = 0; i < 50; i++) {
    state = (await jsonRequest(d.commandPort, { cmd: 'state', gimbal: 'main' })).state;
    if (Math.abs(state.telemetry.pan - 45) < 0.5 && Math.abs(state.telemetry.tilt + 30) < 0.5) break;
    await sleep(100);
  }
  check(Math.abs(state.telemetry.pan - 45) < 0.5 && Math.abs(state.telemetry.tilt + 30) < 0.5,
    `the simulated Orion went to pan 45, tilt -30 (pan ${state.telemetry.pan}, tilt ${state.telemetry.tilt})`);
  // GIMBAL_DEVICE_ATTITUDE_STATUS follows the simulator: compare with the line of sight
  // computed here from the same STATE (mount quaternion, pan, tilt).
  {
    const at = Date.now();
    const s2 = (await jsonRequest(d.commandPort, { cmd: 'state', gimbal: 'main' })).state;
    const expected = yawPitch(qmul(s2.telemetry.quat, fromEuler(s2.telemetry.pan, s2.telemetry.tilt)));
    const msg = await gcs.waitFor((x) => x.name === 'GIMBAL_DEVICE_ATTITUDE_STATUS' && x.data.gimbalDeviceId === 1, 1000, at);
    const got = msg ? yawPitch(msg.data.q) : { yaw: NaN, pitch: NaN };
    check(msg && angleDiff(got.yaw, expected.yaw) < 0.5 && Math.abs(got.pitch - expected.pitch) < 0.5 && (msg.data.flags & 64) !== 0,
      `GIMBAL_DEVICE_ATTITUDE_STATUS line of sight within 0.5 deg (yaw ${got.yaw.toFixed(2)} vs ${expected.yaw.toFixed(2)}, pitch ${got.pitch.toFixed(2)} vs ${expected.pitch.toFixed(2)})`);
  }

  check(await gcs.command(CMD.PITCHYAW, [NaN, NaN, 10, 0, 0, 0, 1]) === MAV_RESULT.ACCEPTED, 'DO_GIMBAL_MANAGER_PITCHYAW rates: ACCEPTED');
  const tiltBefore = (await jsonRequest(d.commandPort, { cmd: 'state', gimbal: 'main' })).state.telemetry.tilt;
  await sleep(600);
  const tiltAfter = (await jsonRequest(d.commandPort, { cmd: 'state', gimbal: 'main' })).state.telemetry.tilt;
  check(tiltAfter > tiltBefore + 2, `rate 10 deg/s moves the tilt (${tiltBefore.toFixed(1)} -> ${tiltAfter.toFixed(1)})`);

  check(await gcs.command(CMD.ROI_LOCATION, [1, 0, 0, 0], { asInt: { x: 457189827, y: -1214993263, z: 20, frame: 6 } }) === MAV_RESULT.ACCEPTED,
    'DO_SET_ROI_LOCATION as COMMAND_INT, GLOBAL_RELATIVE_ALT_INT: ACCEPTED');
  await sleep(300);
  const geo = d.logs.filter((l) => l.event === 'command' && l.cmd === 'geopoint');
  check(geo.length === 1 && geo[0].src === 'mavlink:255/190' && geo[0].ok === true, 'command log line: geopoint from src mavlink:255/190');
  const mode = (await jsonRequest(d.commandPort, { cmd: 'state', gimbal: 'main' })).state.telemetry.mode;
  check(mode === 'geopoint', `the Orion is in geopoint mode (${mode})`);
  check(await gcs.command(CMD.ROI_LOCATION, [1, 0, 0, 0], { asInt: { x: 457189827, y: -1214993263, z: 20, frame: 11 } }) === MAV_RESULT.UNSUPPORTED,
    'terrain altitude frame: UNSUPPORTED');

  check(await gcs.command(CMD.ZOOM, [2, 50, 1, 0, 0, 0, 0]) === MAV_RESULT.ACCEPTED, 'SET_CAMERA_ZOOM range 50%: ACCEPTED');
  await sleep(200);
  check(d.logs.some((l) => l.event === 'command' && l.cmd === 'camera_zoom' && l.ok === true), 'camera_zoom reached the gimbal');

  check(await gcs2.command(CMD.PITCHYAW, [-10, 0, NaN, NaN, 0, 0, 1]) === MAV_RESULT.DENIED, 'a second GCS is DENIED while the first holds control');
  // Gimbal 2 is its own manager component, 171 (contract section 14).
  check(await gcs.command(CMD.PITCHYAW, [-10, 0, NaN, NaN, 0, 0, 2], { targetComponent: 171 }) === MAV_RESULT.TEMPORARILY_REJECTED, 'gimbal 2 (link down) at component 171: TEMPORARILY_REJECTED');
  check(await gcs.command(CMD.PITCHYAW, [-10, 0, NaN, NaN, 0, 0, 1], { targetSystem: 7 }) === null, 'a command for another system gets no answer');
  check(await gcs.command(2000, [0, 0, 0, 0, 0, 0, 0]) === MAV_RESULT.UNSUPPORTED, 'an unknown command: UNSUPPORTED');
  check(await gcs.command(CMD.PITCHYAW, [Infinity, 0, NaN, NaN, 0, 0, 1]) === MAV_RESULT.DENIED, 'an infinite angle: DENIED');

  // Garbage, a truncated frame and a frame with a broken CRC: ignored, the daemon goes on.
  await gcs.sendRaw(Buffer.from([0xfd, 0x20, 0x00, 0x00, 0x03, 0xff]));
  await gcs.sendRaw(Buffer.from(Array.from({ length: 300 }, (_, i) => (i * 37) & 255)));
  const cl = new common.CommandLong();
  Object.assign(cl, { command: CMD.PITCHYAW, targetSystem: 1, targetComponent: 154, _param1: 10, _param2: 10, _param3: NaN, _param4: NaN, _param5: 0, _param6: 0, _param7: 1, confirmation: 0 });
  const bad = gcs.protocol.serialize(cl, 200); bad[bad.length - 1] ^= 0xff;
  const sentBefore = d.logs.filter((l) => l.event === 'command').length;
  await gcs.sendRaw(bad);
  check(await gcs.command(CMD.CONFIGURE, [-1, -1, -1, -1, 0, 0, 0]) === MAV_RESULT.ACCEPTED, 'after garbage and a bad CRC the manager still answers');
  check(d.logs.filter((l) => l.event === 'command').length === sentBefore, 'the bad frames moved nothing');

  check(await gcs.command(CMD.CONFIGURE, [-3, -3, -1, -1, 0, 0, 0]) === MAV_RESULT.ACCEPTED, 'release control');
  check(await gcs2.command(CMD.PITCHYAW, [-10, 0, NaN, NaN, 0, 0, 1]) === MAV_RESULT.ACCEPTED, 'then the second GCS may steer');
  const state2 = (await jsonRequest(d.commandPort, { cmd: 'state', gimbal: 'main' })).state;
  check(state2.mavlink && state2.mavlink.commands > 5 && state2.mavlink.denied >= 2 && state2.mavlink.peers.length >= 3,
    `STATE mavlink: ${JSON.stringify(state2.mavlink)}`);
  check(d.daemon.exitCode === null, 'gimbald is still running');
  if (failures > 0 || process.env.MAVLINK_TEST_VERBOSE) {
    for (const l of d.logs) if (['command', 'mavlink_refused', 'mavlink_start'].includes(l.event)) console.log(JSON.stringify(l));
  }

  clearInterval(ap.timer); ap.close(); gcs.close(); gcs2.close();
  d.daemon.kill('SIGTERM'); d.sim.kill('SIGTERM');
  await sleep(300);
}

async function signingSequence(dir) {
  const key = Buffer.alloc(32);
  for (let i = 0; i < 32; i++) key[i] = (i * 7 + 3) & 255;
  const keyFile = path.join(dir, 'mavlink.key');
  fs.writeFileSync(keyFile, key.toString('hex') + '\n', { mode: 0o600 });
  const d = await startDaemon(dir, { signingKeyFile: keyFile });
  const ap = startAutopilot(d.vehiclePort, null);
  await ap.bind();
  const gcs = new Peer(255, 190, d.vehiclePort, key);
  await gcs.bind();
  await gcs.heartbeat();
  check(await gcs.command(CMD.CONFIGURE, [-2, -2, -1, -1, 0, 0, 0], { sign: false }) === null, 'signing on: an unsigned command is ignored');
  const wrong = new Peer(255, 190, d.vehiclePort, Buffer.alloc(32, 1));
  await wrong.bind();
  check(await wrong.command(CMD.CONFIGURE, [-2, -2, -1, -1, 0, 0, 0]) === null, 'signing on: a command signed with another key is ignored');
  const t = Date.now();
  check(await gcs.command(CMD.CONFIGURE, [-2, -2, -1, -1, 0, 0, 0]) === MAV_RESULT.ACCEPTED, 'signing on: a signed command is ACCEPTED');
  const ack = await gcs.waitFor((x) => x.name === 'COMMAND_ACK', 1000, t);
  check(ack && ack.packet.signature && ack.packet.signature.matches(key), 'the ACK is signed with the same key (node-mavlink verifies it)');
  // Replaying the very frame that was accepted: ignored.
  const cl = new common.CommandLong();
  Object.assign(cl, { command: CMD.CONFIGURE, targetSystem: 1, targetComponent: 154, _param1: -3, _param2: -3, _param3: -1, _param4: -1, _param5: 0, _param6: 0, _param7: 0, confirmation: 0 });
  gcs.ts += 1;
  const frame = gcs.protocol.sign(gcs.protocol.serialize(cl, 1), 0, key, gcs.ts);
  await gcs.sendRaw(frame);
  const first = await gcs.waitFor((x) => x.name === 'COMMAND_ACK' && x.data.command === CMD.CONFIGURE, 2000, Date.now() - 5);
  const t2 = Date.now();
  await gcs.sendRaw(frame);
  const replay = await gcs.waitFor((x) => x.name === 'COMMAND_ACK', 1000, t2);
  check(first !== null && replay === null, 'a replayed signed frame is ignored');
  clearInterval(ap.timer); ap.close(); gcs.close(); wrong.close();
  d.daemon.kill('SIGTERM'); d.sim.kill('SIGTERM');
  await sleep(300);
}

// A Viewpro (gimbald --sim orion,viewpro: device 1 sim-orion, 2 sim-viewpro): angles become
// viewpro_adjust steps from its reported angles; ROI, rates and zoom are UNSUPPORTED.
async function viewproSequence(dir) {
  const commandPort = await freePort('udp');
  const vehiclePort = await freePort('udp');
  const cfgPath = path.join(dir, 'viewpro.json');
  fs.writeFileSync(cfgPath, JSON.stringify({
    command: { port: commandPort },
    vehicle: { source: { type: 'udp', bind: '127.0.0.1', port: vehiclePort } },
    mavlink: { gimbal_manager: true, system_id: 1 },
  }));
  const logs = [];
  const daemon = startProcess(GIMBALD, ['--sim', 'orion,viewpro', '-c', cfgPath], logs);
  const viewpro = async () => {
    const r = await jsonRequest(commandPort, { cmd: 'state', gimbal: 'sim-viewpro' });
    return r && r.ok ? r.state : null;
  };
  let st = null;
  for (let i = 0; i < 100 && !(st && st.output && st.output.gimbal); i++) { st = await viewpro(); await sleep(100); }
  const gcs = new Peer(255, 190, vehiclePort);
  await gcs.bind();
  await gcs.heartbeat();
  const before = st.output.gimbal.pitch;
  // The Viewpro is gimbal device 2, managed by component 171 (contract section 14).
  const viewproAt = { targetComponent: 171 };
  check(await gcs.command(CMD.PITCHYAW, [before + 10, st.output.gimbal.yaw, NaN, NaN, 0, 0, 2], viewproAt) === MAV_RESULT.ACCEPTED,
    'Viewpro: PITCHYAW angles: ACCEPTED');
  await sleep(300);
  check(logs.some((l) => l.event === 'command' && l.cmd === 'viewpro_adjust' && l.gimbal === 'sim-viewpro' && l.ok),
    'Viewpro: sent as viewpro_adjust');
  // The Viewpro adjust frames shift the gimbal's calculated point (its ICD): the target moves.
  const target0 = st.output.target;
  let target1 = target0;
  for (let i = 0; i < 20 && target1.lat === target0.lat && target1.lon === target0.lon; i++) {
    target1 = (await viewpro()).output.target; await sleep(100);
  }
  check(target1.lat !== target0.lat || target1.lon !== target0.lon,
    `Viewpro: the simulated gimbal's calculated point moved (${JSON.stringify(target0)} -> ${JSON.stringify(target1)})`);
  check(await gcs.command(CMD.PITCHYAW, [NaN, NaN, 5, 5, 0, 0, 2], viewproAt) === MAV_RESULT.UNSUPPORTED, 'Viewpro: rates UNSUPPORTED');
  check(await gcs.command(CMD.ROI_LOCATION, [2, 0, 0, 0, 6.95, 79.88, 10], viewproAt) === MAV_RESULT.UNSUPPORTED, 'Viewpro: ROI UNSUPPORTED');
  check(await gcs.command(CMD.ZOOM, [2, 50, 2, 0, 0, 0, 0], viewproAt) === MAV_RESULT.UNSUPPORTED, 'Viewpro: zoom UNSUPPORTED');
  const t = Date.now();
  const status = await gcs.waitFor((x) => x.name === 'GIMBAL_DEVICE_ATTITUDE_STATUS' && x.data.gimbalDeviceId === 2, 1000, t);
  check(status && Number.isFinite(status.data.q[0]) && status.data.failureFlags === 0 && status.packet.header.compid === 171,
    'Viewpro: GIMBAL_DEVICE_ATTITUDE_STATUS for device 2, from component 171');
  gcs.close();
  daemon.kill('SIGTERM');
  await sleep(300);
}

// The same endpoint over a serial line: a socat pseudo-terminal pair, gimbald on one end, the
// autopilot and the GCS on the other.
async function serialSequence(dir) {
  const { execFileSync } = require('child_process');
  try { execFileSync('socat', ['-V'], { stdio: 'ignore' }); } catch (e) {
    console.log('skip serial: socat not installed');
    return;
  }
  const a = path.join(dir, 'pty-gimbald'); const b = path.join(dir, 'pty-vehicle');
  const socat = spawn('socat', [`pty,raw,echo=0,link=${a}`, `pty,raw,echo=0,link=${b}`], { stdio: 'ignore' });
  children.push(socat);
  for (let i = 0; i < 50 && !(fs.existsSync(a) && fs.existsSync(b)); i++) await sleep(50);
  const fd = fs.openSync(b, 'r+');
  const serial = {
    readers: [],
    write: (buf) => new Promise((r) => fs.write(fd, buf, () => r())),
  };
  const stream = fs.createReadStream(null, { fd, autoClose: false });
  stream.on('data', (buf) => { for (const r of serial.readers) r(buf); });
  stream.on('error', () => {});
  const d = await startDaemon(dir, { serialDevice: a });
  const ap = new Peer(1, 1, 0); ap.useSerial(serial);
  const gcs = new Peer(255, 190, 0); gcs.useSerial(serial);
  const gcs2 = new Peer(254, 190, 0); gcs2.useSerial(serial);
  const beat = async () => {
    const hb = new minimal.Heartbeat();
    hb.type = 2; hb.autopilot = 3; hb.baseMode = 0; hb.customMode = 0; hb.systemStatus = 4; hb.mavlinkVersion = 3;
    await ap.send(hb);
  };
  ap.timer = setInterval(beat, 300);
  await beat();
  const hb = await gcs.waitFor((x) => x.name === 'HEARTBEAT' && x.packet.header.compid === 154, 4000);
  check(hb !== null, 'serial: HEARTBEAT from the gimbal manager on the same port');
  let result = await gcs.commandRetried(CMD.CONFIGURE, [-2, -2, -1, -1, 0, 0, 1]);
  check(result === MAV_RESULT.ACCEPTED, `serial: take control: ACCEPTED (${resultName(result)})`);
  result = await gcs.commandRetried(CMD.PITCHYAW, [-20, -60, NaN, NaN, 0, 0, 1]);
  check(result === MAV_RESULT.ACCEPTED, `serial: PITCHYAW angles: ACCEPTED (${resultName(result)})`);
  let state = null;
  for (let i = 0; i < 50; i++) {
    state = (await jsonRequest(d.commandPort, { cmd: 'state', gimbal: 'main' })).state;
    if (Math.abs(state.telemetry.pan + 60) < 0.5 && Math.abs(state.telemetry.tilt + 20) < 0.5) break;
    await sleep(100);
  }
  check(Math.abs(state.telemetry.pan + 60) < 0.5 && Math.abs(state.telemetry.tilt + 20) < 0.5,
    `serial: the simulated Orion went to pan -60, tilt -20 (pan ${state.telemetry.pan}, tilt ${state.telemetry.tilt})`);
  check(await gcs2.command(CMD.PITCHYAW, [-10, 0, NaN, NaN, 0, 0, 1]) === MAV_RESULT.DENIED, 'serial: a second GCS is DENIED');
  check(await gcs.command(CMD.ROI_LOCATION, [1, 0, 0, 0], { asInt: { x: 457189827, y: -1214993263, z: 500, frame: 5 } }) === MAV_RESULT.ACCEPTED,
    'serial: DO_SET_ROI_LOCATION (MSL): ACCEPTED');
  check(state.mavlink && state.mavlink.peers.length === 1 && state.mavlink.peers[0].startsWith('serial '), `serial: STATE mavlink peers ${JSON.stringify(state.mavlink && state.mavlink.peers)}`);
  clearInterval(ap.timer);
  stream.destroy();
  d.daemon.kill('SIGTERM'); d.sim.kill('SIGTERM');
  await sleep(300);
  socat.kill('SIGTERM');
  try { fs.closeSync(fd); } catch (e) { /* closed by the stream */ }
}

async function main() {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'gimbald-mavlink-'));
  const overall = setTimeout(() => { console.log('FAIL timeout'); cleanup(); process.exit(1); }, 120000);
  try {
    await mainSequence(dir);
    await signingSequence(dir);
    await viewproSequence(dir);
    await serialSequence(dir);
  } catch (e) {
    console.log(`FAIL exception: ${e.stack}`);
    failures++;
  }
  clearTimeout(overall);
  cleanup();
  fs.rmSync(dir, { recursive: true, force: true });
  console.log(failures === 0 ? 'all checks passed' : `${failures} check(s) failed`);
  process.exit(failures === 0 ? 0 : 1);
}
function cleanup() { for (const c of children) if (c.exitCode === null) c.kill('SIGKILL'); }
process.on('SIGINT', () => { cleanup(); process.exit(1); });
main();
