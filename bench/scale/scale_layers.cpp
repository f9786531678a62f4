#include "bench/scale/scale_layers.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/glm.hpp>

#include "compositing/rle.h"

namespace sortlast::scale {

namespace {

struct Box {
  glm::dvec3 lo{0.0}, hi{1.0};
};

// The camera: orthonormal screen axes u (right), v (down the frame's rows) and view direction w.
struct View {
  glm::dvec3 u, v, w;
  double u0, v0, side;  // frame = [u0, u0 + side] x [v0, v0 + side] in (u, v)
};

View makeView() {
  const double ay = glm::radians(20.0), ax = glm::radians(15.0);
  // Rotate the axes of a camera looking down +z: first about y, then about x.
  auto rot = [&](glm::dvec3 p) {
    p = {std::cos(ay) * p.x + std::sin(ay) * p.z, p.y, -std::sin(ay) * p.x + std::cos(ay) * p.z};
    return glm::dvec3{p.x, std::cos(ax) * p.y - std::sin(ax) * p.z,
                      std::sin(ax) * p.y + std::cos(ax) * p.z};
  };
  View view{rot({1, 0, 0}), rot({0, 1, 0}), rot({0, 0, 1}), 0, 0, 0};
  double umin = 1e9, umax = -1e9, vmin = 1e9, vmax = -1e9;
  for (int c = 0; c < 8; ++c) {
    glm::dvec3 p{double(c & 1), double(c >> 1 & 1), double(c >> 2 & 1)};
    umin = std::min(umin, glm::dot(p, view.u)), umax = std::max(umax, glm::dot(p, view.u));
    vmin = std::min(vmin, glm::dot(p, view.v)), vmax = std::max(vmax, glm::dot(p, view.v));
  }
  view.side = std::max(umax - umin, vmax - vmin);
  view.u0 = 0.5 * (umin + umax) - 0.5 * view.side;
  view.v0 = 0.5 * (vmin + vmax) - 0.5 * view.side;
  return view;
}

// The kd-split: leaf `target`'s box (leaves numbered low side first), and the far-to-near order.
void split(const Box& box, int first, int count, int axis, const glm::dvec3& w, int target,
           Box* out, std::vector<int>* order) {
  if (count == 1) {
    if (first == target && out) *out = box;
    if (order) order->push_back(first);
    return;
  }
  const int low = count / 2;
  const double cut = box.lo[axis] + (box.hi[axis] - box.lo[axis]) * low / count;
  Box a = box, b = box;
  a.hi[axis] = cut;
  b.lo[axis] = cut;
  const int next = (axis + 1) % 3;
  // Looking along +w, the high side of a cut is the far one where w points to it.
  const bool high_far = w[axis] > 0;
  if (high_far) {
    split(b, first + low, count - low, next, w, target, out, order);
    split(a, first, low, next, w, target, out, order);
  } else {
    split(a, first, low, next, w, target, out, order);
    split(b, first + low, count - low, next, w, target, out, order);
  }
}

double sphereRadius(const View& view, double coverage) {
  if (!(coverage > 0.0) || coverage > maxCoverage() + 1e-12)
    throw std::invalid_argument("scale layers: coverage must be in (0, " +
                                std::to_string(maxCoverage()) + "], got " + std::to_string(coverage));
  return view.side * std::sqrt(coverage / M_PI);
}

}  // namespace

double maxCoverage() {
  const View view = makeView();
  return M_PI * 0.25 / (view.side * view.side);
}

VisibilityOrder sphereOrder(int ranks) {
  if (ranks < 1) throw std::invalid_argument("scale layers: ranks must be >= 1");
  VisibilityOrder order;
  split(Box{}, 0, ranks, 0, makeView().w, -1, nullptr, &order.ranks);
  order.bricks = order.ranks;
  return order;
}

Rect sphereLayerBound(int rank, int ranks, int width, int height, double coverage) {
  if (width < 1 || height < 1) throw std::invalid_argument("scale layers: empty frame");
  if (rank < 0 || rank >= ranks) throw std::invalid_argument("scale layers: rank out of range");
  const View view = makeView();
  const double radius = sphereRadius(view, coverage);
  const glm::dvec3 centre(0.5);
  Box box;
  split(Box{}, 0, ranks, 0, view.w, rank, &box, nullptr);
  // The box's projected corners, clipped to the sphere's disc and the frame.
  const double px_u = width / view.side, px_v = height / view.side;
  double umin = 1e9, umax = -1e9, vmin = 1e9, vmax = -1e9;
  for (int c = 0; c < 8; ++c) {
    glm::dvec3 p{c & 1 ? box.hi.x : box.lo.x, c >> 1 & 1 ? box.hi.y : box.lo.y,
                 c >> 2 & 1 ? box.hi.z : box.lo.z};
    umin = std::min(umin, glm::dot(p, view.u)), umax = std::max(umax, glm::dot(p, view.u));
    vmin = std::min(vmin, glm::dot(p, view.v)), vmax = std::max(vmax, glm::dot(p, view.v));
  }
  const double cu = glm::dot(centre, view.u), cv = glm::dot(centre, view.v);
  umin = std::max(umin, cu - radius), umax = std::min(umax, cu + radius);
  vmin = std::max(vmin, cv - radius), vmax = std::min(vmax, cv + radius);
  if (umax <= umin || vmax <= vmin) return {};
  const int x0 = std::max(0, int(std::floor((umin - view.u0) * px_u)));
  const int x1 = std::min(width, int(std::ceil((umax - view.u0) * px_u)));
  const int y0 = std::max(0, int(std::floor((vmin - view.v0) * px_v)));
  const int y1 = std::min(height, int(std::ceil((vmax - view.v0) * px_v)));
  if (x1 <= x0 || y1 <= y0) return {};
  return {x0, y0, x1 - x0, y1 - y0};
}

BrickImage sphereLayer(int rank, int ranks, int width, int height, double coverage, bool rle) {
  const Rect bound = sphereLayerBound(rank, ranks, width, height, coverage);
  const View view = makeView();
  const double radius = sphereRadius(view, coverage);
  const double sigma = -std::log(0.1) / (2.0 * radius);  // a whole diameter: alpha 0.9
  const glm::dvec3 centre(0.5);
  const double cu = glm::dot(centre, view.u), cv = glm::dot(centre, view.v);
  const double px_u = width / view.side, px_v = height / view.side;
  Box box;
  split(Box{}, 0, ranks, 0, view.w, rank, &box, nullptr);
  BrickImage b;
  b.brick_id = rank;
  if (bound.empty()) return b;
  const int x0 = bound.x, x1 = bound.x + bound.w, y0 = bound.y, y1 = bound.y + bound.h;

  std::vector<uint8_t> px(size_t(x1 - x0) * size_t(y1 - y0) * 4, 0);
  int ax0 = x1, ax1 = x0 - 1, ay0 = y1, ay1 = y0 - 1;  // the active rectangle
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      // The ray through the pixel centre: origin on the plane through the cube centre.
      const double su = view.u0 + (x + 0.5) / px_u, sv = view.v0 + (y + 0.5) / px_v;
      const glm::dvec3 o = centre + (su - cu) * view.u + (sv - cv) * view.v;
      const double d2 = glm::dot(o - centre, o - centre);
      if (d2 >= radius * radius) continue;
      const double half = std::sqrt(radius * radius - d2);
      double t0 = -half, t1 = half;  // along w from o
      for (int a = 0; a < 3; ++a) {
        if (std::abs(view.w[a]) < 1e-12) {
          if (o[a] < box.lo[a] || o[a] >= box.hi[a]) t1 = t0;
          continue;
        }
        double ta = (box.lo[a] - o[a]) / view.w[a], tb = (box.hi[a] - o[a]) / view.w[a];
        t0 = std::max(t0, std::min(ta, tb));
        t1 = std::min(t1, std::max(ta, tb));
      }
      if (t1 <= t0) continue;
      const double alpha = 1.0 - std::exp(-sigma * (t1 - t0));
      const uint8_t A = uint8_t(std::lround(alpha * 255.0));
      if (A == 0) continue;
      uint8_t* p = &px[(size_t(y - y0) * size_t(x1 - x0) + size_t(x - x0)) * 4];
      // A colour that varies over the sphere, so blends are not all alike.
      const double shade = 0.55 + 0.45 * (o.y - centre.y + radius) / (2.0 * radius);
      p[0] = uint8_t(std::lround(A * 0.95 * shade));
      p[1] = uint8_t(std::lround(A * 0.65 * shade));
      p[2] = uint8_t(std::lround(A * 0.35));
      p[3] = A;
      ax0 = std::min(ax0, x), ax1 = std::max(ax1, x), ay0 = std::min(ay0, y), ay1 = y;
    }
  if (ax1 < ax0) return b;
  // Keep the active rectangle only, as a renderer's brick rectangle would be.
  std::vector<uint8_t> active(size_t(ax1 - ax0 + 1) * size_t(ay1 - ay0 + 1) * 4);
  for (int y = ay0; y <= ay1; ++y)
    std::copy_n(&px[(size_t(y - y0) * size_t(x1 - x0) + size_t(ax0 - x0)) * 4],
                size_t(ax1 - ax0 + 1) * 4, &active[size_t(y - ay0) * size_t(ax1 - ax0 + 1) * 4]);
  b.rect = {ax0, ay0, ax1 - ax0 + 1, ay1 - ay0 + 1};
  rleEncode(active, b.rle, 4, rle ? kMaxRun : 1);
  return b;
}

}  // namespace sortlast::scale
