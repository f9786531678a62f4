#pragma once
// The subdivision tests' independent reference: OpenSubdiv's Far patch tables evaluating the
// limit surface of the input mesh (not our control mesh) at a point of one of our control faces.
//
// Parameter mapping: our control face is a child (one Catmull-Clark step, all-quad input) or a
// grandchild (two steps, input with other faces) of an input face; catmullClarkStep's child order
// maps its (u, v) to the parent quad's (u, v) (childToParentQuad). A quad input face is one ptex
// face of OpenSubdiv with (s, t) = our (u, v) (s along its first edge, t along its last edge
// backwards). An n-gon is n ptex sub-faces, sub-face i at corner i, and its (s, t) is our child
// quad's (u, v) unchanged (origin at the corner, s towards edge i's midpoint): the n-gon meshes'
// agreement to 1e-15 away from the end caps pins this; the three other orientations are off by
// about 0.2 of the mesh size.
#include <memory>
#include <vector>

#include "subdiv/subdiv_eval.h"

namespace sortlast {

class OsdReference {
 public:
  // isolation: adaptive refinement depth round extraordinary vertices (OpenSubdiv's maximum is 10
  // here: nearer than 2^-isolation of a base face it evaluates a Gregory end cap, an approximation).
  OsdReference(const PolyMesh& input, int isolation);
  ~OsdReference();
  // The limit point at (u, v) of control face `face` of `control` (built from the same input).
  LimitPoint evaluate(const ControlMesh& control, int face, double u, double v) const;

  // Exact limit positions and normals at the vertices of the input refined uniformly `levels`
  // times (OpenSubdiv's PrimvarRefiner::Limit: closed-form limit masks, no end caps), in
  // OpenSubdiv's vertex order.
  static std::vector<LimitPoint> limitAtVertices(const PolyMesh& input, int levels,
                                                 std::vector<glm::dvec3>& refinedPoints);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sortlast
