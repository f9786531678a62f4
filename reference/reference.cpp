#include "reference/reference.h"

#include "common/trilinear.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <optional>
#include <thread>

#include "common/clip.h"
#include "common/error.h"
#include "reference/ray_segment.h"
#include "reference/step_cuts.h"

namespace sortlast {

double WholeVolume::at(const glm::dvec3& u) const {
  if (adaptive) return sampleIndex(*adaptive, u);
  const glm::ivec3 n = grid.dims;
  int i[3];
  double f[3];
  for (int a = 0; a < 3; ++a) {
    double c = std::clamp(u[a], 0.0, double(n[a] - 1));
    i[a] = std::min(int(c), n[a] - 2);
    f[a] = c - i[a];
  }
  auto s = [&](int dx, int dy, int dz) {
    return double(samples[size_t(i[0] + dx) + size_t(n.x) * (size_t(i[1] + dy) + size_t(n.y) * size_t(i[2] + dz))]);
  };
  return trilinear(s, f);
}

glm::dvec3 WholeVolume::gradient(const glm::dvec3& u) const {
  return centralGradient([this](const glm::dvec3& p) { return at(p); }, u, grid.spacing);
}

namespace {

// One implementation for both overloads: with no stop (nullptr) every step below reduces to the
// volume-only arithmetic exactly (min(t1, inf) = t1; adding a zero surface changes no bit).
ImageF integrate(const WholeVolume& vol, const TransferFunction& tf, const Camera& cam, double step,
                 int threads, const SurfaceImage* stop, const ImageF* stop_colour,
                 const Shading& shading, const GlowRays* glow, bool cells) {
  ImageF img(cam.width, cam.height);
  const double flat = flatGradient(tf.rangeLo(), tf.rangeHi(), vol.grid.spacing);
  Box3 box = vol.grid.worldBox();
  // reference.integrator: cells -- the whole volume as one brick for integrateSegment.
  std::optional<BrickField> whole;
  std::optional<EmptyBlocks> blocks;
  if (cells && !vol.adaptive && !glow) {
    whole = BrickField{vol.grid, IndexBox{glm::ivec3(0), vol.grid.dims - 1}, vol.samples.data()};
    blocks.emplace(*whole, tf, step, shading.enabled);
  }
  std::atomic<int> next_row{0};
  auto worker = [&] {
    for (int y; (y = next_row++) < cam.height;) {
      for (int x = 0; x < cam.width; ++x) {
        size_t pixel = size_t(y) * cam.width + x;
        const CameraRay ray = cam.pixelRay(x, y);  // from the eye, or from the eye plane (orthographic)
        const glm::dvec3 o = ray.origin, d = ray.direction;
        double t0, t1;
        double rgb[3] = {0, 0, 0}, transmit = 1.0;
        const double t_stop = stop && stop->hit(pixel) ? double(stop->t[pixel]) : HUGE_VAL;
        // Glow (emission without opacity) over [ta, tb] seen through transmittance tr.
        auto addGlow = [&](double ta, double tb, double tr) {
          if (!glow || !(tb > ta) || tr <= 0.0) return;
          const glm::dvec3 g = glow->radiance(o, d, ta, tb);
          for (int k = 0; k < 3; ++k) rgb[k] += tr * g[k];
        };
        double t_after = 0.0;  // where the volume's part of the ray ends (glow beyond it: `transmit`)
        if (intersectRayBox(o, d, box, t0, t1)) {
          t0 = std::max(t0, 0.0);
          clipSpan(vol.clip, o, d, t0, t1);  // clip.planes, clip.box (common/clip.h)
          if (stop && stop->hit(pixel)) t1 = std::min(t1, double(stop->t[pixel]));
          addGlow(0.0, std::min(t0, t_stop), 1.0);  // in front of the volume
          long long n = t1 > t0 && !whole ? std::max(1LL, (long long)std::ceil((t1 - t0) / step)) : 0;
          if (whole && t1 > t0) {
            const SegmentIntegral seg = integrateSegment(*whole, tf, shading, flat, o, d, t0, t1, step, &*blocks, 1e-15);
            for (int k = 0; k < 3; ++k) rgb[k] = seg.rgb[k];
            transmit = seg.transmit;
          }
          double h = n > 0 ? (t1 - t0) / double(n) : 0.0;
          // One step over [ta, tb] (its length len): the colour of its middle (index point u),
          // its optical depth by Simpson's rule from the extinctions xa, xb at its ends and its
          // middle's (the midpoint's alone where an end is missing).
          auto stepOver = [&](double ta, double tb, double len, const glm::dvec3& u, double xa, double xb) {
            double v = vol.at(u);  // NaN where the stencil touches a missing sample: transparent
            double a = 0.0;
            std::array<double, 4> f{0, 0, 0, 0};
            if (!std::isnan(v)) {
              f = tf.at(v);
              const double xm = tf.extinctionOfOpacity(f[3]);
              const double tau = std::isnan(xa) || std::isnan(xb) ? xm : (xa + 4.0 * xm + xb) / 6.0;
              a = 1.0 - std::exp(-tau * len);
            }
            // The step's glow: its exact integral times the transmittance at the step's middle
            // (the midpoint rule in transmittance, exact in the emitters' field).
            addGlow(ta, tb, transmit * std::sqrt(std::max(0.0, 1.0 - a)));
            if (a <= 0.0) return;
            std::array<double, 3> c{f[0], f[1], f[2]};
            if (shading.enabled) c = shadeSample(c, vol.gradient(u), d, shading, flat);
            for (int k = 0; k < 3; ++k) rgb[k] += transmit * a * c[k];
            transmit *= 1.0 - a;
          };
          auto indexAt = [&](double t) { return vol.grid.indexOfWorld(o + t * d); };
          auto extinctionOf = [&](double v) { return std::isnan(v) ? v : tf.extinction(v); };
          // A step whose end values straddle a kink of the transfer function (kinkValues) is cut
          // where the values, linear between the ends, meet it, and each part is a step of its
          // own: Simpson's rule is fourth order on a smooth part, first order across a kink.
          // Both measured on neghip's sharp function (512², reference.step 1/16 against 1/256):
          // midpoint steps 56.6 dB, 0.149 % of pixels over 4/255, max 15/255; cut at the kinks
          // 57.1 dB, 0.061 %, 7; cut and Simpson 60.0 dB, none over 4/255, max 4
          // (results/accuracy/reference_convergence.md).
          const std::vector<double>& kinks = tf.kinkValues();
          double va = n > 0 ? vol.at(indexAt(t0)) : 0.0, xa = extinctionOf(va);
          long long i = 0;
          for (; i < n && transmit > 1e-15; ++i) {
            const double ta = t0 + i * h, tb = t0 + (i + 1) * h;
            const double vb = vol.at(indexAt(tb)), xb = extinctionOf(vb);
            std::pair<double, double> cuts[kMaxStepCuts];
            const int m = stepCuts(kinks, ta, tb, va, vb, cuts);
            if (m == 0) {
              stepOver(ta, tb, h, indexAt(t0 + (i + 0.5) * h), xa, xb);
            } else {
              double sa = ta, ea = xa;
              for (int j = 0; j <= m && transmit > 1e-15; ++j) {
                const double sb = j < m ? cuts[j].first : tb, eb = j < m ? tf.extinction(cuts[j].second) : xb;
                if (sb > sa) stepOver(sa, sb, sb - sa, indexAt(0.5 * (sa + sb)), ea, eb);
                sa = sb, ea = eb;
              }
            }
            va = vb, xa = xb;
          }
          t_after = i < n ? HUGE_VAL : std::max(t1, t0);  // stopped early: nothing behind counts
        }
        addGlow(t_after, t_stop, transmit);  // behind the volume, or the whole ray without one
        double alpha = 1.0 - transmit;
        if (stop && stop->hit(pixel)) {
          const float* s = &stop_colour->px[4 * pixel];
          for (int k = 0; k < 3; ++k) rgb[k] += transmit * s[k];
          alpha = 1.0 - transmit * (1.0 - s[3]);
        }
        float* p = &img.px[pixel * 4];
        for (int k = 0; k < 3; ++k) p[k] = float(rgb[k]);
        p[3] = float(alpha);
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 0; t < std::max(1, threads); ++t) pool.emplace_back(worker);
  for (auto& t : pool) t.join();
  return img;
}

}  // namespace

ImageF renderReference(const WholeVolume& vol, const TransferFunction& tf, const Camera& cam,
                       double step, int threads, const Shading& shading, const GlowRays* glow, bool cells) {
  return integrate(vol, tf, cam, step, threads, nullptr, nullptr, shading, glow, cells);
}

ImageF renderReference(const WholeVolume& vol, const TransferFunction& tf, const Camera& cam,
                       double step, int threads, const SurfaceImage& stop,
                       const ImageF& stop_colour, const Shading& shading, const GlowRays* glow, bool cells) {
  if (stop.width != cam.width || stop.height != cam.height || stop_colour.width != cam.width ||
      stop_colour.height != cam.height)
    throw InputError("reference: the surface images (" + std::to_string(stop.width) + "x" +
                     std::to_string(stop.height) + ", colour " + std::to_string(stop_colour.width) +
                     "x" + std::to_string(stop_colour.height) + ") are not the camera's size (" +
                     std::to_string(cam.width) + "x" + std::to_string(cam.height) + ")");
  return integrate(vol, tf, cam, step, threads, &stop, &stop_colour, shading, glow, cells);
}

}  // namespace sortlast
