#pragma once
// The precomputed control points a per-fragment evaluator reads (the paper's section 3.3), in
// single precision as a GL buffer holds them, and the same evaluation on the CPU in float, which
// is what the GL pass computes and what the tests hold against the exact double evaluation.
//
// Layout: per control face one FaceEntry; its control-point sets start at `first_set`, 16 points
// each. A regular face has one set; a face with an extraordinary vertex has kTableLevels x 3 sets,
// set (n - 1) * 3 + (k - 1) for sub-patch (n, k). A face near semi-sharp tags is a tree of such
// entries (SubdivSurface's patch tree). Positions and tangent points (see
// SubdivSurface::controlPoints) are two arrays of the same layout.
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <vector>

#include "subdiv/subdiv_eval.h"

namespace sortlast {

struct SubdivTables {
  // Entry types: a regular patch (one set), an irregular one (kTableLevels x 3 sets), or a split
  // at semi-sharp tags whose four children's entries start at first_set (quadrants (0,0), (1,0),
  // (1,1), (0,1) of its (u, v) square, each in its own square's parameters).
  static constexpr int kIrregular = 0, kRegular = 1, kSplit = 2;
  struct FaceEntry {
    int first_set = 0;
    int type = kRegular;  // (no rotation: every face's extraordinary corner is its corner 0)
  };
  // Entries 0 .. faces - 1 are the control faces'; the splits' children follow.
  std::vector<FaceEntry> faces;
  std::vector<glm::vec4> positions, tangents;  // xyz used; w pads to std430's vec4 stride
  double seconds = 0;                          // time spent building them (with the surface's own setup excluded)
};

SubdivTables buildTables(const SubdivSurface& surface);

// Position and unit normal at (face, u, v) from the tables in float: n = floor(-log2 max(u, v)) + 1
// capped at kTableLevels (nearer the extraordinary vertex, the level-15 sub-patch is extrapolated).
struct FloatLimitPoint {
  glm::vec3 position, normal;
};
FloatLimitPoint evaluateTables(const SubdivTables& tables, int face, float u, float v);

}  // namespace sortlast
