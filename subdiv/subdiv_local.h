#pragma once
// Explicit local Catmull-Clark subdivision round one control face, for the faces that touch a
// boundary or a tagged (sharp) edge or vertex, with the tags' rules: there is no eigenbasis for boundary vertices here, so a point near an irregular
// boundary vertex is evaluated by subdividing the face's neighbourhood with the boundary rules
// (subdiv/subdiv_mesh.h) until the point's sub-patch is regular, as Stam's method does with
// powers of the subdivision matrix. A regular face (every corner regular: interior valence 4,
// boundary valence 3, or a corner) is a bicubic B-spline patch whose grid points beyond the
// boundary are phantoms reflected across it (P_out = 2 P_b - P_in), which reproduces the boundary
// rules exactly.
//
// The neighbourhood kept is the face's one-ring (every face sharing a vertex with it): the
// children of those faces hold, with correct points, the one-ring of every child of the face
// (a point whose own one-ring was cut off gets a wrong point, but no kept face uses it). Under
// Chaikin's crease method the two-ring is kept: an edge point's rule there depends on the
// sharpness round its edge's far end (keepOneRing says why).
// Coordinates are kept relative: world = origin + scale * local, re-centred on the irregular
// vertex and rescaled by a power of two after each step, so that deep levels lose no digits to
// cancellation (the sub-patch shrinks by about lambda_sub per level).
#include <glm/vec3.hpp>

#include <array>

#include "subdiv/subdiv_mesh.h"

namespace sortlast {

class LocalNet {
 public:
  // The one-ring of control face `face`, in the frame whose (0, 0) is the face's corner 0 (where
  // buildControlMesh puts the irregular vertex).
  LocalNet(const PolyMesh& mesh, const MeshTopology& topology, int face);

  using Grid = std::array<glm::dvec3, 16>;  // B-spline control points, row b * 4 + a
  // One step: afterwards the net is the one-ring of the child at the frame's (0, 0). With
  // `world`, the three other children's grids first (sub-patch k = 1, 2, 3 of the new level, in
  // the frame's orientation), in world coordinates and in `tangent` in local ones: the same
  // patch moved and scaled, so the same normal, from points of the order of 1.
  // `only` (1, 2 or 3) computes that sub-patch's grids alone (the others are left as they are).
  void step(std::array<Grid, 3>* world = nullptr, std::array<Grid, 3>* tangent = nullptr, int only = 0);
  // The grid of the current face (which must be regular), in world and in local coordinates.
  void grid(Grid& world, Grid& tangent) const;
  // What the current face is: near a semi-sharp edge or vertex (split further), a B-spline patch
  // (with phantom points across infinitely sharp edges), or irregular at the frame's (0, 0) only
  // (a logic_error if elsewhere: refinement keeps irregular vertices at corner 0).
  enum class Kind { SemiSharp, Regular, Irregular };
  Kind kind() const;
  // One step into each quadrant q of the frame (0: (0,0), 1: (1,0), 2: (1,1), 3: (0,1)), keeping
  // the frame's orientation: net q is the one-ring of that child, its (0,0) at the quadrant's
  // lower left. One refinement serves all four.
  std::array<LocalNet, 4> split() const;

 private:
  // 4 x 4 points round face f with its corner `start` at grid (0, 0) and corner start + 1 at
  // (1, 0); missing cells (beyond a boundary) filled by reflection.
  static Grid gridOf(const PolyMesh& mesh, int f, int start);
  void keepOneRing(const PolyMesh& refined, int face, int start = 0);
  Grid toWorld(const Grid& local) const;

  PolyMesh mesh_;
  int face_ = 0;  // its corner 0 is the frame's (0, 0)
  glm::dvec3 origin_{0.0};
  double scale_ = 1.0;
};

}  // namespace sortlast
