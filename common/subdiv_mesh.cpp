#include "common/subdiv_mesh.h"

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
  for (int f = 0; f < mesh.faceCount(); ++f)
    for (int c = 0; c < mesh.faceSizes[f]; ++c) {
      const int a = mesh.corner(f, c), b = mesh.corner(f, (c + 1) % mesh.faceSizes[f]);
      const auto it = directed.find(edgeKey(b, a));
      if (it == directed.end())
        fail(mesh, "edge (" + std::to_string(a) + ", " + std::to_string(b) + ") of face " + std::to_string(f) +
                       " is a boundary edge: open meshes are not supported (close the mesh; boundary "
                       "rules are not implemented)");
      const int slot = it->second;
      const int g = static_cast<int>(std::upper_bound(mesh.faceOffsets.begin(), mesh.faceOffsets.end(), slot) -
                                     mesh.faceOffsets.begin()) - 1;
      t.twin[mesh.faceOffsets[f] + c] = {g, slot - mesh.faceOffsets[g]};
    }
  return t;
}

MeshTopology checkMesh(const PolyMesh& mesh) {
  checkFaces(mesh);
  MeshTopology t = MeshTopology::build(mesh);
  // A closed manifold vertex's faces form one fan: walking round it from any corner reaches all.
  std::vector<char> seen(mesh.faceCorners.size(), 0);
  for (int f = 0; f < mesh.faceCount(); ++f)
    for (int c = 0; c < mesh.faceSizes[f]; ++c) {
      if (seen[mesh.faceOffsets[f] + c]) continue;
      const int p = mesh.corner(f, c);
      int g = f, d = c, count = 0;
      do {
        seen[mesh.faceOffsets[g] + d] = 1;
        ++count;
        const auto& s = t.twin[mesh.faceOffsets[g] + (d + mesh.faceSizes[g] - 1) % mesh.faceSizes[g]];
        g = s.face;
        d = s.corner;
      } while ((g != f || d != c) && count <= t.valence[p]);
      if (count != t.valence[p])
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
      const int twinSlot = mesh.faceOffsets[tw.face] + tw.corner;
      if (edgeOf[slot] >= 0) continue;
      const int a = mesh.corner(f, c), b = mesh.corner(f, (c + 1) % mesh.faceSizes[f]);
      edgeOf[slot] = edgeOf[twinSlot] = static_cast<int>(edgePoint.size());
      edgePoint.push_back((mesh.points[a] + mesh.points[b] + facePoint[f] + facePoint[tw.face]) * 0.25);
    }
  // Vertex point (Q + 2R + (n - 3) S) / n: in a closed mesh every edge leaving p is the edge
  // after p in exactly one face, so one pass over the corners visits each face and edge once.
  std::vector<glm::dvec3> q(mesh.points.size(), glm::dvec3(0.0)), r(mesh.points.size(), glm::dvec3(0.0));
  for (int f = 0; f < nf; ++f)
    for (int c = 0; c < mesh.faceSizes[f]; ++c) {
      const int a = mesh.corner(f, c), b = mesh.corner(f, (c + 1) % mesh.faceSizes[f]);
      q[a] += facePoint[f];
      r[a] += (mesh.points[a] + mesh.points[b]) * 0.5;
    }
  out.mesh.points.resize(nv + edgePoint.size() + nf);
  for (size_t p = 0; p < mesh.points.size(); ++p) {
    if (vertexIndex[p] < 0) continue;
    const double n = topology.valence[p];
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
    if (topology.valence[p] > 0 && topology.valence[p] < 3)
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
  // After these steps no quad has two extraordinary corners (Catmull-Clark separates them).
  for (int f = 0; f < mesh.faceCount(); ++f) {
    int extraordinary = 0;
    for (int c = 0; c < 4; ++c) extraordinary += topology.valence[mesh.corner(f, c)] != 4;
    if (extraordinary > 1) throw std::logic_error("buildControlMesh: a face kept two extraordinary vertices");
  }
  cm.mesh = std::move(mesh);
  cm.topology = std::move(topology);
  return cm;
}

}  // namespace sortlast
