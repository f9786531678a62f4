#include "subdiv/subdiv_mesh.h"

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
  face_offsets.push_back(static_cast<int>(face_corners.size()));
  face_sizes.push_back(static_cast<int>(corners.size()));
  face_corners.insert(face_corners.end(), corners.begin(), corners.end());
  if (!edge_sharpness.empty()) edge_sharpness.resize(face_corners.size(), 0.0);
  if (!holes.empty()) holes.push_back(0);
}

void PolyMesh::reverseFaces() {
  for (int f = 0; f < faceCount(); ++f) {
    const int o = face_offsets[f], m = face_sizes[f];
    std::reverse(face_corners.begin() + o, face_corners.begin() + o + m);
    if (edge_sharpness.empty()) continue;
    // Reversed, corner j is the old corner m - 1 - j, and its edge the old edge m - 2 - j.
    std::vector<double> old(edge_sharpness.begin() + o, edge_sharpness.begin() + o + m);
    for (int j = 0; j < m; ++j) edge_sharpness[o + j] = old[((m - 2 - j) % m + m) % m];
  }
}

bool PolyMesh::allQuads() const {
  return std::all_of(face_sizes.begin(), face_sizes.end(), [](int s) { return s == 4; });
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
    const int m = mesh.face_sizes[f];
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
  t.twin.assign(mesh.face_corners.size(), {});
  t.valence.assign(mesh.points.size(), 0);
  std::unordered_map<std::uint64_t, int> directed;  // edge a -> b: its corner slot
  std::unordered_map<std::uint64_t, int> uses;      // undirected edge: faces using it
  directed.reserve(mesh.face_corners.size());
  for (int f = 0; f < mesh.faceCount(); ++f)
    for (int c = 0; c < mesh.face_sizes[f]; ++c) {
      const int a = mesh.corner(f, c), b = mesh.corner(f, (c + 1) % mesh.face_sizes[f]);
      const int k = ++uses[edgeKey(std::min(a, b), std::max(a, b))];
      if (k > 2)
        fail(mesh, "edge (" + std::to_string(a) + ", " + std::to_string(b) +
                       ") is non-manifold: shared by more than two faces (face " + std::to_string(f) + " is the third)");
      if (!directed.emplace(edgeKey(a, b), mesh.face_offsets[f] + c).second)
        fail(mesh, "edge (" + std::to_string(a) + ", " + std::to_string(b) +
                       ") is used twice in the same direction (face " + std::to_string(f) +
                       "): faces are not consistently oriented");
      ++t.valence[a];
    }
  t.boundary.assign(mesh.points.size(), 0);
  for (int f = 0; f < mesh.faceCount(); ++f)
    for (int c = 0; c < mesh.face_sizes[f]; ++c) {
      const int a = mesh.corner(f, c), b = mesh.corner(f, (c + 1) % mesh.face_sizes[f]);
      const auto it = directed.find(edgeKey(b, a));
      if (it == directed.end()) {  // a boundary edge: no face on the other side
        t.boundary[a] = t.boundary[b] = 1;
        continue;
      }
      const int slot = it->second;
      const int g = static_cast<int>(std::upper_bound(mesh.face_offsets.begin(), mesh.face_offsets.end(), slot) -
                                     mesh.face_offsets.begin()) - 1;
      t.twin[mesh.face_offsets[f] + c] = {g, slot - mesh.face_offsets[g]};
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
    for (int c = 0; c < mesh.face_sizes[f]; ++c) {
      const int p = mesh.corner(f, c), slot = mesh.face_offsets[f] + c;
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
    int g = static_cast<int>(std::upper_bound(mesh.face_offsets.begin(), mesh.face_offsets.end(), slot) -
                             mesh.face_offsets.begin()) - 1;
    int d = slot - mesh.face_offsets[g];
    const int f0 = g, c0 = d;
    do {
      ++count;
      const auto& s = t.twin[mesh.face_offsets[g] + (d + mesh.face_sizes[g] - 1) % mesh.face_sizes[g]];
      if (s.face < 0) break;  // the boundary edge entering p: the fan's other end
      g = s.face;
      d = s.corner;
    } while ((g != f0 || d != c0) && count <= faces[p]);
    if (count != faces[p])
      fail(mesh, "vertex " + std::to_string(p) + " is non-manifold: its faces form more than one fan");
  }
  return t;
}

void applyTags(PolyMesh& mesh, const SubdivTags& tags) {
  const int np = static_cast<int>(mesh.points.size());
  auto checkSharpness = [&](double s, const std::string& where) {
    if (!(s >= 0.0))  // also NaN
      throw InputError(where + ": sharpness " + std::to_string(s) + " is negative or not a number");
  };
  if (!tags.creases.empty()) {
    std::unordered_map<std::uint64_t, std::vector<int>> slots;  // undirected edge -> its corner slots
    for (int f = 0; f < mesh.faceCount(); ++f)
      for (int c = 0; c < mesh.face_sizes[f]; ++c) {
        const int a = mesh.corner(f, c), b = mesh.corner(f, (c + 1) % mesh.face_sizes[f]);
        slots[edgeKey(std::min(a, b), std::max(a, b))].push_back(mesh.face_offsets[f] + c);
      }
    mesh.edge_sharpness.resize(mesh.face_corners.size(), 0.0);
    for (const CreaseTag& t : tags.creases) {
      checkSharpness(t.sharpness, t.where);
      for (int v : {t.a, t.b})
        if (v < 0 || v >= np)
          throw InputError(t.where + ": crease vertex " + std::to_string(v) + " is out of range (the mesh has " +
                           std::to_string(np) + " vertices)");
      const auto it = slots.find(edgeKey(std::min(t.a, t.b), std::max(t.a, t.b)));
      if (t.a == t.b || it == slots.end())
        throw InputError(t.where + ": crease (" + std::to_string(t.a) + ", " + std::to_string(t.b) +
                         ") is not an edge of the mesh");
      for (int slot : it->second) mesh.edge_sharpness[slot] = std::min(t.sharpness, kInfinitelySharp);
    }
  }
  for (const CornerTag& t : tags.corners) {
    checkSharpness(t.sharpness, t.where);
    if (t.vertex < 0 || t.vertex >= np)
      throw InputError(t.where + ": corner vertex " + std::to_string(t.vertex) + " is out of range (the mesh has " +
                       std::to_string(np) + " vertices)");
    mesh.vertex_sharpness.resize(np, 0.0);
    mesh.vertex_sharpness[t.vertex] = std::min(t.sharpness, kInfinitelySharp);
  }
  for (const HoleTag& t : tags.holes) {
    if (t.face < 0 || t.face >= mesh.faceCount())
      throw InputError(t.where + ": hole face " + std::to_string(t.face) + " is out of range (the mesh has " +
                       std::to_string(mesh.faceCount()) + " faces)");
    mesh.holes.resize(mesh.faceCount(), 0);
    mesh.holes[t.face] = 1;
  }
}

double slotSharpness(const PolyMesh& mesh, const MeshTopology& topology, int slot) {
  return topology.twin[slot].face < 0 ? kInfinitelySharp : mesh.edgeSharp(slot);
}

void prepareBoundary(PolyMesh& mesh, const MeshTopology& topology) {
  if (!topology.open()) return;
  // None first: it looks at the boundary edges' own tags, before they are all made sharp.
  if (mesh.boundary == BoundaryInterpolation::None) {
    std::vector<char> softBoundary(mesh.points.size(), 0);
    for (int f = 0; f < mesh.faceCount(); ++f)
      for (int c = 0; c < mesh.face_sizes[f]; ++c) {
        const int slot = mesh.face_offsets[f] + c;
        if (topology.twin[slot].face < 0 && !isInfinite(mesh.edgeSharp(slot)))
          softBoundary[mesh.corner(f, c)] = softBoundary[mesh.corner(f, (c + 1) % mesh.face_sizes[f])] = 1;
      }
    for (int f = 0; f < mesh.faceCount(); ++f)
      for (int c = 0; c < mesh.face_sizes[f]; ++c)
        if (softBoundary[mesh.corner(f, c)]) {
          mesh.holes.resize(mesh.faceCount(), 0);
          mesh.holes[f] = 1;
        }
  }
  mesh.edge_sharpness.resize(mesh.face_corners.size(), 0.0);
  for (size_t slot = 0; slot < mesh.face_corners.size(); ++slot)
    if (topology.twin[slot].face < 0) mesh.edge_sharpness[slot] = kInfinitelySharp;
  if (mesh.boundary == BoundaryInterpolation::EdgeAndCorner)
    for (size_t p = 0; p < mesh.points.size(); ++p)
      if (topology.boundary[p] && topology.valence[p] == 2) {
        mesh.vertex_sharpness.resize(mesh.points.size(), 0.0);
        mesh.vertex_sharpness[p] = kInfinitelySharp;
      }
}

namespace {

// The edges round corner c of face f (its vertex v): every incident edge's sharpness as
// refinement sees it, and how many faces f's sector holds (f and the faces reached from it round
// v without crossing a sharp edge; all of them round a vertex without sharp edges).
struct Fan {
  std::vector<double> edges;
  int sector = 1;
};

Fan fanAt(const PolyMesh& mesh, const MeshTopology& t, int f, int c) {
  const int v = mesh.corner(f, c);
  auto size = [&](int g) { return mesh.face_sizes[g]; };
  auto cornerOf = [&](int g) {
    for (int d = 0; d < size(g); ++d)
      if (mesh.corner(g, d) == v) return d;
    throw std::logic_error("fanAt: a face of the fan lacks its vertex");
  };
  // The fan's first face: f itself if the fan is closed, else the face whose edge entering v is
  // a boundary edge (walking backwards across the edges entering v).
  int first = f;
  for (int guard = 0; guard < 4096; ++guard) {
    const int d = cornerOf(first);
    const auto tw = t.twin[mesh.face_offsets[first] + (d + size(first) - 1) % size(first)];
    if (tw.face < 0 || tw.face == f) break;
    first = tw.face;
  }
  // Faces in order round v, and out[j] the edge leaving v in face j (between it and face j + 1).
  std::vector<int> faces;
  std::vector<double> out;
  int g = first;
  bool closed = false;
  for (int guard = 0; guard < 4096; ++guard) {
    const int slot = mesh.face_offsets[g] + cornerOf(g);
    faces.push_back(g);
    out.push_back(slotSharpness(mesh, t, slot));
    const auto tw = t.twin[slot];
    if (tw.face < 0) break;
    if (tw.face == first) {
      closed = true;
      break;
    }
    g = tw.face;
  }
  const int m = static_cast<int>(faces.size());
  const int d0 = cornerOf(first);
  const double in0 = closed ? out[m - 1] : slotSharpness(mesh, t, mesh.face_offsets[first] + (d0 + size(first) - 1) % size(first));
  Fan fan;
  fan.edges = out;
  if (!closed) fan.edges.push_back(in0);
  const int k = static_cast<int>(std::find(faces.begin(), faces.end(), f) - faces.begin());
  auto incoming = [&](int j) { return j > 0 ? out[j - 1] : in0; };
  fan.sector = 1;
  for (int j = k, n = 1; n < m && !isSharp(out[j]); ++n) {  // forwards
    j = (j + 1) % m;
    if (j == k) break;
    ++fan.sector;
  }
  if (fan.sector < m)
    for (int j = k, n = 1; n < m && !isSharp(incoming(j)); ++n) {  // backwards
      j = (j + m - 1) % m;
      ++fan.sector;
    }
  fan.sector = std::min(fan.sector, m);
  return fan;
}

}  // namespace

CornerKind faceCornerKind(const PolyMesh& mesh, const MeshTopology& t, int f, int c) {
  const int v = mesh.corner(f, c);
  const double sv = mesh.vertexSharp(v);
  const Fan fan = fanAt(mesh, t, f, c);
  bool semi = isSemiSharp(sv), sharp = isSharp(sv);
  for (double s : fan.edges) semi |= isSemiSharp(s), sharp |= isSharp(s);
  if (semi) return CornerKind::SemiSharp;
  if (!sharp) return CornerKind::Smooth;
  switch (vertexRule(sv, fan.edges)) {
    case VertexRule::Crease: return fan.sector == 2 ? CornerKind::Regular : CornerKind::Irregular;
    case VertexRule::Corner: {
      int sharpEdges = 0;
      for (double s : fan.edges) sharpEdges += isSharp(s);
      return sharpEdges >= 2 && fan.sector == 1 ? CornerKind::Regular : CornerKind::Irregular;
    }
    default: return CornerKind::Irregular;  // a dart (or a smooth vertex that is pinned)
  }
}

RefinedMesh catmullClarkStep(const PolyMesh& mesh, const MeshTopology& topology) {
  RefinedMesh out;
  out.mesh.name = mesh.name;
  out.mesh.boundary = mesh.boundary;
  out.mesh.crease_method = mesh.crease_method;
  const int nf = mesh.faceCount();
  const size_t slots = mesh.face_corners.size();
  // Sharp: some edge or vertex tagged, or a boundary (whose edges are infinitely sharp).
  const bool sharp = !mesh.edge_sharpness.empty() || !mesh.vertex_sharpness.empty() || topology.open();
  // New points: vertex points (used points only), then edge points, then face points.
  std::vector<int> vertexIndex(mesh.points.size(), -1);
  int nv = 0;
  for (size_t p = 0; p < mesh.points.size(); ++p)
    if (topology.valence[p] > 0) vertexIndex[p] = nv++;
  std::vector<glm::dvec3> facePoint(nf);
  for (int f = 0; f < nf; ++f) {
    glm::dvec3 s(0.0);
    for (int c = 0; c < mesh.face_sizes[f]; ++c) s += mesh.points[mesh.corner(f, c)];
    facePoint[f] = s / double(mesh.face_sizes[f]);
  }
  // Each undirected edge once: owned by the corner slot with the smaller index.
  std::vector<int> edgeOf(slots, -1), edgeSlot;
  for (int f = 0; f < nf; ++f)
    for (int c = 0; c < mesh.face_sizes[f]; ++c) {
      const int slot = mesh.face_offsets[f] + c;
      if (edgeOf[slot] >= 0) continue;
      edgeOf[slot] = static_cast<int>(edgeSlot.size());
      edgeSlot.push_back(slot);
      const auto& tw = topology.twin[slot];
      if (tw.face >= 0) edgeOf[mesh.face_offsets[tw.face] + tw.corner] = edgeOf[slot];
    }
  // Round each vertex: its edges (id, other end, sharpness) and, with tags, each edge's child
  // sharpness at this end. Every edge at p leaves p in exactly one face, except a boundary edge
  // entering p.
  struct Incident {
    int edge, other;
    double sharpness;
  };
  std::vector<std::vector<Incident>> around;
  std::vector<std::vector<double>> childAt;
  if (sharp) {
    around.resize(mesh.points.size());
    for (int f = 0; f < nf; ++f)
      for (int c = 0; c < mesh.face_sizes[f]; ++c) {
        const int slot = mesh.face_offsets[f] + c;
        const int a = mesh.corner(f, c), b = mesh.corner(f, (c + 1) % mesh.face_sizes[f]);
        const double s = slotSharpness(mesh, topology, slot);
        around[a].push_back({edgeOf[slot], b, s});
        if (topology.twin[slot].face < 0) around[b].push_back({edgeOf[slot], a, s});
      }
    childAt.resize(mesh.points.size());
    for (size_t p = 0; p < mesh.points.size(); ++p) {
      std::vector<double> s;
      for (const auto& e : around[p]) s.push_back(e.sharpness);
      childAt[p] = childEdgeSharpness(mesh.crease_method, s);
    }
  }
  auto childSharpness = [&](int p, int edge) {
    for (size_t i = 0; i < around[p].size(); ++i)
      if (around[p][i].edge == edge) return childAt[p][i];
    throw std::logic_error("catmullClarkStep: an edge missing round its vertex");
  };
  std::vector<glm::dvec3> edgePoint(edgeSlot.size());
  for (size_t e = 0; e < edgeSlot.size(); ++e) {
    const int slot = edgeSlot[e];
    const int f = static_cast<int>(std::upper_bound(mesh.face_offsets.begin(), mesh.face_offsets.end(), slot) -
                                   mesh.face_offsets.begin()) - 1;
    const int c = slot - mesh.face_offsets[f];
    const int a = mesh.corner(f, c), b = mesh.corner(f, (c + 1) % mesh.face_sizes[f]);
    const glm::dvec3 mid = (mesh.points[a] + mesh.points[b]) * 0.5;
    const auto& tw = topology.twin[slot];
    const double s = sharp ? slotSharpness(mesh, topology, slot) : 0.0;
    if (tw.face < 0) {  // a boundary edge is infinitely sharp
      edgePoint[e] = mid;
      continue;
    }
    const glm::dvec3 smooth = (mesh.points[a] + mesh.points[b] + facePoint[f] + facePoint[tw.face]) * 0.25;
    if (!isSharp(s)) {
      edgePoint[e] = smooth;
      continue;
    }
    // A crease (the midpoint) if the edge point's two child edges stay sharp; else the crease and
    // smooth rules blended by s. This is what OpenSubdiv computes (Far::PrimvarRefiner takes the
    // edge point's own rule from its child edges): under Chaikin's method the halves can differ,
    // and then s is the weight even above 1.
    const bool halvesSharp = mesh.crease_method == CreaseMethod::Uniform
                                 ? isSharp(decrementSharpness(s))
                                 : isSharp(childSharpness(a, static_cast<int>(e))) && isSharp(childSharpness(b, static_cast<int>(e)));
    edgePoint[e] = halvesSharp ? mid : s * mid + (1.0 - s) * smooth;
  }
  // The smooth vertex point (Q + 2R + (n - 3) S) / n: in a closed fan every edge leaving p is the
  // edge after p in exactly one face, so one pass over the corners visits each face and edge once.
  std::vector<glm::dvec3> q(mesh.points.size(), glm::dvec3(0.0)), r(mesh.points.size(), glm::dvec3(0.0));
  for (int f = 0; f < nf; ++f)
    for (int c = 0; c < mesh.face_sizes[f]; ++c) {
      const int m = mesh.face_sizes[f];
      const int a = mesh.corner(f, c), b = mesh.corner(f, (c + 1) % m);
      q[a] += facePoint[f];
      r[a] += (mesh.points[a] + mesh.points[b]) * 0.5;
    }
  out.mesh.points.resize(nv + edgePoint.size() + nf);
  for (size_t p = 0; p < mesh.points.size(); ++p) {
    if (vertexIndex[p] < 0) continue;
    const double n = topology.valence[p];
    const glm::dvec3& x = mesh.points[p];
    const glm::dvec3 smooth = (q[p] / n + 2.0 * r[p] / n + (n - 3.0) * x) / n;
    glm::dvec3& result = out.mesh.points[vertexIndex[p]];
    if (!sharp) {
      result = smooth;
      continue;
    }
    std::vector<double> edges;
    for (const auto& e : around[p]) edges.push_back(e.sharpness);
    const double sv = mesh.vertexSharp(static_cast<int>(p));
    // The crease rule: 3/4 the vertex, 1/8 each end of its two sharp edges (by `sharpness`).
    auto crease = [&](const std::vector<double>& sharpness) {
      glm::dvec3 sum(0.0);
      for (size_t i = 0; i < sharpness.size(); ++i)
        if (isSharp(sharpness[i])) sum += mesh.points[around[p][i].other];
      return 0.75 * x + 0.125 * sum;
    };
    auto apply = [&](VertexRule rule, const std::vector<double>& sharpness) {
      return rule == VertexRule::Crease ? crease(sharpness) : rule == VertexRule::Corner ? x : smooth;
    };
    const VertexRule rule = vertexRule(sv, edges);
    if (rule == VertexRule::Smooth || rule == VertexRule::Dart) {
      result = smooth;
      continue;
    }
    result = apply(rule, edges);
    const double childSv = decrementSharpness(sv);
    const std::vector<double>& childEdges = childAt[p];
    const VertexRule childRule = vertexRule(childSv, childEdges);
    if (childRule == rule) continue;
    // A sharpness decays in this step: the parent's rule blended with the child's.
    const double w = fractionalWeight(mesh.crease_method, sv, childSv, edges, childEdges);
    result = w * result + (1.0 - w) * apply(childRule, childEdges);
  }
  std::copy(edgePoint.begin(), edgePoint.end(), out.mesh.points.begin() + nv);
  std::copy(facePoint.begin(), facePoint.end(), out.mesh.points.begin() + nv + edgePoint.size());
  const int edgeBase = nv, faceBase = nv + static_cast<int>(edgePoint.size());
  const bool childEdgesTagged = sharp;
  if (childEdgesTagged) out.mesh.edge_sharpness.reserve(4 * slots);
  for (int f = 0; f < nf; ++f) {
    const int m = mesh.face_sizes[f];
    for (int c = 0; c < m; ++c) {
      const int a = mesh.corner(f, c);
      const int e0 = edgeOf[mesh.face_offsets[f] + c], e1 = edgeOf[mesh.face_offsets[f] + (c + m - 1) % m];
      out.mesh.addFace({vertexIndex[a], edgeBase + e0, faceBase + f, edgeBase + e1});
      if (childEdgesTagged) {
        // vertex -> edge point: the half of edge c at a; the two edges to the face point are
        // smooth; edge point -> vertex: the half of edge c - 1 at a.
        out.mesh.edge_sharpness.resize(out.mesh.face_corners.size() - 4);
        out.mesh.edge_sharpness.insert(out.mesh.edge_sharpness.end(),
                                      {childSharpness(a, e0), 0.0, 0.0, childSharpness(a, e1)});
      }
      if (!mesh.holes.empty()) {
        out.mesh.holes.resize(out.mesh.faceCount(), 0);
        out.mesh.holes.back() = mesh.holes[f];
      }
      out.parent.push_back(f);
      out.parent_corner.push_back(c);
    }
  }
  if (!mesh.vertex_sharpness.empty()) {
    out.mesh.vertex_sharpness.assign(out.mesh.points.size(), 0.0);
    for (size_t p = 0; p < mesh.points.size(); ++p)
      if (vertexIndex[p] >= 0) out.mesh.vertex_sharpness[vertexIndex[p]] = decrementSharpness(mesh.vertex_sharpness[p]);
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
  prepareBoundary(mesh, topology);
  cm.levels = input.allQuads() ? 1 : 2;
  cm.input_face.resize(input.faceCount());
  cm.corner_chain.assign(input.faceCount(), {});
  for (int f = 0; f < input.faceCount(); ++f) cm.input_face[f] = f;
  for (int level = 0; level < cm.levels; ++level) {
    RefinedMesh r = catmullClarkStep(mesh, topology);
    std::vector<int> input_face(r.parent.size());
    std::vector<std::vector<int>> chain(r.parent.size());
    for (size_t f = 0; f < r.parent.size(); ++f) {
      input_face[f] = cm.input_face[r.parent[f]];
      chain[f] = cm.corner_chain[r.parent[f]];
      chain[f].push_back(r.parent_corner[f]);
    }
    cm.input_face = std::move(input_face);
    cm.corner_chain = std::move(chain);
    mesh = std::move(r.mesh);
    topology = MeshTopology::build(mesh);
  }
  // After these steps no quad has two irregular corners (Catmull-Clark separates them); regular
  // are interior vertices of valence 4, boundary vertices of valence 3 and corners (valence 2),
  // and with tags the sector rules of faceCornerKind. The irregular one is the face's corner 0:
  // the last step's edge and face points are regular (its input is all quads; an edge point of an
  // infinitely sharp edge is a crease of two faces a side), so only a vertex of its input can be
  // irregular, and catmullClarkStep puts that vertex first in each child. The evaluation relies
  // on it (the patch's own frame is the face's (u, v): no per-patch rotation, as the paper
  // stores). Faces near a semi-sharp feature are refined further by the evaluator.
  for (int f = 0; f < mesh.faceCount(); ++f) {
    int irregular = 0;
    bool semi = false, firstIrregular = false;
    for (int c = 0; c < 4; ++c) {
      const CornerKind k = faceCornerKind(mesh, topology, f, c);
      semi |= k == CornerKind::SemiSharp;
      const bool bad = irregularCorner(k, topology, mesh.corner(f, c));
      irregular += bad;
      if (c == 0) firstIrregular = bad;
    }
    if (semi) continue;
    if (irregular > 1) throw std::logic_error("buildControlMesh: a face kept two extraordinary vertices");
    if (irregular == 1 && !firstIrregular)
      throw std::logic_error("buildControlMesh: a face's extraordinary vertex is not its corner 0");
  }
  cm.mesh = std::move(mesh);
  cm.topology = std::move(topology);
  return cm;
}

}  // namespace sortlast
