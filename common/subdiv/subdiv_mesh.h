#pragma once
// Polygon meshes for Catmull-Clark subdivision surfaces: the input (any closed manifold polygon
// mesh), its checks, and the Catmull-Clark refinement step that turns it into the all-quad control
// mesh with at most one extraordinary vertex per face that exact evaluation (subdiv_eval.h) needs.
// CPU only, in double precision; no GL, no MPI.
#include <glm/vec3.hpp>

#include <string>
#include <vector>

namespace sortlast {

// A polygon mesh as OBJ stores it: points, and faces as runs of point indices (counter-clockwise
// seen from outside). `name` is what error messages call it (a file name or a procedural name).
struct PolyMesh {
  std::string name;
  std::vector<glm::dvec3> points;
  std::vector<int> faceSizes;    // corners per face
  std::vector<int> faceOffsets;  // first corner of each face in faceCorners
  std::vector<int> faceCorners;  // point index per corner

  int faceCount() const { return static_cast<int>(faceSizes.size()); }
  int corner(int face, int i) const { return faceCorners[faceOffsets[face] + i]; }
  void addFace(const std::vector<int>& corners);
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
  std::vector<Side> twin;    // indexed by faceOffsets[f] + c; face -1 across a boundary edge
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

// One Catmull-Clark step of a checked mesh: every face of m corners becomes m quads. Child i of
// face f is (vertex point of corner i, edge point of edge i -> i+1, face point, edge point of edge
// i-1 -> i), so its local u runs from corner i along edge i and v along edge i-1 backwards.
// `parent` and `parentCorner` of the result say which face and corner each child came from.
struct RefinedMesh {
  PolyMesh mesh;
  std::vector<int> parent, parentCorner;
};
// Boundaries follow OpenSubdiv's Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER: boundary edges are
// sharp (edge point the midpoint, boundary vertex (1/8, 3/4, 1/8) of its boundary neighbours),
// and corners (boundary vertices of one face) are interpolated.
RefinedMesh catmullClarkStep(const PolyMesh& mesh, const MeshTopology& topology);

// A vertex round which the limit surface is a bicubic B-spline: interior of valence 4, boundary
// of valence 3 (two faces) or a corner (one face; phantom points reflected across the boundary).
bool regularVertex(const MeshTopology& topology, int point);

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
  std::vector<int> inputFace;              // per control face
  std::vector<std::vector<int>> cornerChain;  // per control face: child corner at each step
};
ControlMesh buildControlMesh(const PolyMesh& input);

}  // namespace sortlast
