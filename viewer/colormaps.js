// Colour-map presets for the transfer-function editor: a few control colours of each published
// map (ParaView's "Cool to Warm" is Moreland's diverging map; Viridis, Inferno and Plasma are
// matplotlib's), interpolated linearly in RGB between them. Colours are 0..1. They are previews:
// every name here is one of the server's built-in colour maps (transfer/colormaps/), and a request
// names it (transfer.colormap), so the volume is drawn with the full definition.

const hex = (h) => [1, 3, 5].map((i) => parseInt(h.slice(i, i + 2), 16) / 255);
const even = (colors) => colors.map((c, i) => [i / (colors.length - 1), ...(typeof c === 'string' ? hex(c) : c)]);

// Each preset: a list of [x, r, g, b] knots, x increasing from 0 to 1.
export const PRESETS = {
  'Cool to Warm': even([
    [0.2298, 0.2987, 0.7537], [0.3830, 0.5094, 0.9174], [0.5530, 0.6889, 0.9954],
    [0.7222, 0.8140, 0.9766], [0.8654, 0.8654, 0.8654], [0.9588, 0.7698, 0.6780],
    [0.9580, 0.6028, 0.4818], [0.8692, 0.3783, 0.3003], [0.7057, 0.0156, 0.1502],
  ]),
  Viridis: even(['#440154', '#472c7a', '#3b518b', '#2c718e', '#21908d', '#27ad81', '#5cc863', '#aadc32', '#fde725']),
  Inferno: even(['#000004', '#1f0c48', '#550f6d', '#88226a', '#ba3655', '#e35933', '#f98c0a', '#f9c932', '#fcffa4']),
  Plasma: even(['#0d0887', '#4c02a1', '#7e03a8', '#a92395', '#cc4778', '#e56b5d', '#f89441', '#fdc328', '#f0f921']),
  'Black-Body Radiation': [[0, 0, 0, 0], [0.4, 0.902, 0, 0], [0.8, 0.902, 0.902, 0], [1, 1, 1, 1]],
  Grayscale: [[0, 0, 0, 0], [1, 1, 1, 1]],
  Jet: [[0, 0, 0, 0.5625], [0.1111, 0, 0, 1], [0.3651, 0, 1, 1], [0.4921, 0.5, 1, 0.5],
    [0.6190, 1, 1, 0], [0.8730, 1, 0, 0], [1, 0.5, 0, 0]],
};

// The colour of a knot list at x (clamped to the first and last knot).
export function sampleKnots(knots, x) {
  if (!knots.length) return [1, 1, 1];
  if (x <= knots[0][0]) return knots[0].slice(1, 4);
  for (let i = 1; i < knots.length; i++) {
    const b = knots[i];
    if (x <= b[0]) {
      const a = knots[i - 1];
      const t = b[0] > a[0] ? (x - a[0]) / (b[0] - a[0]) : 1;
      return [1, 2, 3].map((k) => a[k] + (b[k] - a[k]) * t);
    }
  }
  return knots[knots.length - 1].slice(1, 4);
}

// CSS linear-gradient of a knot list (for previews).
export function cssGradient(knots) {
  const stops = [];
  for (let i = 0; i <= 16; i++) {
    const c = sampleKnots(knots, i / 16).map((v) => Math.round(v * 255));
    stops.push(`rgb(${c.join(',')}) ${(i / 16) * 100}%`);
  }
  return `linear-gradient(to right, ${stops.join(', ')})`;
}
