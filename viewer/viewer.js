// The web viewer of `sortlast serve`: asks the server for frames of the current view state
// (camera, image size, renderer, compositing, transfer function, time step, the volume's modes:
// volume_modes.js) and shows them. A scene of several fields (`volumes`) gets a field selector
// above the transfer-function editor, which then edits the chosen field's transfer function, and
// a checkbox per field that shows or hides it.
// While the user interacts it asks for reduced JPEG frames, and for a full-size PNG once the
// interaction stops (progressive refinement).

import { FrameClient } from './connection.js';
import { PRESETS, sampleKnots, cssGradient } from './colormaps.js';
import { TransferEditor, opacityAt } from './transfer_editor.js';
import * as cam from './orbit.js';
import * as modes from './volume_modes.js';
import { valueScale, drawLegend } from './value_scale.js';

const $ = (id) => document.getElementById(id);
const params = new URLSearchParams(location.search);
const token = params.get('token') || '';
const apiUrl = (path) => (token ? `${path}?token=${encodeURIComponent(token)}` : path);

const IDLE_MS = 150;            // no wheel / slider input for this long: ask for the full frame
const REDUCED_QUALITY = 80;     // JPEG quality of reduced frames
const PLAY_QUALITY = 90;        // JPEG quality while a time series plays
const FPS_WINDOW_MS = 2000;
const LATENCY_WINDOW = 20;

const state = {
  scene: null,
  bounds: null,
  camera: null,
  sceneCamera: null,
  sceneSize: [512, 512],
  limits: { max_width: 4096, max_height: 4096 },
  keys: null,                   // request_keys, as a Set (null: send everything)
  // The transfer function in the editor (the scene's, or the chosen field's): the colour knots
  // and opacity points its scene gives, and whether the user has edited it.
  sceneKnots: null,
  sceneOpacity: null,
  tfEdited: false,
  fields: null,                 // several fields: [{info (GET /api/scene's), tf (tfState), visible}]
  field: 0,                     // the field in the editor
  steps: 1,
  step: 0,
  playing: false,
  drags: 0,                     // pointer drags in progress (frame, transfer editor, sliders)
  seq: 0,                       // submission counter
  shownSeq: -1,
  errorSeq: -1,
  frameTimes: [],
  lastFull: null,               // {blob, width, height} of the last full frame shown
  waiters: [],                  // requestFull() promises
  unanswered: null,             // {key, seq} of the newest request while no reply has come
};

const api = {
  ready: false,
  framesShown: 0,
  lastCamera: null,
  lastStats: null,
  lastRequest: null,            // the request body of the last shown frame
  lastMode: null,               // 'full' | 'reduced' | 'play'
  latencies: [],
  shown: { full: 0, reduced: 0, play: 0 },   // frames shown, by kind
  requestFull,
  // true once the newest request has been answered with a full-size frame that is on screen
  get settled() { return state.shownSeq === state.seq && api.lastMode === 'full' && !client.busy; },
  get message() { return $('message').hidden ? null : { text: $('message').textContent, kind: $('message').className }; },
  tfHandles: () => tf.handlePositions(),
  get field() { return state.fields ? state.field : null; },
  get camera() { return state.camera && cam.cloneCamera(state.camera); },
  get transport() { return client.transport; },
};
window.sortlastViewer = api;

// ---------------------------------------------------------------- messages
let connectionMessage = null;
function showMessage(text, kind = 'error') {
  const el = $('message');
  el.textContent = text || '';
  el.className = text ? kind : '';
  el.hidden = !text;
}
function error(text) { showMessage(text, 'error'); }
$('message').addEventListener('click', () => showMessage(null));

// ---------------------------------------------------------------- frame requests
const client = new FrameClient({
  token,
  onFrame: (meta, blob, stats) => { answered(meta); showFrame(meta, blob, stats); },
  onError: (meta, message) => {
    answered(meta);
    state.errorSeq = Math.max(state.errorSeq, meta.seq);
    error(`Server: ${message}`);
    state.waiters = state.waiters.filter((w) => {
      if (meta.mode === 'full' && meta.seq >= w.seq) { w.reject(new Error(message)); return false; }
      return true;
    });
    if (state.playing) setPlaying(false);
    updateBusy();
  },
  onStatus: (text, isError) => {
    connectionMessage = text;
    if (text) showMessage(text, isError ? 'error' : 'info');
    else if ($('message').dataset.connection) showMessage(null);
    $('message').dataset.connection = text ? '1' : '';
    updateTransport();
  },
  onReconnect: () => { state.unanswered = null; submit('full'); },
});

function answered(meta) { if (state.unanswered && state.unanswered.seq <= meta.seq) state.unanswered = null; }

function fullSize() {
  const [sw, sh] = state.sceneSize;
  const v = $('size').value;
  let w = sw, h = sh;
  if (v !== 'scene') {
    const s = Number(v);
    if (sw >= sh) { w = s; h = Math.round((s * sh) / sw); } else { h = s; w = Math.round((s * sw) / sh); }
  }
  return [Math.max(1, Math.min(w, state.limits.max_width || 4096)), Math.max(1, Math.min(h, state.limits.max_height || 4096))];
}

const round6 = (v) => Math.round(v * 1e6) / 1e6;

// transfer.points of opacity points [[x, a], ...] and colour knots: the colour map and the
// opacity curve sampled at 64 evenly spaced values plus every control point of either, strictly
// increasing.
function transferPoints(points = tf.getPoints(), knots = currentKnots()) {
  const xs = [];
  for (let i = 0; i < 64; i++) xs.push(i / 63);
  for (const p of points) xs.push(p[0]);
  for (const k of knots) if (k[0] >= 0 && k[0] <= 1) xs.push(k[0]);
  const sorted = xs.map(round6).sort((a, b) => a - b).filter((x, i, a) => i === 0 || x > a[i - 1]);
  return sorted.map((x) => [x, ...sampleKnots(knots, x).map(round6), round6(opacityAt(points, x))]);
}

// Several fields: each field's keys (its `transfer_prefix`: `volumes[i].transfer.`, or
// `transfer.` for a first field given as `volume`): its transfer function once edited, its scale,
// and whether it is shown (`volumes[i].visible`; a field without that key is hidden by opacity 0).
function fieldKeys(r) {
  saveTfState(state.fields[state.field].tf);
  delete r['transfer.scale'];  // (modeKeys': the scale is each field's)
  for (const f of state.fields) {
    const p = f.info.transfer_prefix, t = f.tf;
    if (t.edited) {
      r[`${p}points`] = transferPoints(t.opacity, knotsOf(t));
      if (t.colormap !== 'scene') r[`${p}colormap`] = t.colormap;
    }
    r[`${p}scale`] = t.scale;
    if (f.info.visible_key) r[f.info.visible_key] = f.visible;
    else if (!f.visible) r[`${p}points`] = [[0, 0, 0, 0, 0], [1, 0, 0, 0, 0]];
  }
}

function buildRequest(mode) {
  const [fw, fh] = fullSize();
  const factor = mode === 'reduced' ? Number($('reduce').value) : 1;
  const w = Math.max(8, Math.round(fw * factor)), h = Math.max(8, Math.round(fh * factor));
  const c = state.camera;
  const r = {
    'camera.position': c.position.map(round6),
    'camera.look_at': c.look_at.map(round6),
    'camera.up': c.up.map(round6),
    'camera.fov': c.fov,
    'image.width': w,
    'image.height': h,
  };
  if (state.scene.has_volume) {
    r['render.method'] = $('method').value;
    // Level of detail while interacting: samples twice as far apart halve the volume's cost
    // (the full frame that follows uses the chosen spacing).
    const coarse = mode === 'reduced' && $('coarse') && $('coarse').checked ? 2 : 1;
    // auto: the session's choice; while interacting, twice the step it chose last (a fixed
    // number: a new probe per reduced frame would cost more than it saves).
    const chosen = api.lastStats && Number.isFinite(api.lastStats.sample_spacing) ? api.lastStats.sample_spacing : null;
    if ($('spacing-auto').checked) r['render.sample_spacing'] = coarse > 1 && chosen ? Math.min(100, chosen * coarse) : 'auto';
    else r['render.sample_spacing'] = Math.min(100, Number($('spacing').value) * coarse);
    r['render.shading'] = $('shading').checked;
    // 'scene' leaves the scene's choice (its auto rule sees the spacing sent above).
    const preint = $('preint').value;
    if (preint !== 'scene') r['transfer.preintegrated'] = preint === 'auto' ? 'auto' : preint === 'on';
    if (state.tfEdited && !state.fields) {
      r['transfer.points'] = transferPoints();
      // A named map is drawn with the server's definition of it (transfer.colormap: ParaView's
      // presets, with their colour spaces), whose colours replace those of transfer.points; the
      // knots here are only the preview. 'scene' sends the scene's own colours as points.
      const map = $('colormap').value;
      if (map !== 'scene') r['transfer.colormap'] = map;
    }
    modes.modeKeys(r, { camera: c, bounds: state.bounds, range: tfRange() });
    if (state.fields) fieldKeys(r);
  }
  r['compositing.strategy'] = $('strategy').value;
  if (state.steps > 1) r['time.step'] = state.step;
  if (state.keys) for (const k of Object.keys(r)) if (!state.keys.has(k)) delete r[k];
  if (mode === 'full') r.format = 'png';
  else { r.format = 'jpeg'; r.quality = mode === 'play' ? PLAY_QUALITY : REDUCED_QUALITY; }
  // The accuracy estimate (render.estimate) on full frames, those an edit settles on: `auto`
  // estimates again only when the settings changed, not for a new camera.
  if (state.scene.has_volume && (!state.keys || state.keys.has('render.estimate')))
    r['render.estimate'] = mode === 'full' ? 'auto' : 'off';
  return { request: r, meta: { mode, fullW: fw, fullH: fh, seq: ++state.seq } };
}

function submit(mode) {
  if (!state.scene) return undefined;
  const { request, meta } = buildRequest(mode);
  // the same state as the request still unanswered: nothing new to ask for
  const key = JSON.stringify(request);
  if (state.unanswered && state.unanswered.key === key) { state.seq -= 1; return state.unanswered.seq; }
  state.unanswered = { key, seq: meta.seq };
  meta.request = request;
  client.submit(request, meta);
  updateBusy();
  return meta.seq;
}

// An interaction step: a reduced frame now, the full frame once input has been idle.
let idleTimer = 0;
function interact() {
  submit('reduced');
  clearTimeout(idleTimer);
  idleTimer = setTimeout(() => { if (state.drags === 0 && !state.playing) submit('full'); }, IDLE_MS);
}
function interactionEnd() {
  clearTimeout(idleTimer);
  if (state.drags === 0 && !state.playing) submit('full');
}

function requestFull() {
  return new Promise((resolve, reject) => {
    const seq = submit('full');
    if (seq === undefined) { reject(new Error('the scene is not loaded')); return; }
    state.waiters.push({ seq, resolve, reject });
  });
}

// ---------------------------------------------------------------- showing frames
const canvas = $('frame');
const ctx = canvas.getContext('2d');

async function showFrame(meta, blob, stats) {
  let bitmap;
  try {
    bitmap = await createImageBitmap(blob);
  } catch (e) {
    error(`Could not decode the ${blob.type} frame: ${e.message}`);
    return;
  }
  if (meta.seq <= state.shownSeq) { bitmap.close(); return; }   // a newer frame is already up
  state.shownSeq = meta.seq;
  if (canvas.width !== meta.fullW || canvas.height !== meta.fullH) {
    canvas.width = meta.fullW;
    canvas.height = meta.fullH;
    layoutFrame();
  }
  ctx.imageSmoothingEnabled = true;
  ctx.imageSmoothingQuality = 'high';
  ctx.drawImage(bitmap, 0, 0, canvas.width, canvas.height);
  bitmap.close();
  const now = performance.now();
  const latency = now - meta.t0;

  api.latencies.push(latency);
  if (api.latencies.length > 200) api.latencies.splice(0, api.latencies.length - 200);
  state.frameTimes.push(now);
  while (state.frameTimes.length && now - state.frameTimes[0] > FPS_WINDOW_MS) state.frameTimes.shift();
  api.framesShown += 1;
  api.shown[meta.mode] += 1;
  api.lastStats = stats;
  api.lastCamera = stats.camera || null;
  api.lastRequest = meta.request;
  api.lastMode = meta.mode;
  if (meta.mode === 'full') state.lastFull = { blob, width: meta.fullW, height: meta.fullH };
  if (meta.seq > state.errorSeq && !connectionMessage) showMessage(null);
  api.ready = true;
  document.body.classList.add('ready');
  updateStats(meta, stats, latency);
  updateBusy();
  if (meta.mode === 'full') {
    state.waiters = state.waiters.filter((w) => {
      if (meta.seq >= w.seq) { w.resolve(stats); return false; }
      return true;
    });
  }
  if (state.playing && meta.mode === 'play') advancePlay();
  if (meta.mode === 'full' && Number.isInteger(stats.step) && stats.step !== state.histogramStep) refreshHistogram(stats.step);
}

// The histogram and data range are the shown step's: fetch them again when the step changes.
async function refreshHistogram(step) {
  state.histogramStep = step;
  try {
    const res = await fetch(apiUrl('/api/scene'));
    if (!res.ok) return;
    const scene = await res.json();
    if (state.histogramStep !== step) return;
    state.scene.data_range = scene.data_range;
    state.scene.histogram = scene.histogram;
    showHistogram();
  } catch { /* keep the old one */ }
}

// What the editor shows the data of: the scene's volume, or the chosen field (each with its
// settings, data_range and histogram).
function tfSource() { return state.fields ? state.fields[state.field].info : state.scene; }

function showHistogram() {
  const scene = tfSource();
  const [lo, hi] = tfRange();
  const tiny = Math.abs(hi - lo) * 1e-6;  // a "minimum" of 1e-33 is a 0
  $('tf-lo').textContent = fmt(Math.abs(lo) < tiny ? 0 : lo);
  $('tf-hi').textContent = fmt(Math.abs(hi) < tiny ? 0 : hi);
  if (scene.histogram && Array.isArray(scene.histogram.counts)) {
    const [hlo, hhi] = scene.histogram.range || scene.data_range || [lo, hi];
    // The bins are even in the histogram's own scale (the scene's transfer.scale when it was
    // loaded); each is drawn where the current transfer.scale puts its edges.
    const sc = valueScale([lo, hi], tfScale(), tfLinearWidth());
    const h = scene.histogram;
    const hs = valueScale([hlo, hhi], h.scale || 'linear', Number.isFinite(h.linear_width) ? h.linear_width : 1);
    tf.setHistogram(h.counts, 0, 1, (f) => sc.place(hs.value(f)));
  } else {
    tf.setHistogram(null);
  }
}

function layoutFrame() {
  const view = $('view');
  const vw = view.clientWidth - 16, vh = view.clientHeight - 16;
  const s = Math.min(vw / canvas.width, vh / canvas.height);
  if (!(s > 0)) return;
  canvas.style.width = `${Math.floor(canvas.width * s)}px`;
  canvas.style.height = `${Math.floor(canvas.height * s)}px`;
  showLegend();
}

// image.legend: drawn over the frame from the transfer function the viewer holds (the frames the
// server sends have none; the written ones get theirs on the server).
function showLegend() {
  const overlay = $('legend');
  if (!overlay) return;
  const settings = (state.scene && state.scene.settings) || {};
  // The scene's image.legend, or (the Legend box ticked without one) a bar on the right.
  let legend = settings['image.legend'] || {};
  if (!$('legend-on').checked) legend = { position: 'none' };
  else if (!legend.position || legend.position === 'none') legend = { ...legend, position: 'right' };
  overlay.hidden = legend.position === 'none';
  if (overlay.hidden) return;
  const w = Math.floor(canvas.width * (parseFloat(canvas.style.width) / canvas.width || 1));
  const h = Math.floor(canvas.height * (parseFloat(canvas.style.height) / canvas.height || 1));
  overlay.width = w; overlay.height = h;
  overlay.style.width = `${w}px`; overlay.style.height = `${h}px`;
  const r = canvas.getBoundingClientRect(), v = $('view').getBoundingClientRect();
  overlay.style.left = `${r.left - v.left}px`; overlay.style.top = `${r.top - v.top}px`;
  const knots = currentKnots();
  drawLegend(overlay, legend, tfRange(), tfScale(), tfLinearWidth(), (x) => sampleKnots(knots, x));
}
new ResizeObserver(layoutFrame).observe($('view'));

// ---------------------------------------------------------------- stats overlay
const ms = (s) => (typeof s === 'number' ? (s * 1000).toFixed(1) : '–');
const maxOf = (v) => (Array.isArray(v) ? (v.length ? Math.max(...v) : undefined) : v);
const sumOf = (v) => (Array.isArray(v) ? v.reduce((a, b) => a + b, 0) : v);
function bytes(n) {
  if (typeof n !== 'number') return '–';
  if (n < 1024) return `${n} B`;
  if (n < 1024 * 1024) return `${(n / 1024).toFixed(1)} KiB`;
  return `${(n / 1024 / 1024).toFixed(2)} MiB`;
}

function updateStats(meta, s, latency) {
  const t = state.frameTimes;
  const fps = t.length > 1 ? ((t.length - 1) * 1000) / (t[t.length - 1] - t[0]) : 0;
  const recent = api.latencies.slice(-LATENCY_WINDOW);
  const mean = recent.reduce((a, b) => a + b, 0) / recent.length;
  const w = s.width ?? meta.request['image.width'], h = s.height ?? meta.request['image.height'];
  const kind = meta.mode === 'full' ? 'full PNG' : meta.mode === 'play' ? 'JPEG' : 'reduced JPEG';
  const rle = typeof s.rle_ratio === 'number' ? s.rle_ratio.toFixed(3) : '–';
  const rows = [
    ['fps', fps ? fps.toFixed(1) : '–'],
    ['frame', `${w}×${h} ${kind}`],
    ['latency', `${latency.toFixed(0)} ms (mean ${mean.toFixed(0)})`],
    ['total', `${ms(s.total_s)} ms`],
    ['render', `${ms(maxOf(s.render_s))} ms`],
    ['composite', `${ms(maxOf(s.composite_s))} ms`],
    ['transfer', `${ms(maxOf(s.transfer_s))} ms`],
    ['sent', bytes(sumOf(s.bytes_sent))],
    ['RLE ratio', rle],
    ['spacing', typeof s.sample_spacing === 'number' ? `${s.sample_spacing} voxel${s.sample_spacing_auto ? ' (auto)' : ''}` : '–'],
    ['ranks', s.ranks ?? state.scene.ranks ?? '–'],
    ['accuracy', accuracyText(s.accuracy_estimate)],
  ];
  // compositing.strategy auto: what it chose this frame, and its forecast.
  if (s.compositing && s.compositing.chose)
    rows.splice(6, 0, ['strategy', `auto: ${s.compositing.chose} (${ms(s.compositing.forecast_s)} ms forecast)`]);
  const el = $('stats');
  el.replaceChildren(...rows.map(([k, v]) => {
    const row = document.createElement('div');
    const a = document.createElement('span'); a.textContent = k;
    const b = document.createElement('b'); b.textContent = v;
    row.append(a, b);
    return row;
  }));
}

// render.estimate (session/frame_estimate.h): the estimated PSNR against the exact model with its
// 95 % lower bound, and the estimated share of pixels more than 4/255 off.
function accuracyText(e) {
  if (!e) return '–';
  if (e.available === false) return `not estimated (${e.why})`;
  const db = v => (v === 'inf' ? '∞' : v.toFixed(1));
  const share = (100 * e.over4_share).toFixed(2);
  return `≈${db(e.estimated_psnr_db)} dB (≥${db(e.psnr_db_95[0])}), ${share}% >4/255${e.fresh === false ? ' (earlier frame)' : ''}`;
}

function updateBusy() { $('busy').hidden = !client.busy; }
function updateTransport() {
  const el = $('transport');
  el.textContent = client.transport;
  el.className = client.transport;
}
setInterval(() => { updateBusy(); updateTransport(); }, 500);

// ---------------------------------------------------------------- camera interaction
const pointers = new Map();   // pointerId -> {x, y}
let dragMode = null;          // 'orbit' | 'pan' | 'pinch'

function viewHeight() { return canvas.getBoundingClientRect().height || canvas.height; }

canvas.addEventListener('contextmenu', (e) => e.preventDefault());
canvas.addEventListener('pointerdown', (e) => {
  if (!state.camera) return;
  canvas.setPointerCapture(e.pointerId);
  pointers.set(e.pointerId, { x: e.clientX, y: e.clientY });
  if (pointers.size === 1) {
    state.drags += 1;
    dragMode = e.altKey && $('clip-on').checked ? 'clip' : e.button === 2 || e.button === 1 || e.shiftKey ? 'pan' : 'orbit';
  } else {
    dragMode = 'pinch';
  }
  canvas.classList.add('dragging');
  e.preventDefault();
});
canvas.addEventListener('pointermove', (e) => {
  const p = pointers.get(e.pointerId);
  if (!p) return;
  const dx = e.clientX - p.x, dy = e.clientY - p.y;
  if (dx === 0 && dy === 0) return;
  const vh = viewHeight();
  if (dragMode === 'pinch' && pointers.size >= 2) {
    const [a, b] = [...pointers.values()];
    const before = Math.hypot(a.x - b.x, a.y - b.y);
    const midBefore = [(a.x + b.x) / 2, (a.y + b.y) / 2];
    p.x = e.clientX; p.y = e.clientY;
    const [c, d] = [...pointers.values()];
    const after = Math.hypot(c.x - d.x, c.y - d.y);
    const midAfter = [(c.x + d.x) / 2, (c.y + d.y) / 2];
    if (before > 0 && after > 0) state.camera = cam.zoom(state.camera, before / after, state.bounds);
    state.camera = cam.pan(state.camera, midAfter[0] - midBefore[0], midAfter[1] - midBefore[1], vh);
  } else {
    p.x = e.clientX; p.y = e.clientY;
    if (dragMode === 'clip') modes.dragClip(dy, vh);
    else if (dragMode === 'pan') state.camera = cam.pan(state.camera, dx, dy, vh);
    else state.camera = cam.orbit(state.camera, dx, dy, vh);
  }
  state.camera = keepOut(state.camera);
  submit('reduced');
});
function pointerEnd(e) {
  if (!pointers.delete(e.pointerId)) return;
  if (pointers.size === 1 && dragMode === 'pinch') dragMode = 'orbit';
  if (pointers.size > 0) return;
  dragMode = null;
  canvas.classList.remove('dragging');
  state.drags = Math.max(0, state.drags - 1);
  interactionEnd();
}
canvas.addEventListener('pointerup', pointerEnd);
canvas.addEventListener('pointercancel', pointerEnd);
canvas.addEventListener('wheel', (e) => {
  if (!state.camera) return;
  e.preventDefault();
  const unit = e.deltaMode === 1 ? 0.05 : e.deltaMode === 2 ? 1 : 0.0015;
  state.camera = cam.zoom(state.camera, Math.exp(e.deltaY * unit), modes.flyInside() ? null : state.bounds);
  interact();
}, { passive: false });

function aspect() { const [w, h] = fullSize(); return w / h; }
function resetView() {
  state.camera = cam.frameBounds(state.sceneCamera, state.bounds, aspect());
  submit('full');
}
$('reset').addEventListener('click', resetView);
window.addEventListener('keydown', (e) => {
  if (e.target instanceof HTMLInputElement || e.target instanceof HTMLSelectElement || e.target === $('tf-canvas')) return;
  if (e.key === 'r' || e.key === 'R') resetView();
  // Flying: the eye and look_at move along the view, 5 % of the scene's radius a key press.
  if ((e.key === 'w' || e.key === 's') && modes.flyInside() && state.camera) {
    const f = cam.frame(state.camera);
    const step = cam.scale(f.forward, (e.key === 'w' ? 0.05 : -0.05) * cam.sphere(state.bounds).radius);
    state.camera = { ...state.camera, position: cam.add(state.camera.position, step), look_at: cam.add(state.camera.look_at, step) };
    interact();
  }
  if (e.key === ' ' && state.steps > 1) { e.preventDefault(); setPlaying(!state.playing); }
});

// ---------------------------------------------------------------- controls
// Sliders: reduced frames while dragged, the full frame on release.
function trackSlider(el, onInput) {
  let held = false;
  el.addEventListener('pointerdown', () => { if (!held) { held = true; state.drags += 1; } });
  const release = () => { if (held) { held = false; state.drags = Math.max(0, state.drags - 1); interactionEnd(); } };
  window.addEventListener('pointerup', release);
  window.addEventListener('pointercancel', release);
  el.addEventListener('input', () => { onInput(); interact(); });
  el.addEventListener('change', () => { onInput(); if (!held) interactionEnd(); });
}

for (const id of ['size', 'method', 'strategy', 'shading', 'preint']) $(id).addEventListener('change', () => submit('full'));

// the volume's modes (volume_modes.js)
function keepOut(c) { return modes.flyInside() ? c : cam.keepOutside(c, state.bounds); }
for (const id of ['blend', 'projection', 'clip-on', 'clip-axis', 'clip-flip', 'tf-scale']) {
  $(id).addEventListener('change', () => { modes.showModeControls(); showHistogram(); showLegend(); submit('full'); });
}
$('fly-inside').addEventListener('change', () => { state.camera = keepOut(state.camera); submit('full'); });
$('legend-on').addEventListener('change', showLegend);
trackSlider($('iso-value'), () => {});
trackSlider($('iso-opacity'), () => {});
trackSlider($('clip-pos'), () => {});


// sample spacing: a log slider and a number box, 0.01 .. 100
const SPACING_MIN = 0.01, SPACING_MAX = 100;
const clampSpacing = (v) => Math.min(Math.max(v, SPACING_MIN), SPACING_MAX);
function syncSpacingSlider() { $('spacing-range').value = Math.log10(clampSpacing(Number($('spacing').value) || 1)); }
trackSlider($('spacing-range'), () => {
  $('spacing-auto').checked = false;  // a step dragged to takes over from auto
  const v = 10 ** Number($('spacing-range').value);
  $('spacing').value = v >= 1 ? v.toFixed(2) : v.toPrecision(2);
});
$('spacing-auto').addEventListener('change', () => submit('full'));
$('spacing').addEventListener('change', () => {
  $('spacing-auto').checked = false;  // a number typed in takes over from auto
  const v = Number($('spacing').value);
  if (!(v > 0)) { error('Sample spacing must be a number between 0.01 and 100'); return; }
  $('spacing').value = clampSpacing(v);
  syncSpacingSlider();
  submit('full');
});

// time steps
trackSlider($('step'), () => { state.step = Number($('step').value); showStep(); });
function showStep() { $('step-label').textContent = `${state.step + 1} / ${state.steps}`; }
let playTimer = 0;
function setPlaying(on) {
  state.playing = on && state.steps > 1;
  $('play').textContent = state.playing ? 'Pause' : 'Play';
  $('play').classList.toggle('active', state.playing);
  clearTimeout(playTimer);
  if (state.playing) advancePlay();
  else submit('full');
}
function advancePlay() {
  clearTimeout(playTimer);
  playTimer = setTimeout(() => {
    if (!state.playing) return;
    state.step = (state.step + 1) % state.steps;
    $('step').value = state.step;
    showStep();
    submit('play');
  }, 30);
}
$('play').addEventListener('click', () => setPlaying(!state.playing));

$('show-stats').addEventListener('change', () => { $('stats').hidden = !$('show-stats').checked; });

// save
$('save').addEventListener('click', async () => {
  let blob = state.lastFull && state.lastFull.blob.type === 'image/png' ? state.lastFull.blob : null;
  if (!blob) blob = await new Promise((r) => canvas.toBlob(r, 'image/png'));
  if (!blob) { error('No frame to save yet'); return; }
  const a = document.createElement('a');
  a.href = URL.createObjectURL(blob);
  a.download = `sortlast_${canvas.width}x${canvas.height}.png`;
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(a.href), 10000);
});

// record: the service writes every frame it sends into a movie under its --record-dir
let recording = false;
async function postRecord(body) {
  const res = await fetch(apiUrl('/api/record'), {
    method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify(body),
  });
  const j = await res.json().catch(() => ({}));
  if (!res.ok) throw new Error(j.error || `HTTP ${res.status}`);
  return j;
}
$('record').addEventListener('click', async () => {
  try {
    if (!recording) {
      const stamp = new Date().toISOString().replace(/[:.]/g, '-').slice(0, 19);
      const path = window.prompt('Movie file under the service\'s record directory (.mp4 or .webm)', `sortlast_${stamp}.mp4`);
      if (!path) return;
      const j = await postRecord({ path });
      recording = true;
      showMessage(`Recording ${j.recording} at ${j.frame_rate} frames/s`, 'info');
      submit('full');  // the current view is the movie's first frame
    } else {
      const j = await postRecord({ stop: true });
      recording = false;
      showMessage(`Recorded ${j.frames} frame(s), ${j.width}x${j.height}, into ${j.name}`, 'info');
    }
  } catch (e) {
    error(`Record: ${e.message}`);
    if (recording && /not recording/.test(e.message)) recording = false;
  }
  $('record').textContent = recording ? 'Stop recording' : 'Record';
  $('record').classList.toggle('active', recording);
});

// ---------------------------------------------------------------- transfer function
const tf = new TransferEditor($('tf-canvas'), {
  onChange: (interactive) => {
    state.tfEdited = true;
    if (interactive) {
      if (!tfDragging) { tfDragging = true; state.drags += 1; }
      submit('reduced');
    } else {
      if (tfDragging) { tfDragging = false; state.drags = Math.max(0, state.drags - 1); }
      interactionEnd();
    }
  },
  onHover: (x, a) => {
    const el = $('tf-readout');
    if (x === null) { el.textContent = ''; return; }
    const v = valueScale(tfRange(), tfScale(), tfLinearWidth()).value(x);
    el.textContent = `value ${fmt(v)} · opacity ${a.toFixed(2)}`;
  },
});
let tfDragging = false;

function fmt(v) {
  if (!Number.isFinite(v)) return '–';
  const a = Math.abs(v);
  return a !== 0 && (a >= 1e5 || a < 1e-3) ? v.toExponential(2) : String(Math.round(v * 1000) / 1000);
}

function tfRange() {
  const src = state.scene && tfSource();
  const r = src && src.settings && src.settings['transfer.range'];
  if (Array.isArray(r) && r.length === 2 && r.every(Number.isFinite)) return r;
  return (src && src.data_range) || [0, 1];
}

// The scale the viewer asks for (its Scale control, set from the scene's transfer.scale).
function tfScale() {
  const s = $('tf-scale').value;
  return s === 'log' || s === 'symlog' ? s : 'linear';
}
function tfLinearWidth() {
  const src = state.scene && tfSource();
  const w = src && src.settings && src.settings['transfer.linear_width'];
  return Number.isFinite(w) && w > 0 ? w : 1;
}

function currentKnots() {
  const name = $('colormap').value;
  return name === 'scene' ? state.sceneKnots : PRESETS[name];
}
const knotsOf = (t) => (t.colormap === 'scene' ? t.sceneKnots : PRESETS[t.colormap]);

// A transfer function as the scene's settings give it (transfer.points, transfer.scale), unedited.
function tfState(settings) {
  const pts = Array.isArray(settings['transfer.points']) ? settings['transfer.points'].filter((p) => Array.isArray(p) && p.length >= 5) : [];
  const fromScene = pts.length > 0;
  const sceneOpacity = fromScene ? pts.map((p) => [p[0], p[4]]) : [[0, 0], [1, 1]];
  return {
    fromScene,
    sceneKnots: fromScene ? pts.map((p) => [p[0], p[1], p[2], p[3]]) : PRESETS['Cool to Warm'],
    sceneOpacity,
    opacity: sceneOpacity,
    colormap: fromScene ? 'scene' : 'Cool to Warm',
    edited: false,
    scale: ['linear', 'log', 'symlog'].includes(settings['transfer.scale']) ? settings['transfer.scale'] : 'linear',
  };
}
// Into the editor and its controls (colour map, scale), and back.
function loadTfState(t) {
  state.sceneKnotsFromScene = t.fromScene;
  state.sceneKnots = t.sceneKnots;
  state.sceneOpacity = t.sceneOpacity;
  state.tfEdited = t.edited;
  const maps = Object.keys(PRESETS).map((k) => [k, k]);
  setOptions($('colormap'), t.fromScene ? [['scene', 'Scene'], ...maps] : maps, t.colormap);
  tf.setPoints(t.opacity);
  tf.setColormap(currentKnots());
  $('colormap-preview').style.background = cssGradient(currentKnots());
  $('tf-scale').value = t.scale;
}
function saveTfState(t) {
  t.opacity = tf.getPoints();
  t.colormap = $('colormap').value;
  t.edited = state.tfEdited;
  t.scale = $('tf-scale').value;
}

// Several fields: the selector and a show/hide checkbox per field.
function setupFields(scene) {
  const list = Array.isArray(scene.fields) && scene.fields.length > 1 ? scene.fields : null;
  state.fields = list && list.map((info) => ({ info, tf: tfState(info.settings || {}), visible: info.visible !== false }));
  state.field = 0;
  $('fields-controls').hidden = !state.fields;
  if (!state.fields) return;
  const label = (f) => (f.info.source ? `${f.info.name}: ${f.info.source}` : f.info.name);
  setOptions($('field'), state.fields.map((f, i) => [String(i), label(f)]), '0');
  $('field-list').replaceChildren(...state.fields.map((f, i) => {
    const row = document.createElement('label');
    row.textContent = `Show ${label(f)}`;
    const box = document.createElement('input');
    box.type = 'checkbox';
    box.checked = f.visible;
    box.id = `field-visible-${i}`;
    box.addEventListener('change', () => { f.visible = box.checked; submit('full'); });
    row.append(box);
    return row;
  }));
  loadTfState(state.fields[0].tf);
}
$('field').addEventListener('change', () => {
  if (!state.fields) return;
  saveTfState(state.fields[state.field].tf);
  state.field = Math.min(Math.max(0, Number($('field').value) | 0), state.fields.length - 1);
  loadTfState(state.fields[state.field].tf);
  showHistogram();
  showLegend();
});

$('colormap').addEventListener('change', () => {
  tf.setColormap(currentKnots());
  $('colormap-preview').style.background = cssGradient(currentKnots());
  state.tfEdited = true;
  showLegend();
  submit('full');
});
$('tf-reset').addEventListener('click', () => {
  tf.setPoints(state.sceneOpacity);
  $('colormap').value = state.sceneKnotsFromScene ? 'scene' : 'Cool to Warm';
  tf.setColormap(currentKnots());
  $('colormap-preview').style.background = cssGradient(currentKnots());
  state.tfEdited = !state.sceneKnotsFromScene;
  submit('full');
});

// ---------------------------------------------------------------- start
function setOptions(select, values, current) {
  const list = [...values];
  if (current !== undefined && !list.some((v) => String(Array.isArray(v) ? v[0] : v) === String(current))) list.push([current, String(current)]);
  select.replaceChildren(...list.map((v) => {
    const [value, label] = Array.isArray(v) ? v : [v, v];
    const o = document.createElement('option');
    o.value = value; o.textContent = label;
    return o;
  }));
  if (current !== undefined) select.value = String(current);
}

function validVec(v) { return Array.isArray(v) && v.length === 3 && v.every(Number.isFinite); }

function applyScene(scene) {
  state.scene = scene;
  $('record').hidden = !scene.record_dir;  // the service allows recording (--record-dir)
  const settings = scene.settings || {};
  state.keys = Array.isArray(scene.request_keys) ? new Set(scene.request_keys) : null;
  if (scene.limits) state.limits = scene.limits;
  const b = scene.bounds;
  state.bounds = b && validVec(b.lo) && validVec(b.hi) ? { lo: b.lo, hi: b.hi } : { lo: [-1, -1, -1], hi: [1, 1, 1] };
  const c = scene.camera || {};
  state.sceneSize = [scene.image?.width || 512, scene.image?.height || 512];
  const centre = cam.sphere(state.bounds).center;
  const sc = {
    position: validVec(c.position) ? c.position : null,
    look_at: validVec(c.look_at) ? c.look_at : centre,
    up: validVec(c.up) ? c.up : [0, 1, 0],
    fov: Number.isFinite(c.fov) ? c.fov : 35,
  };
  if (!sc.position) {
    state.sceneCamera = { ...sc, position: cam.add(sc.look_at, [0.55, 0.35, 1]) };
    state.sceneCamera = cam.frameBounds(state.sceneCamera, state.bounds, state.sceneSize[0] / state.sceneSize[1]);
  } else {
    state.sceneCamera = sc;
  }
  state.camera = cam.cloneCamera(state.sceneCamera);

  const [sw, sh] = state.sceneSize;
  const sizes = [256, 512, 768, 1024].filter((s) => s <= Math.max(state.limits.max_width || 4096, state.limits.max_height || 4096));
  setOptions($('size'), [['scene', `${sw}×${sh} (scene)`], ...sizes.map((s) => [String(s), `${s} px`])], 'scene');
  setOptions($('method'), ['slicing', 'raycast'], settings['render.method'] || 'raycast');
  $('shading').checked = settings['render.shading'] === true;
  const scenePreint = settings['transfer.preintegrated'] === true ? 'on' : 'off';
  setOptions($('preint'), [['scene', `as in scene (${scenePreint})`], ['auto', 'auto'], ['on', 'on'], ['off', 'off']], 'scene');
  setOptions($('strategy'), ['direct', 'binary-swap', 'radix-k', 'auto'], settings['compositing.strategy'] || 'direct');
  // The scene's own `auto` (the default) leaves the choice to the session; the number box then
  // shows 1 until the user takes it over.
  $('spacing-auto').checked = settings['render.sample_spacing'] === 'auto';
  $('spacing').value = Number.isFinite(settings['render.sample_spacing']) ? settings['render.sample_spacing'] : 1;
  syncSpacingSlider();

  state.steps = Math.max(1, scene.steps | 0);
  state.step = Math.min(Math.max(0, scene.step | 0), state.steps - 1);
  $('time-group').hidden = state.steps <= 1;
  $('step').max = state.steps - 1;
  $('step').value = state.step;
  showStep();

  const hasVolume = scene.has_volume !== false;
  $('volume-controls').hidden = !hasVolume;
  $('tf-group').hidden = !hasVolume;
  // The scene's own transfer function until the user edits it (several fields: the first's).
  loadTfState(tfState(settings));
  state.histogramStep = state.step;
  modes.applyModeSettings(settings);
  setupFields(scene);
  $('modes-group').hidden = !hasVolume;
  showHistogram();
  showLegend();

  const parts = [];
  if (scene.ranks) parts.push(`${scene.ranks} rank${scene.ranks === 1 ? '' : 's'}`);
  const kinds = [scene.has_volume && 'volume',
    scene.has_particles && (Number.isFinite(scene.particles) ? `${scene.particles.toLocaleString('en-US')} particles` : 'particles')].filter(Boolean);
  if (kinds.length) parts.push(kinds.join(' + '));
  if (state.steps > 1) parts.push(`${state.steps} time steps`);
  $('scene-info').textContent = parts.join(' · ');

  canvas.width = fullSize()[0];
  canvas.height = fullSize()[1];
  layoutFrame();
}

async function loadScene() {
  showMessage('Loading the scene…', 'info');
  for (let attempt = 0; ; attempt++) {
    try {
      const res = await fetch(apiUrl('/api/scene'));
      if (!res.ok) {
        let msg = `HTTP ${res.status}`;
        try { msg = (await res.json()).error || msg; } catch { /* not JSON */ }
        throw new Error(msg);
      }
      return await res.json();
    } catch (e) {
      error(`Could not load /api/scene: ${e.message} (retrying)`);
      await new Promise((r) => setTimeout(r, Math.min(1000 * 2 ** attempt, 5000)));
    }
  }
}

async function main() {
  const scene = await loadScene();
  showMessage(null);
  applyScene(scene);
  client.connect();
  submit('full');
}

main();
