#pragma once
// Axis-aligned boxes in world space (double precision, so brick faces shared by two bricks are
// bit-identical however they are computed) and in integer sample-index space.
#include <glm/glm.hpp>

namespace sortlast {

// The scale sortlast accepts for world lengths and coordinates (cameras, the volume's extent and
// spacing, particles, radii): the GPU computes in float and squares distances, and 1e18 squared
// is 1e36, under float's largest 3.4e38; 1e-12 squared (1e-24) is far above its smallest normal.
constexpr double kMaxCoordinate = 1e18;
constexpr double kMinLength = 1e-12;
// A camera this many times further from the scene's centre than the scene is large sees it below
// float precision: positions relative to the eye keep ~7 digits, so the scene's own detail would
// be rounding noise (and it covers well under a pixel at any sane field of view).
constexpr double kMaxDistanceToExtent = 1e6;

struct Box3 {
  glm::dvec3 lo{0.0}, hi{0.0};

  bool contains(const glm::dvec3& p) const {
    return p.x >= lo.x && p.y >= lo.y && p.z >= lo.z && p.x <= hi.x && p.y <= hi.y && p.z <= hi.z;
  }
  glm::dvec3 centre() const { return 0.5 * (lo + hi); }
  glm::dvec3 extent() const { return hi - lo; }
  // Corner c (0..7): bit 0 picks x, bit 1 y, bit 2 z.
  glm::dvec3 corner(int c) const {
    return {(c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z};
  }
};

// Box algebra, as closed boxes: a box holds its faces, so lo > hi on some axis is empty and a box
// of zero thickness (lo == hi: two boxes that only touch) is not. Exact: min and max round
// nothing, so a brick face shared by two bricks stays bit-identical.
//
// "No box": empty on every axis. Uniting with it would not give the other box (its lo and hi
// would join the result), so callers unite only boxes that are not empty.
inline Box3 noBox() { return {glm::dvec3(1.0), glm::dvec3(-1.0)}; }
inline Box3 intersect(const Box3& a, const Box3& b) {
  return {glm::max(a.lo, b.lo), glm::min(a.hi, b.hi)};
}
inline Box3 unite(const Box3& a, const Box3& b) {
  return {glm::min(a.lo, b.lo), glm::max(a.hi, b.hi)};
}
inline bool isEmpty(const Box3& b) { return b.lo.x > b.hi.x || b.lo.y > b.hi.y || b.lo.z > b.hi.z; }
// The half-open view: the box holds a positive volume (lo < hi on every axis), so a share of zero
// thickness, where two boxes only touch, counts as nothing.
inline bool hasVolume(const Box3& b) {
  return b.lo.x < b.hi.x && b.lo.y < b.hi.y && b.lo.z < b.hi.z;
}

// Inclusive range of sample indices [lo, hi] on each axis.
struct IndexBox {
  glm::ivec3 lo{0}, hi{-1};

  glm::ivec3 size() const { return hi - lo + 1; }
  long long count() const {
    glm::ivec3 s = size();
    return (s.x <= 0 || s.y <= 0 || s.z <= 0) ? 0 : 1LL * s.x * s.y * s.z;
  }
};

// The samples both hold (inclusive, so count() == 0 when they share none).
inline IndexBox intersect(const IndexBox& a, const IndexBox& b) {
  return {glm::max(a.lo, b.lo), glm::min(a.hi, b.hi)};
}

// Ray-box slab test. Returns false if the ray misses; otherwise [t0, t1] is the parametric overlap
// (t0 may be negative if the origin is inside).
bool intersectRayBox(const glm::dvec3& origin, const glm::dvec3& dir, const Box3& box, double& t0,
                     double& t1);

}  // namespace sortlast
