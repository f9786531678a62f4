// The viewer's camera and colour-map math, without a browser: node viewer_math_test.mjs
import assert from 'node:assert/strict';
import * as cam from '../../viewer/orbit.js';
import { PRESETS, sampleKnots } from '../../viewer/colormaps.js';

const near = (a, b, eps = 1e-9) => assert.ok(Math.abs(a - b) <= eps, `${a} != ${b}`);
const bounds = { lo: [-64, -64, -64], hi: [64, 64, 64] };
const c0 = { position: [118, 75, 214], look_at: [0, 0, 0], up: [0, 1, 0], fov: 35 };
const dist = (c) => cam.length(cam.sub(c.position, c.look_at));

// Orbit keeps the distance to look_at and an up orthogonal to the view; dragging right moves
// the eye left (the scene turns right), dragging down moves it up.
{
  const f0 = cam.frame(c0);
  const c1 = cam.orbit(c0, 30, 0, 500);
  near(dist(c1), dist(c0), 1e-9);
  assert.ok(cam.dot(cam.sub(c1.position, c0.position), f0.right) < 0, 'drag right: eye moves left');
  const c2 = cam.orbit(c0, 0, 30, 500);
  assert.ok(cam.dot(cam.sub(c2.position, c0.position), f0.up) > 0, 'drag down: eye moves up');
  let c = c0;
  for (let i = 0; i < 200; i++) c = cam.orbit(c, 13, -7, 400);  // tumble, also over the poles
  near(dist(c), dist(c0), 1e-6);
  near(cam.dot(cam.normalize(c.up), cam.frame(c).forward), 0, 1e-9);
  near(cam.length(c.up), 1, 1e-9);
}
// Pan moves eye and look_at together; half a view height of drag moves by half the view height
// at look_at's distance.
{
  const c1 = cam.pan(c0, 0, 250, 500);
  const move = cam.sub(c1.look_at, c0.look_at);
  near(cam.length(cam.sub(cam.sub(c1.position, c0.position), move)), 0, 1e-9);
  near(cam.length(move), dist(c0) * Math.tan((35 * Math.PI) / 360), 1e-9);
}
// Zoom scales the distance but never puts the eye inside the box.
{
  near(dist(cam.zoom(c0, 0.5, bounds)), dist(c0) * 0.5, 1e-9);
  const c1 = cam.zoom(c0, 0.01, bounds);
  const p = c1.position;
  assert.ok(p.some((v, i) => v < bounds.lo[i] || v > bounds.hi[i]), `eye inside the box: ${p}`);
}
// Reset frames the bounding sphere: its angular radius fits the smaller half field of view.
for (const aspect of [1, 2, 0.5]) {
  const c = cam.frameBounds(c0, bounds, aspect);
  const { center, radius } = cam.sphere(bounds);
  near(cam.length(cam.sub(c.look_at, center)), 0, 1e-9);
  const half = Math.min((35 * Math.PI) / 360, Math.atan(Math.tan((35 * Math.PI) / 360) * aspect));
  const angular = Math.asin(radius / dist(c));
  assert.ok(angular <= half && angular > half * 0.95, `aspect ${aspect}: ${angular} vs ${half}`);
  near(cam.dot(cam.normalize(cam.sub(c.position, c.look_at)), cam.normalize(cam.sub(c0.position, c0.look_at))), 1, 1e-9);
}
// Colour maps: knots from 0 to 1, colours in [0, 1], sampling interpolates and clamps.
for (const [name, knots] of Object.entries(PRESETS)) {
  assert.equal(knots[0][0], 0, name);
  assert.equal(knots[knots.length - 1][0], 1, name);
  for (let i = 1; i < knots.length; i++) assert.ok(knots[i][0] > knots[i - 1][0], name);
  for (const k of knots) for (const v of k.slice(1)) assert.ok(v >= 0 && v <= 1, name);
}
assert.deepEqual(sampleKnots(PRESETS.Grayscale, 0.25), [0.25, 0.25, 0.25]);
assert.deepEqual(sampleKnots(PRESETS.Grayscale, -1), [0, 0, 0]);
assert.deepEqual(sampleKnots(PRESETS.Grayscale, 2), [1, 1, 1]);
console.log('viewer math ok');
