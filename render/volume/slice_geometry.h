#pragma once
// View-aligned slices through a brick for 3D-texture slicing. Every brick is cut by the same
// family of planes {x : forward . (x - eye) = k * spacing}, k integer, so samples line up across
// brick faces: a sample on a shared face is drawn by exactly one of the two bricks (the planes'
// polygons meet edge to edge, and edges are computed from the same corner coordinates in both).
#include <vector>

#include <glm/glm.hpp>

#include "common/box.h"

namespace sortlast {

// Triangles (x, y, z per vertex, world space) of every slice polygon with plane distance > min_t,
// ordered far to near so that GL blends them back to front in submission order.
std::vector<float> sliceTriangles(const Box3& box, const glm::dvec3& eye, const glm::dvec3& forward,
                                  double spacing, double min_t);

}  // namespace sortlast
