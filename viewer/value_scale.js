// transfer.scale in the viewer (the server's definition: transfer/value_scale.h): a value's place
// in the transfer range, its inverse, and the colour legend drawn over the frame from the
// transfer function the viewer already has (image.legend of the scene; the written frames' legend
// is session/frame_legend.cpp, with the same ticks).

const C = 1 / (1 - 0.1);  // SymLogNorm's linscale / (1 - 1 / base)

export function scaled(v, scale, w) {
  if (scale === 'log') return v > 0 ? Math.log10(v) : -Infinity;
  if (scale === 'symlog') {
    const a = Math.abs(v);
    return a <= w ? v * C : Math.sign(v) * w * (C + Math.log10(a / w));
  }
  return v;
}

export function unscaled(s, scale, w) {
  if (scale === 'log') return 10 ** s;
  if (scale === 'symlog') {
    const a = Math.abs(s);
    return a <= w * C ? s / C : Math.sign(s) * w * 10 ** (a / w - C);
  }
  return s;
}

// {place(v) -> [0, 1] (clamped), value(x) -> data value} over range [lo, hi].
export function valueScale(range, scale = 'linear', w = 1) {
  const [lo, hi] = range;
  const slo = scaled(lo, scale, w), shi = scaled(hi, scale, w);
  const ok = Number.isFinite(slo) && Number.isFinite(shi) && shi > slo;
  return {
    place: (v) => {
      if (!ok) return Math.min(Math.max((v - lo) / (hi - lo || 1), 0), 1);
      const s = scaled(v, scale, w);
      return Math.min(Math.max((s - slo) / (shi - slo), 0), 1) || 0;
    },
    value: (x) => (ok ? unscaled(slo + x * (shi - slo), scale, w) : lo + x * (hi - lo)),
  };
}

function decade(k) { return k >= 0 && k <= 3 ? String(10 ** k) : `1e${k}`; }

// About `count` ticks [{value, label}] as the server's legendTicks picks them.
export function legendTicks(range, scale, w, count) {
  const [lo, hi] = range;
  const out = [];
  if (scale === 'log' && lo > 0) {
    const k0 = Math.ceil(Math.log10(lo) - 1e-9), k1 = Math.floor(Math.log10(hi) + 1e-9);
    const every = Math.max(1, Math.ceil((k1 - k0 + 1) / count));
    for (let k = k0; k <= k1; k += every) out.push({ value: 10 ** k, label: decade(k) });
    if (out.length >= 2) return out;
  }
  if (scale === 'symlog') {
    const c = [];
    if (lo <= 0 && hi >= 0) c.push(0);
    for (let k = Math.ceil(Math.log10(w) - 1e-9); 10 ** k <= Math.max(-lo, hi); k++) c.push(10 ** k, -(10 ** k));
    const inside = c.filter((v) => v >= lo && v <= hi).sort((a, b) => a - b);
    const every = Math.max(1, Math.ceil(inside.length / count));
    let centre = inside.indexOf(0);
    if (centre < 0) centre = Math.floor(inside.length / 2);
    inside.forEach((v, i) => {
      if ((i - centre) % every === 0)
        out.push({ value: v, label: v === 0 ? '0' : (v < 0 ? '-' : '') + decade(Math.round(Math.log10(Math.abs(v)))) });
    });
    return out;
  }
  const raw = (hi - lo) / Math.max(1, count - 1);
  const mag = 10 ** Math.floor(Math.log10(raw || 1));
  let step = 10 * mag, best = Infinity;
  for (const m of [10, 5, 2, 1]) {
    const n = Math.floor(hi / (m * mag) + 1e-9) - Math.ceil(lo / (m * mag) - 1e-9) + 1;
    if (Math.abs(n - count) < best) { best = Math.abs(n - count); step = m * mag; }
  }
  const digits = Math.min(6, Math.max(0, Math.ceil(-Math.log10(step) - 1e-9)));
  for (let v = Math.ceil(lo / step - 1e-9) * step; v <= hi + 1e-9 * step; v += step) {
    const x = Math.abs(v) < 1e-12 * step ? 0 : v;
    out.push({ value: x, label: Math.abs(x) >= 1e5 || (x !== 0 && Math.abs(x) < 1e-3) ? x.toExponential(2) : x.toFixed(digits) });
  }
  return out;
}

// Draws the legend into `canvas` (an overlay of the frame's size in CSS pixels): a bar of
// colour(x) ([r, g, b] in 0..1) plain, low end at the bottom (or left), ticks and a title.
export function drawLegend(canvas, { position, title = '', units = '', ticks = 5 }, range, scale, w, colour) {
  const g = canvas.getContext('2d');
  g.clearRect(0, 0, canvas.width, canvas.height);
  if (!position || position === 'none') return;
  const W = canvas.width, H = canvas.height;
  const vertical = position === 'right' || position === 'left';
  const font = Math.min(32, Math.max(8, Math.round(Math.min(W, H) / 30)));
  const margin = Math.max(2, font >> 1), thick = Math.max(6, Math.round(Math.min(W, H) / 32));
  const tick = Math.max(2, Math.round(thick / 3));
  const sc = valueScale(range, scale, w);
  const marks = legendTicks(range, scale, w, ticks);
  g.font = `${font}px "DejaVu Sans", sans-serif`;
  g.fillStyle = g.strokeStyle = '#ffffff';
  g.textBaseline = 'middle';
  const label = [title, units && `[${units}]`].filter(Boolean).join(' ');
  const labelW = Math.max(0, ...marks.map((m) => g.measureText(m.label).width));
  const css = (x) => `rgb(${colour(x).map((v) => Math.round(Math.min(Math.max(v, 0), 1) * 255)).join(',')})`;
  if (vertical) {
    const len = Math.round(0.6 * H), blockW = Math.max(thick + tick + 2 + labelW, label ? g.measureText(label).width : 0);
    const left = position === 'right' ? W - margin - blockW : margin;
    const top = Math.round((H - len) / 2);
    for (let y = 0; y < len; y++) { g.fillStyle = css((len - 1 - y + 0.5) / len); g.fillRect(left, top + y, thick, 1); }
    g.fillStyle = '#ffffff';
    g.strokeRect(left + 0.5, top + 0.5, thick - 1, len - 1);
    for (const m of marks) {
      const y = top + len - 1 - Math.round(sc.place(m.value) * (len - 1));
      g.fillRect(left + thick, y, tick, 1);
      g.fillText(m.label, left + thick + tick + 2, y);
    }
    if (label) { g.textBaseline = 'bottom'; g.fillText(label, left, top - 2); }
  } else {
    const len = Math.round(0.6 * W), left = Math.round((W - len) / 2);
    const top = position === 'bottom' ? H - margin - (thick + tick + font + 2) : margin + (label ? font + 4 : 0);
    for (let x = 0; x < len; x++) { g.fillStyle = css((x + 0.5) / len); g.fillRect(left + x, top, 1, thick); }
    g.fillStyle = '#ffffff';
    g.strokeRect(left + 0.5, top + 0.5, len - 1, thick - 1);
    g.textAlign = 'center'; g.textBaseline = 'top';
    for (const m of marks) {
      const x = left + Math.round(sc.place(m.value) * (len - 1));
      g.fillRect(x, top + thick, 1, tick);
      g.fillText(m.label, x, top + thick + tick + 1);
    }
    if (label) { g.textAlign = 'left'; g.textBaseline = 'bottom'; g.fillText(label, left, top - 2); }
    g.textAlign = 'left';
  }
}
