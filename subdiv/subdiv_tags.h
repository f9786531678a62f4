#pragma once
// Subdivision tags (creases, corners, boundary interpolation, holes) with OpenSubdiv's semantics
// (Sdc, the Pixar/RenderMan rules): the options a mesh carries, the sharpness arithmetic of one
// refinement step (uniform decrement or Chaikin), which rule a vertex takes (smooth, dart, crease,
// corner) and the weight that blends a parent's rule with its child's when a sharpness decays.
// The masks themselves are applied by catmullClarkStep (subdiv_mesh.cpp).
#include <string>
#include <vector>

namespace sortlast {

// Sharpness at or above this is infinitely sharp (OpenSubdiv's Sdc::Crease::SHARPNESS_INFINITE).
constexpr double kInfinitelySharp = 10.0;

inline bool isSharp(double s) { return s > 0.0; }
inline bool isInfinite(double s) { return s >= kInfinitelySharp; }
inline bool isSemiSharp(double s) { return s > 0.0 && s < kInfinitelySharp; }

// Sdc::Options::VtxBoundaryInterpolation. Boundary edges are infinitely sharp in every mode.
// EdgeAndCorner also makes corners (boundary vertices of one face) infinitely sharp vertices;
// None additionally leaves out (as holes) the faces at boundary vertices whose boundary edges were
// not tagged infinitely sharp.
enum class BoundaryInterpolation { None, EdgeOnly, EdgeAndCorner };
// Sdc::Options::CreasingMethod: Uniform decrements every semi-sharp value by 1 per level; Chaikin
// blends an edge's value with the other semi-sharp edges' at each end vertex first.
enum class CreaseMethod { Uniform, Chaikin };

const char* boundaryName(BoundaryInterpolation b);
const char* creaseMethodName(CreaseMethod m);

// A vertex's subdivision rule (Sdc::Crease::Rule): from its own sharpness and how many of its
// edges are sharp (> 0): 0 smooth, 1 dart, 2 crease, more (or a sharp vertex) corner.
enum class VertexRule { Smooth, Dart, Crease, Corner };
VertexRule vertexRule(double vertex_sharpness, const std::vector<double>& edge_sharpness);

// One level's subdivided sharpness of a vertex, and of a vertex's incident edges at that vertex
// (each edge's child at this end), by `method`.
double decrementSharpness(double s);
std::vector<double> childEdgeSharpness(CreaseMethod method, const std::vector<double>& edge_sharpness);

// Weight of the parent's rule when the parent's and child's rules differ
// (Sdc::Crease::ComputeFractionalWeightAtVertex): the mean of the sharpness values that decayed to
// zero in this step, clamped to 1.
double fractionalWeight(CreaseMethod method, double vertex_sharpness, double childVertexSharpness,
                        const std::vector<double>& edge_sharpness, const std::vector<double>& childEdges);

// A tag as the input names it, before it is checked against the mesh: `where` names its source
// (file and line, or the procedural mesh) for error messages.
struct CreaseTag {
  int a = 0, b = 0;
  double sharpness = 0;
  std::string where;
};
struct CornerTag {
  int vertex = 0;
  double sharpness = 0;
  std::string where;
};
struct HoleTag {
  int face = 0;
  std::string where;
};
struct SubdivTags {
  std::vector<CreaseTag> creases;
  std::vector<CornerTag> corners;
  std::vector<HoleTag> holes;
};

}  // namespace sortlast
