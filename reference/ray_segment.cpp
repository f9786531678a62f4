#include "reference/ray_segment.h"

#include <algorithm>
#include <cmath>

#include "common/box.h"
#include "common/trilinear.h"

namespace sortlast {

double BrickField::at(const glm::dvec3& u) const {
  const glm::ivec3 n = grid.dims;
  const glm::ivec3 s = stored.size();
  // The corner's offset in `samples` and, per axis, the step to the next corner (0 where the held
  // samples end: the same clamped corners as before, read without a clamp per corner; the
  // estimate's integration spends about a third of its time here, perf on the head CT).
  size_t base = 0;
  size_t next[3];
  double f[3];
  const size_t stride[3] = {1, size_t(s.x), size_t(s.x) * size_t(s.y)};
  for (int a = 0; a < 3; ++a) {
    // Whole-grid clamp first (the reference's), then the held samples' box.
    double c = std::clamp(u[a], 0.0, double(n[a] - 1));
    c = std::clamp(c, double(stored.lo[a]), double(stored.hi[a]));
    const int hi_cell = std::max(stored.lo[a], stored.hi[a] - 1);
    int i = std::min(int(c), hi_cell);
    f[a] = s[a] > 1 ? c - i : 0.0;
    i -= stored.lo[a];
    base += size_t(i) * stride[a];
    next[a] = i + 1 < s[a] ? stride[a] : 0;
  }
  const float* p = samples + base;
  auto v = [&](int dx, int dy, int dz) {
    return double(p[(dx ? next[0] : 0) + (dy ? next[1] : 0) + (dz ? next[2] : 0)]);
  };
  return trilinear(v, f);
}

glm::dvec3 BrickField::gradient(const glm::dvec3& u) const {
  return centralGradient([this](const glm::dvec3& p) { return at(p); }, u, grid.spacing);
}

namespace {

// The most tau (per world unit) and c tau vary over values in [vlo, vhi]: the function is
// piecewise linear in the normalised value, so its extremes lie at the ends or at its points.
double oscillation(const TransferFunction& tf, double vlo, double vhi) {
  const double xl = tf.normalise(vlo), xh = tf.normalise(vhi);
  double lo[4] = {HUGE_VAL, HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[4] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  auto take = [&](double x) {
    const std::array<double, 4> f = tf.atNormalised(x);
    for (int c = 0; c < 4; ++c) lo[c] = std::min(lo[c], f[c]), hi[c] = std::max(hi[c], f[c]);
  };
  take(xl);
  take(xh);
  for (const TfPoint& p : tf.points())
    if (p.value > xl && p.value < xh) take(p.value);
  auto tau = [&](double op) { return -std::log1p(-std::min(op, TransferFunction::kMaxOpacity)) / tf.unitLength(); };
  const double tlo = tau(lo[3]), thi = tau(hi[3]);
  double osc = thi - tlo;
  for (int c = 0; c < 3; ++c) osc = std::max(osc, hi[c] * thi - lo[c] * tlo);  // c, tau >= 0
  return osc;
}

}  // namespace

EmptyBlocks::EmptyBlocks(const BrickField& field, const TransferFunction& tf, double step, bool shading) {
  const glm::ivec3 s = field.stored.size();
  const glm::ivec3 cells = glm::max(s - 1, glm::ivec3(1));
  count = (cells + kCells - 1) / kCells;
  empty.assign(size_t(count.x) * count.y * count.z, 0);
  multiple.assign(empty.size(), 1);
  for (int bz = 0; bz < count.z; ++bz)
    for (int by = 0; by < count.y; ++by)
      for (int bx = 0; bx < count.x; ++bx) {
        double lo = HUGE_VAL, hi = -HUGE_VAL;
        bool nan = false;
        for (int z = bz * kCells; z <= std::min(s.z - 1, (bz + 1) * kCells); ++z)
          for (int y = by * kCells; y <= std::min(s.y - 1, (by + 1) * kCells); ++y)
            for (int x = bx * kCells; x <= std::min(s.x - 1, (bx + 1) * kCells); ++x) {
              const float v = field.samples[size_t(x) + size_t(s.x) * (size_t(y) + size_t(s.y) * size_t(z))];
              if (std::isnan(v)) nan = true;
              lo = std::min(lo, double(v));
              hi = std::max(hi, double(v));
            }
        const size_t b = size_t(bx) + size_t(count.x) * (size_t(by) + size_t(count.y) * size_t(bz));
        empty[b] = !nan && lo <= hi && tf.maxOpacity(lo, hi) <= 0.0;
        if (nan || shading || !(step > 0.0) || !(lo <= hi)) continue;
        const double osc = oscillation(tf, lo, hi);
        int m = 1;
        while (m < kMaxMultiple && 2 * m * step * osc <= kTolerance) m *= 2;
        multiple[b] = uint8_t(m);
      }
}

namespace {

// One sample of the midpoint rule: the step [ta, ta + h] composited into `out`.
inline void addStep(SegmentIntegral& out, const BrickField& field, const TransferFunction& tf,
                    const Shading& shading, double flat, const glm::dvec3& o, const glm::dvec3& d,
                    double tm, double h) {
  const glm::dvec3 u = field.grid.indexOfWorld(o + tm * d);
  const double v = field.at(u);  // NaN where the stencil touches a missing sample: transparent
  if (std::isnan(v)) return;
  // The function once per step (colour and opacity); a = 1 - exp(-tau h) with tau =
  // -log(1 - opacity) / unit_length, as TransferFunction::extinction, in one pow.
  const std::array<double, 4> f = tf.atNormalised(tf.normalise(v));
  if (f[3] <= 0.0) return;
  const double a = 1.0 - std::pow(1.0 - std::min(f[3], TransferFunction::kMaxOpacity), h / tf.unitLength());
  std::array<double, 3> c{f[0], f[1], f[2]};
  if (shading.enabled) c = shadeSample(c, field.gradient(u), d, shading, flat);
  for (int k = 0; k < 3; ++k) out.rgb[k] += out.transmit * a * c[k];
  out.transmit *= 1.0 - a;
}

constexpr double kStopTransmit = 1e-4;

}  // namespace

SegmentIntegral integrateSegment(const BrickField& field, const TransferFunction& tf,
                                 const Shading& shading, double flat, const glm::dvec3& o,
                                 const glm::dvec3& d, double t0, double t1, double step,
                                 const EmptyBlocks* blocks) {
  SegmentIntegral out;
  if (!(t1 > t0)) return out;
  if (!blocks) {
    const long long n = std::max(1LL, (long long)std::ceil((t1 - t0) / step));
    const double h = (t1 - t0) / double(n);
    for (long long i = 0; i < n && out.transmit > kStopTransmit; ++i)
      addStep(out, field, tf, shading, flat, o, d, t0 + (double(i) + 0.5) * h, h);
    return out;
  }
  // Block by block: the block holding a point just past t, its exit along the ray, and in it
  // equal steps of at most its multiple of `step` (an empty block: none).
  double t = t0;
  while (t < t1 && out.transmit > kStopTransmit) {
    const double probe = t + std::min(0.25 * step, 0.5 * (t1 - t));
    const glm::dvec3 local = (field.grid.indexOfWorld(o + probe * d) - glm::dvec3(field.stored.lo)) /
                             double(EmptyBlocks::kCells);
    const glm::ivec3 b = glm::clamp(glm::ivec3(glm::floor(local)), glm::ivec3(0), blocks->count - 1);
    const size_t bi = size_t(b.x) + size_t(blocks->count.x) * (size_t(b.y) + size_t(blocks->count.y) * size_t(b.z));
    const glm::dvec3 lo_i = glm::dvec3(field.stored.lo + b * EmptyBlocks::kCells);
    const Box3 box{field.grid.worldOfIndex(lo_i), field.grid.worldOfIndex(lo_i + double(EmptyBlocks::kCells))};
    double ta, tb;
    if (!intersectRayBox(o, d, box, ta, tb) || tb <= probe) tb = probe + 0.25 * step;  // rounding at a face
    tb = std::min(tb, t1);
    if (!blocks->empty[bi]) {
      const double len = tb - t, big = blocks->multiple[bi] * step;
      const long long n = std::max(1LL, (long long)std::ceil(len / big));
      const double h = len / double(n);
      for (long long i = 0; i < n && out.transmit > kStopTransmit; ++i)
        addStep(out, field, tf, shading, flat, o, d, t + (double(i) + 0.5) * h, h);
    }
    t = tb;
  }
  return out;
}

}  // namespace sortlast
