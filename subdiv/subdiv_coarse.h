#pragma once
// The coarse mesh a per-fragment evaluator rasterises (the paper's pass 1): each control face cut
// into a grid of quads whose corners lie on the limit surface and carry (control face, u, v), so
// that interpolating (u, v) over a quad gives each fragment its parameters on one control face.
#include <glm/vec3.hpp>

#include <vector>

#include "subdiv/subdiv_eval.h"

namespace sortlast {

struct CoarseVertex {
  glm::vec3 position;  // the limit point at (face, u, v)
  float u, v;
  int face;
};

struct CoarseMesh {
  std::vector<CoarseVertex> vertices;
  std::vector<unsigned> triangles;  // two per quad, counter-clockwise like the faces
  int level = 0;                    // Catmull-Clark steps from the input mesh
};

// `level`: Catmull-Clark steps from the input, as the paper counts them (1 to 3 in its figures);
// at least the control mesh's own level (a coarser quad would span several control faces), so
// each control face is cut into 2^(level - control levels) quads a side. Throws InputError
// naming `key` if the level is below that or above 6.
CoarseMesh buildCoarseMesh(const SubdivSurface& surface, int level, const char* key = "level");

// How far the coarse mesh's flat quads are from the limit surface: the largest distance between
// a point of a quad (bilinear in its corners) and the limit point at the same (u, v), over a
// 5 x 5 grid per quad, relative to the mesh size. This bounds how far a silhouette drawn from the
// coarse mesh can be from the limit surface's, along the surface.
double coarseDeviation(const SubdivSurface& surface, int level);

}  // namespace sortlast
