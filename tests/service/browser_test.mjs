// Headless-browser test of the `sortlast serve` web viewer.
//   node browser_test.mjs URL OUTDIR [SORTLAST_BIN]
// URL: the viewer (e.g. http://127.0.0.1:8080/?token=T). Loads it in Debian's chromium, waits for
// the first frame, orbits with a mouse drag, waits for the full-size frame, checks the image
// changed, saves it with the Save button (OUTDIR/frame.png) and writes what the page reports:
//   camera.json    window.sortlastViewer.lastCamera (the camera the frame was rendered with)
//   request.json   the request body of that frame (every key the viewer set)
//   render_args.txt  `--set key=value` arguments (one per line) for `sortlast render` to
//                  render the same frame (camera from camera.json, the rest from request.json)
// then drags a transfer-function point, checks the image changed again and saves that frame too
// (tf_frame.png, tf_request.json, tf_render_args.txt), then picks the Viridis colour map, checks
// the request names it (transfer.colormap) and the image changed, and saves that frame
// (cm_frame.png, cm_request.json, cm_render_args.txt), then turns shading on, checks the request
// has render.shading and the image changed (sh_frame.png, ...), picks MIP (render.blend;
// mip_frame.png, ...), then turns a clip plane on and moves it by Alt-dragging the frame
// (clip.planes; clip_frame.png, ...); with FIELDS_SCENE_NAME set (browser.sh), a scene of several
// fields: field 1's transfer function and field 0 hidden (fields_*, fhide_*). Screenshots:
// initial.png, orbit.png, fields.png, final.png. Every wait is bounded; exits 1 with a message on failure.

import { chromium } from 'playwright-core';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';

const [url, outDir, sortlastBin] = process.argv.slice(2);
if (!url || !outDir) {
  console.error('usage: node browser_test.mjs URL OUTDIR [SORTLAST_BIN]');
  process.exit(2);
}
const CHROMIUM = process.env.CHROMIUM || '/usr/bin/chromium';
const WAIT_MS = Number(process.env.BROWSER_TEST_WAIT_MS || 60000);   // any single wait
const TOTAL_MS = Number(process.env.BROWSER_TEST_TOTAL_MS || 300000); // the whole test
fs.mkdirSync(outDir, { recursive: true });

const log = (...a) => console.log('[browser_test]', ...a);
let browser = null;
let userDataDir = null;
async function cleanup() {
  if (browser) await browser.close().catch(() => {});
  browser = null;
  if (userDataDir) fs.rmSync(userDataDir, { recursive: true, force: true });
  userDataDir = null;
}
async function fail(msg) {
  console.error(`FAIL: ${msg}`);
  if (page) await page.screenshot({ path: path.join(outDir, 'failure.png') }).catch(() => {});
  await cleanup();
  process.exit(1);
}
const watchdog = setTimeout(() => fail(`the test took longer than ${TOTAL_MS / 1000} s`), TOTAL_MS);

let page = null;
const pageErrors = [];

// Wait for fn (run in the page) to return truthy, at most WAIT_MS.
async function waitFor(what, fn, arg) {
  try {
    await page.waitForFunction(fn, arg, { timeout: WAIT_MS, polling: 50 });
  } catch (e) {
    const msg = await page.evaluate(() => window.sortlastViewer && window.sortlastViewer.message).catch(() => null);
    await fail(`timed out after ${WAIT_MS / 1000} s waiting for ${what}` +
      (msg ? ` (the page says: ${msg.text})` : '') +
      (pageErrors.length ? `; page errors: ${pageErrors.join(' | ')}` : ''));
  }
}

// The frame canvas, scaled down to 64x64 RGBA, as a plain array.
const snapshot = () => page.evaluate(() => {
  const src = document.getElementById('frame');
  const c = document.createElement('canvas');
  c.width = 64; c.height = 64;
  const g = c.getContext('2d');
  g.drawImage(src, 0, 0, 64, 64);
  return Array.from(g.getImageData(0, 0, 64, 64).data);
});
// Mean absolute difference (0..255) over the colour channels, and the share of pixels that differ.
function difference(a, b) {
  let sum = 0, changed = 0;
  for (let i = 0; i < a.length; i += 4) {
    let d = 0;
    for (let k = 0; k < 3; k++) d = Math.max(d, Math.abs(a[i + k] - b[i + k]));
    sum += Math.abs(a[i] - b[i]) + Math.abs(a[i + 1] - b[i + 1]) + Math.abs(a[i + 2] - b[i + 2]);
    if (d > 8) changed++;
  }
  return { mean: sum / ((a.length / 4) * 3), changed: changed / (a.length / 4) };
}
const viewerState = () => page.evaluate(() => {
  const v = window.sortlastViewer;
  return {
    framesShown: v.framesShown, shown: { ...v.shown }, lastCamera: v.lastCamera, lastStats: v.lastStats,
    lastRequest: v.lastRequest, latencies: v.latencies, message: v.message, transport: v.transport,
  };
});

// `--set` arguments for sortlast render that reproduce a frame: every key of the request
// (values as JSON, which YAML reads), the camera and image size from the frame's stats.
function renderArgs(request, camera, stats) {
  const keys = { ...request };
  delete keys.format;
  delete keys.quality;
  // render.sample_spacing: auto is a policy, not a step: the service probes for the frames a
  // session will serve, a batch job of one frame takes a still image's step checked by its own
  // estimate (session/auto_spacing.h), so the same frame is the step the service chose.
  if (keys['render.sample_spacing'] === 'auto' && stats && Number.isFinite(stats.sample_spacing))
    keys['render.sample_spacing'] = stats.sample_spacing;
  if (camera) {
    for (const k of ['position', 'look_at', 'up', 'fov']) if (camera[k] !== undefined) keys[`camera.${k}`] = camera[k];
    if (camera.width) keys['image.width'] = camera.width;
    if (camera.height) keys['image.height'] = camera.height;
  }
  return Object.entries(keys).flatMap(([k, v]) => ['--set', `${k}=${JSON.stringify(v)}`]);
}

// Click Save image and keep the download.
async function saveFrame(file) {
  let download;
  try {
    [download] = await Promise.all([page.waitForEvent('download', { timeout: WAIT_MS }), page.click('#save')]);
  } catch (e) {
    await fail(`Save image did not download a file: ${e.message}`);
  }
  await download.saveAs(path.join(outDir, file));
  const head = fs.readFileSync(path.join(outDir, file)).subarray(0, 8);
  if (!head.equals(Buffer.from([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]))) await fail(`${file} is not a PNG`);
}

function writeFrameFiles(prefix, st) {
  fs.writeFileSync(path.join(outDir, `${prefix}camera.json`), JSON.stringify(st.lastCamera, null, 2) + '\n');
  fs.writeFileSync(path.join(outDir, `${prefix}request.json`), JSON.stringify(st.lastRequest, null, 2) + '\n');
  fs.writeFileSync(path.join(outDir, `${prefix}stats.json`), JSON.stringify(st.lastStats, null, 2) + '\n');
  const args = renderArgs(st.lastRequest, st.lastCamera, st.lastStats);
  fs.writeFileSync(path.join(outDir, `${prefix}render_args.txt`), args.join('\n') + '\n');
  return args;
}

async function main() {
  userDataDir = fs.mkdtempSync(path.join(os.tmpdir(), 'sortlast-chromium-'));
  try {
    const context = await chromium.launchPersistentContext(userDataDir, {
      executablePath: CHROMIUM,
      headless: true,
      args: ['--headless=new', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
        '--disable-background-networking', '--disable-component-update', '--disable-sync'],
      viewport: { width: 1280, height: 800 },
      acceptDownloads: true,
      timeout: WAIT_MS,
    });
    browser = context;
    page = context.pages()[0] || await context.newPage();
  } catch (e) {
    await fail(`could not start ${CHROMIUM}: ${e.message}`);
  }
  page.on('pageerror', (e) => { pageErrors.push(e.message); console.error('page error:', e.message); });
  page.on('console', (m) => { if (m.type() === 'error') console.error('page console:', m.text()); });

  log(`loading ${url.replace(/token=[^&]*/, 'token=…')}`);
  try {
    await page.goto(url, { timeout: WAIT_MS });
  } catch (e) {
    await fail(`could not load the viewer: ${e.message}`);
  }
  await waitFor('the first frame', () => window.sortlastViewer && window.sortlastViewer.ready);
  await waitFor('the first full-size frame', () => window.sortlastViewer.settled);
  await page.screenshot({ path: path.join(outDir, 'initial.png') });
  const first = await viewerState();
  log(`first frame shown (${first.transport}); latency ${first.latencies[0].toFixed(0)} ms; camera ${JSON.stringify(first.lastCamera)}`);
  if (!first.lastCamera || !Array.isArray(first.lastCamera.position)) await fail('the frame stats hold no camera');
  // A scene that leaves render.sample_spacing at `auto` (the default) keeps it: the box is
  // ticked, the request says auto, and the stats give the step the session chose.
  const autoShown = await page.evaluate(() => document.getElementById('spacing-auto').checked);
  if (first.lastStats.sample_spacing_auto) {
    if (!autoShown || first.lastRequest['render.sample_spacing'] !== 'auto')
      await fail(`the scene's sample spacing is auto but the viewer sent ${JSON.stringify(first.lastRequest['render.sample_spacing'])}`);
    log(`sample spacing: auto chose ${first.lastStats.sample_spacing} voxel`);
  }
  const before = await snapshot();

  // ---- orbit: drag across the frame
  const box = await page.locator('#frame').boundingBox();
  if (!box || box.width < 50 || box.height < 50) await fail(`the frame is too small to drag: ${JSON.stringify(box)}`);
  const cx = box.x + box.width / 2, cy = box.y + box.height / 2;
  await page.mouse.move(cx - box.width * 0.2, cy);
  await page.mouse.down();
  for (let i = 1; i <= 20; i++) {
    await page.mouse.move(cx - box.width * 0.2 + (box.width * 0.4 * i) / 20, cy - (box.height * 0.1 * i) / 20);
    await page.waitForTimeout(40);
  }
  // hold still at the end of the drag until a reduced frame is up (bounded), then release
  await page.waitForFunction(() => window.sortlastViewer.shown.reduced > 0, null, { timeout: WAIT_MS }).catch(() => {});
  await page.mouse.up();
  await waitFor('the full-size frame after the orbit', (n) => window.sortlastViewer.settled && window.sortlastViewer.framesShown > n, first.framesShown);
  const orbited = await viewerState();
  if (orbited.shown.reduced < 1) await fail('no reduced frame was shown while dragging');
  if (orbited.lastRequest.format !== 'png') await fail(`the final frame is not a PNG request: ${JSON.stringify(orbited.lastRequest)}`);
  const same = ['position', 'up'].every((k) => JSON.stringify(orbited.lastCamera[k]) === JSON.stringify(first.lastCamera[k]));
  if (same) await fail('the camera did not change after the drag');
  const after = await snapshot();
  const d1 = difference(before, after);
  log(`after the orbit: ${orbited.shown.reduced} reduced + ${orbited.shown.full} full frames shown; image difference mean ${d1.mean.toFixed(2)}, ${(d1.changed * 100).toFixed(1)}% of pixels`);
  if (d1.mean < 0.5 && d1.changed < 0.005) await fail('the image did not change after orbiting');
  await page.screenshot({ path: path.join(outDir, 'orbit.png') });
  await saveFrame('frame.png');
  const args = writeFrameFiles('', orbited);
  log(`camera: ${JSON.stringify(orbited.lastCamera)}`);
  if (sortlastBin) log(`same frame: mpirun -np N ${sortlastBin} render [SCENE] -o render.png ${args.map((a) => (a.startsWith('--') ? a : `'${a}'`)).join(' ')}`);

  // ---- transfer function: drag a control point
  const hasTf = await page.locator('#tf-canvas').isVisible();
  if (!hasTf) {
    log('the scene has no volume: no transfer-function editor to test');
  } else {
    const handles = await page.evaluate(() => window.sortlastViewer.tfHandles());
    if (!handles.length) await fail('the transfer-function editor shows no points');
    // the point whose opacity can change most (interior points first: the ends of the range
    // are often empty), dragged to opacity 1 (from below 0.5) or 0 (from above)
    const interior = handles.length > 2 ? handles.slice(1, -1) : handles;
    const h = interior.reduce((best, p) => (Math.max(p.opacity, 1 - p.opacity) > Math.max(best.opacity, 1 - best.opacity) ? p : best));
    const i = handles.indexOf(h);
    const tfBox = await page.locator('#tf-canvas').boundingBox();
    const targetY = h.opacity < 0.5 ? tfBox.y - 10 : tfBox.y + tfBox.height + 10;
    const beforeTf = after;
    const n0 = (await viewerState()).framesShown;
    await page.mouse.move(h.x, h.y);
    await page.mouse.down();
    for (let k = 1; k <= 10; k++) {
      await page.mouse.move(h.x, h.y + ((targetY - h.y) * k) / 10);
      await page.waitForTimeout(40);
    }
    await page.mouse.up();
    await waitFor('the full-size frame after the transfer-function edit', (n) => window.sortlastViewer.settled && window.sortlastViewer.framesShown > n, n0);
    const edited = await viewerState();
    if (!Array.isArray(edited.lastRequest['transfer.points'])) await fail('the request after the edit holds no transfer.points');
    const moved = await page.evaluate(() => window.sortlastViewer.tfHandles());
    log(`moved point ${i} from opacity ${h.opacity.toFixed(3)} to ${moved[i].opacity.toFixed(3)}; request has ${edited.lastRequest['transfer.points'].length} transfer points`);
    const d2 = difference(beforeTf, await snapshot());
    log(`after the edit: image difference mean ${d2.mean.toFixed(2)}, ${(d2.changed * 100).toFixed(1)}% of pixels`);
    if (d2.mean < 0.5 && d2.changed < 0.005) await fail('the image did not change after the transfer-function edit');
    await saveFrame('tf_frame.png');
    writeFrameFiles('tf_', edited);

    // ---- colour map: one of the viewer's presets, drawn with the server's definition
    const beforeCm = await snapshot();
    const n1 = (await viewerState()).framesShown;
    await page.selectOption('#colormap', 'Viridis');
    await waitFor('the full-size frame after choosing a colour map', (n) => window.sortlastViewer.settled && window.sortlastViewer.framesShown > n, n1);
    const coloured = await viewerState();
    if (coloured.lastRequest['transfer.colormap'] !== 'Viridis')
      await fail(`the request after choosing Viridis has transfer.colormap ${JSON.stringify(coloured.lastRequest['transfer.colormap'])}`);
    const d3 = difference(beforeCm, await snapshot());
    log(`after choosing Viridis: image difference mean ${d3.mean.toFixed(2)}, ${(d3.changed * 100).toFixed(1)}% of pixels`);
    if (d3.mean < 0.5 && d3.changed < 0.005) await fail('the image did not change with the colour map');
    await saveFrame('cm_frame.png');
    writeFrameFiles('cm_', coloured);

    // ---- shading: the checkbox sends render.shading and the image changes
    const beforeSh = await snapshot();
    const n2 = (await viewerState()).framesShown;
    await page.check('#shading');
    await waitFor('the full-size frame after turning shading on', (n) => window.sortlastViewer.settled && window.sortlastViewer.framesShown > n, n2);
    const shaded = await viewerState();
    if (shaded.lastRequest['render.shading'] !== true)
      await fail(`the request after turning shading on has render.shading ${JSON.stringify(shaded.lastRequest['render.shading'])}`);
    const d4 = difference(beforeSh, await snapshot());
    log(`after turning shading on: image difference mean ${d4.mean.toFixed(2)}, ${(d4.changed * 100).toFixed(1)}% of pixels`);
    if (d4.mean < 0.5 && d4.changed < 0.005) await fail('the image did not change with shading');
    await saveFrame('sh_frame.png');
    writeFrameFiles('sh_', shaded);

    // ---- the volume's modes: maximum intensity projection, then a clip plane dragged with Alt
    const beforeMip = await snapshot();
    const n3 = (await viewerState()).framesShown;
    await page.uncheck('#shading');
    await page.selectOption('#blend', 'mip');
    await waitFor('the full-size frame after choosing MIP', (n) => window.sortlastViewer.settled && window.sortlastViewer.framesShown > n, n3);
    const mip = await viewerState();
    if (mip.lastRequest['render.blend'] !== 'mip')
      await fail(`the request after choosing MIP has render.blend ${JSON.stringify(mip.lastRequest['render.blend'])}`);
    const d5 = difference(beforeMip, await snapshot());
    log(`after choosing MIP: image difference mean ${d5.mean.toFixed(2)}, ${(d5.changed * 100).toFixed(1)}% of pixels`);
    if (d5.mean < 0.5 && d5.changed < 0.005) await fail('the image did not change with MIP');
    await saveFrame('mip_frame.png');
    writeFrameFiles('mip_', mip);

    const n4 = (await viewerState()).framesShown;
    await page.selectOption('#blend', 'composite');
    await page.check('#clip-on');
    await waitFor('the full-size frame after turning the clip plane on', (n) => window.sortlastViewer.settled && window.sortlastViewer.framesShown > n, n4);
    const beforeClip = await snapshot();
    const p0 = await page.evaluate(() => Number(document.getElementById('clip-pos').value));
    const n5 = (await viewerState()).framesShown;
    await page.keyboard.down('Alt');
    await page.mouse.move(cx, cy - box.height * 0.2);
    await page.mouse.down();
    for (let k = 1; k <= 10; k++) {
      await page.mouse.move(cx, cy - box.height * 0.2 + (box.height * 0.15 * k) / 10);
      await page.waitForTimeout(40);
    }
    await page.mouse.up();
    await page.keyboard.up('Alt');
    await waitFor('the full-size frame after dragging the clip plane', (n) => window.sortlastViewer.settled && window.sortlastViewer.framesShown > n, n5);
    const clipped = await viewerState();
    const p1 = await page.evaluate(() => Number(document.getElementById('clip-pos').value));
    const planes = clipped.lastRequest['clip.planes'];
    if (!Array.isArray(planes) || planes.length !== 1) await fail(`the request after the clip drag has clip.planes ${JSON.stringify(planes)}`);
    if (!(p1 > p0)) await fail(`Alt-dragging the frame did not move the clip plane (${p0} -> ${p1})`);
    const d6 = difference(beforeClip, await snapshot());
    log(`clip plane dragged from ${p0.toFixed(3)} to ${p1.toFixed(3)} of the box: image difference mean ${d6.mean.toFixed(2)}, ${(d6.changed * 100).toFixed(1)}% of pixels`);
    if (d6.mean < 0.5 && d6.changed < 0.005) await fail('the image did not change when the clip plane moved');
    await saveFrame('clip_frame.png');
    writeFrameFiles('clip_', clipped);
  }

  // ---- several fields (browser.sh's FIELDS.yaml, loaded through --data-dir): pick field 1 in the
  // selector, drag one of its transfer points (fields_frame.png, ...), hide field 0 with its
  // checkbox (fhide_frame.png, ...); browser.sh renders both with `sortlast render`.
  const fieldsScene = process.env.FIELDS_SCENE_NAME;
  if (fieldsScene) {
    const tFields = Date.now();
    const loadUrl = new URL('/api/load', url);
    loadUrl.search = new URL(url).search;
    const res = await fetch(loadUrl, { method: 'POST', body: JSON.stringify({ scene: fieldsScene }) });
    if (!res.ok) await fail(`POST /api/load ${fieldsScene} answered ${res.status}: ${await res.text()}`);
    await page.reload({ timeout: WAIT_MS });
    await waitFor('the fields scene\'s first full-size frame', () => window.sortlastViewer && window.sortlastViewer.ready && window.sortlastViewer.settled);
    if (!(await page.locator('#field').isVisible())) await fail('a scene of several fields shows no field selector');
    // A fixed step: with `auto` every transfer-function edit probes again (3 more frames each).
    const nFix = (await viewerState()).framesShown;
    await page.fill('#spacing', '1');
    await page.dispatchEvent('#spacing', 'change');
    await waitFor('the full-size frame at 1 voxel', (n) => window.sortlastViewer.settled && window.sortlastViewer.framesShown > n, nFix);
    const base = await snapshot();
    const f0 = await viewerState();
    await page.selectOption('#field', '1');
    if ((await page.evaluate(() => window.sortlastViewer.field)) !== 1) await fail('the field selector did not pick field 1');
    await page.locator('#tf-canvas').scrollIntoViewIfNeeded();
    const handles = await page.evaluate(() => window.sortlastViewer.tfHandles());
    // (a scene's colour map arrives as many points: the one nearest the middle of the range)
    const h = handles.reduce((best, p) => (Math.abs(p.value - 0.6) < Math.abs(best.value - 0.6) ? p : best));
    const hi = handles.indexOf(h);
    const tfBox = await page.locator('#tf-canvas').boundingBox();
    const targetY = h.opacity < 0.5 ? tfBox.y - 10 : tfBox.y + tfBox.height + 10;
    await page.mouse.move(h.x, h.y);
    await page.mouse.down();
    for (let k = 1; k <= 5; k++) { await page.mouse.move(h.x, h.y + ((targetY - h.y) * k) / 5); await page.waitForTimeout(40); }
    await page.mouse.up();
    await waitFor('the full-size frame after editing field 1', (n) => window.sortlastViewer.settled && window.sortlastViewer.framesShown > n, f0.framesShown);
    const movedTo = (await page.evaluate(() => window.sortlastViewer.tfHandles()))[hi];
    log(`field 1: moved point ${hi} (value ${h.value.toFixed(3)}) from opacity ${h.opacity.toFixed(3)} to ${movedTo.opacity.toFixed(3)}`);
    if (Math.abs(movedTo.opacity - h.opacity) < 0.3) await fail('the drag did not move field 1\'s point');
    // and field 1's colour map (inferno in the scene)
    const n6 = (await viewerState()).framesShown;
    await page.selectOption('#colormap', 'Viridis');
    await waitFor('the full-size frame after field 1\'s colour map', (n) => window.sortlastViewer.settled && window.sortlastViewer.framesShown > n, n6);
    const edited = await viewerState();
    const sent = Object.keys(edited.lastRequest);
    if (!Array.isArray(edited.lastRequest['volumes[1].transfer.points']) || edited.lastRequest['volumes[1].transfer.colormap'] !== 'Viridis' ||
        sent.some((k) => k.startsWith('volumes[0].transfer.points') || k.startsWith('volumes[0].transfer.colormap') || k.startsWith('transfer.')))
      await fail(`editing field 1 sent ${JSON.stringify(sent)}`);
    const d7 = difference(base, await snapshot());
    log(`field 1's point moved and colour map Viridis: image difference mean ${d7.mean.toFixed(2)}, ${(d7.changed * 100).toFixed(1)}% of pixels`);
    if (d7.mean < 0.5 && d7.changed < 0.005) await fail('the image did not change when field 1\'s transfer function did');
    await saveFrame('fields_frame.png');
    writeFrameFiles('fields_', edited);
    const beforeHide = await snapshot();
    await page.uncheck('#field-visible-0');
    await waitFor('the full-size frame after hiding field 0', (n) => window.sortlastViewer.settled && window.sortlastViewer.framesShown > n, edited.framesShown);
    const hidden = await viewerState();
    if (hidden.lastRequest['volumes[0].visible'] !== false || !Array.isArray(hidden.lastRequest['volumes[1].transfer.points']))
      await fail(`hiding field 0 sent ${JSON.stringify(hidden.lastRequest)}`);
    const d8 = difference(beforeHide, await snapshot());
    log(`field 0 hidden: image difference mean ${d8.mean.toFixed(2)}, ${(d8.changed * 100).toFixed(1)}% of pixels`);
    if (d8.mean < 0.5 && d8.changed < 0.005) await fail('the image did not change when field 0 was hidden');
    await saveFrame('fhide_frame.png');
    writeFrameFiles('fhide_', hidden);
    await page.screenshot({ path: path.join(outDir, 'fields.png') });
    log(`several fields: ${((Date.now() - tFields) / 1000).toFixed(1)} s`);
  }

  const end = await viewerState();
  if (end.message && end.message.kind === 'error') await fail(`the page shows an error: ${end.message.text}`);
  if (pageErrors.length) await fail(`page errors: ${pageErrors.join(' | ')}`);
  await page.screenshot({ path: path.join(outDir, 'final.png') });
  const lat = end.latencies.slice(-20);
  log(`OK: ${end.framesShown} frames shown; latency last ${lat[lat.length - 1].toFixed(0)} ms, mean of last ${lat.length} ${(lat.reduce((a, b) => a + b, 0) / lat.length).toFixed(0)} ms`);
  clearTimeout(watchdog);
  await cleanup();
}

main().catch((e) => fail(e.stack || String(e)));
