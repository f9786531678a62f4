// The volume's modes in the viewer: blend mode (emission-absorption, the projections, isosurface
// with one isovalue), projection (perspective or orthographic), one clip plane (an axis or the view
// direction, moved by its slider or by Alt-dragging the frame), the transfer function's scale, and
// whether the colour legend (value_scale.js) is drawn over the frame. Each control becomes scene keys of the frame request
// (docs/scene.md); keys the server does not take (its request_keys) are dropped by the caller.
import * as cam from './orbit.js';

const $ = (id) => document.getElementById(id);

// The scene keys of the mode controls, added to request r. `camera` is the view being asked for;
// `bounds` the scene's box {lo, hi}; `range` the transfer function's [lo, hi] in data units.
export function modeKeys(r, { camera, bounds, range }) {
  r['render.blend'] = $('blend').value;
  if ($('blend').value === 'isosurface') {
    r['render.isovalues'] = [{ value: isoValue(range), color: [0.9, 0.9, 0.9], opacity: Number($('iso-opacity').value) }];
  }
  const ortho = $('projection').value === 'orthographic';
  r['camera.projection'] = ortho ? 'orthographic' : 'perspective';
  if (ortho) {
    // The view height the perspective camera shows at look_at: switching keeps the framing.
    const dist = cam.length(cam.sub(camera.position, camera.look_at));
    r['camera.parallel_scale'] = Math.max(1e-6, dist * Math.tan((camera.fov * Math.PI) / 360));
  }
  r['clip.planes'] = $('clip-on').checked ? [clipPlane(camera, bounds)] : [];
  r['transfer.scale'] = $('tf-scale').value;
}

// The isovalue of the slider (0..1 over the transfer function's range), in data units.
function isoValue(range) {
  const [lo, hi] = range;
  return lo + (hi - lo) * Number($('iso-value').value);
}

// The clip plane {normal, offset} keeping n . x <= offset: its normal is an axis (or the view
// direction), its offset the slider's fraction of the box's extent along that normal; "flip"
// keeps the other side.
function clipPlane(camera, bounds) {
  const n = clipNormal(camera);
  const [lo, hi] = extent(n, bounds);
  const offset = lo + (hi - lo) * Number($('clip-pos').value);
  return $('clip-flip').checked ? { normal: cam.scale(n, -1), offset: -offset } : { normal: n, offset };
}

function clipNormal(camera) {
  const axis = $('clip-axis').value;
  if (axis === 'view') return cam.frame(camera).forward.map((v) => Math.round(v * 1e6) / 1e6);
  return { x: [1, 0, 0], y: [0, 1, 0], z: [0, 0, 1] }[axis];
}

// The smallest and largest n . x over the box's corners.
function extent(n, bounds) {
  let lo = Infinity, hi = -Infinity;
  for (let i = 0; i < 8; i++) {
    const p = [i & 1 ? bounds.hi[0] : bounds.lo[0], i & 2 ? bounds.hi[1] : bounds.lo[1], i & 4 ? bounds.hi[2] : bounds.lo[2]];
    const d = cam.dot(n, p);
    lo = Math.min(lo, d); hi = Math.max(hi, d);
  }
  return [lo, hi];
}

// Alt-dragging the frame moves the clip plane along its normal: dy pixels of a view viewH high
// move it by dy / viewH of the box's extent (down: towards the far side of the normal).
export function dragClip(dy, viewH) {
  if (!$('clip-on').checked) return false;
  const v = Math.min(1, Math.max(0, Number($('clip-pos').value) + dy / Math.max(viewH, 1)));
  $('clip-pos').value = v;
  return true;
}

// Whether the eye may enter the data (a fly-through); the orbit then does not push it out.
export const flyInside = () => $('fly-inside').checked;

// The scene's settings into the controls.
export function applyModeSettings(settings) {
  const pick = (select, value) => { if ([...select.options].some((o) => o.value === value)) select.value = value; };
  pick($('blend'), settings['render.blend'] || 'composite');
  pick($('projection'), settings['camera.projection'] || 'perspective');
  pick($('tf-scale'), settings['transfer.scale'] || 'linear');
  const legend = settings['image.legend'];
  $('legend-on').checked = !!(legend && legend.position && legend.position !== 'none');
  const planes = settings['clip.planes'];
  $('clip-on').checked = Array.isArray(planes) && planes.length > 0;
  showModeControls();
}

export function showModeControls() {
  $('iso-controls').hidden = $('blend').value !== 'isosurface';
  $('clip-controls').hidden = !$('clip-on').checked;
}
