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
const kLinearSliderSteps = 1000;     // positions of a linear parameter slider
const kLogSliderSteps = 500;         // positions of a logarithmic slider on each side of 0
const kLogSliderSpan = 50;           // a range wider than this (and holding 0) is logarithmic

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
    // Wide ranges get a slider only where it is logarithmic (sliderScale); a wide integer range
    // (rays 4..16384) stays a number field.
    const holdsZero = spec.kind === 'number' && spec.min <= 0 && spec.max >= 0;
    const slider = !spec.auto && isFinite(span) && span > 0 && (span <= 1e4 || holdsZero);
    spec.scale = sliderScale(spec, slider);
    input = document.createElement('input');
    input.type = slider ? 'range' : 'number';
    if (spec.kind === 'pow2') {
      input.min = Math.log2(spec.min); input.max = Math.log2(spec.max); input.step = 1;
    } else if (spec.scale === 'log') {
      input.min = spec.min < 0 ? -kLogSliderSteps : 0;
      input.max = spec.max > 0 ? kLogSliderSteps : 0;
      input.step = 1;
    } else {
      input.min = spec.min; input.max = spec.max;
      input.step = spec.kind === 'integer' ? 1 : (slider ? span / kLinearSliderSteps : 'any');
    }
    setSliderValue(spec, input, current);
    if (slider) {
      // The exact value, editable: typing moves the slider, the slider rewrites the box.
      const box = document.createElement('input');
      box.type = 'number';
      box.className = 'value';
      box.step = 'any';
      box.value = current;
      box.dataset.valueOf = spec.id;
      input.addEventListener('input', () => { box.value = valueOf(spec, input); });
      box.addEventListener('change', () => {
        if (box.value === '' || !isFinite(Number(box.value))) { box.value = valueOf(spec, input); return; }
        setSliderValue(spec, input, box.value);
        setValue(l, spec, String(box.value));
        requestFrame(lane);
      });
      label.appendChild(input);
      label.appendChild(box);
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
    setValue(l, spec, valueOf(spec, input));
    requestFrame(lane);
  };
  input.addEventListener(input.type === 'range' ? 'input' : 'change', changed);
  return label;
}

function setValue(l, spec, v) {
  if (v === String(spec.default) || v === '') delete l.values[spec.id]; else l.values[spec.id] = v;
}

// A number whose range holds 0 and spans more than kLogSliderSpan (polygon offset factor
// -100..100, units -1e6..1e6, depth bias 0..255) gets a signed logarithmic slider: steps of
// about 0.01 near 0, where acne appears, and still the whole range at the ends.
function sliderScale(spec, slider) {
  if (!slider || spec.kind !== 'number') return 'linear';
  return spec.min <= 0 && spec.max >= 0 && spec.max - spec.min > kLogSliderSpan ? 'log' : 'linear';
}

function logRange(spec) { return Math.log1p(Math.max(Math.abs(spec.min), Math.abs(spec.max))); }

function setSliderValue(spec, input, value) {
  const v = Number(value);
  if (spec.kind === 'pow2') input.value = Math.log2(v);
  else if (spec.scale === 'log') input.value = Math.sign(v) * Math.round(kLogSliderSteps * Math.log1p(Math.abs(v)) / logRange(spec));
  else input.value = value;
}

function valueOf(spec, input) {
  if (spec.kind === 'flag') return input.checked ? 'on' : 'off';
  if (spec.kind === 'pow2') return String(2 ** Number(input.value));
  if (spec.scale === 'log' && input.type === 'range') {
    const p = Number(input.value);
    const v = Math.sign(p) * Math.expm1(Math.abs(p) / kLogSliderSteps * logRange(spec));
    return String(Number(Math.min(spec.max, Math.max(spec.min, v)).toPrecision(3)));
  }
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
  // The scene's own light and camera are left out, as `shadowlab render` leaves them out.
  if (!samePose(state.light, currentScene().light)) q.append('light-position', poseText(state.light));
  if (!samePose(state.orbit, currentScene().orbit)) q.append('orbit', poseText(state.orbit));
  q.append('view', view);
  return q;
}

const poseText = (v) => v.map((x) => String(Number(x.toFixed(4)))).join(',');
const samePose = (v, scene) => poseText(v) === poseText(scene);

// ------------------------------------------------------------------ the page's URL
//
// The whole state of the page lives in its query, so that any view can be shared as a link
// (docs/lab.md "Links"). The keys are the command line's option names:
//   scene=S  size=WxH  view=image|mask|difference|error
//   a=T  b=T                                 techniques A and B
//   a-shadow-map=N  a-filter=K  a-precision=P  a-param=key=value (repeatable); b-... the same
//   light-position=X,Y,Z  orbit=AZ,EL,DIST   when not the scene's own
//   zoom=Z  center=X,Y  wipe=W               magnification, the image point at the centre
//                                            (fractions from the top left), wipe position %
// readUrlState applies a query; writeUrlState writes the current state back (replaceState).

const kLaneOptions = ['shadow-map', 'filter', 'precision'];

function urlText(v) {
  return encodeURIComponent(v).replace(/%3D/g, '=').replace(/%2C/g, ',').replace(/%3A/g, ':');
}

function pageQuery() {
  const pairs = [['scene', $('scene').value], ['size', $('size').value]];
  if ($('view').value !== 'image') pairs.push(['view', $('view').value]);
  for (const lane of kLanes) pairs.push([lane, state.lanes[lane].technique]);
  for (const lane of kLanes) {
    const l = state.lanes[lane];
    const t = state.byName[l.technique];
    for (const o of kLaneOptions) if (l.values[o] !== undefined) pairs.push([lane + '-' + o, l.values[o]]);
    for (const p of t.params) {
      const v = l.values['param:' + p.key];
      if (v !== undefined) pairs.push([lane + '-param', p.key + '=' + v]);
    }
  }
  if (!samePose(state.light, currentScene().light)) pairs.push(['light-position', poseText(state.light)]);
  if (!samePose(state.orbit, currentScene().orbit)) pairs.push(['orbit', poseText(state.orbit)]);
  if (state.zoom !== 1) {
    pairs.push(['zoom', String(Number(state.zoom.toPrecision(4)))]);
    pairs.push(['center', [state.panX, state.panY].map((x) => String(Number(x.toFixed(4)))).join(',')]);
  }
  if (Number($('wipe').value) !== 50) pairs.push(['wipe', $('wipe').value]);
  return pairs.map(([k, v]) => k + '=' + urlText(v)).join('&');
}

function writeUrlState() {
  if (!state.ready) return;
  const q = pageQuery();
  if (location.search !== '?' + q) history.replaceState(null, '', '?' + q);
  document.body.dataset.query = q;
}

function parseNumbers(text, n) {
  const parts = String(text).split(',');
  if (parts.length !== n || parts.some((x) => x.trim() === '' || !isFinite(Number(x)))) return null;
  return parts.map(Number);
}

// Applies the page's query; returns the problems (one line each) with what it could not use.
function readUrlState(search) {
  const q = new URLSearchParams(search);
  const problems = [];
  const known = new Set(['scene', 'size', 'view', 'a', 'b', 'light-position', 'orbit', 'zoom',
                         'center', 'wipe']);
  for (const lane of kLanes) {
    known.add(lane + '-param');
    for (const o of kLaneOptions) known.add(lane + '-' + o);
  }
  for (const k of new Set(q.keys())) if (!known.has(k)) problems.push('unknown key ' + k);
  const select = (id, value, what) => {
    if (value === null) return;
    if ([...$(id).options].some((o) => o.value === value)) $(id).value = value;
    else problems.push('no ' + what + ' ' + value);
  };
  select('scene', q.get('scene'), 'scene');
  const size = q.get('size');
  if (size !== null) {
    const m = /^(\d{1,4})x(\d{1,4})$/.exec(size);
    if (!m || Number(m[1]) < 1 || Number(m[2]) < 1 || Number(m[1]) > state.caps.width ||
        Number(m[2]) > state.caps.height) {
      problems.push('size must be WxH up to ' + state.caps.width + 'x' + state.caps.height);
    } else {
      if (![...$('size').options].some((o) => o.value === size)) {
        const o = document.createElement('option');
        o.value = o.textContent = size;
        $('size').appendChild(o);
      }
      $('size').value = size;
    }
  }
  select('view', q.get('view'), 'view');
  for (const lane of kLanes) {
    select('technique-' + lane, q.get(lane), 'technique');
    buildOptions(lane);
    const l = state.lanes[lane];
    const t = state.byName[l.technique];
    for (const o of kLaneOptions) {
      const v = q.get(lane + '-' + o);
      if (v === null) continue;
      if (t.reads[o]) l.values[o] = v; else problems.push(t.name + ' does not read ' + o);
    }
    for (const kv of q.getAll(lane + '-param')) {
      const eq = kv.indexOf('=');
      const key = eq > 0 ? kv.slice(0, eq) : kv;
      if (eq <= 0) problems.push(lane + '-param must be key=value, got ' + kv);
      else if (!t.params.some((p) => p.key === key)) problems.push(t.name + ' has no parameter ' + key);
      else l.values['param:' + key] = kv.slice(eq + 1);
    }
    buildOptions(lane);  // the controls show the values read
  }
  resetView();
  for (const [key, field] of [['light-position', 'light'], ['orbit', 'orbit']]) {
    if (q.get(key) === null) continue;
    const v = parseNumbers(q.get(key), 3);
    if (v) state[field] = v; else problems.push(key + ' must be three numbers X,Y,Z');
  }
  if (q.get('zoom') !== null) {
    const z = Number(q.get('zoom'));
    const c = parseNumbers(q.get('center') || '0.5,0.5', 2);
    if (isFinite(z) && z >= 1 && z <= kMaxZoom && c) {
      state.zoom = z; state.panX = c[0]; state.panY = c[1];
    } else {
      problems.push('zoom must lie in 1..' + kMaxZoom + ' with center=X,Y');
    }
  }
  if (q.get('wipe') !== null) {
    const w = Number(q.get('wipe'));
    if (isFinite(w) && w >= 0 && w <= 100) $('wipe').value = String(w); else problems.push('wipe must lie in 0..100');
  }
  showPose();
  return problems;
}

// One request in flight per lane: a change while one is out marks the lane dirty, and only
// the latest settings are sent when it returns (the server drops stale ones too).
async function requestFrame(lane) {
  const l = state.lanes[lane];
  writeUrlState();
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
  writeUrlState();
  showLegend();
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

// ------------------------------------------------------------------ the legend of a view

const clamp01 = (x) => Math.min(1, Math.max(0, x));
// core/base/image.cpp differenceHeatMap, which /api/error?view=image draws (d = |mask - truth|).
function errorRamp(d) {
  if (!(d > 0)) return [0, 0, 0];
  const t = 0.15 + 0.85 * d;
  return [clamp01(3 * t - 0.5), clamp01(3 * t - 1.5), t < 0.33 ? 0.6 : clamp01(3 * t - 2)];
}
// differenceImage's ramp (d = |A - B| of the masks).
const differenceRamp = (d) => [clamp01(3 * d), clamp01(3 * d - 1), clamp01(3 * d - 2)];
const maskRamp = (d) => [d, d, d];

const kLegends = {
  mask: { ramp: maskRamp, low: 'in shadow 0', high: '1 lit',
          text: 'visibility: black in shadow, white lit, grey partly lit (filtered edges).' },
  difference: { ramp: differenceRamp, low: 'equal 0', high: '1',
                text: '|A − B| of the visibility masks: black where A and B agree; red, yellow, ' +
                      'white as they differ more (white: one lit, the other in shadow).' },
  error: { ramp: errorRamp, low: 'exact 0', high: '1', grey: true,
           text: '|visibility − reference| (reference.hard pixel=area): black where the ' +
                 'technique matches the ray-traced truth; dark blue for tiny errors, then red, ' +
                 'yellow, white (1: lit where the truth is shadow, or the reverse).' },
};

function showLegend() {
  const legend = kLegends[$('view').value];
  $('legend').hidden = !legend;
  if (!legend) return;
  const c = $('legend-ramp');
  const g = c.getContext('2d');
  const image = g.createImageData(c.width, c.height);
  for (let x = 0; x < c.width; ++x) {
    const rgb = legend.ramp(x / (c.width - 1));
    for (let y = 0; y < c.height; ++y) {
      const i = 4 * (y * c.width + x);
      image.data[i] = 255 * rgb[0]; image.data[i + 1] = 255 * rgb[1];
      image.data[i + 2] = 255 * rgb[2]; image.data[i + 3] = 255;
    }
  }
  g.putImageData(image, 0, 0);
  $('legend-low').textContent = legend.low;
  $('legend-high').textContent = legend.high;
  $('legend-text').textContent = legend.text;
  $('legend-grey').hidden = !legend.grey;
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
  const problems = readUrlState(location.search);
  state.ready = true;
  if (problems.length) {
    $('link-problems').textContent = 'the link asks for what the lab cannot show: ' + problems.join('; ');
    $('link-problems').hidden = false;
  }
  for (const lane of kLanes) {
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
