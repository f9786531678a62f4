#pragma once
// Polygon meshes for Catmull-Clark subdivision surfaces: the input (any closed manifold polygon
// mesh), its checks, and the Catmull-Clark refinement step that turns it into the all-quad control
// mesh with at most one extraordinary vertex per face that exact evaluation (subdiv_eval.h) needs.
// CPU only, in double precision; no GL, no MPI.
#include <glm/vec3.hpp>

#include <string>
#include <vector>

#include "subdiv/subdiv_tags.h"

namespace sortlast {

// A polygon mesh as OBJ stores it: points, and faces as runs of point indices (counter-clockwise
// seen from outside), with its subdivision tags. `name` is what error messages call it (a file
// name or a procedural name).
struct PolyMesh {
  std::string name;
  std::vector<glm::dvec3> points;
  std::vector<int> face_sizes;    // corners per face
  std::vector<int> face_offsets;  // first corner of each face in face_corners
  std::vector<int> face_corners;  // point index per corner

  // Tags (subdiv_tags.h). Per corner slot, as face_corners: the sharpness of the edge from that
  // corner to the next, the same in both faces of an edge; empty while no edge is sharp. Per
  // point: the vertex sharpness; empty while none is. Per face: a hole (refined with the rest,
  // but no part of the limit surface); empty while there is none.
  std::vector<double> edge_sharpness;
  std::vector<double> vertex_sharpness;
  std::vector<char> holes;
  BoundaryInterpolation boundary = BoundaryInterpolation::EdgeAndCorner;
  CreaseMethod crease_method = CreaseMethod::Uniform;

  int faceCount() const { return static_cast<int>(face_sizes.size()); }
  int corner(int face, int i) const { return face_corners[face_offsets[face] + i]; }
  double edgeSharp(int slot) const { return edge_sharpness.empty() ? 0.0 : edge_sharpness[slot]; }
  double vertexSharp(int p) const { return vertex_sharpness.empty() ? 0.0 : vertex_sharpness[p]; }
  bool hole(int f) const { return !holes.empty() && holes[f]; }
  void addFace(const std::vector<int>& corners);
  // Every face's corners in reverse order (a mirroring transform), the edge sharpness with them.
  void reverseFaces();
  bool allQuads() const;
  // Diagonal of the points' bounding box: the "mesh size" error bounds are relative to.
  double size() const;
};

// Directed-edge connectivity of a checked mesh: for corner c of face f (the edge from corner c to
// corner c+1), the face and corner on the other side, and each point's valence.
struct MeshTopology {
  struct Side {
    int face = -1, corner = -1;
  };
  std::vector<Side> twin;    // indexed by face_offsets[f] + c; face -1 across a boundary edge
  std::vector<int> valence;  // edges per point (0 for points no face uses)
  std::vector<char> boundary;  // per point: on a boundary edge
  static MeshTopology build(const PolyMesh& mesh);
  // An open mesh (some edge has one face): both sides of its surface can face a camera, so
  // renderers draw it two-sided; a closed one's back side is always hidden.
  bool open() const;
};

// Throws InputError naming the mesh and the problem unless `mesh` is a consistently oriented,
// manifold polygon mesh (closed or with boundaries) with finite points: empty meshes, NaN or
// infinite points, out-of-range indices, faces of fewer than three corners or with a repeated
// corner, edges shared by more than two faces or twice in one direction, vertices whose faces form
// more than one fan (two boundary fans, or a boundary fan and a closed one, meeting there).
MeshTopology checkMesh(const PolyMesh& mesh);

// Sets the tags on `mesh` (which must have all its faces): a crease on the edge (a, b) in either
// direction, a corner's vertex sharpness, a hole's face. Throws InputError naming the tag's
// `where` for a vertex or face index out of range, a crease on two points that share no edge,
// and a sharpness that is negative or not a number. Sharpness above kInfinitelySharp is kept as
// infinitely sharp.
void applyTags(PolyMesh& mesh, const SubdivTags& tags);

// One Catmull-Clark step of a checked mesh: every face of m corners becomes m quads. Child i of
// face f is (vertex point of corner i, edge point of edge i -> i+1, face point, edge point of edge
// i-1 -> i), so its local u runs from corner i along edge i and v along edge i-1 backwards.
// `parent` and `parent_corner` of the result say which face and corner each child came from.
struct RefinedMesh {
  PolyMesh mesh;
  std::vector<int> parent, parent_corner;
};
// OpenSubdiv's Catmark rules with its tags: an edge of sharpness s >= 1 (or a boundary edge) gets
// its midpoint, s in (0, 1) blends midpoint and smooth rule by s; a vertex takes the smooth, crease
// (3/4 itself, 1/8 each sharp neighbour) or corner (itself) rule by vertexRule, blended with its
// child's rule by fractionalWeight where a sharpness decays in this step. The children carry the
// subdivided sharpness (decrementSharpness / childEdgeSharpness by the mesh's crease method).
// Boundary edges are infinitely sharp whatever their slots say (prepareBoundary sets the
// corners' sharpness), so a cut-out piece of a mesh refines like the whole near its middle.
RefinedMesh catmullClarkStep(const PolyMesh& mesh, const MeshTopology& topology);

// Applies the mesh's boundary interpolation as OpenSubdiv does before refining: boundary edges
// infinitely sharp; EdgeAndCorner: corners (a boundary vertex of one face) infinitely sharp;
// None: faces at a boundary vertex with a boundary edge not tagged infinitely sharp become holes.
void prepareBoundary(PolyMesh& mesh, const MeshTopology& topology);

// The sharpness of the edge at a corner slot as refinement uses it: infinite on a boundary.
double slotSharpness(const PolyMesh& mesh, const MeshTopology& topology, int slot);

// A vertex round which the limit surface is a bicubic B-spline: interior of valence 4, boundary
// of valence 3 (two faces) or a corner (one face; phantom points reflected across the boundary).
// Untagged meshes only: with tags, regularity is per face and corner (faceCornerKind).
bool regularVertex(const MeshTopology& topology, int point);

// What the limit surface of face f is like near its corner c, from the tags of the edges at that
// corner and its vertex sharpness:
//   Smooth     no sharp edge, no vertex sharpness (regular if interior valence 4)
//   SemiSharp  some edge at the corner, or the vertex, is semi-sharp: local subdivision must go on
//   Regular    every sharpness 0 or infinite, and the face's sector (its faces between two sharp
//              edges round the vertex) is that of a regular B-spline patch with phantom points
//              reflected across the sharp edges: 2 faces under the crease rule, 1 under the corner
//              rule, or 4 faces of a smooth interior vertex
//   Irregular  anything else (a dart, a crease or corner with another sector, an extraordinary
//              valence)
enum class CornerKind { Smooth, SemiSharp, Regular, Irregular };
CornerKind faceCornerKind(const PolyMesh& mesh, const MeshTopology& topology, int f, int c);
// Not a B-spline patch's corner: Irregular, or Smooth at a vertex that is not interior valence 4.
inline bool irregularCorner(CornerKind kind, const MeshTopology& topology, int point) {
  return kind == CornerKind::Irregular || (kind == CornerKind::Smooth && !regularVertex(topology, point));
}

// (u, v) of a child quad (as catmullClarkStep orders it) in its parent quad's (u, v).
void childToParentQuad(int corner, double u, double v, double& pu, double& pv);

// The control mesh exact evaluation runs on: the input refined once (all-quad input) or twice
// (input with triangles or n-gons), so that every face is a quad with at most one extraordinary
// vertex, its corner 0, and every extraordinary vertex's neighbourhood is regular. Per control
// face, which input face it lies in and the chain of children down to it, so a point (face, u, v)
// maps back to the input mesh's faces (the reference evaluator needs that). Throws InputError as checkMesh does,
// and for interior vertices of valence 2 (legal in a closed mesh, but outside Stam's method).
struct ControlMesh {
  PolyMesh mesh;
  MeshTopology topology;
  int levels = 0;                          // Catmull-Clark steps from the input
  std::vector<int> input_face;              // per control face
  std::vector<std::vector<int>> corner_chain;  // per control face: child corner at each step
};
ControlMesh buildControlMesh(const PolyMesh& input);

}  // namespace sortlast
