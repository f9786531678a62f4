#include "reference/ray_segment.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include "common/box.h"
#include "common/pixel_threads.h"
#include "common/trilinear.h"
#include "reference/step_cuts.h"
#include "transfer/value_scale.h"

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
  // Every frame's estimate builds these (a fifth of the engine's estimate, 256^3, perf): slabs of
  // blocks in parts, each block written by one.
  std::atomic<int> next_slab{0};
  auto slabs = [&] {
    for (int bz; (bz = next_slab.fetch_add(1)) < count.z;)
      for (int by = 0; by < count.y; ++by)
        for (int bx = 0; bx < count.x; ++bx) {
          float lo_f = HUGE_VALF, hi_f = -HUGE_VALF;
          bool nan = false;
          for (int z = bz * kCells; z <= std::min(s.z - 1, (bz + 1) * kCells); ++z)
            for (int y = by * kCells; y <= std::min(s.y - 1, (by + 1) * kCells); ++y)
              for (int x = bx * kCells; x <= std::min(s.x - 1, (bx + 1) * kCells); ++x) {
                const float v =
                    field.samples[size_t(x) + size_t(s.x) * (size_t(y) + size_t(s.y) * size_t(z))];
                nan |= std::isnan(v);
                lo_f = std::min(lo_f, v);
                hi_f = std::max(hi_f, v);
              }
          const double lo = lo_f, hi = hi_f;
          const size_t b = size_t(bx) + size_t(count.x) * (size_t(by) + size_t(count.y) * size_t(bz));
          empty[b] = !nan && lo <= hi && tf.maxOpacity(lo, hi) <= 0.0;
          if (nan || shading || !(step > 0.0) || !(lo <= hi)) continue;
          const double osc = oscillation(tf, lo, hi);
          int m = 1;
          while (m < kMaxMultiple && 2 * m * step * osc <= kTolerance) m *= 2;
          multiple[b] = uint8_t(m);
        }
  };
  // On the rank's pixel pool (common/pixel_threads.h: its share of the node's cores), not a
  // thread per core on every rank: 4 ranks on 2 cores ran 8 threads here.
  parallelParts(std::min(count.z, pixelThreads()), [&](int) { slabs(); });
}

namespace {

constexpr double kStopTransmit = 1e-4;
// The cell march's error per voxel (the smallest spacing) of the ray's length: a ray through 100
// visible voxels is within 100 kCellTolerance of the exact integral (and of the fine steps).
constexpr double kCellTolerance = 1e-5;

// The transfer function along a ray: the piece a value falls in is walked to from the previous
// sample's (the values change little from step to step) instead of searched, and the linear
// scale's normalisation is inlined. The same arithmetic as TransferFunction::normalise and
// atNormalised, so the same doubles.
class TfCursor {
 public:
  explicit TfCursor(const TransferFunction& tf)
      : tf_(tf), p_(tf.points()), linear_(tf.scale().kind == ValueScaleKind::kLinear),
        lo_(tf.rangeLo()), hi_(tf.rangeHi()) {}
  bool linear() const { return linear_; }
  // (r, g, b, opacity) at raw value v.
  std::array<double, 4> at(double v) {
    const double x = linear_ ? std::clamp((v - lo_) / (hi_ - lo_), 0.0, 1.0) : tf_.normalise(v);
    if (x <= p_.front().value) return {p_.front().r, p_.front().g, p_.front().b, p_.front().a};
    if (x >= p_.back().value) return {p_.back().r, p_.back().g, p_.back().b, p_.back().a};
    // j: the first point above x (std::upper_bound's), so p_[j - 1].value <= x < p_[j].value.
    while (j_ < p_.size() - 1 && x >= p_[j_].value) ++j_;
    while (j_ > 1 && x < p_[j_ - 1].value) --j_;
    const TfPoint& b = p_[j_];
    const TfPoint& a = p_[j_ - 1];
    const double f = (b.value > a.value) ? (x - a.value) / (b.value - a.value) : 1.0;
    return {a.r + f * (b.r - a.r), a.g + f * (b.g - a.g), a.b + f * (b.b - a.b), a.a + f * (b.a - a.a)};
  }

 private:
  const TransferFunction& tf_;
  const std::vector<TfPoint>& p_;
  bool linear_;
  double lo_, hi_;
  size_t j_ = 1;
};

// The field along a ray o + t d: inside one cell the trilinear field is a cubic in t, its
// coefficients found once per cell the ray crosses and evaluated by Horner's rule (the ray's
// samples in one cell: up to 16 a voxel at the reference's step). Where BrickField::at would clamp
// (outside the grid or the held samples), it is BrickField::at. Equal to it within rounding: the
// same eight corners, the products expanded (within 1e-12 in the test
// FrameEstimate.CellCubicsAndPieceWalksAreTheReferencesArithmetic).
class FieldCursor {
 public:
  FieldCursor(const BrickField& field, const glm::dvec3& o, const glm::dvec3& d)
      : field_(field), o_(o), d_(d), du_(d / field.grid.spacing) {}

  // Builds the cubic of the cell holding the ray's point at t; false where BrickField::at would
  // clamp there (then at() answers per sample).
  bool enterAt(double t) { return enter(t, field_.grid.indexOfWorld(o_ + t * d_)); }
  double exitT() const { return t_hi_; }  // where the ray leaves the cell entered last
  double refT() const { return t_ref_; }  // the cubic is in s = t - refT()
  const double* cubic() const { return k_; }

  // The value at ray parameter t.
  double at(double t) {
    if (t >= t_lo_ && t <= t_hi_) {
      const double s = t - t_ref_;
      return ((k_[3] * s + k_[2]) * s + k_[1]) * s + k_[0];
    }
    const glm::dvec3 u = field_.grid.indexOfWorld(o_ + t * d_);
    if (!enter(t, u)) return field_.at(u);
    return k_[0];
  }

 private:
  // The cubic of the cell holding index point u (at ray parameter t); false where at() clamps.
  bool enter(double t, const glm::dvec3& u) {
    t_lo_ = HUGE_VAL, t_hi_ = -HUGE_VAL;  // nothing cached until this succeeds
    const glm::ivec3 n = field_.grid.dims, s = field_.stored.size();
    const size_t stride[3] = {1, size_t(s.x), size_t(s.x) * size_t(s.y)};
    size_t base = 0;
    double f[3], lo = -HUGE_VAL, hi = HUGE_VAL;
    for (int a = 0; a < 3; ++a) {
      if (s[a] < 2) return false;
      const double c = std::clamp(std::clamp(u[a], 0.0, double(n[a] - 1)), double(field_.stored.lo[a]),
                                  double(field_.stored.hi[a]));
      if (c != u[a]) return false;
      const int i = std::min(int(c), field_.stored.hi[a] - 1);
      f[a] = c - i;
      base += size_t(i - field_.stored.lo[a]) * stride[a];
      // Where the ray is in this cell along axis a: f + du (t' - t) in [0, 1].
      if (du_[a] > 0) lo = std::max(lo, t - f[a] / du_[a]), hi = std::min(hi, t + (1.0 - f[a]) / du_[a]);
      if (du_[a] < 0) lo = std::max(lo, t + (1.0 - f[a]) / du_[a]), hi = std::min(hi, t - f[a] / du_[a]);
    }
    const float* p = field_.samples + base;
    auto corner = [&](int dx, int dy, int dz) {
      return double(p[(dx ? stride[0] : 0) + (dy ? stride[1] : 0) + (dz ? stride[2] : 0)]);
    };
    // Along x: linear (a0 + a1 s) per (y, z) edge; then y: quadratic; then z: cubic.
    double q[2][3];
    for (int dz = 0; dz < 2; ++dz) {
      double e[2][2];
      for (int dy = 0; dy < 2; ++dy) {
        const double c0 = corner(0, dy, dz), dc = corner(1, dy, dz) - c0;
        e[dy][0] = c0 + dc * f[0];
        e[dy][1] = dc * du_[0];
      }
      const double d0 = e[1][0] - e[0][0], d1 = e[1][1] - e[0][1];
      q[dz][0] = e[0][0] + d0 * f[1];
      q[dz][1] = e[0][1] + d0 * du_[1] + d1 * f[1];
      q[dz][2] = d1 * du_[1];
    }
    const double g0 = q[1][0] - q[0][0], g1 = q[1][1] - q[0][1], g2 = q[1][2] - q[0][2];
    k_[0] = q[0][0] + g0 * f[2];
    k_[1] = q[0][1] + g0 * du_[2] + g1 * f[2];
    k_[2] = q[0][2] + g1 * du_[2] + g2 * f[2];
    k_[3] = g2 * du_[2];
    t_ref_ = t, t_lo_ = lo, t_hi_ = hi;
    return true;
  }

  const BrickField& field_;
  glm::dvec3 o_, d_, du_;
  double t_ref_ = 0.0, t_lo_ = HUGE_VAL, t_hi_ = -HUGE_VAL;
  double k_[4] = {0, 0, 0, 0};
};

// The longest midpoint step that keeps one step's error within `tol` on one cell's crossing, the
// field there v(s) = k0 + k1 s + k2 s^2 + k3 s^3 for s in [sa, sb] (a cubic: FieldCursor); 0 where
// nothing on the crossing has opacity (or a sample is missing: every sample is then NaN) and the
// crossing contributes exactly nothing. Linear scale only (x = (v - lo) / (hi - lo), clamped).
//
// The bound. From the cubic: the crossing's value range, V1 >= |v'| and V2 >= |v''| on it. On
// each piece of the function (between its points) opacity a and colour c are linear in x (slopes
// ka, kc), so tau = -log(1 - a) / L has tau' = ka / ((1 - a) L) and tau'' = ka^2 / ((1 - a)^2 L),
// both largest where a is: over the pieces the crossing's values reach, T0 >= tau, T1 >= |tau'|,
// T2 >= |tau''|, C0 >= c, C1 >= |kc| (derivatives in x), and with x' = v' / (hi - lo) the
// integrands tau and c tau along the ray have |f'| <= F1 and |f''| <= F2 (chain rule).
// - The opacity cap not reached on the crossing: tau and c tau are smooth on each part of the
//   crossing between the function's kinks (Marcher::steps cuts its steps there), and a midpoint
//   step of length h, composited exactly for its midpoint's tau and c (1 - exp(-tau h)) -- or
//   with Simpson's optical depth, closer still -- is off from the exact
//   integral by h^3 (F2 / 24 + (F1(c tau) T0 + C0 T0 F1(tau)) / 12) to leading order, in optical
//   depth and emission (the first: the midpoint rule's h^3 f'' / 24; the second: the emission's
//   transmittance inside the step); a factor 2 covers what follows, and h <= 0.5 / T0 keeps it
//   small.
// - Otherwise (the cap: a kink no step is cut at): Lipschitz, |f(s) - f(mid)| <= F1 |s - mid|,
//   so off by at most h^2 (F1(tau) + F1(c tau)) / 4 + h^3 C0 T0 F1(tau) / 2.
// An error d in a step's optical depth or emission moves the pixel by at most d (what lies behind
// is at most 1), as the blocks' first-order rule (EmptyBlocks) counts it.
double cellStep(const TransferFunction& tf, const double* k, double sa, double sb, double tol) {
  // tol: per unit length (a step of h may be off by tol h), so a ray's steps add up to tol times
  // the length it integrates, whatever their number.
  auto v = [&](double s) { return ((k[3] * s + k[2]) * s + k[1]) * s + k[0]; };
  auto dv = [&](double s) { return (3.0 * k[3] * s + 2.0 * k[2]) * s + k[1]; };
  double vlo = std::min(v(sa), v(sb)), vhi = std::max(v(sa), v(sb));
  double v1 = std::max(std::abs(dv(sa)), std::abs(dv(sb)));
  const double v2 = std::max(std::abs(6.0 * k[3] * sa + 2.0 * k[2]), std::abs(6.0 * k[3] * sb + 2.0 * k[2]));
  // v' = 3 k3 s^2 + 2 k2 s + k1: its roots (v's extremes) and its vertex (|v'|'s) inside [sa, sb].
  const double qa = 3.0 * k[3], qb = 2.0 * k[2], qc = k[1];
  auto take = [&](double s) {
    if (s > sa && s < sb) vlo = std::min(vlo, v(s)), vhi = std::max(vhi, v(s));
  };
  if (qa != 0.0) {
    const double disc = qb * qb - 4.0 * qa * qc;
    if (disc >= 0.0) {
      const double r = std::sqrt(disc);
      take((-qb - r) / (2.0 * qa));
      take((-qb + r) / (2.0 * qa));
    }
    const double vert = -qb / (2.0 * qa);
    if (vert > sa && vert < sb) v1 = std::max(v1, std::abs(dv(vert)));
  } else if (qb != 0.0) {
    take(-qc / qb);
  }
  if (!std::isfinite(vlo + vhi + v1 + v2)) return 0.0;  // a missing corner: every sample NaN
  const double lo = tf.rangeLo(), hi = tf.rangeHi();
  bool kink = false;  // the opacity cap inside the crossing (the function's own kinks: below)
  const double xl = tf.normalise(vlo), xh = tf.normalise(vhi);
  const std::vector<TfPoint>& p = tf.points();
  const double cap = TransferFunction::kMaxOpacity, unit = tf.unitLength();
  double t0 = 0.0, t1 = 0.0, t2 = 0.0, c0 = 0.0, c1 = 0.0;
  // The pieces the range reaches, the constant ends beyond the first and last points included.
  auto piece = [&](double u0, double u1, double ka, const double kc[3]) {
    const std::array<double, 4> e0 = tf.atNormalised(u0), e1 = tf.atNormalised(u1);
    double amax = std::max(e0[3], e1[3]);
    if (amax >= cap) kink = true, amax = cap;
    if (!(amax > 0.0)) return;  // no opacity: tau = 0, nothing emitted
    t0 = std::max(t0, -std::log1p(-amax) / unit);
    t1 = std::max(t1, std::abs(ka) / ((1.0 - amax) * unit));
    t2 = std::max(t2, ka * ka / ((1.0 - amax) * (1.0 - amax) * unit));
    for (int c = 0; c < 3; ++c) {
      c0 = std::max({c0, std::abs(e0[c]), std::abs(e1[c])});
      c1 = std::max(c1, std::abs(kc[c]));
    }
  };
  const double zero[3] = {0, 0, 0};
  if (xl < p.front().value) piece(xl, std::min(xh, p.front().value), 0.0, zero);
  if (xh > p.back().value) piece(std::max(xl, p.back().value), xh, 0.0, zero);
  for (size_t i = 0; i + 1 < p.size(); ++i) {
    const double u0 = std::max(xl, p[i].value), u1 = std::min(xh, p[i + 1].value);
    if (!(p[i + 1].value > p[i].value) || u0 > u1) continue;
    const double w = p[i + 1].value - p[i].value;
    const double kc[3] = {(p[i + 1].r - p[i].r) / w, (p[i + 1].g - p[i].g) / w, (p[i + 1].b - p[i].b) / w};
    piece(u0, u1, (p[i + 1].a - p[i].a) / w, kc);
  }
  if (!(t0 > 0.0)) return 0.0;
  const double x1 = v1 / (hi - lo), x2 = v2 / (hi - lo);
  const double f1 = t1 * x1, f1c = (c1 * t0 + c0 * t1) * x1;
  if (!kink) {
    const double f2 = t2 * x1 * x1 + t1 * x2;
    const double f2c = (2.0 * c1 * t1 + c0 * t2) * x1 * x1 + (c1 * t0 + c0 * t1) * x2;
    const double b = 2.0 * ((f2 + f2c) / 24.0 + (f1c * t0 + c0 * t0 * f1) / 12.0);
    return std::min(std::sqrt(tol / b), 0.5 / t0);
  }
  const double a2 = (f1 + f1c) / 4.0, a3 = c0 * t0 * f1 / 2.0;
  return std::min(tol / (2.0 * a2), std::sqrt(tol / (2.0 * a3)));
}

// The midpoint rule along one ray through one brick: each step [ta, ta + h] composited into `out`.
class Marcher {
 public:
  Marcher(const BrickField& field, const TransferFunction& tf, const Shading& shading, double flat,
          const glm::dvec3& o, const glm::dvec3& d)
      : field_(field), tf_(tf), tfc_(tf), shading_(shading), flat_(flat), o_(o), d_(d), cursor_(field, o, d) {}

  // Whether cells() can march this ray (unshaded, the function's linear scale).
  bool cellwise() const { return !shading_.enabled && tfc_.linear(); }

  // [ta, tb] cell by cell: in each cell crossed, equal steps of the longest length cellStep
  // allows for `tol`, at least `h_min` (the fine step, or the block's multiple of it), none where
  // cellStep finds nothing to integrate. Where the field clamps (the grid's or the held samples'
  // edge), steps of h_min to tb.
  void cells(SegmentIntegral& out, double ta, double tb, double step, double h_min, double tol) {
    double t = ta;
    while (t < tb && out.transmit > kStopTransmit) {
      const double probe = t + std::min(0.25 * step, 0.5 * (tb - t));
      if (!cursor_.enterAt(probe)) {
        const long long n = std::max(1LL, (long long)std::ceil((tb - t) / h_min));
        steps(out, t, n, (tb - t) / double(n));
        return;
      }
      double te = std::min(cursor_.exitT(), tb);
      if (te <= probe) te = std::min(tb, probe + 0.25 * step);  // rounding at a face
      const double h = cellStep(tf_, cursor_.cubic(), t - cursor_.refT(), te - cursor_.refT(), tol);
      if (h > 0.0) {
        const long long n = std::max(1LL, (long long)std::ceil((te - t) / std::max(h, h_min)));
        steps(out, t, n, (te - t) / double(n));
      }
      t = te;
    }
  }

  // n equal steps of h from ta (stopping once the transmittance is below kStopTransmit), with
  // the reference's rule (reference/reference.cpp): a step whose end values straddle a kink of
  // the function (TransferFunction::kinkValues) is cut where the values, linear between the
  // ends, meet it; each part composited with its middle's colour and its optical depth by
  // Simpson's rule over its ends and middle.
  void steps(SegmentIntegral& out, double ta, long long n, double h) {
    const std::vector<double>& kinks = tf_.kinkValues();
    double va = cursor_.at(ta), xa = extinctionOf(va);
    for (long long i = 0; i < n && out.transmit > kStopTransmit; ++i) {
      const double sa = ta + double(i) * h, sb = ta + double(i + 1) * h;
      const double vb = cursor_.at(sb), xb = extinctionOf(vb);
      std::pair<double, double> cuts[kMaxStepCuts];
      const int m = stepCuts(kinks, sa, sb, va, vb, cuts);
      if (m == 0) {
        part(out, sa, sb, xa, xb);
      } else {
        double pa = sa, ea = xa;
        for (int j = 0; j <= m && out.transmit > kStopTransmit; ++j) {
          const double pb = j < m ? cuts[j].first : sb, eb = j < m ? extinctionOf(cuts[j].second) : xb;
          if (pb > pa) part(out, pa, pb, ea, eb);
          pa = pb, ea = eb;
        }
      }
      va = vb, xa = xb;
    }
  }

 private:
  // tau (per world unit) at raw value v; NaN where v is (a missing sample).
  double extinctionOf(double v) {
    if (std::isnan(v)) return v;
    const double a = tfc_.at(v)[3];
    return a > 0.0 ? tf_.extinctionOfOpacity(a) : 0.0;  // the same 0 without the log
  }

  // One step over [pa, pb] (the extinctions xa, xb at its ends: Simpson's rule with its middle's;
  // the middle's alone where an end is missing) composited into `out`.
  void part(SegmentIntegral& out, double pa, double pb, double xa, double xb) {
    const double tm = 0.5 * (pa + pb);
    const double v = cursor_.at(tm);
    if (std::isnan(v)) return;  // the stencil touches a missing sample: transparent
    const std::array<double, 4> f = tfc_.at(v);
    if (!(f[3] > 0.0) && !(xa > 0.0) && !(xb > 0.0)) return;  // nothing here to integrate
    const double xm = f[3] > 0.0 ? tf_.extinctionOfOpacity(f[3]) : 0.0;
    const double tau = std::isnan(xa) || std::isnan(xb) ? xm : (xa + 4.0 * xm + xb) / 6.0;
    if (!(tau > 0.0)) return;
    const double a = 1.0 - std::exp(-tau * (pb - pa));
    std::array<double, 3> c{f[0], f[1], f[2]};
    if (shading_.enabled)
      c = shadeSample(c, field_.gradient(field_.grid.indexOfWorld(o_ + tm * d_)), d_, shading_, flat_);
    for (int k = 0; k < 3; ++k) out.rgb[k] += out.transmit * a * c[k];
    out.transmit *= 1.0 - a;
  }

  const BrickField& field_;
  const TransferFunction& tf_;
  TfCursor tfc_;
  const Shading& shading_;
  double flat_;
  glm::dvec3 o_, d_;
  FieldCursor cursor_;
};

}  // namespace

SegmentIntegral integrateSegment(const BrickField& field, const TransferFunction& tf,
                                 const Shading& shading, double flat, const glm::dvec3& o,
                                 const glm::dvec3& d, double t0, double t1, double step,
                                 const EmptyBlocks* blocks) {
  SegmentIntegral out;
  if (!(t1 > t0)) return out;
  Marcher march(field, tf, shading, flat, o, d);
  if (!blocks) {
    const long long n = std::max(1LL, (long long)std::ceil((t1 - t0) / step));
    march.steps(out, t0, n, (t1 - t0) / double(n));
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
    if (!blocks->empty[bi] && march.cellwise()) {
      march.cells(out, t, tb, step, blocks->multiple[bi] * step, kCellTolerance / field.grid.minSpacing());
    } else if (!blocks->empty[bi]) {
      const double len = tb - t, big = blocks->multiple[bi] * step;
      const long long n = std::max(1LL, (long long)std::ceil(len / big));
      march.steps(out, t, n, len / double(n));
    }
    t = tb;
  }
  return out;
}

}  // namespace sortlast
