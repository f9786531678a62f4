#include "reference/metaball_reference.h"

#include <algorithm>
#include <atomic>
#include <thread>

#include "common/error.h"
#include "transfer/metaball_shading.h"

namespace sortlast {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// A particle's stretch of the ray: where it is within h of O + t D, clipped to [entry, exit].
struct Span {
  double t_in, t_out;
  uint32_t particle;
};

// P(r) = (1 - r/h)^2 and its contribution to grad F at offset v = x - P_j (|v| = r): P'(r) v / r,
// defined 0 at r = 0 where P has no derivative.
double kernel(double r, double h) {
  double u = 1.0 - r / h;
  return r <= h ? u * u : 0.0;
}
glm::dvec3 kernelGradient(const glm::dvec3& v, double r, double h) {
  if (r <= 0.0 || r > h) return glm::dvec3(0.0);
  return (-2.0 * (1.0 - r / h) / h / r) * v;
}

}  // namespace

MetaballField::MetaballField(MetaballModel model) : model_(std::move(model)) {
  const double h = model_.h, T = model_.threshold;
  if (!(std::isfinite(h) && h > 0.0))
    throw InputError("metaballs: influence radius h must be positive and finite (got " +
                     std::to_string(h) + ")");
  if (!(std::isfinite(T) && T > 0.0))
    throw InputError("metaballs: threshold T must be positive and finite (got " +
                     std::to_string(T) + ")");
  if (!model_.kernels.empty() && model_.kernels.size() != model_.positions.size())
    throw std::logic_error("MetaballModel: kernels and positions differ in count");
  cell_ = model_.kernels.empty() ? h : std::max(maxReach(model_.kernels), 1e-300);
  if (model_.positions.size() >= size_t(UINT32_MAX))
    throw InputError("metaballs: too many particles for the reference (at most 2^32 - 2)");
  Box3 bounds{glm::dvec3(kInf), glm::dvec3(-kInf)};
  for (size_t i = 0; i < model_.positions.size(); ++i) {
    const glm::dvec3& p = model_.positions[i];
    if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)))
      throw InputError("metaballs: NaN or infinite position at particle " + std::to_string(i));
    bounds.lo = glm::min(bounds.lo, p);
    bounds.hi = glm::max(bounds.hi, p);
  }
  if (model_.positions.empty()) {
    reach_ = bounds;  // lo > hi: no ray meets it
    return;
  }
  glm::dvec3 span = (bounds.hi - bounds.lo) / cell_;
  if (span.x > 0x1p30 || span.y > 0x1p30 || span.z > 0x1p30)
    throw InputError(
        "metaballs: the particles span over 2^30 influence radii; h is too small "
        "for the reference's neighbour grid");
  reach_ = {bounds.lo - cell_, bounds.hi + cell_};
  origin_ = bounds.lo;
  cell_count_ = glm::ivec3(glm::floor(span)) + 1;

  // Group particle indices by cell: sort by cell, then record each cell's run.
  std::vector<std::pair<glm::ivec3, uint32_t>> keyed(model_.positions.size());
  for (size_t i = 0; i < keyed.size(); ++i) keyed[i] = {cellOf(model_.positions[i]), uint32_t(i)};
  auto less = [](const auto& a, const auto& b) {
    if (a.first.x != b.first.x) return a.first.x < b.first.x;
    if (a.first.y != b.first.y) return a.first.y < b.first.y;
    if (a.first.z != b.first.z) return a.first.z < b.first.z;
    return a.second < b.second;
  };
  std::sort(keyed.begin(), keyed.end(), less);
  order_.resize(keyed.size());
  for (size_t i = 0; i < keyed.size();) {
    size_t j = i;
    for (; j < keyed.size() && keyed[j].first == keyed[i].first; ++j) order_[j] = keyed[j].second;
    cells_[keyed[i].first] = {uint32_t(i), uint32_t(j)};
    i = j;
  }
}

glm::ivec3 MetaballField::cellOf(const glm::dvec3& x) const {
  // Clamped so that points outside the grid (queries reach h beyond it) stay in int range and
  // map to the empty border cells.
  glm::dvec3 c = glm::floor((x - origin_) / cell_);
  c = glm::clamp(c, glm::dvec3(-2.0), glm::dvec3(cell_count_) + 1.0);
  return glm::ivec3(c);
}

template <typename Visit>
void MetaballField::forEachInCell(const glm::ivec3& c, Visit visit) const {
  auto it = cells_.find(c);
  if (it == cells_.end()) return;
  for (uint32_t k = it->second.first; k < it->second.second; ++k) visit(order_[k]);
}

double MetaballField::particleReach(uint32_t j) const {
  return model_.kernels.empty() ? model_.h : double(model_.kernels[j].reach);
}

// |A v| in double from the float kernel (A symmetric).
namespace {
glm::dvec3 frameOf(const ParticleKernel& k, const glm::dvec3& v) {
  glm::dmat3 a(k.a);
  return a * v;
}
}  // namespace

double MetaballField::particleField(uint32_t j, const glm::dvec3& x) const {
  glm::dvec3 v = x - model_.positions[j];
  if (model_.kernels.empty()) return kernel(glm::length(v), model_.h);
  const ParticleKernel& k = model_.kernels[j];
  return double(k.c) * kernel(glm::length(frameOf(k, v)), model_.h);
}

glm::dvec3 MetaballField::particleGradient(uint32_t j, const glm::dvec3& x) const {
  glm::dvec3 v = x - model_.positions[j];
  if (model_.kernels.empty()) return kernelGradient(v, glm::length(v), model_.h);
  const ParticleKernel& k = model_.kernels[j];
  glm::dvec3 u = frameOf(k, v);
  // grad of C P(|A v|) = C P'(|u|) A^T u / |u|, A^T = A.
  return double(k.c) * frameOf(k, kernelGradient(u, glm::length(u), model_.h));
}

double MetaballField::field(const glm::dvec3& x) const {
  if (!reach_.contains(x)) return 0.0;
  glm::ivec3 c = cellOf(x);
  double f = 0.0;
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        forEachInCell(c + glm::ivec3(dx, dy, dz), [&](uint32_t j) {
          f += particleField(j, x);
        });
  return f;
}

glm::dvec3 MetaballField::gradient(const glm::dvec3& x) const {
  if (!reach_.contains(x)) return glm::dvec3(0.0);
  glm::ivec3 c = cellOf(x);
  glm::dvec3 g(0.0);
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        forEachInCell(c + glm::ivec3(dx, dy, dz), [&](uint32_t j) {
          g += particleGradient(j, x);
        });
  return g;
}

double MetaballField::implicit(const glm::dvec3& x) const {
  return std::sqrt(field(x)) - model_.threshold;
}

// Walks the grid cells along O + t D, t in [a, b], front to back (Amanatides-Woo) and visits the
// particles of each cell's 3x3x3 neighbourhood the first time that neighbourhood reaches them.
// The DDA steps one cell along one axis at a time, always the same way on that axis, so the
// neighbourhood gains exactly the 3x3 layer beyond it: no cell is visited twice. A rounding slip
// at a cell face only affects particles at distance h - O(ulp), whose contribution is O(ulp^2).
class MetaballCellWalk {
 public:
  MetaballCellWalk(const MetaballField& f, const glm::dvec3& o, const glm::dvec3& d, double a,
                   double b)
      : f_(f), b_(b), cell_(f.cellOf(o + a * d)) {
    const double h = f.cell_;
    for (int k = 0; k < 3; ++k) {
      if (d[k] > 0.0) {
        step_[k] = 1;
        t_max_[k] = (f.origin_[k] + (cell_[k] + 1) * h - o[k]) / d[k];
        t_delta_[k] = h / d[k];
      } else if (d[k] < 0.0) {
        step_[k] = -1;
        t_max_[k] = (f.origin_[k] + cell_[k] * h - o[k]) / d[k];
        t_delta_[k] = -h / d[k];
      }
    }
    // The segment lies in the grid grown by a cell or two: it crosses at most this many cells.
    steps_left_ = f.cell_count_.x + f.cell_count_.y + f.cell_count_.z + 12;
  }

  bool done() const { return done_; }
  // Every particle within h of the ray at some t <= knownUntil() has been visited.
  double knownUntil() const {
    return done_ ? kInf : started_ ? std::min({t_max_.x, t_max_.y, t_max_.z}) : -kInf;
  }

  // Visits the next cell's new neighbours: visit(particle index).
  template <typename Visit>
  void advance(Visit visit) {
    if (done_) return;
    if (!started_) {
      started_ = true;
      for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) f_.forEachInCell(cell_ + glm::ivec3(dx, dy, dz), visit);
    } else {
      int k =
          t_max_.x <= t_max_.y ? (t_max_.x <= t_max_.z ? 0 : 2) : (t_max_.y <= t_max_.z ? 1 : 2);
      cell_[k] += step_[k];
      t_max_[k] += t_delta_[k];
      int u = (k + 1) % 3, v = (k + 2) % 3;
      glm::ivec3 c = cell_;
      c[k] += step_[k];
      for (int i = -1; i <= 1; ++i)
        for (int j = -1; j <= 1; ++j) {
          glm::ivec3 n = c;
          n[u] += i, n[v] += j;
          f_.forEachInCell(n, visit);
        }
    }
    if (!(std::min({t_max_.x, t_max_.y, t_max_.z}) <= b_) || --steps_left_ <= 0) done_ = true;
  }

 private:
  const MetaballField& f_;
  double b_;
  glm::ivec3 cell_, step_{0};
  glm::dvec3 t_max_{kInf}, t_delta_{kInf};
  int steps_left_ = 0;
  bool started_ = false, done_ = false;
};

RayHit MetaballField::firstHit(const glm::dvec3& o, const glm::dvec3& d, const Box3& clip) const {
  const double h = model_.h, T = model_.threshold;
  RayHit miss;
  double t0, t1, r0, r1;
  if (!intersectRayBox(o, d, clip, t0, t1)) return miss;
  const double entry = std::max(t0, 0.0), exit = t1;
  if (!(entry <= exit)) return miss;
  // F = 0 outside reach_: no particle can matter on a segment that misses it.
  if (!intersectRayBox(o, d, reach_, r0, r1)) return miss;
  if (std::max(entry, r0) > std::min(exit, r1)) return miss;
  MetaballCellWalk walk(*this, o, d, std::max(entry, r0), std::min(exit, r1));

  // Spans met by the walk wait in a min-heap by t_in until the samples reach them; `active` holds
  // every span with t_in <= t and t_out >= the previous sample, so it also serves the bracket
  // [t_prev, t] when refining.
  thread_local std::vector<Span> pending, active;
  pending.clear();
  active.clear();
  auto later = [](const Span& a, const Span& b) { return a.t_in > b.t_in; };
  auto visit = [&](uint32_t j) {
    glm::dvec3 v = model_.positions[j] - o;
    double tb = glm::dot(v, d);
    glm::dvec3 off = v - tb * d;  // closest approach, not |v|^2 - tb^2: no cancellation
    double d2 = glm::dot(off, off);
    const double reach = particleReach(j);
    if (d2 > reach * reach) return;
    double s = std::sqrt(reach * reach - d2);
    double in = std::max(tb - s, entry), out = std::min(tb + s, exit);
    if (in > out) return;
    pending.push_back({in, out, j});
    std::push_heap(pending.begin(), pending.end(), later);
  };
  auto walkTo = [&](double t) {  // until every span with t_in <= t is known
    while (!walk.done() && walk.knownUntil() < t) walk.advance(visit);
  };
  // I at a point, summed over the active spans (exact distances; the spans only select).
  auto implicitAt = [&](double t) {
    glm::dvec3 x = o + t * d;
    double f = 0.0;
    for (const Span& s : active) f += particleField(s.particle, x);
    return std::sqrt(f) - T;
  };

  const double w = h / kReferenceStepsPerH;
  double t_prev = entry, value_prev = -T;
  for (long long i = 0;; ++i) {
    double t = entry + double(i) * w;
    walkTo(t);
    if (active.empty()) {
      // F = 0 from the previous sample on, up to the first span not yet active: the nearer of
      // the next pending one and the first the walk has not reached. Jump to that sample.
      while (pending.empty() && !walk.done()) walk.advance(visit);
      if (pending.empty()) return miss;
      double next = std::min(pending.front().t_in, walk.knownUntil());
      if (next > t) {
        i = std::max(i, (long long)std::ceil((next - entry) / w));
        t = entry + double(i) * w;
      }
    }
    bool last = t >= exit;
    if (last) t = exit;  // always sample the exit: a surface just inside the far face counts here
    walkTo(t);
    while (!pending.empty() && pending.front().t_in <= t) {
      std::pop_heap(pending.begin(), pending.end(), later);
      active.push_back(pending.back());
      pending.pop_back();
    }
    std::erase_if(active, [&](const Span& s) { return s.t_out < t_prev; });
    double value = implicitAt(t);
    if (value >= 0.0) {
      if (i == 0) return miss;  // entered the box inside the surface: it lies in front of the box
      // Bisect the bracket, then one secant step inside the final, tiny bracket.
      double lo = t_prev, hi = t, v_lo = value_prev, v_hi = value;
      while (hi - lo > 1e-10 * h) {
        double mid = 0.5 * (lo + hi);
        if (mid <= lo || mid >= hi) break;
        double v = implicitAt(mid);
        (v >= 0.0 ? hi : lo) = mid;
        (v >= 0.0 ? v_hi : v_lo) = v;
      }
      RayHit hit;
      hit.t = lo + (hi - lo) * (-v_lo / (v_hi - v_lo));
      glm::dvec3 x = o + hit.t * d, g(0.0);
      for (const Span& s : active) g += particleGradient(s.particle, x);
      double len = glm::length(g);
      hit.normal = len > 0.0 ? -g / len : -d;
      return hit;
    }
    if (last) return miss;
    t_prev = t;
    value_prev = value;
  }
}

SurfaceImage referenceSurface(const MetaballModel& model, const Camera& cam, const Box3& clip,
                              int threads) {
  MetaballField field(model);
  SurfaceImage img(cam.width, cam.height);
  std::atomic<int> next_row{0};
  auto worker = [&] {
    for (int y; (y = next_row++) < cam.height;)
      for (int x = 0; x < cam.width; ++x) {
        const CameraRay ray = cam.pixelRay(x, y);  // from the eye, or the eye plane (orthographic)
        RayHit hit = field.firstHit(ray.origin, ray.direction, clip);
        if (!hit.hit()) continue;
        size_t i = size_t(y) * cam.width + x;
        img.t[i] = float(hit.t);
        img.normal[i] = glm::vec3(hit.normal);
      }
  };
  if (threads <= 0) threads = int(std::max(1u, std::thread::hardware_concurrency()));
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t) pool.emplace_back(worker);
  for (auto& t : pool) t.join();
  return img;
}

ImageF shadeSurfaceFloat(const SurfaceImage& surface, const Camera& cam, const glm::dvec3& colour) {
  if (surface.width != cam.width || surface.height != cam.height)
    throw InputError("shading: surface image is " + std::to_string(surface.width) + "x" +
                     std::to_string(surface.height) + ", camera image is " +
                     std::to_string(cam.width) + "x" + std::to_string(cam.height));
  ImageF out(surface.width, surface.height);
  for (int y = 0; y < surface.height; ++y)
    for (int x = 0; x < surface.width; ++x) {
      size_t i = size_t(y) * surface.width + x;
      if (!surface.hit(i)) continue;
      glm::dvec3 d = cam.rayDirection(x, y), n(surface.normal[i]);
      double len = glm::length(n);
      n = len > 0.0 ? n / len : -d;  // a file with no normal there: face the eye, like grad F = 0
      glm::dvec4 c = shadeMetaball(n, d, colour);
      for (int k = 0; k < 4; ++k) out.px[4 * i + k] = float(c[k]);
    }
  return out;
}

ImageRGBA8 shadeSurface(const SurfaceImage& surface, const Camera& cam, const glm::dvec3& colour) {
  return toRGBA8(shadeSurfaceFloat(surface, cam, colour));
}

}  // namespace sortlast
