#include "reference/fields_reference.h"

#include <atomic>
#include <cmath>
#include <thread>

namespace sortlast {

ImageF renderFieldsReference(const std::vector<FieldInput>& fields, const Box3& box, const Camera& cam,
                             double step, int threads, const ClipRegion& clip) {
  ImageF img(cam.width, cam.height);
  std::vector<Box3> boxes;
  for (const FieldInput& f : fields) boxes.push_back(f.vol.grid.worldBox());
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
          for (long long i = 0; i < n && transmit > 1e-15; ++i) {
            const glm::dvec3 p = o + (t0 + (i + 0.5) * h) * d;
            double tau = 0.0, emitted[3] = {0, 0, 0};
            for (size_t f = 0; f < fields.size(); ++f) {
              if (!boxes[f].contains(p)) continue;
              const double v = fields[f].vol.at(fields[f].vol.grid.indexOfWorld(p));
              if (std::isnan(v)) continue;
              const double tau_f = fields[f].tf.extinction(v);
              if (!(tau_f > 0.0)) continue;
              const auto c = fields[f].tf.colour(v);
              tau += tau_f;
              for (int k = 0; k < 3; ++k) emitted[k] += tau_f * c[k];
            }
            if (!(tau > 0.0)) continue;
            const double a = 1.0 - std::exp(-tau * h);
            for (int k = 0; k < 3; ++k) rgb[k] += transmit * a * (emitted[k] / tau);
            transmit *= 1.0 - a;
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
