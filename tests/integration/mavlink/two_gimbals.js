// Two gimbals behind one gimbald, seen the way MAVSDK's Gimbal plugin sees them (contract
// section 14): a client that keeps one gimbal per gimbal manager component id - as MAVSDK does
// (gimbal_impl.cpp, `_discovery[message.compid]`) - discovers both, takes control of each and
// steers each on its own; each simulator must receive its own command and nothing of the
// other's. node-mavlink is the MAVLink side (an implementation we did not write); the gimbals
// are two real gimbal-sim processes (an Orion and a Viewpro) with rx logs as witnesses.
// Exit 0 on success, 1 on a failed check.
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
const ACCEPTED = 0; const DENIED = 2;
const CMD = { REQUEST_MESSAGE: 512, PITCHYAW: 1000, CONFIGURE: 1001 };
const MAV_TYPE_GIMBAL = 26;
const children = [];
let failures = 0;

function check(ok, what) {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
  if (!ok) failures++;
}
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

async function freePort(kind) {
  return new Promise((resolve) => {
    const s = kind === 'tcp' ? net.createServer() : dgram.createSocket('udp4');
    const done = () => { const p = s.address().port; s.close(() => resolve(p)); };
    if (kind === 'tcp') s.listen(0, '127.0.0.1', done); else s.bind(0, '127.0.0.1', done);
  });
}

function startProcess(cmd, args, onLine) {
  const child = spawn(cmd, args, { stdio: ['ignore', 'pipe', 'pipe'] });
  children.push(child);
  let rest = '';
  child.stdout.on('data', (d) => {
    rest += d.toString();
    const lines = rest.split('\n'); rest = lines.pop();
    for (const l of lines) onLine(l);
  });
  child.stderr.on('data', (d) => process.stderr.write(d));
  return child;
}

// A gimbal-sim on a free TCP port; resolves once it printed its endpoint.
function startSim(dir, protocol) {
  const rxLog = path.join(dir, `rx-${protocol}.jsonl`);
  return new Promise((resolve) => {
    startProcess(GIMBAL_SIM, ['--protocol', protocol, '--port', '0', '--no-discovery',
      '--rx-log', rxLog], (line) => {
      const m = /^tcp: .*:(\d+)$/.exec(line.trim());
      if (m) resolve({ port: Number(m[1]), rxLog });
    });
  });
}

// Every packet the simulator received so far (its rx log).
function rx(sim) {
  let text = '';
  try { text = fs.readFileSync(sim.rxLog, 'utf8'); } catch (e) { return []; }
  return text.split('\n').filter((l) => l.trim()).map((l) => JSON.parse(l));
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
        name: clazz.MSG_NAME, data: packet.protocol.data(packet.payload, clazz) });
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
  // COMMAND_LONG to (1, compid); the ACK must come from that component.
  async command(compid, command, params) {
    const msg = new common.CommandLong();
    [msg._param1, msg._param2, msg._param3, msg._param4, msg._param5, msg._param6, msg._param7] = params;
    msg.command = command; msg.targetSystem = 1; msg.targetComponent = compid; msg.confirmation = 0;
    const since = Date.now();
    await this.send(msg);
    const ack = await this.waitFor((x) => x.name === 'COMMAND_ACK' && x.data.command === command, 3000, since);
    if (!ack) return { result: null };
    return { result: ack.data.result, from: ack.compid };
  }
}

async function main() {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'gimbald-two-'));
  const overall = setTimeout(() => { console.log('FAIL timeout'); cleanup(); process.exit(1); }, 90000);
  try {
    const orion = await startSim(dir, 'orion');
    const viewpro = await startSim(dir, 'viewpro');
    const commandPort = await freePort('udp');
    const vehiclePort = await freePort('udp');
    const cfgPath = path.join(dir, 'gimbald.json');
    fs.writeFileSync(cfgPath, JSON.stringify({
      gimbals: [
        { name: 'left', protocol: 'orion', link: { type: 'tcp', host: '127.0.0.1', port: orion.port } },
        { name: 'right', protocol: 'viewpro', link: { type: 'tcp', host: '127.0.0.1', port: viewpro.port } },
      ],
      command: { port: commandPort },
      vehicle: { source: { type: 'udp', bind: '127.0.0.1', port: vehiclePort } },
      mavlink: { gimbal_manager: true, system_id: 1 },
    }));
    const logs = [];
    startProcess(GIMBALD, ['-c', cfgPath], (l) => { try { logs.push(JSON.parse(l)); } catch (e) { /* text */ } });
    const gcs = new Gcs(vehiclePort);
    await gcs.bind();
    // A ground station's HEARTBEAT at 2 Hz: gimbald answers every peer it has heard.
    const hb = new minimal.Heartbeat();
    Object.assign(hb, { type: 6, autopilot: 8, baseMode: 0, customMode: 0, systemStatus: 4, mavlinkVersion: 3 });
    await gcs.send(hb);
    const beating = setInterval(() => gcs.send(hb), 500);

    // Each gimbal manager is a component with its own heartbeat.
    const beat = (c) => gcs.waitFor((x) => x.name === 'HEARTBEAT' && x.compid === c && x.data.type === MAV_TYPE_GIMBAL, 4000);
    check(await beat(154) !== null, 'HEARTBEAT (MAV_TYPE_GIMBAL) from component 154');
    check(await beat(171) !== null, 'HEARTBEAT (MAV_TYPE_GIMBAL) from component 171');

    // Discovery as MAVSDK does it: GIMBAL_MANAGER_INFORMATION, one gimbal per sender compid.
    // Wait for the Viewpro's first angles (its information is there from the start anyway).
    await sleep(1500);
    const t0 = Date.now();
    const req = new common.CommandLong();
    Object.assign(req, { command: CMD.REQUEST_MESSAGE, targetSystem: 1, targetComponent: 0, confirmation: 0,
      _param1: 280, _param2: 0, _param3: 0, _param4: 0, _param5: 0, _param6: 0, _param7: 0 });
    await gcs.send(req);
    await sleep(500);
    const discovery = {};
    for (const m of gcs.messages)
      if (m.at >= t0 && m.name === 'GIMBAL_MANAGER_INFORMATION') discovery[m.compid] = m.data.gimbalDeviceId;
    check(JSON.stringify(discovery) === JSON.stringify({ 154: 1, 171: 2 }),
      `discovery by component: ${JSON.stringify(discovery)} (want {"154":1,"171":2})`);

    // The attitude streams, matched by component and device id as MAVSDK matches them.
    const att = (c, d) => gcs.waitFor((x) => x.name === 'GIMBAL_DEVICE_ATTITUDE_STATUS' && x.compid === c && x.data.gimbalDeviceId === d, 2000, Date.now());
    check(await att(154, 1) !== null, 'GIMBAL_DEVICE_ATTITUDE_STATUS from 154 for device 1');
    check(await att(171, 2) !== null, 'GIMBAL_DEVICE_ATTITUDE_STATUS from 171 for device 2');
    const st = (c, d) => gcs.waitFor((x) => x.name === 'GIMBAL_MANAGER_STATUS' && x.compid === c && x.data.gimbalDeviceId === d, 2000, Date.now());
    check(await st(154, 1) !== null && await st(171, 2) !== null, 'GIMBAL_MANAGER_STATUS from each component for its device');

    // Take control of each and steer each on its own.
    for (const [compid, device] of Object.entries(discovery)) {
      const r = await gcs.command(Number(compid), CMD.CONFIGURE, [-2, -2, -1, -1, 0, 0, device]);
      check(r.result === ACCEPTED && r.from === Number(compid), `take control of device ${device} at component ${compid}: ACK from ${r.from}`);
    }
    const orionBefore = rx(orion).length;
    const viewproBefore = rx(viewpro).length;
    const left = await gcs.command(154, CMD.PITCHYAW, [-25, 40, NaN, NaN, 0, 0, 1]);
    check(left.result === ACCEPTED && left.from === 154, `PITCHYAW to 154 (Orion): ACCEPTED from ${left.from}`);
    await sleep(500);
    const rightState = JSON.parse(await new Promise((resolve) => {
      const s = dgram.createSocket('udp4');
      s.on('message', (b) => { s.close(); resolve(b.toString()); });
      s.send(JSON.stringify({ cmd: 'state', gimbal: 'right' }), commandPort, '127.0.0.1');
    }));
    const g = rightState.state.output.gimbal;
    const right = await gcs.command(171, CMD.PITCHYAW, [g.pitch + 6, g.yaw - 8, NaN, NaN, 0, 0, 2]);
    check(right.result === ACCEPTED && right.from === 171, `PITCHYAW to 171 (Viewpro): ACCEPTED from ${right.from}`);
    // MAVSDK's set_angles: GIMBAL_MANAGER_SET_ATTITUDE to the manager component.
    const sa = new common.GimbalManagerSetAttitude();
    const yaw = 10 * Math.PI / 360; const pitch = -15 * Math.PI / 360;
    Object.assign(sa, { targetSystem: 1, targetComponent: 154, flags: 0, gimbalDeviceId: 1,
      q: [Math.cos(yaw) * Math.cos(pitch), -Math.sin(yaw) * Math.sin(pitch), Math.cos(yaw) * Math.sin(pitch), Math.sin(yaw) * Math.cos(pitch)],
      angularVelocityX: NaN, angularVelocityY: NaN, angularVelocityZ: NaN });
    await gcs.send(sa);
    // The other manager's device at the wrong component: DENIED, nothing sent.
    const wrong = await gcs.command(154, CMD.PITCHYAW, [-5, 5, NaN, NaN, 0, 0, 2]);
    check(wrong.result === DENIED, `device 2 addressed to component 154: DENIED (${wrong.result})`);
    await sleep(800);

    // The witnesses: each simulator received its own command, and only its own.
    const orionCmds = rx(orion).slice(orionBefore).filter((e) => e.name === 'cmd');
    // OrionCmd carries milliradians: 0.06 degrees.
    const fromLeft = orionCmds.find((e) => Math.abs(e.packet.target[0] - 40) < 0.1 && Math.abs(e.packet.target[1] + 25) < 0.1);
    check(fromLeft !== undefined, `the Orion sim received pan 40, tilt -25 (${JSON.stringify(orionCmds.map((e) => e.packet.target))})`);
    const fromSetAttitude = orionCmds.find((e) => Math.abs(e.packet.target[0] - 10) < 0.1 && Math.abs(e.packet.target[1] + 15) < 0.1);
    check(fromSetAttitude !== undefined, 'the Orion sim received the SET_ATTITUDE angles (pan 10, tilt -15)');
    check(orionCmds.every((e) => Math.abs(e.packet.target[0] - 5) > 0.1), 'the Orion sim got nothing of the refused command');
    const shifts = rx(viewpro).slice(viewproBefore).filter((e) => e.kind === 'yaw_shift' || e.kind === 'pitch_shift');
    check(shifts.some((e) => e.kind === 'yaw_shift') && shifts.some((e) => e.kind === 'pitch_shift'),
      `the Viewpro sim received yaw and pitch shifts (${JSON.stringify(shifts.map((e) => [e.kind, e.frame]))})`);
    const cmdLines = logs.filter((l) => l.event === 'command' && l.transport === 'mavlink');
    check(cmdLines.filter((l) => l.gimbal === 'left').length === 2 && cmdLines.filter((l) => l.gimbal === 'right').length === 1,
      `command lines: ${JSON.stringify(cmdLines.map((l) => [l.gimbal, l.cmd]))}`);
    const refused = logs.filter((l) => l.event === 'mavlink_refused');
    check(refused.length === 1 && refused[0].result === 'MAV_RESULT_DENIED' && /component 171/.test(refused[0].msg),
      `mavlink_refused: ${JSON.stringify(refused)}`);
    clearInterval(beating);
    gcs.socket.close();
  } catch (e) {
    console.log(`FAIL exception: ${e.stack}`);
    failures++;
  }
  clearTimeout(overall);
  cleanup();
  await sleep(200);
  fs.rmSync(dir, { recursive: true, force: true });
  console.log(failures === 0 ? 'all checks passed' : `${failures} check(s) failed`);
  process.exit(failures === 0 ? 0 : 1);
}
function cleanup() { for (const c of children) if (c.exitCode === null) c.kill('SIGTERM'); }
process.on('SIGINT', () => { cleanup(); process.exit(1); });
main();
