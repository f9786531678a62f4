#pragma once
// Exact evaluation of a Catmull-Clark limit surface at any (face, u, v) of its control mesh
// (Stam 1998), with the per-(patch, n, k) control points the paper precomputes for the GPU.
//
// Parameters: (u, v) in [0,1]^2 of control face f (a quad of ControlMesh::mesh), u along the edge
// from corner 0 to corner 1, v from corner 0 to corner 3. A face's extraordinary corner, if any, is
// its corner 0 (buildControlMesh checks), so (u, v) is the patch's own frame: the paper's
// per-patch rotation is always 0 here, and there is none to store.
#include <glm/vec3.hpp>

#include <array>
#include <map>
#include <memory>
#include <vector>

#include "subdiv/subdiv_basis.h"
#include "subdiv/subdiv_local.h"
#include "subdiv/subdiv_mesh.h"

namespace sortlast {

struct LimitPoint {
  glm::dvec3 position;
  glm::dvec3 normal;  // unit, on the side the faces' counter-clockwise order points to
};

// Deepest level the CPU evaluator goes to near an extraordinary vertex: beyond every positive
// double, so each (u, v) other than the vertex itself falls in its own sub-patch. At u = v = 0 the
// level-1100 sub-patch is extrapolated to its corner; Lambda^1099 then keeps only the constant
// eigen-component for the position (the exact limit point) and only the subdominant pair for the
// tangents (the exact limit tangent plane).
constexpr int kCpuMaxLevel = 1100;
// Deepest level of the explicit local subdivision round an irregular boundary vertex (no
// eigenbasis there): nearer than 2^-48 of a control face the level-48 sub-patch is extrapolated,
// which moves the point by about lambda^48 (< 1e-9) of the face's size.
constexpr int kBoundaryMaxLevel = 48;
// Deepest split of a face's patch tree at semi-sharp tags (sharpness below 10 decays within 10
// levels; more is a bug).
constexpr int kMaxSemiSharpDepth = 24;
// Levels the GPU tables hold, as in the paper (n <= 15, 45 control-point sets per patch).
constexpr int kTableLevels = 15;

class SubdivSurface {
 public:
  // Checks the mesh (InputError on bad input), refines it to the control mesh and prepares a patch
  // per control face and an eigenbasis per extraordinary valence present.
  explicit SubdivSurface(const PolyMesh& input);

  const ControlMesh& control() const { return control_; }
  int patchCount() const { return control_.mesh.faceCount(); }
  LimitPoint evaluate(int face, double u, double v) const;

  // Which (n, k) sub-patch holds (u, v) of a face (extraordinary vertex at (0, 0)), and its
  // parameters t in that sub-patch's cell. Regular patches:
  // n = 0, k = 0, t = (u, v) in the patch's own 4 x 4 grid.
  struct Location {
    int n = 0, k = 0;
    double s = 0, t = 0;
  };
  Location locate(int face, double u, double v, int maxLevel = kCpuMaxLevel) const;
  // The 16 B-spline control points of a regular patch (n = 0) or of sub-patch (n, k) of an
  // irregular one: row b * 4 + a multiplies B_a(s) B_b(t).
  //
  // With `tangent`, control points whose patch has the same derivative directions (so the same
  // normal) without the cancellation that ruins them near an extraordinary vertex: the sub-patch
  // at level n spans about lambda_sub^n of the mesh, so its derivatives are differences of points
  // that agree to that many digits (in float, 15 levels lose all of them). The constant
  // eigen-component (lambda = 1), which has no derivative, is left out, and the others are
  // scaled by 1 / lambda_sub^(n-1), so the points stay of the order of the mesh.
  std::array<glm::dvec3, 16> controlPoints(int face, int n, int k, bool tangent = false) const;
  // Sub-patches (n, k) for n = 1..levels of an irregular face, set (n - 1) * 3 + (k - 1), positions
  // and tangent points: what the tables hold (one pass of local subdivision on boundary faces).
  void subPatches(int face, int levels, std::vector<std::array<glm::dvec3, 16>>& positions,
                  std::vector<std::array<glm::dvec3, 16>>& tangents) const;
  // Regular: a bicubic B-spline patch (interior, or with phantom points across a boundary or an
  // infinitely sharp crease).
  bool regular(int face) const { return patches_[face].kind == Kind::Regular; }
  // Not part of the limit surface (a hole tag, or a face at a boundary with interpolation none).
  bool hole(int face) const { return control_.mesh.hole(face); }
  // Some face is a hole or the control mesh has a boundary: both sides can face a camera.
  bool twoSided() const;
  const std::map<int, std::unique_ptr<ValenceBasis>>& bases() const { return bases_; }

  // Faces near tags or boundaries that are not one regular patch are trees of patches: a Split
  // node's four children cover the quadrants (0: (0,0), 1: (1,0), 2: (1,1), 3: (0,1)) of its
  // (u, v) square, each in the same orientation (a semi-sharp feature subdivided until its
  // sharpness has decayed); a Regular leaf is a B-spline patch over its square; an Irregular leaf
  // has its irregular vertex at its (0,0) and is evaluated as Stam's sub-patches (n, k), by
  // explicit local subdivision. rootNode is -1 for a face that is one regular or Stam patch.
  enum class NodeType { Regular, Irregular, Split };
  int rootNode(int face) const { return patches_[face].root; }
  NodeType nodeType(int node) const { return nodes_[node].type; }
  int first_child(int node) const { return nodes_[node].first_child; }
  // A Regular node's grid (positions, and the tangent points: same patch, moved and scaled).
  void nodeGrid(int node, std::array<glm::dvec3, 16>& position, std::array<glm::dvec3, 16>& tangent) const;
  // An Irregular node's sub-patches (n, k), n = 1..levels, as subPatches lays them out.
  void nodeSubPatches(int node, int levels, std::vector<std::array<glm::dvec3, 16>>& positions,
                      std::vector<std::array<glm::dvec3, 16>>& tangents) const;
  int nodeCount() const { return static_cast<int>(nodes_.size()); }

 private:
  enum class Kind { Regular, Stam, Tree };
  struct Patch {
    Kind kind = Kind::Regular;
    int valence = 4;
    Eigen::MatrixXd points;     // regular: 16 x 3 grid; Stam: (2N+8) x 3, V^-1 C0 (Stam's C-hat)
    int root = -1;              // Tree: its root node
  };
  struct Node {
    NodeType type = NodeType::Regular;
    int first_child = -1;                        // Split: children first_child + q
    std::array<glm::dvec3, 16> grid, tangent;   // Regular
    std::shared_ptr<const LocalNet> net;        // Irregular: level 0 of its local subdivision
  };
  ControlMesh control_;
  std::map<int, std::unique_ptr<ValenceBasis>> bases_;
  std::vector<Patch> patches_;
  std::vector<Node> nodes_;
  int buildNode(const LocalNet& net, int depth);
  void fillNode(int index, const LocalNet& net, int depth);
  // Sub-patch (n, k) of an Irregular node by n steps of local subdivision.
  void irregularSubPatch(int node, int n, int k, std::array<glm::dvec3, 16>& position,
                         std::array<glm::dvec3, 16>& tangent) const;
};

// Uniform cubic B-spline basis B_0..B_3 at t and its derivative: in double for the exact
// evaluation here, in float for the tables' (subdiv/subdiv_tables.h), which mirror the GPU's.
template <typename T>
void bsplineBasis(T t, T b[4], T db[4]) {
  const T s = T(1) - t, t2 = t * t, t3 = t2 * t;
  b[0] = s * s * s / T(6);
  b[1] = (T(3) * t3 - T(6) * t2 + T(4)) / T(6);
  b[2] = (T(-3) * t3 + T(3) * t2 + T(3) * t + T(1)) / T(6);
  b[3] = t3 / T(6);
  db[0] = T(-0.5) * s * s;
  db[1] = T(1.5) * t2 - T(2) * t;
  db[2] = T(-1.5) * t2 + t + T(0.5);
  db[3] = T(0.5) * t2;
}
// A bicubic B-spline patch: position and both partial derivatives at (s, t).
void bsplinePatch(const std::array<glm::dvec3, 16>& p, double s, double t, glm::dvec3& position,
                  glm::dvec3& ds, glm::dvec3& dt);

}  // namespace sortlast
