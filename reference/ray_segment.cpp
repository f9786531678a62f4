#include "reference/ray_segment.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include "common/box.h"
#include "common/pixel_threads.h"
#include "common/trilinear.h"
#include "reference/ray_cubic.h"
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

// The cell march's error per voxel (the smallest spacing) of the ray's length: a ray through 100
// visible voxels is within about 100 kCellTolerance of the exact integral (Marcher::refine).
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
      return cubicAt(k_, s);
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

// The reference's integral along one ray through one brick, composited into `out`: in equal steps
// with the reference's rule (steps()), or cell by cell to a tolerance (cells()).
class Marcher {
 public:
  Marcher(const BrickField& field, const TransferFunction& tf, const Shading& shading, double flat,
          const glm::dvec3& o, const glm::dvec3& d, double stop)
      : field_(field), tf_(tf), tfc_(tf), shading_(shading), flat_(flat), o_(o), d_(d), cursor_(field, o, d),
        stop_(stop) {}

  // [ta, tb] cell by cell: each cell's crossing integrated to `tol` (crossing()). Where the
  // field clamps (the grid's or the held samples' edge), steps of h_min to tb.
  void cells(SegmentIntegral& out, double ta, double tb, double step, double h_min, double tol) {
    double t = ta;
    while (t < tb && out.transmit > stop_) {
      const double probe = t + std::min(0.25 * step, 0.5 * (tb - t));
      if (!cursor_.enterAt(probe)) {
        const long long n = std::max(1LL, (long long)std::ceil((tb - t) / h_min));
        steps(out, t, n, (tb - t) / double(n));
        return;
      }
      double te = std::min(cursor_.exitT(), tb);
      if (te <= probe) te = std::min(tb, probe + 0.25 * step);  // rounding at a face
      crossing(out, t, te, tol);
      t = te;
    }
  }

  // n equal steps of h from ta (stopping once the transmittance is below stop_), with
  // the reference's rule (reference/reference.cpp): a step whose end values straddle a kink of
  // the function (TransferFunction::kinkValues) is cut where the values, linear between the
  // ends, meet it; each part composited with its middle's colour and its optical depth by
  // Simpson's rule over its ends and middle.
  void steps(SegmentIntegral& out, double ta, long long n, double h) {
    const std::vector<double>& kinks = tf_.kinkValues();
    double va = cursor_.at(ta), xa = extinctionOf(va);
    for (long long i = 0; i < n && out.transmit > stop_; ++i) {
      const double sa = ta + double(i) * h, sb = ta + double(i + 1) * h;
      const double vb = cursor_.at(sb), xb = extinctionOf(vb);
      std::pair<double, double> cuts[kMaxStepCuts];
      const int m = stepCuts(kinks, sa, sb, va, vb, cuts);
      if (m == 0) {
        part(out, sa, sb, xa, xb);
      } else {
        double pa = sa, ea = xa;
        for (int j = 0; j <= m && out.transmit > stop_; ++j) {
          const double pb = j < m ? cuts[j].first : sb, eb = j < m ? extinctionOf(cuts[j].second) : xb;
          if (pb > pa) part(out, pa, pb, ea, eb);
          pa = pb, ea = eb;
        }
      }
      va = vb, xa = xb;
    }
  }

 private:
  // One cell's crossing [ta, tb] (the field the cursor's cubic in s = t - refT; nothing below moves the cursor): cut where the field
  // turns and where it meets a kink of opacity, so that on each piece the value is a monotone
  // cubic and opacity linear in its scaled value (transfer/value_scale.h: smooth and monotone in
  // the value between the kinks) -- extinction smooth along the ray -- and each piece integrated
  // by adaptive Simpson (refine), skipped where neither end has opacity (then nothing inside
  // has). Colour's own kinks (a colour map's many points) are left to refine's halving: cut at
  // each of viridis's points, hydrogen_log's estimate took 3.3x as long for the same figures.
  // Nothing where a corner is missing (every sample there NaN: the reference's steps are
  // transparent there too).
  void crossing(SegmentIntegral& out, double ta, double tb, double tol) {
    const double ref = cursor_.refT(), sa = ta - ref, sb = tb - ref;
    const double* k = cursor_.cubic();
    if (!std::isfinite(k[0] + k[1] + k[2] + k[3])) return;
    const Turns c = turnsOf(k, sa, sb);
    // The piece ends in ray order: on a rising part the kinks it meets in increasing order, on a
    // falling one in decreasing order.
    const std::vector<double>& kinks = tf_.opacityKinkValues();
    cuts_.clear();
    cuts_.push_back(sa);
    for (int i = 0; i <= c.count; ++i) {
      const double p = i == 0 ? sa : c.at[i - 1], q = i == c.count ? sb : c.at[i];
      const double vp = cubicAt(k, p), vq = cubicAt(k, q);
      const auto first = std::upper_bound(kinks.begin(), kinks.end(), std::min(vp, vq));
      auto last = first;
      while (last != kinks.end() && *last < std::max(vp, vq)) ++last;
      if (vp < vq)
        for (auto kv = first; kv != last; ++kv) cuts_.push_back(cubicRoot(k, p, q, vp, *kv));
      else
        for (auto kv = last; kv != first; --kv) cuts_.push_back(cubicRoot(k, p, q, vp, *(kv - 1)));
      cuts_.push_back(q);
    }
    // Each piece's start is the previous piece's end; the first piece's start, the previous
    // crossing's last end where this crossing starts there (the field is continuous across a
    // cell's face: the same value within rounding).
    Point a = last_t_ == ta ? Point{sa, {last_.c[0], last_.c[1], last_.c[2]}, last_.tau} : point(sa);
    for (size_t i = 0; i + 1 < cuts_.size() && out.transmit > stop_; ++i) {
      if (!(cuts_[i + 1] > cuts_[i])) continue;
      const Point b = point(cuts_[i + 1]);
      // Opacity is linear in the scaled value on a piece, and that monotone: none at both
      // ends, none inside.
      if (a.tau > 0.0 || b.tau > 0.0) {
        const Point m = point(0.5 * (cuts_[i] + cuts_[i + 1]));
        refine(out, a, m, b, simpson(a, m, b), tol, 0);
      }
      a = b;
    }
    last_ = a, last_t_ = a.s == sb ? tb : -HUGE_VAL;
  }

  // The integrand at s (the current cell's cubic): colour and extinction.
  struct Point {
    double s, c[3], tau;
  };
  // Shaded, the colour as the reference's (transfer/shading.h): the central-difference gradient's
  // taps lie one voxel either side, in the neighbouring cells at the same place within them, so
  // it too is smooth inside a crossing (where a tap clamps at the grid's edge, it clamps for the
  // whole crossing); the model's own kinks (the two-sided cosine, the flat-gradient blend, the
  // clamp) are left to refine's halving.
  Point point(double s) {
    const std::array<double, 4> f = tfc_.at(cubicAt(cursor_.cubic(), s));
    Point p{s, {f[0], f[1], f[2]}, f[3] > 0.0 ? tf_.extinctionOfOpacity(f[3]) : 0.0};
    if (shading_.enabled && p.tau > 0.0) {  // where tau is 0 the colour weighs nothing
      const glm::dvec3 u = field_.grid.indexOfWorld(o_ + (s + cursor_.refT()) * d_);
      const std::array<double, 3> c = shadeSample({f[0], f[1], f[2]}, field_.gradient(u), d_, shading_, flat_);
      p.c[0] = c[0], p.c[1] = c[1], p.c[2] = c[2];
    }
    return p;
  }

  // Simpson's rule for one piece [a.s, b.s] (m its middle): its optical depth over the three
  // points, the depth to the middle from the parabola through them, and its emission
  // int c tau T ds with T the transmittance from a.s. The emission's weights (tau T at the three
  // points) are scaled to sum to the piece's opacity 1 - T(b), so that a constant colour c gives
  // exactly c (1 - T(b)) -- as the reference's steps do -- and the colour is still weighed by
  // Simpson's rule (fourth order: the scale is 1 + O(h^4)).
  static SegmentIntegral simpson(const Point& a, const Point& m, const Point& b) {
    SegmentIntegral r;
    if (!(a.tau > 0.0) && !(m.tau > 0.0) && !(b.tau > 0.0)) return r;
    const double h = b.s - a.s;
    const double depth = h / 6.0 * (a.tau + 4.0 * m.tau + b.tau);
    const double to_mid = std::max(0.0, h / 24.0 * (5.0 * a.tau + 8.0 * m.tau - b.tau));
    r.transmit = std::exp(-depth);
    const double wa = a.tau, wm = 4.0 * m.tau * std::exp(-to_mid), wb = b.tau * r.transmit;
    const double w = wa + wm + wb;
    if (!(w > 0.0)) return r;
    const double scale = (1.0 - r.transmit) / w;
    for (int k = 0; k < 3; ++k) r.rgb[k] = scale * (wa * a.c[k] + wm * m.c[k] + wb * b.c[k]);
    return r;
  }

  // Adaptive Simpson: the piece's rule against its two halves'; the halves' result kept where
  // the two agree within tol h (h the piece's length) divided by the transmittance in front of
  // the piece (an error there moves the pixel by that much less), else each half refined again.
  // Not 15 tol h (Richardson's factor for a smooth integrand, which assumes the halves are 16
  // times closer to the integral than the whole): shaded, where the lighting has kinks inside a
  // piece, that was 1.2e-4 from a march 32 times finer in the unit test (the plain march 6e-6);
  // with tol h, 1.2e-5, for 1.2-1.6x the shaded estimate's time and the same unshaded.
  void refine(SegmentIntegral& out, const Point& a, const Point& m, const Point& b,
              const SegmentIntegral& whole, double tol, int depth) {
    const Point q1 = point(0.5 * (a.s + m.s)), q3 = point(0.5 * (m.s + b.s));
    const SegmentIntegral left = simpson(a, q1, m), right = simpson(m, q3, b);
    SegmentIntegral both = left;
    for (int k = 0; k < 3; ++k) both.rgb[k] += left.transmit * right.rgb[k];
    both.transmit *= right.transmit;
    double err = std::abs(both.transmit - whole.transmit);
    for (int k = 0; k < 3; ++k) err = std::max(err, std::abs(both.rgb[k] - whole.rgb[k]));
    if (depth >= kMaxRefine || err * out.transmit <= tol * (b.s - a.s)) {
      for (int k = 0; k < 3; ++k) out.rgb[k] += out.transmit * both.rgb[k];
      out.transmit *= both.transmit;
      return;
    }
    refine(out, a, q1, m, left, tol, depth + 1);
    if (out.transmit > stop_) refine(out, m, q3, b, right, tol, depth + 1);
  }
  static constexpr int kMaxRefine = 12;  // halves down to 1/8192 of a piece

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
  const double stop_;           // the transmittance the march stops below
  std::vector<double> cuts_;    // crossing()'s piece ends
  Point last_{};                // the last crossing's end (at ray parameter last_t_)
  double last_t_ = -HUGE_VAL;
};

}  // namespace

SegmentIntegral integrateSegment(const BrickField& field, const TransferFunction& tf,
                                 const Shading& shading, double flat, const glm::dvec3& o,
                                 const glm::dvec3& d, double t0, double t1, double step,
                                 const EmptyBlocks* blocks, double stop_transmit) {
  SegmentIntegral out;
  if (!(t1 > t0)) return out;
  Marcher march(field, tf, shading, flat, o, d, stop_transmit);
  if (!blocks) {
    const long long n = std::max(1LL, (long long)std::ceil((t1 - t0) / step));
    march.steps(out, t0, n, (t1 - t0) / double(n));
    return out;
  }
  // Block by block: the block holding a point just past t, its exit along the ray, and in it
  // equal steps of at most its multiple of `step` (an empty block: none).
  double t = t0;
  while (t < t1 && out.transmit > stop_transmit) {
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
    if (!blocks->empty[bi])
      march.cells(out, t, tb, step, blocks->multiple[bi] * step, kCellTolerance / field.grid.minSpacing());
    t = tb;
  }
  return out;
}

}  // namespace sortlast
