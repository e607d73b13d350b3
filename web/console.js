// The operator console: loads /api/console and /api/state, follows /api/stream (WebSocket,
// reconnecting), keeps a track per gimbal, fills the side panels, sends commands with
// POST /api/command, shows the gimbal's video with its overlays, click-to-point and
// drag-to-track (video.js, video_overlay.js, track_box.js), and exposes what it drew as
// window.gimbaldConsole (docs/console.md).
'use strict';

(function () {
  const Geo = window.GimbaldGeo;
  const TRACK_SECONDS = 300;
  const MAX_EVENTS = 40;
  const LASER_CONFIRM_S = 5;
  // Ground height assumed for a click when the gimbal reports no target (docs/console.md).
  const FALLBACK_BELOW_AIRCRAFT_M = 300;

  const $ = (id) => document.getElementById(id);
  const app = {
    info: null, // /api/console
    states: {}, // gimbal name -> latest STATE
    received: {}, // gimbal name -> Date.now() of the latest STATE
    tracks: {}, // gimbal name -> [{t, lat, lon}]
    groundAlt: {}, // gimbal name -> latest known target altitude (WGS84)
    clicks: {}, // gimbal name -> last click {lat, lon}
    objects: new window.GimbaldObjectTrails(), // the visually tracked objects' ground trails
    events: [],
    selected: null,
    socket: null,
    reconnectDelay: 1000,
    lastClick: null,
  };
  const map = new window.GimbaldPlanView($('map'));
  const LAYOUTS = { side: 'side by side', video: 'video large', map: 'plan view large' };
  const PROJECT_EVERY_MS = 500;
  const video = {
    panel: new window.GimbaldVideoPanel($('video'), (label, kind) => setBadge($('video-status'), label, kind)),
    overlay: new window.GimbaldVideoOverlay($('video-overlay')),
    points: [], // [{name, label, x, y}] from `project`
    projecting: false,
    projectedAt: 0,
    lastClick: null, // the last click on the picture: {x, y, stare, reply}
    lastTrack: null, // the last `track` sent from the picture: {request, reply}
    located: {}, // gimbal name -> the ground point the last picture click located
    layout: 'side',
    zoomSentAt: 0,
  };
  window.gimbaldVideo = video.panel;

  // ---- formatting ----------------------------------------------------------------------
  const num = (v, d) => (typeof v === 'number' && Number.isFinite(v) ? v.toFixed(d) : '-');
  const latlon = (q) => (q && Number.isFinite(q.lat) ? `${q.lat.toFixed(6)}, ${q.lon.toFixed(6)}` : '-');
  const text = (id, s) => { $(id).textContent = s; };
  function setBadge(node, label, cls) {
    node.textContent = label;
    node.className = 'badge ' + cls;
  }

  // ---- what to draw for a gimbal -------------------------------------------------------
  // What STATE holds, whatever the protocol: `telemetry` (position, heading = mount yaw,
  // target, footprint), else the UAV and target a gimbal reports in `output`, else the
  // vehicle feed's position.
  function viewOf(name) {
    const s = app.states[name];
    if (!s) return null;
    const t = s.telemetry;
    const out = s.output;
    const veh = s.vehicle;
    const vpos = veh && veh.position;
    const vyaw = veh && veh.attitude ? veh.attitude.yaw : veh && Number.isFinite(veh.heading) ? veh.heading : undefined;
    let aircraft = null;
    let target = null;
    let footprint = null;
    let uav = null;
    let alt = null;
    if (t && Number.isFinite(t.lat)) {
      aircraft = { lat: t.lat, lon: t.lon, heading: Number.isFinite(t.yaw) ? t.yaw : vyaw };
      alt = t.alt;
      target = t.target || null;
      footprint = t.footprint || null;
    } else if (out && out.uav && Number.isFinite(out.uav.lat)) {
      aircraft = { lat: out.uav.lat, lon: out.uav.lon, heading: Number.isFinite(out.uav.yaw) ? out.uav.yaw : vyaw };
      alt = out.uav.alt_msl;
    } else if (vpos && Number.isFinite(vpos.lat)) {
      aircraft = { lat: vpos.lat, lon: vpos.lon, heading: vyaw };
      alt = vpos.alt_msl;
    }
    if (out) {
      // An `output` target at 0,0 means "no target".
      if (out.target && Number.isFinite(out.target.lat) && (out.target.lat !== 0 || out.target.lon !== 0)) {
        target = target || out.target;
      }
      if (out.uav && Number.isFinite(out.uav.lat) && aircraft && (out.uav.lat !== aircraft.lat || out.uav.lon !== aircraft.lon)) {
        uav = out.uav;
      }
    }
    return {
      gimbal: name,
      time_ms: t ? t.system_time_ms : null,
      aircraft, alt, target, footprint, uav,
      track: app.tracks[name] || [],
      click: app.clicks[name] || null,
      object: app.objects.view(name, s.track),
    };
  }

  function render() {
    const view = app.selected ? viewOf(app.selected) : null;
    layoutVideo();
    map.render(view);
    publishHook();
    renderPanels(view);
    renderMapAlert();
  }

  // A plan view that is not live must not look live: say why over the map.
  function renderMapAlert() {
    const s = app.selected && app.states[app.selected];
    const streamUp = app.socket && app.socket.readyState === 1;
    let msg = '';
    if (!streamUp) msg = 'NO LIVE DATA - reconnecting to gimbald';
    else if (s && s.link && !s.link.connected) msg = 'GIMBAL LINK DOWN - last known position';
    else if (s && s.stale) msg = 'TELEMETRY STALE - last known position';
    const node = $('map-alert');
    node.textContent = msg;
    node.hidden = !msg;
    $('map-pane').classList.toggle('alert', !!msg);
  }

  // ---- test hook -----------------------------------------------------------------------
  function publishHook() {
    const p = map.projection;
    window.gimbaldConsole = {
      selected: app.selected,
      info: app.info,
      stream: app.socket && app.socket.readyState === 1 ? 'open' : 'closed',
      projection: p && { lat0: p.lat0, lon0: p.lon0, cx: p.cx, cy: p.cy, px_per_m: p.px_per_m,
        m_per_deg_lat: p.m_per_deg_lat, m_per_deg_lon: p.m_per_deg_lon },
      drawn: map.drawn,
      lastClick: app.lastClick,
      video: { shown: !$('video-pane').hidden, layout: video.layout, overlay: video.overlay.drawn,
        points: video.points, lastClick: video.lastClick, located: video.located[app.selected] || null,
        lastTrack: video.lastTrack },
      toScreen: (lat, lon) => map.projection && map.projection.toScreen(lat, lon),
      toLatLon: (x, y) => map.projection && map.projection.toLatLon(x, y),
    };
  }

  // ---- side panels ---------------------------------------------------------------------
  // The commands the gimbal takes (STATE `capabilities.commands`): which controls to show.
  function takes(s, cmd) {
    const caps = s && s.capabilities;
    return !!(caps && Array.isArray(caps.commands) && caps.commands.includes(cmd));
  }

  function renderPanels(view) {
    const s = app.selected && app.states[app.selected];
    const proto = s ? s.protocol : app.info && (app.info.gimbals.find((g) => g.name === app.selected) || {}).protocol;
    setBadge($('protocol'), proto || '-', 'neutral');
    $('viewpro-panel').hidden = !(s && s.output);
    $('pointing-controls').hidden = !(takes(s, 'position') || takes(s, 'rate') || takes(s, 'camera_zoom'));
    $('position-form').hidden = !takes(s, 'position');
    $('rate-controls').hidden = !takes(s, 'rate');
    $('zoom-form').hidden = !takes(s, 'camera_zoom');
    $('shift-controls').hidden = !takes(s, 'viewpro_adjust');
    $('map-hint').textContent = !s || takes(s, 'geopoint') ? 'click the map: geopoint' : 'geopoint: not a command of this gimbal';
    $('video-hint').textContent = videoHint(s);
    if (!s) return;
    const t = s.telemetry;
    const out = s.output;
    const link = s.link || {};
    text('mode', t ? String(t.mode) : out ? 'output ' + (out.format || '') : '-');
    setBadge($('link'), link.connected ? 'connected' : 'down', link.connected ? 'good' : 'bad');
    text('endpoint', link.type === 'sim' ? 'in-process simulator' : `${link.type || '?'} ${link.endpoint || ''}`);
    const src = t || out;
    text('telemetry-age', src && Number.isFinite(src.age_s) ? src.age_s.toFixed(2) + ' s' : 'none');
    setBadge($('stale'), s.stale ? 'STALE' : 'fresh', s.stale ? 'bad' : 'good');
    updateStateAge();

    if (view && view.aircraft) {
      text('aircraft-pos', latlon(view.aircraft));
      text('aircraft-alt', t ? `${num(t.alt, 1)} m WGS84 (${num(t.alt_msl, 1)} MSL)` : view.alt != null ? num(view.alt, 1) + ' m MSL' : '-');
      text('heading', num(view.aircraft.heading, 1) + '\u00b0');
    } else {
      text('aircraft-pos', 'no position');
      text('aircraft-alt', '-');
      text('heading', '-');
    }
    text('pan-tilt', t ? `${num(t.pan, 1)}\u00b0 / ${num(t.tilt, 1)}\u00b0` : '-');
    text('fov', t ? `${num(t.hfov, 2)}\u00b0 / ${num(t.vfov, 2)}\u00b0` : '-');
    if (view && view.target) {
      text('target-pos', latlon(view.target) + (Number.isFinite(view.target.alt) ? ` @ ${num(view.target.alt, 1)} m` : ''));
      text('target-range', view.aircraft ? num(Geo.groundDistance(view.aircraft.lat, view.aircraft.lon, view.target.lat, view.target.lon), 0) + ' m' : '-');
    } else {
      text('target-pos', 'none');
      text('target-range', '-');
    }

    if (out) {
      text('vp-format', String(out.format || '-'));
      text('vp-uav', out.uav ? latlon(out.uav) + (Number.isFinite(out.uav.alt_msl) ? ` @ ${num(out.uav.alt_msl, 1)} m MSL` : '') : '-');
      text('vp-uav-att', out.uav ? `r ${num(out.uav.roll, 1)} p ${num(out.uav.pitch, 1)} y ${num(out.uav.yaw, 1)}` : '-');
      text('vp-target', out.target ? latlon(out.target) + (Number.isFinite(out.target.alt_msl) ? ` @ ${num(out.target.alt_msl, 1)} m MSL` : '') : '-');
      text('vp-gimbal', out.gimbal ? `${num(out.gimbal.roll, 1)} / ${num(out.gimbal.pitch, 1)} / ${num(out.gimbal.yaw, 1)}` : '-');
      text('vp-lrf', `${num(out.lrf_m, 1)} m / ${out.zoom != null ? out.zoom : '-'}`);
    }
    renderLasers(s);
  }

  function updateStateAge() {
    const at = app.received[app.selected];
    const node = $('state-age');
    if (!at) { node.textContent = '-'; return; }
    const age = (Date.now() - at) / 1000;
    setBadge(node, age.toFixed(1) + ' s ago', age > 3 ? 'bad' : 'good');
  }

  function renderLasers(s) {
    const box = $('lasers');
    const lasers = Array.isArray(s.lasers) ? s.lasers : null;
    if (!lasers || lasers.length === 0) {
      box.textContent = takes(s, 'laser') ? 'no laser state' : 'not reported by this protocol';
      box.className = 'dim';
      return;
    }
    box.className = '';
    box.replaceChildren(...lasers.map((l, i) => {
      const row = document.createElement('div');
      row.className = 'laser-row';
      const firing = !!l.active; // "active": emitting
      const flags = [['enabled', 'enabled'], ['armed', 'armed'], ['active', 'FIRING']]
        .filter(([k]) => l[k]).map(([, label]) => label).join(' ') || 'off';
      const locks = Object.keys(l).filter((k) => k.endsWith('_lock') && l[k] === true);
      row.innerHTML = '';
      const name = document.createElement('span');
      name.textContent = `${i} ${l.type != null ? l.type : ''}`;
      const st = document.createElement('span');
      st.className = 'badge ' + (firing ? 'bad blink' : l.armed ? 'warn' : 'neutral');
      st.textContent = flags;
      row.append(name, st);
      if (locks.length) {
        const lk = document.createElement('span');
        lk.className = 'dim';
        lk.textContent = ' locks: ' + locks.map((k) => k.replace(/_lock$/, '')).join(', ');
        row.append(lk);
      }
      return row;
    }));
  }

  // ---- laser controls (only when /api/console says laser_allow_fire) ---------------------
  // Two deliberate steps: tick "arm", then press FIRE, then press CONFIRM within 5 s.
  function buildLaserControls() {
    const box = $('laser-controls');
    box.replaceChildren();
    if (!app.info || app.info.laser_allow_fire !== true) { box.hidden = true; return; }
    box.hidden = false;
    for (const index of [0, 1]) {
      const row = document.createElement('div');
      row.className = 'row laser-fire';
      const armLabel = document.createElement('label');
      const arm = document.createElement('input');
      arm.type = 'checkbox';
      arm.id = `laser-arm-${index}`;
      armLabel.append(arm, ` arm laser ${index}`);
      const fire = document.createElement('button');
      fire.id = `laser-fire-${index}`;
      fire.className = 'danger';
      fire.disabled = true;
      fire.textContent = `FIRE ${index}`;
      const cease = document.createElement('button');
      cease.textContent = 'cease';
      cease.id = `laser-cease-${index}`;
      let confirmUntil = 0;
      let timer = null;
      const reset = () => {
        confirmUntil = 0;
        clearInterval(timer);
        fire.textContent = `FIRE ${index}`;
        fire.classList.remove('confirm');
        fire.disabled = !arm.checked;
      };
      arm.addEventListener('change', reset);
      fire.addEventListener('click', () => {
        if (!arm.checked) return;
        if (Date.now() < confirmUntil) {
          reset();
          arm.checked = false;
          fire.disabled = true;
          sendCommand({ cmd: 'laser', index, enable: true, arm: true, fire: true });
          return;
        }
        confirmUntil = Date.now() + LASER_CONFIRM_S * 1000;
        fire.classList.add('confirm');
        const tick = () => {
          const left = Math.ceil((confirmUntil - Date.now()) / 1000);
          if (left <= 0) reset(); else fire.textContent = `CONFIRM FIRE ${index} (${left} s)`;
        };
        tick();
        timer = setInterval(tick, 250);
      });
      cease.addEventListener('click', () => {
        reset();
        sendCommand({ cmd: 'laser', index, enable: true, arm: false, fire: false });
      });
      row.append(armLabel, fire, cease);
      box.append(row);
    }
  }

  // ---- events --------------------------------------------------------------------------
  function addEvent(msg) {
    const { type, gimbal, event, ...rest } = msg;
    app.events.unshift({ at: new Date(), gimbal, event, detail: rest });
    app.events.length = Math.min(app.events.length, MAX_EVENTS);
    renderEvents();
  }
  function renderEvents() {
    const list = $('events');
    const shown = app.events.filter((e) => !e.gimbal || e.gimbal === app.selected);
    list.replaceChildren(...shown.map((e) => {
      const li = document.createElement('li');
      const time = document.createElement('span');
      time.className = 'dim';
      time.textContent = e.at.toISOString().slice(11, 19) + ' ';
      const kind = document.createElement('b');
      kind.textContent = e.event;
      const detail = document.createElement('span');
      detail.textContent = ' ' + JSON.stringify(e.detail);
      li.className = 'ev-' + e.event;
      li.append(time, kind, detail);
      return li;
    }));
  }

  // ---- state intake --------------------------------------------------------------------
  function takeState(name, state) {
    app.states[name] = state;
    app.received[name] = Date.now();
    app.objects.take(name, state.track);
    const view = viewOf(name);
    if (view && view.aircraft) {
      const track = (app.tracks[name] = app.tracks[name] || []);
      const now = Date.now();
      const last = track[track.length - 1];
      if (!last || last.lat !== view.aircraft.lat || last.lon !== view.aircraft.lon) {
        track.push({ t: now, lat: view.aircraft.lat, lon: view.aircraft.lon });
      }
      while (track.length && track[0].t < now - TRACK_SECONDS * 1000) track.shift();
    }
    const tgt = state.telemetry && state.telemetry.target;
    if (tgt && Number.isFinite(tgt.alt)) app.groundAlt[name] = tgt.alt;
    if (!app.selected) selectGimbal(name);
    else if (name === app.selected) render();
  }

  function selectGimbal(name) {
    app.selected = name;
    const sel = $('gimbal-select');
    if (![...sel.options].some((o) => o.value === name)) {
      const o = document.createElement('option');
      o.value = o.textContent = name;
      sel.append(o);
    }
    sel.value = name;
    map.fitted = false;
    renderEvents();
    render();
  }

  // ---- WebSocket with reconnect --------------------------------------------------------
  function connect() {
    // Relative to the page, so the console also works behind a reverse proxy under a prefix.
    const url = new URL('api/stream', location.href);
    url.protocol = location.protocol === 'https:' ? 'wss:' : 'ws:';
    let socket;
    try { socket = new WebSocket(url); } catch (e) { scheduleReconnect(); return; }
    app.socket = socket;
    setBadge($('stream-status'), 'connecting', 'warn');
    socket.onopen = () => {
      app.reconnectDelay = 1000;
      setBadge($('stream-status'), 'live', 'good');
      publishHook();
      renderMapAlert();
    };
    socket.onmessage = (ev) => {
      let msg;
      try { msg = JSON.parse(ev.data); } catch (e) { return; }
      if (msg.type === 'state' && msg.gimbal && msg.state) takeState(msg.gimbal, msg.state);
      else if (msg.type === 'event') addEvent(msg);
    };
    socket.onclose = () => {
      if (app.socket !== socket) return;
      setBadge($('stream-status'), 'reconnecting', 'bad');
      publishHook();
      renderMapAlert();
      scheduleReconnect();
    };
    socket.onerror = () => { /* onclose follows */ };
  }
  function scheduleReconnect() {
    const delay = app.reconnectDelay;
    app.reconnectDelay = Math.min(10000, app.reconnectDelay * 2);
    setTimeout(() => { loadInfo(); connect(); }, delay);
  }

  async function getJson(path) {
    const r = await fetch(path, { cache: 'no-store' });
    if (!r.ok) throw new Error(`${path}: HTTP ${r.status}`);
    return r.json();
  }

  async function loadInfo() {
    try {
      const info = await getJson('api/console');
      // A restarted daemon may have another laser.allow_fire: rebuild the controls then.
      const lasersChanged = !app.info || app.info.laser_allow_fire !== info.laser_allow_fire;
      app.info = info;
      text('daemon-version', 'gimbald ' + (info.version || '?'));
      map.tilesUrl = typeof info.tiles_url === 'string' && info.tiles_url ? info.tiles_url : null;
      const sel = $('gimbal-select');
      for (const g of info.gimbals || []) {
        if (![...sel.options].some((o) => o.value === g.name)) {
          const o = document.createElement('option');
          o.value = g.name;
          o.textContent = `${g.name} (${g.protocol})`;
          sel.append(o);
        }
      }
      if (lasersChanged) buildLaserControls();
      if (!app.selected && info.gimbals && info.gimbals.length) selectGimbal(info.gimbals[0].name);
      const st = await getJson('api/state');
      for (const [name, state] of Object.entries(st.gimbals || {})) {
        if (!app.received[name]) takeState(name, state);
      }
    } catch (e) {
      showBanner('cannot reach gimbald: ' + e.message, 'bad');
      return;
    }
    hideBanner('bad-conn');
  }

  // ---- commands ------------------------------------------------------------------------
  function showBanner(message, kind, tag) {
    const b = $('banner');
    b.textContent = message;
    b.className = 'banner ' + kind;
    b.dataset.tag = tag || 'bad-conn';
    b.hidden = false;
  }
  function hideBanner(tag) {
    const b = $('banner');
    if (b.dataset.tag === tag) b.hidden = true;
  }

  async function sendCommand(request) {
    if (!app.selected) return null;
    const body = Object.assign({ gimbal: app.selected }, request);
    const box = $('last-command');
    box.className = 'reply';
    box.textContent = '\u2192 ' + JSON.stringify(body) + '\n  \u2026';
    let reply;
    try {
      const r = await fetch('api/command', {
        method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify(body),
      });
      const raw = await r.text();
      try { reply = JSON.parse(raw); } catch (e) { reply = { ok: false, error: { code: 'http_' + r.status, message: raw.slice(0, 200) } }; }
      if (!r.ok && reply.ok !== false) reply = { ok: false, error: { code: 'http_' + r.status, message: raw.slice(0, 200) } };
    } catch (e) {
      reply = { ok: false, error: { code: 'network', message: String(e.message || e) } };
    }
    box.className = 'reply ' + (reply.ok ? 'ok' : 'err');
    box.textContent = '\u2192 ' + JSON.stringify(body) + '\n\u2190 ' + JSON.stringify(reply);
    if (!reply.ok && reply.error && reply.error.code === 'forbidden') {
      showBanner(`forbidden: ${reply.error.message}. The console holds no token and no signing key ` +
        '(command.token, command.auth "signed"): command this daemon with gimbalctl. Watching still works.',
      'bad', 'forbidden');
    } else if (reply.ok) {
      hideBanner('forbidden');
    }
    app.lastReply = reply;
    return reply;
  }

  // ---- map interaction -----------------------------------------------------------------
  function svgPoint(ev) {
    const r = $('map').getBoundingClientRect();
    return { x: ev.clientX - r.left, y: ev.clientY - r.top };
  }

  $('map').addEventListener('click', (ev) => {
    const p = map.projection;
    if (!p || !app.selected) return;
    const s = app.states[app.selected];
    const q = svgPoint(ev);
    const ll = p.toLatLon(q.x, q.y);
    const t = s && s.telemetry;
    // Without terrain the click is on the flat world: the target's altitude, else a guess.
    let alt;
    let altFrom;
    if (t && t.target && Number.isFinite(t.target.alt)) { alt = t.target.alt; altFrom = 'target'; }
    else if (Number.isFinite(app.groundAlt[app.selected])) { alt = app.groundAlt[app.selected]; altFrom = 'last target'; }
    else if (t && Number.isFinite(t.alt)) { alt = t.alt - FALLBACK_BELOW_AIRCRAFT_M; altFrom = `aircraft - ${FALLBACK_BELOW_AIRCRAFT_M} m`; }
    else { alt = 0; altFrom = 'ellipsoid'; }
    const lat = Number(ll.lat.toFixed(7));
    const lon = Number(ll.lon.toFixed(7));
    alt = Number(alt.toFixed(2));
    // With terrain (contract section 15) gimbald takes the ground's height there itself.
    const onTerrain = !!(app.info && app.info.terrain);
    const flatFrom = altFrom;
    if (onTerrain) altFrom = 'terrain';
    app.lastClick = { gimbal: app.selected, x: q.x, y: q.y, lat, lon, alt: onTerrain ? null : alt, alt_from: altFrom,
      centre: { lat: p.lat0, lon: p.lon0, system_time_ms: map.drawn && map.drawn.system_time_ms },
      px_per_m: p.px_per_m, cx: p.cx, cy: p.cy };
    publishHook();
    if (s && !takes(s, 'geopoint')) {
      const box = $('last-command');
      box.className = 'reply err';
      box.textContent = `geopoint is not a command of ${s.protocol} gimbals (an Orion command); this gimbal points by itself`;
      return;
    }
    app.clicks[app.selected] = { lat, lon };
    render();
    const click = app.lastClick;
    sendCommand(onTerrain ? { cmd: 'geopoint', lat, lon } : { cmd: 'geopoint', lat, lon, alt }).then((reply) => {
      // Outside the terrain's coverage: the flat world's altitude after all.
      if (onTerrain && reply && !reply.ok && reply.error && reply.error.code === 'unavailable') {
        click.alt = alt;
        click.alt_from = `no terrain there: ${flatFrom}`;
        return sendCommand({ cmd: 'geopoint', lat, lon, alt });
      }
      return reply;
    }).then((reply) => {
      click.reply = reply;
      publishHook();
    });
  });

  $('map').addEventListener('mousemove', (ev) => {
    const p = map.projection;
    if (!p) return;
    const q = svgPoint(ev);
    const ll = p.toLatLon(q.x, q.y);
    const d = Math.hypot(q.x - p.cx, q.y - p.cy) / p.px_per_m;
    text('cursor-readout', `${ll.lat.toFixed(6)}, ${ll.lon.toFixed(6)}  \u00b7  ${d.toFixed(0)} m from aircraft`);
  });

  $('map').addEventListener('wheel', (ev) => {
    ev.preventDefault();
    map.zoom(ev.deltaY < 0 ? 1 : -1);
    render();
  }, { passive: false });
  $('zoom-in').addEventListener('click', () => { map.zoom(1); render(); });
  $('zoom-out').addEventListener('click', () => { map.zoom(-1); render(); });
  $('zoom-fit').addEventListener('click', () => { map.fitted = false; render(); });
  window.addEventListener('resize', render);

  $('gimbal-select').addEventListener('change', (ev) => selectGimbal(ev.target.value));

  // ---- controls ------------------------------------------------------------------------
  $('position-form').addEventListener('submit', (ev) => {
    ev.preventDefault();
    sendCommand({ cmd: 'position', pan: Number($('pos-pan').value), tilt: Number($('pos-tilt').value),
      stabilized: $('pos-stab').checked });
  });
  for (const b of document.querySelectorAll('[data-rate]')) {
    b.addEventListener('click', () => {
      const [dp, dt] = b.dataset.rate.split(',').map(Number);
      const speed = Number($('rate-speed').value) || 0;
      const impulse = dp === 0 && dt === 0 ? 0 : Number($('rate-impulse').value) || 0;
      sendCommand({ cmd: 'rate', pan: dp * speed, tilt: dt * speed, impulse_time_s: impulse });
    });
  }
  const zoomInput = $('cam-zoom');
  $('zoom-minus').addEventListener('click', () => { zoomInput.value = Math.max(1, Number(zoomInput.value) / 2); sendZoom(); });
  $('zoom-plus').addEventListener('click', () => { zoomInput.value = Number(zoomInput.value) * 2; sendZoom(); });
  $('zoom-form').addEventListener('submit', (ev) => { ev.preventDefault(); sendZoom(); });
  function sendZoom() { sendCommand({ cmd: 'camera_zoom', zoom: Number(zoomInput.value) }); }
  for (const b of document.querySelectorAll('[data-adjust]')) {
    b.addEventListener('click', () => {
      const [key, value] = b.dataset.adjust.split(',');
      sendCommand({ cmd: 'viewpro_adjust', [key]: Number(value) });
    });
  }

  // ---- video (contract section 18) ------------------------------------------------------
  function hasVideo(name) {
    const g = app.info && (app.info.gimbals || []).find((x) => x.name === name);
    return !!(g && g.video);
  }

  // Shows the video pane when the selected gimbal has video, fits the picture into it
  // (letterboxed, its own aspect ratio) and redraws the overlay.
  function layoutVideo() {
    const shown = !!app.selected && hasVideo(app.selected);
    const pane = $('video-pane');
    pane.hidden = !shown;
    $('layout-toggle').hidden = !shown;
    video.panel.show(shown ? app.selected : null);
    if (!shown) return;
    const r = pane.getBoundingClientRect();
    const aspect = video.panel.width / video.panel.height || 16 / 9;
    let w = r.width;
    let h = w / aspect;
    if (h > r.height) { h = r.height; w = h * aspect; }
    const box = $('video-box');
    box.style.width = w + 'px';
    box.style.height = h + 'px';
    box.style.left = (r.width - w) / 2 + 'px';
    box.style.top = (r.height - h) / 2 + 'px';
    video.overlay.render(app.states[app.selected], video.points, Number($('cam-zoom').value));
    maybeProject();
  }

  function setLayout(name) {
    video.layout = LAYOUTS[name] ? name : 'side';
    $('main').className = 'layout-' + video.layout;
    $('layout-toggle').textContent = 'layout: ' + LAYOUTS[video.layout];
    try { localStorage.setItem('gimbald.layout', video.layout); } catch (e) { /* private mode */ }
    render();
  }
  $('layout-toggle').addEventListener('click', () => {
    const names = Object.keys(LAYOUTS);
    setLayout(names[(names.indexOf(video.layout) + 1) % names.length]);
  });

  // A quiet command (not shown in the command panel): the reply, or null.
  async function quietCommand(request) {
    try {
      const r = await fetch('api/command', { method: 'POST', headers: { 'Content-Type': 'application/json' },
        body: JSON.stringify(Object.assign({ gimbal: app.selected }, request)) });
      const reply = await r.json();
      return reply && reply.ok ? reply : null;
    } catch (e) { return null; }
  }

  // The plan view's points placed on the picture with `project`: the target, the track's
  // start, the last map click and the last point located by a click on the picture.
  async function maybeProject() {
    const now = Date.now();
    if (video.projecting || now - video.projectedAt < PROJECT_EVERY_MS) return;
    const s = app.states[app.selected];
    const t = s && s.telemetry;
    if (!t) return;
    const groundAlt = t.target && Number.isFinite(t.target.alt) ? t.target.alt : app.groundAlt[app.selected];
    const wanted = [];
    if (t.target) wanted.push({ name: 'target', label: 'target', lat: t.target.lat, lon: t.target.lon, alt: t.target.alt });
    const track = app.tracks[app.selected] || [];
    if (track.length > 1 && Number.isFinite(groundAlt)) wanted.push({ name: 'start', label: 'track start', lat: track[0].lat, lon: track[0].lon, alt: groundAlt });
    const c = app.clicks[app.selected];
    if (c && Number.isFinite(c.alt !== undefined ? c.alt : groundAlt)) wanted.push({ name: 'click', label: 'clicked', lat: c.lat, lon: c.lon, alt: c.alt !== undefined ? c.alt : groundAlt });
    const gimbal = app.selected;
    video.projecting = true;
    video.projectedAt = now;
    const points = [];
    for (const w of wanted) {
      const reply = await quietCommand({ cmd: 'project', lat: w.lat, lon: w.lon, alt: Number(w.alt.toFixed(2)) });
      if (reply && reply.x !== null && reply.visible !== false) points.push({ name: w.name, label: w.label, x: reply.x, y: reply.y });
    }
    video.projecting = false;
    if (gimbal !== app.selected) return;
    video.points = points;
    video.overlay.render(app.states[app.selected], video.points, Number($('cam-zoom').value));
    publishHook();
  }

  // A position on the picture in image coordinates (contract section 16: -1..1 from the
  // centre, +y down), from the page's client pixels.
  function imagePoint(clientX, clientY) {
    const r = $('video').getBoundingClientRect();
    return { x: Number((((clientX - r.left) / r.width) * 2 - 1).toFixed(5)),
      y: Number((((clientY - r.top) / r.height) * 2 - 1).toFixed(5)) };
  }

  // ---- visual tracking (contract section 20) ---------------------------------------------
  // /api/console says which gimbals' video has `tracking` configured.
  function canTrack(s) {
    const g = s && app.info && (app.info.gimbals || []).find((x) => x.name === app.selected);
    return !!(g && g.tracking);
  }
  function videoHint(s) {
    const track = !s || canTrack(s) ? 'drag a box or alt+click: track \u00b7 Esc: stop tracking'
      : 'tracking: not configured for this gimbal (video.tracking)';
    return `click: point \u00b7 shift+click: stare \u00b7 ${track} \u00b7 wheel: zoom \u00b7 arrows: rate \u00b7 space: stop`;
  }
  // `track` on a box or at a point; a refusal shows in the command panel like any other.
  async function sendTrack(request) {
    const sent = { gimbal: app.selected, request, reply: null };
    video.lastTrack = sent;
    publishHook();
    sent.reply = await sendCommand(Object.assign({ cmd: 'track' }, request));
    if (sent.reply && sent.reply.ok) takeTrack(sent.gimbal, sent.reply.track);
    publishHook();
    return sent.reply;
  }
  // A `track` or `track_stop` reply is the track as STATE shows it now: drawn (and Esc
  // works) without waiting for the next STATE.
  function takeTrack(name, track) {
    const s = app.states[name];
    if (!s || track === undefined) return;
    s.track = track;
    app.objects.take(name, track);
    if (name === app.selected) render();
  }
  async function stopTrack() {
    const gimbal = app.selected;
    const reply = await sendCommand({ cmd: 'track_stop' });
    if (reply && reply.ok) takeTrack(gimbal, null);
  }
  const trackBox = new window.GimbaldTrackBox($('video'), $('track-band'), {
    toImage: imagePoint,
    enabled: () => !!app.selected && canTrack(app.states[app.selected]),
    onBox: (box) => sendTrack(box),
  });

  // A click on the picture: `point` at that image position (shift: stare); the plan view
  // marks the ground point gimbald located. Alt+click: `track` at that point.
  $('video').addEventListener('click', async (ev) => {
    if (trackBox.swallowClick() || !app.selected) return;
    const { x, y } = imagePoint(ev.clientX, ev.clientY);
    if (ev.altKey) {
      if (canTrack(app.states[app.selected])) { sendTrack({ x, y }); return; }
      const box = $('last-command');
      box.className = 'reply err';
      box.textContent = `track: ${app.selected} has no visual tracking (its video has no \`tracking\` section)`;
      return;
    }
    const click = { gimbal: app.selected, x, y, stare: ev.shiftKey, reply: null };
    video.lastClick = click;
    publishHook();
    const reply = await sendCommand({ cmd: 'point', x, y, stare: ev.shiftKey });
    click.reply = reply;
    if (reply && reply.ok && Number.isFinite(reply.lat)) {
      video.located[click.gimbal] = { lat: reply.lat, lon: reply.lon, alt: reply.alt };
      app.clicks[click.gimbal] = { lat: reply.lat, lon: reply.lon, alt: reply.alt };
      video.projectedAt = 0;
      render();
    }
    publishHook();
  });

  function cameraZoom(up) {
    const zoomInput = $('cam-zoom');
    zoomInput.value = up ? Number(zoomInput.value) * 2 : Math.max(1, Number(zoomInput.value) / 2);
    sendCommand({ cmd: 'camera_zoom', zoom: Number(zoomInput.value) });
  }
  $('video').addEventListener('wheel', (ev) => {
    ev.preventDefault();
    // One step per notch burst: a trackpad sends dozens of small wheel events.
    if (Date.now() - video.zoomSentAt < 300) return;
    video.zoomSentAt = Date.now();
    cameraZoom(ev.deltaY < 0);
  }, { passive: false });
  $('vzoom-in').addEventListener('click', () => cameraZoom(true));
  $('vzoom-out').addEventListener('click', () => cameraZoom(false));

  // Arrows: `rate` at the control panel's speed for its impulse time; space: stop.
  const KEY_RATES = { ArrowLeft: [-1, 0], ArrowRight: [1, 0], ArrowUp: [0, 1], ArrowDown: [0, -1] };
  document.addEventListener('keydown', (ev) => {
    if (ev.target.closest && ev.target.closest('input, select, textarea')) return;
    const s = app.states[app.selected];
    // Esc: abandon a drag in progress, else stop the visual track.
    if (ev.key === 'Escape') {
      if (trackBox.cancel()) return;
      if (s && s.track) {
        ev.preventDefault();
        stopTrack();
      }
      return;
    }
    if (!takes(s, 'rate')) return;
    if (KEY_RATES[ev.key]) {
      ev.preventDefault();
      const [dp, dt] = KEY_RATES[ev.key];
      const speed = Number($('rate-speed').value) || 0;
      sendCommand({ cmd: 'rate', pan: dp * speed, tilt: dt * speed, impulse_time_s: Number($('rate-impulse').value) || 0 });
    } else if (ev.key === ' ') {
      ev.preventDefault();
      // Not also a press of the focused button.
      if (ev.target.closest && ev.target.closest('button')) ev.target.blur();
      sendCommand({ cmd: 'rate', pan: 0, tilt: 0, impulse_time_s: 0 });
    }
  });
  video.panel.onFrame = () => {
    // The picture's size is known from the first frame: fit the pane to it once.
    if (video.fittedTo !== video.panel.width + 'x' + video.panel.height) {
      video.fittedTo = video.panel.width + 'x' + video.panel.height;
      layoutVideo();
    }
  };
  let savedLayout = 'side';
  try { savedLayout = localStorage.getItem('gimbald.layout') || 'side'; } catch (e) { /* private mode */ }

  setInterval(updateStateAge, 500);
  setLayout(savedLayout);
  publishHook();
  loadInfo().then(connect);
})();
