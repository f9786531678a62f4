// Transfer-function editor: the data histogram (log scale), the opacity curve with draggable
// control points over it, and the colour map as a strip underneath. x is the value normalised
// over the transfer range (0..1), y the opacity (0..1).
//   drag a point: move it (between its neighbours)   double-click: add a point
//   right-click a point, or Delete / Backspace on the selected one: remove it

import { sampleKnots } from './colormaps.js';

// The opacity of control points [[x, a], ...] (sorted by x) at x: linear between points,
// constant beyond the first and last.
export function opacityAt(p, x) {
  if (x <= p[0][0]) return p[0][1];
  for (let i = 1; i < p.length; i++) {
    if (x <= p[i][0]) {
      const t = p[i][0] > p[i - 1][0] ? (x - p[i - 1][0]) / (p[i][0] - p[i - 1][0]) : 1;
      return p[i - 1][1] + (p[i][1] - p[i - 1][1]) * t;
    }
  }
  return p[p.length - 1][1];
}

const PAD = { left: 8, right: 8, top: 8 };
const STRIP = 14;   // colour strip height (CSS px)
const GAP = 4;
const HIT = 9;      // pick radius (CSS px)

export class TransferEditor {
  // onChange(interactive): the curve changed; interactive is true while a point is being dragged.
  // onHover(x, a | null): the pointer is over value x (a: the opacity there), or left (x = null).
  constructor(canvas, { onChange = () => {}, onHover = () => {} } = {}) {
    this.canvas = canvas;
    this.onChange = onChange;
    this.onHover = onHover;
    this.points = [[0, 0], [1, 1]];
    this.knots = [[0, 1, 1, 1], [1, 1, 1, 1]];
    this.hist = null;      // {counts, x0, x1}: bins spread over x0..x1 (normalised values)
    this.selected = -1;
    this.dragging = -1;
    this.moved = false;
    canvas.tabIndex = 0;
    canvas.addEventListener('pointerdown', (e) => this.#down(e));
    canvas.addEventListener('pointermove', (e) => this.#move(e));
    canvas.addEventListener('pointerup', (e) => this.#up(e));
    canvas.addEventListener('pointercancel', (e) => this.#up(e));
    canvas.addEventListener('pointerleave', () => { if (this.dragging < 0) this.onHover(null); });
    canvas.addEventListener('dblclick', (e) => this.#dblclick(e));
    canvas.addEventListener('contextmenu', (e) => this.#contextmenu(e));
    canvas.addEventListener('keydown', (e) => this.#key(e));
    new ResizeObserver(() => this.draw()).observe(canvas);
  }

  setPoints(points) {
    this.points = points.map((p) => [clamp01(p[0]), clamp01(p[1])]).sort((a, b) => a[0] - b[0]);
    if (!this.points.length) this.points = [[0, 0], [1, 1]];
    this.selected = -1;
    this.draw();
  }

  getPoints() { return this.points.map((p) => [...p]); }

  // The control points in client (page) coordinates, with their values: [{x, y, value, opacity}].
  handlePositions() {
    const r = this.canvas.getBoundingClientRect();
    return this.points.map((p) => {
      const [sx, sy] = this.#toScreen(p);
      return { x: r.left + sx, y: r.top + sy, value: p[0], opacity: p[1] };
    });
  }

  setColormap(knots) { this.knots = knots; this.draw(); }

  // place(f), if given: the normalised x of the histogram's edge at fraction f of its range (a log
  // or symlog transfer.scale puts even bins at uneven places).
  setHistogram(counts, x0 = 0, x1 = 1, place = null) {
    this.hist = counts && counts.length ? { counts, x0, x1, place } : null;
    this.draw();
  }

  // Opacity at x: linear between points, constant beyond the first and last.
  opacity(x) { return opacityAt(this.points, x); }

  // ---- geometry (CSS pixels) ----
  #area() {
    const w = this.canvas.clientWidth, h = this.canvas.clientHeight;
    return { x: PAD.left, y: PAD.top, w: Math.max(w - PAD.left - PAD.right, 1), h: Math.max(h - PAD.top - STRIP - GAP, 1) };
  }
  #toScreen(p) { const a = this.#area(); return [a.x + p[0] * a.w, a.y + (1 - p[1]) * a.h]; }
  #fromEvent(e) {
    const r = this.canvas.getBoundingClientRect(), a = this.#area();
    return [clamp01((e.clientX - r.left - a.x) / a.w), clamp01(1 - (e.clientY - r.top - a.y) / a.h)];
  }
  #hit(e) {
    const r = this.canvas.getBoundingClientRect();
    const mx = e.clientX - r.left, my = e.clientY - r.top;
    let best = -1, bestD = HIT * HIT;
    this.points.forEach((p, i) => {
      const [sx, sy] = this.#toScreen(p);
      const d = (sx - mx) ** 2 + (sy - my) ** 2;
      if (d <= bestD) { best = i; bestD = d; }
    });
    return best;
  }

  // ---- events ----
  #down(e) {
    if (e.button !== 0) return;
    const i = this.#hit(e);
    this.selected = i;
    if (i >= 0) {
      this.dragging = i;
      this.moved = false;
      this.canvas.setPointerCapture(e.pointerId);
      e.preventDefault();
      this.canvas.focus({ preventScroll: true });
    }
    this.draw();
  }
  #move(e) {
    const [x, a] = this.#fromEvent(e);
    if (this.dragging >= 0) {
      const i = this.dragging, p = this.points;
      const eps = 1e-3;
      const lo = i > 0 ? p[i - 1][0] + eps : 0, hi = i < p.length - 1 ? p[i + 1][0] - eps : 1;
      p[i] = [Math.min(Math.max(x, lo), hi), a];
      this.moved = true;
      this.draw();
      this.onHover(p[i][0], p[i][1]);
      this.onChange(true);
    } else {
      this.canvas.style.cursor = this.#hit(e) >= 0 ? 'grab' : 'crosshair';
      this.onHover(x, this.opacity(x));
    }
  }
  #up(e) {
    if (this.dragging < 0) return;
    this.dragging = -1;
    if (this.canvas.hasPointerCapture(e.pointerId)) this.canvas.releasePointerCapture(e.pointerId);
    if (this.moved) this.onChange(false);
  }
  #dblclick(e) {
    if (this.#hit(e) >= 0) return;
    const [x, a] = this.#fromEvent(e);
    if (this.points.some((p) => Math.abs(p[0] - x) < 1e-3)) return;
    this.points.push([x, a]);
    this.points.sort((p, q) => p[0] - q[0]);
    this.selected = this.points.findIndex((p) => p[0] === x);
    this.draw();
    this.onChange(false);
  }
  #contextmenu(e) {
    e.preventDefault();
    const i = this.#hit(e);
    if (i >= 0) this.#remove(i);
  }
  #key(e) {
    if ((e.key === 'Delete' || e.key === 'Backspace') && this.selected >= 0) {
      e.preventDefault();
      this.#remove(this.selected);
    }
  }
  #remove(i) {
    if (this.points.length <= 1) return;
    this.points.splice(i, 1);
    this.selected = -1;
    this.draw();
    this.onChange(false);
  }

  // ---- drawing ----
  draw() {
    const c = this.canvas, dpr = window.devicePixelRatio || 1;
    const cw = c.clientWidth, ch = c.clientHeight;
    if (!cw || !ch) return;
    if (c.width !== Math.round(cw * dpr) || c.height !== Math.round(ch * dpr)) {
      c.width = Math.round(cw * dpr);
      c.height = Math.round(ch * dpr);
    }
    const g = c.getContext('2d');
    g.setTransform(dpr, 0, 0, dpr, 0, 0);
    g.clearRect(0, 0, cw, ch);
    const a = this.#area();
    g.fillStyle = '#15181d';
    g.fillRect(a.x, a.y, a.w, a.h);

    // grid: opacity quarters
    g.strokeStyle = 'rgba(255,255,255,0.07)';
    g.lineWidth = 1;
    for (let k = 1; k < 4; k++) {
      const y = Math.round(a.y + (a.h * k) / 4) + 0.5;
      g.beginPath(); g.moveTo(a.x, y); g.lineTo(a.x + a.w, y); g.stroke();
    }

    // histogram, log scale
    if (this.hist) {
      const { counts, x0, x1, place } = this.hist;
      const max = Math.log1p(Math.max(...counts));
      if (max > 0) {
        g.fillStyle = 'rgba(170,180,195,0.45)';
        const n = counts.length;
        for (let i = 0; i < n; i++) {
          if (!counts[i]) continue;
          const bx0 = place ? place(i / n) : x0 + ((x1 - x0) * i) / n;
          const bx1 = place ? place((i + 1) / n) : x0 + ((x1 - x0) * (i + 1)) / n;
          if (bx1 < 0 || bx0 > 1) continue;
          const sx0 = a.x + Math.max(bx0, 0) * a.w, sx1 = a.x + Math.min(bx1, 1) * a.w;
          const bh = (Math.log1p(counts[i]) / max) * a.h;
          g.fillRect(sx0, a.y + a.h - bh, Math.max(sx1 - sx0, 1), bh);
        }
      }
    }

    // area under the opacity curve, in the colour map's colours
    const cols = Math.max(Math.round(a.w), 1);
    for (let i = 0; i < cols; i++) {
      const x = (i + 0.5) / cols;
      const rgb = sampleKnots(this.knots, x).map((v) => Math.round(v * 255));
      const h = this.opacity(x) * a.h;
      g.fillStyle = `rgba(${rgb.join(',')},0.45)`;
      g.fillRect(a.x + i, a.y + a.h - h, 1, h);
      g.fillStyle = `rgb(${rgb.join(',')})`;
      g.fillRect(a.x + i, a.y + a.h + GAP, 1, STRIP);
    }

    // the curve and its points
    g.strokeStyle = '#f2f4f8';
    g.lineWidth = 1.5;
    g.beginPath();
    const p = this.points;
    g.moveTo(a.x, this.#toScreen([0, p[0][1]])[1]);
    for (const q of p) g.lineTo(...this.#toScreen(q));
    g.lineTo(a.x + a.w, this.#toScreen([1, p[p.length - 1][1]])[1]);
    g.stroke();
    p.forEach((q, i) => {
      const [sx, sy] = this.#toScreen(q);
      g.beginPath();
      g.arc(sx, sy, i === this.selected ? 6 : 4.5, 0, 2 * Math.PI);
      g.fillStyle = i === this.selected ? '#ffb02e' : '#ffffff';
      g.fill();
      g.strokeStyle = '#15181d';
      g.lineWidth = 1.5;
      g.stroke();
    });
    g.strokeStyle = 'rgba(255,255,255,0.18)';
    g.lineWidth = 1;
    g.strokeRect(a.x + 0.5, a.y + 0.5, a.w - 1, a.h - 1);
  }
}

function clamp01(v) { return Math.min(Math.max(Number(v) || 0, 0), 1); }
