// Client-side camera control: orbit, pan and zoom around camera.look_at, and a reset that frames
// the scene's bounds. A camera is {position, look_at, up, fov} (world units, fov = vertical
// degrees), as in /api/scene and the scene keys camera.*; screen right is forward x up.

export const add = (a, b) => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
export const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
export const scale = (a, s) => [a[0] * s, a[1] * s, a[2] * s];
export const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
export const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
export const length = (a) => Math.sqrt(dot(a, a));
export const normalize = (a) => { const l = length(a); return l > 0 ? scale(a, 1 / l) : [0, 0, 0]; };

// Rodrigues' rotation of v about the unit axis k by angle (radians).
export function rotate(v, k, angle) {
  const c = Math.cos(angle), s = Math.sin(angle);
  return add(add(scale(v, c), scale(cross(k, v), s)), scale(k, dot(k, v) * (1 - c)));
}

export const cloneCamera = (c) => ({ position: [...c.position], look_at: [...c.look_at], up: [...c.up], fov: c.fov });

// The camera's orthonormal frame: forward (eye to look_at), right, true up.
export function frame(cam) {
  const forward = normalize(sub(cam.look_at, cam.position));
  let right = normalize(cross(forward, cam.up));
  if (length(right) < 1e-9) {  // up parallel to the view: pick any perpendicular
    right = normalize(cross(forward, Math.abs(forward[1]) < 0.9 ? [0, 1, 0] : [1, 0, 0]));
  }
  const up = cross(right, forward);
  return { forward, right, up };
}

// Rotate the eye (and up) around look_at: dx, dy in pixels of a view viewH pixels high; half
// the view's height turns the scene by 90 degrees. Dragging right turns the scene right.
export function orbit(cam, dx, dy, viewH) {
  const k = Math.PI / Math.max(viewH, 1);
  const f = frame(cam);
  let d = sub(cam.position, cam.look_at);
  let up = f.up;
  const yaw = -dx * k, pitch = -dy * k;
  d = rotate(d, f.up, yaw);
  const right = rotate(f.right, f.up, yaw);
  d = rotate(d, right, pitch);
  up = rotate(up, right, pitch);
  return { ...cam, position: add(cam.look_at, d), up: normalize(up) };
}

// Move eye and look_at in the view plane so the point under the cursor follows it.
export function pan(cam, dx, dy, viewH) {
  const f = frame(cam);
  const dist = length(sub(cam.position, cam.look_at));
  const perPx = (2 * dist * Math.tan((cam.fov * Math.PI) / 360)) / Math.max(viewH, 1);
  const move = add(scale(f.right, -dx * perPx), scale(f.up, dy * perPx));
  return { ...cam, position: add(cam.position, move), look_at: add(cam.look_at, move) };
}

// Scale the eye's distance to look_at by factor (< 1: closer).
export function zoom(cam, factor, bounds) {
  const d = sub(cam.position, cam.look_at);
  let dist = length(d) * factor;
  const r = bounds ? sphere(bounds).radius : 1;
  dist = Math.min(Math.max(dist, r * 1e-3), r * 1e3);
  return keepOutside({ ...cam, position: add(cam.look_at, scale(normalize(d), dist)) }, bounds);
}

export function sphere(bounds) {
  const center = scale(add(bounds.lo, bounds.hi), 0.5);
  return { center, radius: Math.max(length(sub(bounds.hi, bounds.lo)) / 2, 1e-6) };
}

// The renderer refuses an eye inside the scene's box: if the eye is in (or within 2% of) it,
// move it out along the line from look_at through the eye.
export function keepOutside(cam, bounds) {
  if (!bounds) return cam;
  const d = sub(cam.position, cam.look_at);
  const dist = length(d);
  if (dist === 0) return cam;
  const dir = scale(d, 1 / dist);
  const size = sub(bounds.hi, bounds.lo);
  const margin = 0.02 * Math.max(size[0], size[1], size[2]);
  let t0 = -Infinity, t1 = Infinity;
  for (let i = 0; i < 3; i++) {
    const lo = bounds.lo[i] - margin, hi = bounds.hi[i] + margin;
    if (Math.abs(dir[i]) < 1e-12) {
      if (cam.look_at[i] < lo || cam.look_at[i] > hi) return cam;  // the line misses the box
      continue;
    }
    let a = (lo - cam.look_at[i]) / dir[i], b = (hi - cam.look_at[i]) / dir[i];
    if (a > b) [a, b] = [b, a];
    t0 = Math.max(t0, a); t1 = Math.min(t1, b);
  }
  if (t0 > t1 || dist < t0 || dist > t1) return cam;
  return { ...cam, position: add(cam.look_at, scale(dir, t1 * 1.001)) };
}

// A camera looking at the centre of bounds from the direction of cam's eye, far enough that the
// bounding sphere fits in both the vertical and the horizontal field of view (aspect = w / h).
export function frameBounds(cam, bounds, aspect = 1) {
  const { center, radius } = sphere(bounds);
  let dir = normalize(sub(cam.position, cam.look_at));
  if (length(dir) === 0) dir = [0, 0, 1];
  const vhalf = (cam.fov * Math.PI) / 360;
  const hhalf = Math.atan(Math.tan(vhalf) * aspect);
  const half = Math.min(vhalf, hhalf);
  const dist = (radius / Math.sin(half)) * 1.02;
  const position = add(center, scale(dir, dist));
  // keep the given up unless it is (nearly) parallel to the view
  const up = length(cross(dir, normalize(cam.up))) > 1e-3 ? [...cam.up] : frame({ position, look_at: center, up: cam.up }).up;
  return keepOutside({ position, look_at: center, up, fov: cam.fov }, bounds);
}
