#include "common/visibility.h"

#include <algorithm>

namespace sortlast {

std::vector<int> slabOrder(const std::vector<double>& planes, double eye) {
  int n = int(planes.size()) - 1;
  std::vector<std::pair<double, int>> dist;  // distance of the slab from the eye along the axis
  for (int i = 0; i < n; ++i) {
    double d = 0.0;
    if (planes[i + 1] <= eye)
      d = eye - planes[i + 1];
    else if (planes[i] >= eye)
      d = planes[i] - eye;
    dist.push_back({d, i});
  }
  // Farther first; a stable sort keeps ties in index order (ties are on opposite sides of the eye,
  // where either order is right).
  std::stable_sort(dist.begin(), dist.end(), [](auto& a, auto& b) { return a.first > b.first; });
  std::vector<int> order;
  for (auto& [d, i] : dist) order.push_back(i);
  return order;
}

std::vector<int> backToFrontOrder(const std::array<std::vector<double>, 3>& planes,
                                  const glm::dvec3& eye) {
  auto ox = slabOrder(planes[0], eye.x), oy = slabOrder(planes[1], eye.y),
       oz = slabOrder(planes[2], eye.z);
  int dx = int(ox.size()), dy = int(oy.size());
  std::vector<int> order;
  order.reserve(ox.size() * oy.size() * oz.size());
  for (int x : ox)
    for (int y : oy)
      for (int z : oz) order.push_back(x + dx * (y + dy * z));
  return order;
}

}  // namespace sortlast

namespace sortlast {

namespace {

void visitFarToNear(const Assignment& a, int node, const BrickPlanes& planes, const glm::dvec3& eye,
                    std::vector<int>& out) {
  const KdNode& n = a.tree[size_t(node)];
  if (n.axis < 0) {
    for (int r = n.first_rank + 1; r < n.first_rank + n.ranks; ++r)
      out.push_back(r);  // own nothing
    out.push_back(n.first_rank);
    return;
  }
  // The eye below the cut plane sees the upper side behind the lower one, and vice versa; an eye
  // on the plane sees through neither, so either order is right.
  bool eye_below = eye[n.axis] < planes[size_t(n.axis)][size_t(n.cut)];
  visitFarToNear(a, eye_below ? n.upper : n.lower, planes, eye, out);
  visitFarToNear(a, eye_below ? n.lower : n.upper, planes, eye, out);
}

}  // namespace

std::vector<int> backToFrontRanks(const Assignment& assignment, const BrickPlanes& planes,
                                  const glm::dvec3& eye) {
  std::vector<int> order;
  order.reserve(assignment.region.size());
  if (!assignment.tree.empty()) visitFarToNear(assignment, 0, planes, eye, order);
  return order;
}

glm::dvec3 orderEye(const Camera& cam, const Box3& bounds) {
  if (!cam.orthographic()) return cam.position;
  const glm::dvec3 f = cam.forward();
  const double margin = 1.0 + glm::length(bounds.extent());
  glm::dvec3 eye = cam.position;
  for (int a = 0; a < 3; ++a) {
    if (f[a] > 0.0) eye[a] = std::min(bounds.lo[a], cam.position[a]) - margin;
    else if (f[a] < 0.0) eye[a] = std::max(bounds.hi[a], cam.position[a]) + margin;
  }
  return eye;
}

VisibilityOrder visibilityOrder(const Assignment& assignment, const BrickPlanes& planes,
                                const glm::dvec3& eye) {
  return {backToFrontOrder(planes, eye), backToFrontRanks(assignment, planes, eye)};
}

}  // namespace sortlast
