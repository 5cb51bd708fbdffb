// lab/web/lab.js — the live lab's page: controls built from /api/techniques and /api/scenes,
// frames from /api/render and /api/error (lab/lab_server.h). No library, no network beyond
// the server that sent the page.
'use strict';

const $ = (id) => document.getElementById(id);
const kLanes = ['a', 'b'];
const kOrbitDegreesPerPixel = 0.4;   // camera drag
const kLightUnitsPerPixel = 0.01;    // light drag, times the scene's size
const kMaxZoom = 16;                 // image magnification of the wipe view
const kMaxPlotPoints = 60;           // points kept on the error/time plot
const kErrorDelayMs = 250;           // error request after a frame settles

const state = {
  techniques: [], scenes: [], byName: {},
  lanes: { a: newLane(), b: newLane() },
  orbit: null, light: null, zoom: 1, panX: 0.5, panY: 0.5,
  plot: [], frameCount: 0,
};

function newLane() {
  return { technique: null, values: {}, bitmap: null, errorBitmap: null, maskBitmap: null,
           inFlight: false, dirty: false, command: '', frameMs: null, error: null,
           errorTimer: null, errorInFlight: false, errorDirty: false };
}

function setStatus(text, isError) {
  const s = $('status');
  s.textContent = text;
  s.classList.toggle('error', !!isError);
}

async function getJson(url) {
  const r = await fetch(url);
  if (!r.ok) throw new Error(await r.text());
  return r.json();
}

function currentScene() { return state.scenes.find((s) => s.name === $('scene').value); }

// ------------------------------------------------------------------ controls

function optionControl(lane, spec) {
  // spec: {key, label, kind, min, max, step, values, default, isParam}
  const l = state.lanes[lane];
  const label = document.createElement('label');
  const name = document.createElement('span');
  name.textContent = spec.label;
  label.appendChild(name);
  let input;
  const current = l.values[spec.id] !== undefined ? l.values[spec.id] : spec.default;
  if (spec.values) {
    input = document.createElement('select');
    for (const v of spec.values) {
      const o = document.createElement('option');
      o.value = o.textContent = v;
      input.appendChild(o);
    }
    input.value = current;
  } else if (spec.kind === 'flag') {
    input = document.createElement('input');
    input.type = 'checkbox';
    input.checked = current === 'on';
  } else if (spec.kind === 'number' || spec.kind === 'integer' || spec.kind === 'pow2') {
    const span = spec.max - spec.min;
    const slider = !spec.auto && isFinite(span) && span > 0 && span <= 1e4;
    input = document.createElement('input');
    input.type = slider ? 'range' : 'number';
    if (spec.kind === 'pow2') {
      input.min = Math.log2(spec.min); input.max = Math.log2(spec.max); input.step = 1;
      input.value = Math.log2(Number(current));
    } else {
      input.min = spec.min; input.max = spec.max;
      input.step = spec.kind === 'integer' ? 1 : (slider ? span / 200 : 'any');
      input.value = current;
    }
    if (slider) {
      const shown = document.createElement('span');
      shown.className = 'value';
      shown.textContent = current;
      input.addEventListener('input', () => { shown.textContent = valueOf(spec, input); });
      label.appendChild(input);
      label.appendChild(shown);
    }
  } else {
    input = document.createElement('input');
    input.type = 'text';
    input.value = current === undefined || current === 'auto' ? '' : current;
  }
  input.dataset.option = spec.id;
  if (spec.meaning) label.title = spec.meaning;
  if (spec.auto && input.type === 'number') input.placeholder = 'auto';
  if (!label.contains(input)) label.appendChild(input);
  const changed = () => {
    const v = valueOf(spec, input);
    if (v === String(spec.default) || v === '') delete l.values[spec.id]; else l.values[spec.id] = v;
    requestFrame(lane);
  };
  input.addEventListener(input.type === 'range' ? 'input' : 'change', changed);
  return label;
}

function valueOf(spec, input) {
  if (spec.kind === 'flag') return input.checked ? 'on' : 'off';
  if (spec.kind === 'pow2') return String(2 ** Number(input.value));
  if (spec.kind === 'number' && input.type === 'range') {
    return String(Number(Number(input.value).toPrecision(4)));
  }
  return String(input.value);
}

function buildOptions(lane) {
  const l = state.lanes[lane];
  const t = state.byName[$('technique-' + lane).value];
  if (l.technique !== t.name) l.values = {};
  l.technique = t.name;
  $('paper-' + lane).textContent = t.paper + ' — ' + t.summary;
  const box = $('options-' + lane);
  box.replaceChildren();
  const d = state.defaults;
  if (t.reads['shadow-map']) {
    box.appendChild(optionControl(lane, { id: 'shadow-map', label: 'shadow map', kind: 'pow2',
      min: 16, max: state.caps['shadow-map'], default: String(d['shadow-map']) }));
  }
  if (t.reads.filter) {
    box.appendChild(optionControl(lane, { id: 'filter', label: 'filter K', kind: 'integer',
      min: 1, max: state.caps.filter, default: String(d.filter) }));
  }
  if (t.reads.precision) {
    box.appendChild(optionControl(lane, { id: 'precision', label: 'precision',
      values: ['8', '12', 'float'], default: d.precision }));
  }
  for (const p of t.params) {
    box.appendChild(optionControl(lane, { id: 'param:' + p.key, label: p.key, kind: p.kind,
      min: p.min, max: p.max, values: p.values, default: p.default, auto: p.auto, meaning: p.meaning }));
  }
}

// ------------------------------------------------------------------ requests

function query(lane, view) {
  const l = state.lanes[lane];
  const q = new URLSearchParams();
  q.append('scene', $('scene').value);
  q.append('technique', l.technique);
  q.append('size', $('size').value);
  for (const [id, v] of Object.entries(l.values)) {
    if (id.startsWith('param:')) q.append('param', id.slice(6) + '=' + v);
    else q.append(id, v);
  }
  const fmt = (x) => String(Number(x.toFixed(4)));
  q.append('light-position', state.light.map(fmt).join(','));
  q.append('orbit', state.orbit.map(fmt).join(','));
  q.append('view', view);
  return q;
}

// One request in flight per lane: a change while one is out marks the lane dirty, and only
// the latest settings are sent when it returns (the server drops stale ones too).
async function requestFrame(lane) {
  const l = state.lanes[lane];
  if (l.inFlight) { l.dirty = true; return; }
  l.inFlight = true;
  l.dirty = false;
  const mode = $('view').value;
  const view = mode === 'image' ? 'image' : 'mask';
  const q = query(lane, view);
  q.append('lane', lane);
  const started = performance.now();
  try {
    const r = await fetch('/api/render?' + q.toString());
    if (r.status === 409) return;  // superseded by a newer request
    if (!r.ok) throw new Error(await r.text());
    const bitmap = await createImageBitmap(await r.blob());
    if (view === 'image') l.bitmap = bitmap; else l.maskBitmap = bitmap;
    l.command = r.headers.get('X-Shadowlab-Command') || '';
    l.frameMs = Number(r.headers.get('X-Shadowlab-Frame-Ms'));
    l.roundTripMs = performance.now() - started;
    l.failure = null;
    state.frameCount += 1;
    document.body.dataset.frames = String(state.frameCount);
    setStatus('frame ' + state.frameCount + ': ' + l.technique + ' in ' +
              l.roundTripMs.toFixed(0) + ' ms');
    scheduleError(lane);
  } catch (e) {
    l.failure = e.message;
    setStatus(lane.toUpperCase() + ': ' + e.message, true);
  } finally {
    l.inFlight = false;
    showNumbers(lane);
    draw();
    if (l.dirty) requestFrame(lane);
  }
}

function scheduleError(lane) {
  const l = state.lanes[lane];
  clearTimeout(l.errorTimer);
  l.errorTimer = setTimeout(() => requestError(lane), kErrorDelayMs);
}

async function requestError(lane) {
  const l = state.lanes[lane];
  if (l.errorInFlight) { l.errorDirty = true; return; }
  l.errorInFlight = true;
  l.errorDirty = false;
  try {
    const q = query(lane, 'json');
    q.append('lane', 'error-' + lane);
    const r = await fetch('/api/error?' + q.toString());
    if (r.status === 409) return;
    if (!r.ok) throw new Error(await r.text());
    l.error = await r.json();
    addPlotPoint(lane, l.error);
    if ($('view').value === 'error') {
      q.set('view', 'image');
      const ri = await fetch('/api/error?' + q.toString());
      if (ri.ok) l.errorBitmap = await createImageBitmap(await ri.blob());
      draw();
    }
  } catch (e) {
    setStatus('error of ' + lane.toUpperCase() + ': ' + e.message, true);
  } finally {
    l.errorInFlight = false;
    showNumbers(lane);
    drawPlot();
    if (l.errorDirty) requestError(lane);
  }
}

function requestBoth() { for (const lane of kLanes) requestFrame(lane); }

async function loadPasses() {
  $('load-passes').disabled = true;
  try {
    const q = query('a', 'passes');
    q.append('lane', 'passes');
    const r = await fetch('/api/render?' + q.toString());
    if (!r.ok) throw new Error(await r.text());
    const doc = await r.json();
    const table = $('pass-times');
    table.replaceChildren();
    for (const t of doc.median_timings) {
      const row = table.insertRow();
      row.insertCell().textContent = t.name;
      const ms = row.insertCell();
      ms.className = 'ms';
      ms.textContent = t.median_ms.toFixed(2) + ' ms';
    }
    const total = table.insertRow();
    total.insertCell().textContent = 'frame (median of ' + doc.timing_frames + ')';
    const ms = total.insertCell();
    ms.className = 'ms';
    ms.textContent = doc.median_frame_ms.toFixed(2) + ' ms';
    const strip = $('pass-strip');
    strip.replaceChildren();
    for (const image of doc.images || []) {
      if (image.channel) continue;  // the per-channel panels stay in --dump-passes
      const fig = document.createElement('figure');
      const img = document.createElement('img');
      img.src = image.url;
      img.alt = image.caption;
      const cap = document.createElement('figcaption');
      cap.textContent = image.file + ': ' + image.caption;
      fig.append(img, cap);
      strip.appendChild(fig);
    }
    if (!(doc.images || []).length) strip.textContent = 'this technique keeps no intermediate buffer';
  } catch (e) {
    setStatus('passes: ' + e.message, true);
  } finally {
    $('load-passes').disabled = false;
  }
}

// ------------------------------------------------------------------ drawing

function laneImage(lane) {
  const l = state.lanes[lane];
  const mode = $('view').value;
  if (mode === 'image') return l.bitmap;
  if (mode === 'error') return l.errorBitmap;
  return l.maskBitmap;
}

let differenceCache = null;
function differenceImage() {
  const a = state.lanes.a.maskBitmap, b = state.lanes.b.maskBitmap;
  if (!a || !b || a.width !== b.width || a.height !== b.height) return null;
  if (differenceCache && differenceCache.a === a && differenceCache.b === b) {
    return differenceCache.canvas;
  }
  const c = document.createElement('canvas');
  c.width = a.width; c.height = a.height;
  const g = c.getContext('2d', { willReadFrequently: true });
  g.drawImage(a, 0, 0);
  const da = g.getImageData(0, 0, c.width, c.height);
  g.drawImage(b, 0, 0);
  const db = g.getImageData(0, 0, c.width, c.height);
  for (let i = 0; i < da.data.length; i += 4) {
    const d = Math.abs(da.data[i] - db.data[i]) / 255;  // heat: black, red, yellow, white
    da.data[i] = Math.min(255, 3 * d * 255);
    da.data[i + 1] = Math.min(255, Math.max(0, 3 * d - 1) * 255);
    da.data[i + 2] = Math.min(255, Math.max(0, 3 * d - 2) * 255);
  }
  g.putImageData(da, 0, 0);
  differenceCache = { a, b, canvas: c };
  return c;
}

function draw() {
  const canvas = $('canvas');
  const [w, h] = $('size').value.split('x').map(Number);
  if (canvas.width !== w || canvas.height !== h) { canvas.width = w; canvas.height = h; }
  const g = canvas.getContext('2d');
  g.imageSmoothingEnabled = false;
  g.fillStyle = '#000';
  g.fillRect(0, 0, w, h);
  const z = state.zoom;
  const sx = state.panX * w - w / (2 * z), sy = state.panY * h - h / (2 * z);
  const blit = (img, x0, x1) => {
    if (!img) return;
    g.save();
    g.beginPath();
    g.rect(x0, 0, x1 - x0, h);
    g.clip();
    g.setTransform(z, 0, 0, z, -sx * z, -sy * z);
    g.drawImage(img, 0, 0, w, h);
    g.restore();
  };
  if ($('view').value === 'difference') {
    blit(differenceImage(), 0, w);
    $('tag-a').textContent = '|A − B|';
    $('tag-b').hidden = true;
    return;
  }
  $('tag-a').textContent = 'A ' + (state.lanes.a.technique || '');
  $('tag-b').textContent = 'B ' + (state.lanes.b.technique || '');
  $('tag-b').hidden = false;
  const split = Math.round(w * $('wipe').value / 100);
  blit(laneImage('a'), 0, split);
  blit(laneImage('b'), split, w);
  g.strokeStyle = '#fff';
  g.beginPath();
  g.moveTo(split + 0.5, 0);
  g.lineTo(split + 0.5, h);
  g.stroke();
}

function showNumbers(lane) {
  const l = state.lanes[lane];
  const dl = $('numbers-' + lane);
  dl.replaceChildren();
  const add = (k, v) => {
    const dt = document.createElement('dt'); dt.textContent = k;
    const dd = document.createElement('dd'); dd.textContent = v;
    dl.append(dt, dd);
  };
  add('technique', l.technique || '');
  if (l.frameMs !== null) add('frame (GL passes)', l.frameMs.toFixed(1) + ' ms');
  if (l.roundTripMs) add('request round trip', l.roundTripMs.toFixed(0) + ' ms');
  if (l.error) {
    add('RMSE (' + l.error.metric + ' metric)', l.error.rmse.toFixed(4));
    add('truth', l.error.truth);
    add('max |error|', l.error.max_abs.toFixed(3));
    add('scored pixels off by > 0.5', (100 * l.error.share_above_half).toFixed(2) + ' %');
    add('not scored (grey in the error view)', (100 * l.error.left_out.share).toFixed(1) + ' %');
  }
  if (l.failure) add('failed', l.failure);
  $('command-' + lane).textContent = l.command;
}

function addPlotPoint(lane, e) {
  state.plot.push({ lane, ms: e.frame_ms, rmse: e.rmse, technique: e.technique });
  if (state.plot.length > kMaxPlotPoints) state.plot.shift();
}

function drawPlot() {
  const svg = $('plot');
  const ns = 'http://www.w3.org/2000/svg';
  svg.replaceChildren();
  const W = 360, H = 220, L = 48, B = 30, T = 8, R = 16;
  const pts = state.plot;
  const maxMs = Math.max(1, ...pts.map((p) => p.ms)) * 1.1;
  const maxE = Math.max(0.01, ...pts.map((p) => p.rmse)) * 1.1;
  const X = (ms) => L + (W - L - R) * ms / maxMs;
  const Y = (e) => H - B - (H - B - T) * e / maxE;
  const el = (name, attrs, text) => {
    const n = document.createElementNS(ns, name);
    for (const [k, v] of Object.entries(attrs)) n.setAttribute(k, v);
    if (text !== undefined) n.textContent = text;
    svg.appendChild(n);
    return n;
  };
  el('line', { x1: L, y1: H - B, x2: W - R, y2: H - B, stroke: '#888' });
  el('line', { x1: L, y1: T, x2: L, y2: H - B, stroke: '#888' });
  el('text', { x: (L + W) / 2, y: H - 6, 'text-anchor': 'middle', 'font-size': 11 },
     'frame time (ms)');
  el('text', { x: 12, y: (H - B) / 2, 'font-size': 11, transform: `rotate(-90 12 ${(H - B) / 2})`,
               'text-anchor': 'middle' }, 'RMSE');
  for (const f of [0, 0.5, 1]) {
    el('text', { x: X(f * maxMs), y: H - B + 12, 'font-size': 9,
                 'text-anchor': f === 1 ? 'end' : 'middle' },
       (f * maxMs).toFixed(0));
    el('text', { x: L - 4, y: Y(f * maxE) + 3, 'font-size': 9, 'text-anchor': 'end' },
       (f * maxE).toFixed(3));
  }
  pts.forEach((p, i) => {
    el('circle', { cx: X(p.ms), cy: Y(p.rmse), r: 2.5, fill: p.lane === 'a' ? '#1f77b4' : '#d62728',
                   opacity: 0.35 + 0.65 * (i + 1) / pts.length });
  });
  for (const lane of kLanes) {
    const e = state.lanes[lane].error;
    if (!e) continue;
    el('circle', { cx: X(e.frame_ms), cy: Y(e.rmse), r: 6, fill: 'none', 'stroke-width': 2,
                   stroke: lane === 'a' ? '#1f77b4' : '#d62728' });
  }
}

function showPose() {
  const f = (v) => v.map((x) => x.toFixed(2)).join(', ');
  $('pose').textContent = 'light ' + f(state.light) + ' · orbit ' + f(state.orbit);
}

// ------------------------------------------------------------------ interaction

function resetView() {
  const s = currentScene();
  state.orbit = s.orbit.slice();
  state.light = s.light.slice();
  state.zoom = 1; state.panX = 0.5; state.panY = 0.5;
  showPose();
}

function sceneSize() {
  const b = currentScene().bounds;
  return Math.max(1e-3, Math.hypot(b[1][0] - b[0][0], b[1][1] - b[0][1], b[1][2] - b[0][2]));
}

function installDragging() {
  const canvas = $('canvas');
  let drag = null;
  canvas.addEventListener('pointerdown', (e) => {
    drag = { x: e.clientX, y: e.clientY, light: e.shiftKey };
    canvas.setPointerCapture(e.pointerId);
  });
  canvas.addEventListener('pointermove', (e) => {
    if (!drag) return;
    const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
    drag.x = e.clientX; drag.y = e.clientY;
    if (drag.light) {
      // Moves the light in the ground plane, in the camera's azimuth frame (screen right/up).
      const az = state.orbit[0] * Math.PI / 180;
      const k = kLightUnitsPerPixel * sceneSize();
      state.light[0] += k * (dx * Math.cos(az) - dy * Math.sin(az));
      state.light[2] += k * (-dx * Math.sin(az) - dy * Math.cos(az));
    } else {
      state.orbit[0] = ((state.orbit[0] - dx * kOrbitDegreesPerPixel + 540) % 360) - 180;
      state.orbit[1] = Math.max(-89, Math.min(89, state.orbit[1] + dy * kOrbitDegreesPerPixel));
    }
    showPose();
    requestBoth();
  });
  const end = () => { drag = null; };
  canvas.addEventListener('pointerup', end);
  canvas.addEventListener('pointercancel', end);
  canvas.addEventListener('wheel', (e) => {
    e.preventDefault();
    const r = canvas.getBoundingClientRect();
    const fx = (e.clientX - r.left) / r.width, fy = (e.clientY - r.top) / r.height;
    const before = state.zoom;
    state.zoom = Math.max(1, Math.min(kMaxZoom, state.zoom * (e.deltaY < 0 ? 1.25 : 0.8)));
    // Keep the point under the cursor where it is.
    const px = state.panX + (fx - 0.5) / before, py = state.panY + (fy - 0.5) / before;
    state.panX = px - (fx - 0.5) / state.zoom;
    state.panY = py - (fy - 0.5) / state.zoom;
    if (state.zoom === 1) { state.panX = 0.5; state.panY = 0.5; }
    draw();
  }, { passive: false });
}

function fillSelect(select, names, chosen) {
  select.replaceChildren();
  for (const n of names) {
    const o = document.createElement('option');
    o.value = o.textContent = n;
    select.appendChild(o);
  }
  select.value = chosen;
}

async function main() {
  try {
    const [t, s] = await Promise.all([getJson('/api/techniques'), getJson('/api/scenes')]);
    state.techniques = t.techniques;
    state.defaults = t.defaults;
    state.caps = t.caps;
    for (const x of t.techniques) state.byName[x.name] = x;
    state.scenes = s.scenes.filter((x) => !x.error);
    const names = t.techniques.map((x) => x.name);
    fillSelect($('scene'), state.scenes.map((x) => x.name), s.default);
    fillSelect($('technique-a'), names, names.includes('legacy.hw') ? 'legacy.hw' : names[0]);
    fillSelect($('technique-b'), names, names.includes('modern.gems16') ? 'modern.gems16' : names[1]);
  } catch (e) {
    setStatus('cannot load the lab: ' + e.message, true);
    return;
  }
  resetView();
  for (const lane of kLanes) {
    buildOptions(lane);
    $('technique-' + lane).addEventListener('change', () => { buildOptions(lane); requestFrame(lane); });
  }
  $('scene').addEventListener('change', () => { resetView(); requestBoth(); });
  $('size').addEventListener('change', requestBoth);
  $('view').addEventListener('change', () => {
    draw();
    requestBoth();
    if ($('view').value === 'error') for (const lane of kLanes) requestError(lane);
  });
  $('wipe').addEventListener('input', draw);
  $('reset-view').addEventListener('click', () => { resetView(); requestBoth(); });
  $('load-passes').addEventListener('click', loadPasses);
  installDragging();
  draw();
  drawPlot();
  requestBoth();
}

main();
