#include "reference/fields_reference.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>

#include "reference/step_cuts.h"

namespace sortlast {

ImageF renderFieldsReference(const std::vector<FieldInput>& fields, const Box3& box, const Camera& cam,
                             double step, int threads, const ClipRegion& clip) {
  ImageF img(cam.width, cam.height);
  std::vector<Box3> boxes;
  for (const FieldInput& f : fields) boxes.push_back(f.vol.grid.worldBox());
  // The steps' ends: a span's first and last end lie on a box's face up to rounding, where the
  // values clamp to the face's (as WholeVolume::at does for the one-field reference).
  std::vector<Box3> ends = boxes;
  for (Box3& b : ends) {
    const glm::dvec3 pad = 1e-9 * (glm::abs(b.lo) + glm::abs(b.hi) + 1.0);
    b.lo -= pad, b.hi += pad;
  }
  std::atomic<int> next_row{0};
  auto worker = [&] {
    for (int y; (y = next_row++) < cam.height;) {
      for (int x = 0; x < cam.width; ++x) {
        const CameraRay ray = cam.pixelRay(x, y);  // from the eye, or the eye plane (orthographic)
        const glm::dvec3 o = ray.origin, d = ray.direction;
        double rgb[3] = {0, 0, 0}, transmit = 1.0, t0, t1;
        if (intersectRayBox(o, d, box, t0, t1)) {
          t0 = std::max(t0, 0.0);
          clipSpan(clip, o, d, t0, t1);  // clip.planes, clip.box
          const long long n = t1 > t0 ? std::max(1LL, (long long)std::ceil((t1 - t0) / step)) : 0;
          const double h = n > 0 ? (t1 - t0) / double(n) : 0.0;
          // The one-field reference's rule (reference/reference.cpp), field by field: each
          // field's value at a step's ends, the step cut where a field's values cross a kink of
          // its function, each part's optical depth by Simpson's rule per field (the middle's
          // alone where an end lies outside the field or is missing), its colour the fields'
          // colours at its middle weighted by their optical depths.
          const size_t nf = fields.size();
          auto valueAt = [&](size_t f, double t) {
            const glm::dvec3 p = o + t * d;
            if (!ends[f].contains(p)) return double(NAN);
            return fields[f].vol.at(fields[f].vol.grid.indexOfWorld(p));
          };
          auto tauOf = [&](size_t f, double v) {
            return std::isnan(v) ? v : fields[f].tf.extinction(v);
          };
          std::vector<double> va(nf), vb(nf), xa(nf), xb(nf), ea(nf), eb(nf);
          std::vector<std::pair<double, std::pair<size_t, double>>> cuts;  // (where, (field, value))
          for (size_t f = 0; f < nf; ++f) va[f] = valueAt(f, t0), xa[f] = tauOf(f, va[f]);
          // One part [pa, pb] with the fields' end extinctions ea, eb.
          auto part = [&](double pa, double pb, const std::vector<double>& ends_a,
                          const std::vector<double>& ends_b) {
            const glm::dvec3 p = o + (0.5 * (pa + pb)) * d;
            double tau = 0.0, emitted[3] = {0, 0, 0};
            for (size_t f = 0; f < nf; ++f) {
              if (!boxes[f].contains(p)) continue;
              const double v = fields[f].vol.at(fields[f].vol.grid.indexOfWorld(p));
              if (std::isnan(v)) continue;
              const double xm = fields[f].tf.extinction(v);
              const bool ends_known = !std::isnan(ends_a[f]) && !std::isnan(ends_b[f]);
              const double tau_f = ends_known ? (ends_a[f] + 4.0 * xm + ends_b[f]) / 6.0 : xm;
              if (!(tau_f > 0.0)) continue;
              const auto c = fields[f].tf.colour(v);
              tau += tau_f;
              for (int k = 0; k < 3; ++k) emitted[k] += tau_f * c[k];
            }
            if (!(tau > 0.0)) return;
            const double a = 1.0 - std::exp(-tau * (pb - pa));
            for (int k = 0; k < 3; ++k) rgb[k] += transmit * a * (emitted[k] / tau);
            transmit *= 1.0 - a;
          };
          for (long long i = 0; i < n && transmit > 1e-15; ++i) {
            const double ta = t0 + double(i) * h, tb = t0 + double(i + 1) * h;
            cuts.clear();
            for (size_t f = 0; f < nf; ++f) {
              vb[f] = valueAt(f, tb), xb[f] = tauOf(f, vb[f]);
              std::pair<double, double> mine[kMaxStepCuts];
              const int m = stepCuts(fields[f].tf.kinkValues(), ta, tb, va[f], vb[f], mine);
              for (int j = 0; j < m; ++j) cuts.push_back({mine[j].first, {f, mine[j].second}});
            }
            std::sort(cuts.begin(), cuts.end());
            ea = xa;
            double pa = ta;
            for (const auto& cut : cuts) {
              if (transmit <= 1e-15) break;
              // The part's far end: each field's extinction there, its kink's where it is cut.
              for (size_t f = 0; f < nf; ++f) eb[f] = tauOf(f, valueAt(f, cut.first));
              eb[cut.second.first] = fields[cut.second.first].tf.extinction(cut.second.second);
              if (cut.first > pa) part(pa, cut.first, ea, eb);
              pa = cut.first, ea = eb;
            }
            if (transmit > 1e-15) part(pa, tb, ea, xb);
            va = vb, xa = xb;
          }
        }
        float* px = &img.px[(size_t(y) * cam.width + x) * 4];
        for (int k = 0; k < 3; ++k) px[k] = float(rgb[k]);
        px[3] = float(1.0 - transmit);
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 0; t < std::max(1, threads); ++t) pool.emplace_back(worker);
  for (auto& t : pool) t.join();
  return img;
}

}  // namespace sortlast
