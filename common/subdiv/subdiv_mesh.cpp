#include "common/subdiv/subdiv_mesh.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <unordered_map>

#include "common/error.h"

namespace sortlast {

void PolyMesh::addFace(const std::vector<int>& corners) {
  faceOffsets.push_back(static_cast<int>(faceCorners.size()));
  faceSizes.push_back(static_cast<int>(corners.size()));
  faceCorners.insert(faceCorners.end(), corners.begin(), corners.end());
}

bool PolyMesh::allQuads() const {
  return std::all_of(faceSizes.begin(), faceSizes.end(), [](int s) { return s == 4; });
}

double PolyMesh::size() const {
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  for (const auto& p : points) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  return points.empty() ? 0.0 : glm::length(hi - lo);
}

namespace {

std::uint64_t edgeKey(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
         static_cast<std::uint32_t>(b);
}

[[noreturn]] void fail(const PolyMesh& mesh, const std::string& what) {
  throw InputError("surface mesh '" + mesh.name + "': " + what);
}

void checkFaces(const PolyMesh& mesh) {
  if (mesh.faceCount() == 0 || mesh.points.empty()) fail(mesh, "is empty (no faces or no vertices)");
  for (size_t i = 0; i < mesh.points.size(); ++i) {
    const auto& p = mesh.points[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      fail(mesh, "vertex " + std::to_string(i) + " is not a finite number (NaN or infinite)");
  }
  const int n = static_cast<int>(mesh.points.size());
  for (int f = 0; f < mesh.faceCount(); ++f) {
    const int m = mesh.faceSizes[f];
    if (m < 3) fail(mesh, "face " + std::to_string(f) + " has " + std::to_string(m) + " corners (at least 3 needed)");
    for (int i = 0; i < m; ++i) {
      const int p = mesh.corner(f, i);
      if (p < 0 || p >= n)
        fail(mesh, "face " + std::to_string(f) + " uses vertex index " + std::to_string(p) +
                       ", out of range (the mesh has " + std::to_string(n) + " vertices)");
      for (int j = 0; j < i; ++j)
        if (mesh.corner(f, j) == p)
          fail(mesh, "face " + std::to_string(f) + " uses vertex " + std::to_string(p) + " twice");
    }
  }
}

}  // namespace

bool MeshTopology::open() const {
  for (char b : boundary)
    if (b) return true;
  return false;
}

MeshTopology MeshTopology::build(const PolyMesh& mesh) {
  MeshTopology t;
  t.twin.assign(mesh.faceCorners.size(), {});
  t.valence.assign(mesh.points.size(), 0);
  std::unordered_map<std::uint64_t, int> directed;  // edge a -> b: its corner slot
  std::unordered_map<std::uint64_t, int> uses;      // undirected edge: faces using it
  directed.reserve(mesh.faceCorners.size());
  for (int f = 0; f < mesh.faceCount(); ++f)
    for (int c = 0; c < mesh.faceSizes[f]; ++c) {
      const int a = mesh.corner(f, c), b = mesh.corner(f, (c + 1) % mesh.faceSizes[f]);
      const int k = ++uses[edgeKey(std::min(a, b), std::max(a, b))];
      if (k > 2)
        fail(mesh, "edge (" + std::to_string(a) + ", " + std::to_string(b) +
                       ") is non-manifold: shared by more than two faces (face " + std::to_string(f) + " is the third)");
      if (!directed.emplace(edgeKey(a, b), mesh.faceOffsets[f] + c).second)
        fail(mesh, "edge (" + std::to_string(a) + ", " + std::to_string(b) +
                       ") is used twice in the same direction (face " + std::to_string(f) +
                       "): faces are not consistently oriented");
      ++t.valence[a];
    }
  t.boundary.assign(mesh.points.size(), 0);
  for (int f = 0; f < mesh.faceCount(); ++f)
    for (int c = 0; c < mesh.faceSizes[f]; ++c) {
      const int a = mesh.corner(f, c), b = mesh.corner(f, (c + 1) % mesh.faceSizes[f]);
      const auto it = directed.find(edgeKey(b, a));
      if (it == directed.end()) {  // a boundary edge: no face on the other side
        t.boundary[a] = t.boundary[b] = 1;
        continue;
      }
      const int slot = it->second;
      const int g = static_cast<int>(std::upper_bound(mesh.faceOffsets.begin(), mesh.faceOffsets.end(), slot) -
                                     mesh.faceOffsets.begin()) - 1;
      t.twin[mesh.faceOffsets[f] + c] = {g, slot - mesh.faceOffsets[g]};
    }
  // Valence counts edges: a boundary vertex of m faces has m + 1 (a manifold one; checkMesh
  // refuses the others).
  for (size_t p = 0; p < mesh.points.size(); ++p) t.valence[p] += t.boundary[p];
  return t;
}

MeshTopology checkMesh(const PolyMesh& mesh) {
  checkFaces(mesh);
  MeshTopology t = MeshTopology::build(mesh);
  // A manifold vertex's faces form one fan: walking round it across its edges from the first
  // face (any face if it is interior; the one whose next edge is a boundary edge if it is on the
  // boundary) reaches all of them. A vertex on two boundary fans, or a boundary fan and a closed
  // one, is non-manifold.
  std::vector<int> faces(mesh.points.size(), 0), start(mesh.points.size(), -1), fans(mesh.points.size(), 0);
  for (int f = 0; f < mesh.faceCount(); ++f)
    for (int c = 0; c < mesh.faceSizes[f]; ++c) {
      const int p = mesh.corner(f, c), slot = mesh.faceOffsets[f] + c;
      ++faces[p];
      if (t.twin[slot].face < 0) {  // the boundary edge leaving p: its face starts p's fan
        ++fans[p];
        start[p] = slot;
      } else if (!t.boundary[p] && start[p] < 0) {
        start[p] = slot;
      }
    }
  for (size_t p = 0; p < mesh.points.size(); ++p) {
    if (faces[p] == 0) continue;
    if (fans[p] > 1)
      fail(mesh, "vertex " + std::to_string(p) + " is non-manifold: its faces form more than one fan");
    if (start[p] < 0) fail(mesh, "vertex " + std::to_string(p) + " is non-manifold: its faces form more than one fan");
    int slot = start[p], count = 0;
    int g = static_cast<int>(std::upper_bound(mesh.faceOffsets.begin(), mesh.faceOffsets.end(), slot) -
                             mesh.faceOffsets.begin()) - 1;
    int d = slot - mesh.faceOffsets[g];
    const int f0 = g, c0 = d;
    do {
      ++count;
      const auto& s = t.twin[mesh.faceOffsets[g] + (d + mesh.faceSizes[g] - 1) % mesh.faceSizes[g]];
      if (s.face < 0) break;  // the boundary edge entering p: the fan's other end
      g = s.face;
      d = s.corner;
    } while ((g != f0 || d != c0) && count <= faces[p]);
    if (count != faces[p])
      fail(mesh, "vertex " + std::to_string(p) + " is non-manifold: its faces form more than one fan");
  }
  return t;
}

RefinedMesh catmullClarkStep(const PolyMesh& mesh, const MeshTopology& topology) {
  RefinedMesh out;
  out.mesh.name = mesh.name;
  const int nf = mesh.faceCount();
  // New points: vertex points (used points only), then edge points, then face points.
  std::vector<int> vertexIndex(mesh.points.size(), -1);
  int nv = 0;
  for (size_t p = 0; p < mesh.points.size(); ++p)
    if (topology.valence[p] > 0) vertexIndex[p] = nv++;
  std::vector<glm::dvec3> facePoint(nf);
  for (int f = 0; f < nf; ++f) {
    glm::dvec3 s(0.0);
    for (int c = 0; c < mesh.faceSizes[f]; ++c) s += mesh.points[mesh.corner(f, c)];
    facePoint[f] = s / double(mesh.faceSizes[f]);
  }
  // Each undirected edge once: owned by the corner slot with the smaller index.
  std::vector<int> edgeOf(mesh.faceCorners.size(), -1);
  std::vector<glm::dvec3> edgePoint;
  for (int f = 0; f < nf; ++f)
    for (int c = 0; c < mesh.faceSizes[f]; ++c) {
      const int slot = mesh.faceOffsets[f] + c;
      const auto& tw = topology.twin[slot];
      if (edgeOf[slot] >= 0) continue;
      const int a = mesh.corner(f, c), b = mesh.corner(f, (c + 1) % mesh.faceSizes[f]);
      edgeOf[slot] = static_cast<int>(edgePoint.size());
      if (tw.face < 0) {  // boundary edge: a sharp crease, its midpoint
        edgePoint.push_back((mesh.points[a] + mesh.points[b]) * 0.5);
        continue;
      }
      edgeOf[mesh.faceOffsets[tw.face] + tw.corner] = edgeOf[slot];
      edgePoint.push_back((mesh.points[a] + mesh.points[b] + facePoint[f] + facePoint[tw.face]) * 0.25);
    }
  // Vertex point (Q + 2R + (n - 3) S) / n: in a closed mesh every edge leaving p is the edge
  // after p in exactly one face, so one pass over the corners visits each face and edge once.
  // Boundary vertices (Sdc VTX_BOUNDARY_EDGE_AND_CORNER): a corner (one face, valence 2) stays
  // put; any other gets (1/8, 3/4, 1/8) of its two boundary neighbours and itself, so the
  // boundary curve is the cubic B-spline of the boundary vertices.
  std::vector<glm::dvec3> q(mesh.points.size(), glm::dvec3(0.0)), r(mesh.points.size(), glm::dvec3(0.0));
  std::vector<glm::dvec3> rim(mesh.points.size(), glm::dvec3(0.0));
  for (int f = 0; f < nf; ++f)
    for (int c = 0; c < mesh.faceSizes[f]; ++c) {
      const int m = mesh.faceSizes[f];
      const int a = mesh.corner(f, c), b = mesh.corner(f, (c + 1) % m);
      q[a] += facePoint[f];
      r[a] += (mesh.points[a] + mesh.points[b]) * 0.5;
      if (topology.twin[mesh.faceOffsets[f] + c].face < 0) {  // boundary edge a -> b
        rim[a] += mesh.points[b];
        rim[b] += mesh.points[a];
      }
    }
  out.mesh.points.resize(nv + edgePoint.size() + nf);
  for (size_t p = 0; p < mesh.points.size(); ++p) {
    if (vertexIndex[p] < 0) continue;
    const double n = topology.valence[p];
    if (topology.boundary[p])
      out.mesh.points[vertexIndex[p]] = n == 2 ? mesh.points[p] : (rim[p] + 6.0 * mesh.points[p]) / 8.0;
    else
      out.mesh.points[vertexIndex[p]] = (q[p] / n + 2.0 * r[p] / n + (n - 3.0) * mesh.points[p]) / n;
  }
  std::copy(edgePoint.begin(), edgePoint.end(), out.mesh.points.begin() + nv);
  std::copy(facePoint.begin(), facePoint.end(), out.mesh.points.begin() + nv + edgePoint.size());
  const int edgeBase = nv, faceBase = nv + static_cast<int>(edgePoint.size());
  for (int f = 0; f < nf; ++f) {
    const int m = mesh.faceSizes[f];
    for (int c = 0; c < m; ++c) {
      out.mesh.addFace({vertexIndex[mesh.corner(f, c)], edgeBase + edgeOf[mesh.faceOffsets[f] + c], faceBase + f,
                        edgeBase + edgeOf[mesh.faceOffsets[f] + (c + m - 1) % m]});
      out.parent.push_back(f);
      out.parentCorner.push_back(c);
    }
  }
  return out;
}

bool regularVertex(const MeshTopology& t, int p) {
  return t.boundary[p] ? t.valence[p] <= 3 : t.valence[p] == 4;
}

void childToParentQuad(int corner, double u, double v, double& pu, double& pv) {
  // Child c sits at parent corner c; its u runs along the parent's edge c -> c+1 and its v along
  // edge c -> c-1, each over half the parent's side.
  switch (corner) {
    case 0: pu = 0.5 * u, pv = 0.5 * v; break;
    case 1: pu = 1.0 - 0.5 * v, pv = 0.5 * u; break;
    case 2: pu = 1.0 - 0.5 * u, pv = 1.0 - 0.5 * v; break;
    case 3: pu = 0.5 * v, pv = 1.0 - 0.5 * u; break;
    default: throw std::logic_error("childToParentQuad: corner out of range");
  }
}

ControlMesh buildControlMesh(const PolyMesh& input) {
  ControlMesh cm;
  MeshTopology topology = checkMesh(input);
  // Refinement keeps a vertex's valence, and Stam's eigenbasis needs at least 3 (a valence-2
  // vertex is a closed mesh's legal fold, but no Catmull-Clark patch layout fits it).
  for (size_t p = 0; p < topology.valence.size(); ++p)
    if (topology.valence[p] > 0 && topology.valence[p] < 3 && !topology.boundary[p])
      fail(input, "vertex " + std::to_string(p) + " has valence " + std::to_string(topology.valence[p]) +
                      ": exact evaluation needs every vertex on at least 3 edges");
  PolyMesh mesh = input;
  cm.levels = input.allQuads() ? 1 : 2;
  cm.inputFace.resize(input.faceCount());
  cm.cornerChain.assign(input.faceCount(), {});
  for (int f = 0; f < input.faceCount(); ++f) cm.inputFace[f] = f;
  for (int level = 0; level < cm.levels; ++level) {
    RefinedMesh r = catmullClarkStep(mesh, topology);
    std::vector<int> inputFace(r.parent.size());
    std::vector<std::vector<int>> chain(r.parent.size());
    for (size_t f = 0; f < r.parent.size(); ++f) {
      inputFace[f] = cm.inputFace[r.parent[f]];
      chain[f] = cm.cornerChain[r.parent[f]];
      chain[f].push_back(r.parentCorner[f]);
    }
    cm.inputFace = std::move(inputFace);
    cm.cornerChain = std::move(chain);
    mesh = std::move(r.mesh);
    topology = MeshTopology::build(mesh);
  }
  // After these steps no quad has two irregular corners (Catmull-Clark separates them); regular
  // are interior vertices of valence 4, boundary vertices of valence 3 and corners (valence 2).
  // The irregular one is the face's corner 0: the last step's edge and face points are regular
  // (its input is all quads), so only a vertex of its input can be irregular, and
  // catmullClarkStep puts that vertex first in each child. The evaluation relies on it (the
  // patch's own frame is the face's (u, v): no per-patch rotation, as the paper stores).
  for (int f = 0; f < mesh.faceCount(); ++f) {
    int extraordinary = 0;
    for (int c = 0; c < 4; ++c) extraordinary += !regularVertex(topology, mesh.corner(f, c));
    if (extraordinary > 1) throw std::logic_error("buildControlMesh: a face kept two extraordinary vertices");
    if (extraordinary == 1 && regularVertex(topology, mesh.corner(f, 0)))
      throw std::logic_error("buildControlMesh: a face's extraordinary vertex is not its corner 0");
  }
  cm.mesh = std::move(mesh);
  cm.topology = std::move(topology);
  return cm;
}

}  // namespace sortlast
