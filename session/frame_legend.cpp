#include "session/frame_legend.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "io/text_raster.h"

namespace sortlast {

namespace {

std::string formatValue(double v, double step) {
  if (v == 0.0) return "0";
  char buf[32];
  const double a = std::abs(v);
  if (a >= 1e5 || a < 1e-3) {
    std::snprintf(buf, sizeof buf, "%.3g", v);
    // 1e+05 -> 1e5, 2.5e-04 -> 2.5e-4
    std::string s = buf;
    const size_t e = s.find('e');
    if (e != std::string::npos) {
      std::string mant = s.substr(0, e), ex = s.substr(e + 1);
      const bool neg = ex[0] == '-';
      ex = ex.substr(1);
      while (ex.size() > 1 && ex[0] == '0') ex.erase(0, 1);
      s = mant + "e" + (neg ? "-" : "") + ex;
    }
    return s;
  }
  // Enough decimals to tell ticks `step` apart.
  const int decimals = step > 0.0 ? std::clamp(int(std::ceil(-std::log10(step) - 1e-9)), 0, 6) : 3;
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

std::string decadeLabel(int k) {
  if (k >= 0 && k <= 3) return std::to_string(int(std::lround(std::pow(10.0, k))));
  return "1e" + std::to_string(k);
}

}  // namespace

std::vector<LegendTick> legendTicks(const TransferFunction& tf, int count) {
  count = std::max(2, count);
  const double lo = tf.rangeLo(), hi = tf.rangeHi();
  std::vector<LegendTick> out;
  auto add = [&](double v, std::string label) {
    if (v < lo - 1e-9 * std::abs(hi - lo) || v > hi + 1e-9 * std::abs(hi - lo)) return;
    out.push_back({v, tf.normalise(v), std::move(label)});
  };
  const ValueScale& s = tf.scale();
  if (s.kind == ValueScaleKind::kLog) {
    const int k0 = int(std::ceil(std::log10(lo) - 1e-9)), k1 = int(std::floor(std::log10(hi) + 1e-9));
    if (k1 - k0 + 1 >= 2) {
      const int every = std::max(1, int(std::ceil(double(k1 - k0 + 1) / count)));
      for (int k = k0; k <= k1; k += every) add(std::pow(10.0, k), decadeLabel(k));
      return out;
    }
    // Less than two decades: evenly spaced in log10, labelled to 3 significant digits.
    for (int i = 0; i < count; ++i) {
      const double v = tf.denormalise(double(i) / (count - 1));
      char buf[32];
      std::snprintf(buf, sizeof buf, "%.3g", v);
      out.push_back({v, double(i) / (count - 1), buf});
    }
    return out;
  }
  if (s.kind == ValueScaleKind::kSymlog) {
    std::vector<double> cands;
    if (lo <= 0.0 && hi >= 0.0) cands.push_back(0.0);
    const int kw = int(std::ceil(std::log10(s.linear_width) - 1e-9));
    const double amax = std::max(std::abs(lo), std::abs(hi));
    for (int k = kw; std::pow(10.0, k) <= amax * (1 + 1e-9); ++k) {
      cands.push_back(std::pow(10.0, k));
      cands.push_back(-std::pow(10.0, k));
    }
    std::vector<double> in;
    for (double v : cands)
      if (v >= lo && v <= hi) in.push_back(v);
    std::sort(in.begin(), in.end());
    const int every = std::max(1, int(std::ceil(double(in.size()) / count)));
    // Keep 0 (or the middle one) and every `every`-th either side of it.
    size_t centre = size_t(std::find(in.begin(), in.end(), 0.0) - in.begin());
    if (centre == in.size()) centre = in.size() / 2;
    for (size_t i = 0; i < in.size(); ++i) {
      const long d = long(i) - long(centre);
      if (d % every != 0) continue;
      const double v = in[i];
      const int k = v == 0.0 ? 0 : int(std::lround(std::log10(std::abs(v))));
      add(v, v == 0.0 ? "0" : (v < 0 ? "-" : "") + decadeLabel(k));
    }
    return out;
  }
  // Linear: a round step, 1, 2 or 5 x 10^k, whose tick count is nearest `count` (ties: fewer).
  const double raw = (hi - lo) / (count - 1);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = 10.0 * mag;
  int best = 1 << 30;
  for (double m : {10.0, 5.0, 2.0, 1.0}) {
    const double st = m * mag;
    const int n = int(std::floor(hi / st + 1e-9) - std::ceil(lo / st - 1e-9)) + 1;
    if (std::abs(n - count) < best) best = std::abs(n - count), step = st;
  }
  for (double v = std::ceil(lo / step - 1e-9) * step; v <= hi + 1e-9 * step; v += step)
    add(std::abs(v) < 1e-12 * step ? 0.0 : v, formatValue(std::abs(v) < 1e-12 * step ? 0.0 : v, step));
  return out;
}

namespace {

struct Painter {
  ImageRGBA8& f;
  int x0 = 1 << 30, y0 = 1 << 30, x1 = -1, y1 = -1;  // the drawn box, inclusive
  void touch(int x, int y) {
    x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
  }
  bool inside(int x, int y) const { return x >= 0 && y >= 0 && x < f.width && y < f.height; }
  void opaque(int x, int y, const std::array<uint8_t, 3>& c) {
    if (!inside(x, y)) return;
    uint8_t* p = f.at(x, y);
    p[0] = c[0], p[1] = c[1], p[2] = c[2], p[3] = 255;
    touch(x, y);
  }
  // Text of colour c over the premultiplied pixel, by coverage.
  void text(int left, int top, const TextMask& m, const std::array<uint8_t, 3>& c) {
    for (int y = 0; y < m.height; ++y)
      for (int x = 0; x < m.width; ++x) {
        const int cov = m.coverage[size_t(y) * m.width + size_t(x)];
        if (cov == 0 || !inside(left + x, top + y)) continue;
        uint8_t* p = f.at(left + x, top + y);
        for (int k = 0; k < 3; ++k) p[k] = uint8_t((c[size_t(k)] * cov + p[k] * (255 - cov) + 127) / 255);
        p[3] = uint8_t((255 * cov + p[3] * (255 - cov) + 127) / 255);
        touch(left + x, top + y);
      }
  }
};

std::array<uint8_t, 3> colourAt(const TransferFunction& tf, double t) {
  const auto e = tf.atNormalised(t);
  auto q = [](double v) { return uint8_t(std::lround(std::clamp(v, 0.0, 1.0) * 255.0)); };
  return {q(e[0]), q(e[1]), q(e[2])};
}

}  // namespace

LegendRect drawLegend(ImageRGBA8& frame, const TransferFunction& tf, const LegendSpec& spec,
                      const glm::dvec3& background) {
  LegendRect r;
  if (!spec.enabled() || tf.points().empty()) return r;  // (no volume: no transfer function)
  const int W = frame.width, H = frame.height;
  const bool vertical = spec.position == LegendPosition::kRight || spec.position == LegendPosition::kLeft;
  const int font_px = std::clamp(int(std::lround(std::min(W, H) / 30.0)), 8, 32);
  TextRaster raster(font_px);
  const double lum = 0.2126 * background.x + 0.7152 * background.y + 0.0722 * background.z;
  const std::array<uint8_t, 3> ink = lum > 0.5 ? std::array<uint8_t, 3>{0, 0, 0} : std::array<uint8_t, 3>{255, 255, 255};
  const int margin = std::max(2, font_px / 2);
  const int thick = std::max(6, int(std::lround(std::min(W, H) / 32.0)));  // across the bar
  const int tick_len = std::max(2, thick / 3);
  const std::vector<LegendTick> ticks = legendTicks(tf, spec.ticks);
  std::vector<TextMask> labels;
  int label_w = 0;
  for (const LegendTick& t : ticks) {
    labels.push_back(raster.render(t.label));
    label_w = std::max(label_w, labels.back().width);
  }
  std::string title = spec.title;
  if (!spec.units.empty()) title += (title.empty() ? "" : " ") + ("[" + spec.units + "]");
  const TextMask title_mask = title.empty() ? TextMask{} : raster.render(title);
  const int line = raster.lineHeight();
  const int title_h = title.empty() ? 0 : line + margin / 2;
  Painter p{frame};

  if (vertical) {
    const int length = std::max(8, int(std::lround(0.6 * H)));
    const int block_w = std::max(thick + tick_len + 2 + label_w, title_mask.width);
    const int left = spec.position == LegendPosition::kRight ? W - margin - block_w : margin;
    const int top = (H - length - title_h) / 2 + title_h;  // the bar's top (outline included)
    // Bar with a one-pixel outline; the inside runs from the range's low end (bottom) up.
    r.bar_x = left + 1, r.bar_y = top + 1, r.bar_width = thick - 2, r.bar_height = length - 2;
    for (int y = 0; y < length; ++y)
      for (int x = 0; x < thick; ++x) {
        const bool edge = x == 0 || y == 0 || x == thick - 1 || y == length - 1;
        const double t = (double(r.bar_height - 1 - (y - 1)) + 0.5) / r.bar_height;
        p.opaque(left + x, top + y, edge ? ink : colourAt(tf, t));
      }
    for (size_t i = 0; i < ticks.size(); ++i) {
      const int y = r.bar_y + r.bar_height - 1 - int(std::lround(ticks[i].place * (r.bar_height - 1)));
      for (int x = 0; x < tick_len; ++x) p.opaque(left + thick + x, y, ink);
      // The digits' middle (about 0.36 em above the baseline) level with the tick.
      p.text(left + thick + tick_len + 2, y - labels[i].baseline + int(std::lround(0.36 * font_px)), labels[i], ink);
    }
    if (!title.empty()) p.text(left, top - title_h, title_mask, ink);
  } else {
    const int length = std::max(8, int(std::lround(0.6 * W)));
    const int block_h = title_h + thick + tick_len + 2 + line;
    const int left = (W - length) / 2;
    const int top = (spec.position == LegendPosition::kBottom ? H - margin - block_h : margin) + title_h;
    r.bar_x = left + 1, r.bar_y = top + 1, r.bar_width = length - 2, r.bar_height = thick - 2;
    for (int y = 0; y < thick; ++y)
      for (int x = 0; x < length; ++x) {
        const bool edge = x == 0 || y == 0 || x == length - 1 || y == thick - 1;
        const double t = (double(x - 1) + 0.5) / r.bar_width;
        p.opaque(left + x, top + y, edge ? ink : colourAt(tf, t));
      }
    for (size_t i = 0; i < ticks.size(); ++i) {
      const int x = r.bar_x + int(std::lround(ticks[i].place * (r.bar_width - 1)));
      for (int y = 0; y < tick_len; ++y) p.opaque(x, top + thick + y, ink);
      p.text(x - labels[i].width / 2, top + thick + tick_len + 1, labels[i], ink);
    }
    if (!title.empty()) p.text(left, top - title_h, title_mask, ink);
  }
  r.vertical = vertical;
  if (p.x1 >= 0) r.x = p.x0, r.y = p.y0, r.width = p.x1 - p.x0 + 1, r.height = p.y1 - p.y0 + 1;
  return r;
}

}  // namespace sortlast
