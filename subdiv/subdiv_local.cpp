#include "subdiv/subdiv_local.h"

#include <glm/common.hpp>
#include <glm/vec2.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

namespace sortlast {

namespace {

// The faces of `mesh` sharing a vertex with face f, walking each corner's fan both ways (a fan
// ends at a boundary edge).
std::vector<int> oneRing(const PolyMesh& mesh, const MeshTopology& t, int f) {
  std::vector<int> out{f};
  auto add = [&](int g) {
    if (std::find(out.begin(), out.end(), g) == out.end()) out.push_back(g);
  };
  for (int c = 0; c < mesh.face_sizes[f]; ++c) {
    int g = f, d = c;
    for (int guard = 0; guard < 64; ++guard) {  // backwards: across the edge entering the corner
      const int m = mesh.face_sizes[g];
      const auto s = t.twin[mesh.face_offsets[g] + (d + m - 1) % m];
      if (s.face < 0 || s.face == f) break;
      g = s.face, d = s.corner;
      add(g);
    }
    g = f, d = c;
    for (int guard = 0; guard < 64; ++guard) {  // forwards: across the edge leaving the corner
      const auto s = t.twin[mesh.face_offsets[g] + d];
      if (s.face < 0 || s.face == f) break;
      g = s.face, d = (s.corner + 1) % mesh.face_sizes[s.face];
      add(g);
    }
  }
  return out;
}

// `faces` of `src` as a mesh of their own with their tags, corners in the same order but the
// first face's turned to start at its corner `start`.
PolyMesh extract(const PolyMesh& src, const std::vector<int>& faces, int start = 0) {
  PolyMesh out;
  out.name = src.name;
  out.boundary = src.boundary;
  out.crease_method = src.crease_method;
  std::unordered_map<int, int> index;
  std::vector<double> vertex_sharpness;
  for (size_t i = 0; i < faces.size(); ++i) {
    const int f = faces[i], m = src.face_sizes[f], turn = i == 0 ? start : 0;
    std::vector<int> corners;
    for (int j = 0; j < m; ++j) {
      const int c = (j + turn) % m;
      const int p = src.corner(f, c);
      auto [it, added] = index.emplace(p, static_cast<int>(out.points.size()));
      if (added) {
        out.points.push_back(src.points[p]);
        vertex_sharpness.push_back(src.vertexSharp(p));
      }
      corners.push_back(it->second);
    }
    out.addFace(corners);
    if (!src.edge_sharpness.empty()) {
      out.edge_sharpness.resize(out.face_corners.size() - m);
      for (int j = 0; j < m; ++j) out.edge_sharpness.push_back(src.edge_sharpness[src.face_offsets[f] + (j + turn) % m]);
    }
  }
  if (!src.vertex_sharpness.empty()) out.vertex_sharpness = std::move(vertex_sharpness);
  return out;
}

}  // namespace

LocalNet::LocalNet(const PolyMesh& mesh, const MeshTopology& topology, int face) {
  // Chaikin's method needs a second ring (see keepOneRing): the one-rings of the first's faces.
  std::vector<int> faces = oneRing(mesh, topology, face);
  if (mesh.crease_method == CreaseMethod::Chaikin) {
    const std::vector<int> first = faces;
    for (int g : first)
      for (int h : oneRing(mesh, topology, g))
        if (std::find(faces.begin(), faces.end(), h) == faces.end()) faces.push_back(h);
  }
  keepOneRing(extract(mesh, faces), 0);
}

LocalNet::Grid LocalNet::toWorld(const Grid& local) const {
  Grid out;
  for (int i = 0; i < 16; ++i) out[i] = origin_ + scale_ * local[i];
  return out;
}

void LocalNet::grid(Grid& world, Grid& tangent) const {
  tangent = gridOf(mesh_, face_, 0);
  world = toWorld(tangent);
}

LocalNet::Kind LocalNet::kind() const {
  const MeshTopology t = MeshTopology::build(mesh_);
  int irregular = -1;
  for (int c = 0; c < 4; ++c) {
    const CornerKind k = faceCornerKind(mesh_, t, face_, c);
    if (k == CornerKind::SemiSharp) return Kind::SemiSharp;
    if (irregularCorner(k, t, mesh_.corner(face_, c))) {
      if (irregular >= 0 || c != 0) throw std::logic_error("LocalNet: an irregular corner off the frame's (0, 0)");
      irregular = c;
    }
  }
  return irregular < 0 ? Kind::Regular : Kind::Irregular;
}

std::array<LocalNet, 4> LocalNet::split() const {
  const MeshTopology t = MeshTopology::build(mesh_);
  const RefinedMesh r = catmullClarkStep(mesh_, t);
  // Quadrant q of the frame is child q of face_ (its corner q sits there); the child's corner at
  // the quadrant's lower left is its corner (4 - q) % 4, with the next corner along the frame's
  // u: see step().
  std::array<LocalNet, 4> out{*this, *this, *this, *this};
  for (int q = 0; q < 4; ++q) out[q].keepOneRing(r.mesh, 4 * face_ + q, (4 - q) % 4);
  return out;
}

void LocalNet::keepOneRing(const PolyMesh& refined, int face, int start) {
  // The faces sharing a vertex with `face`; under Chaikin's method also those sharing a vertex
  // with them: an edge point's rule there depends on its edge's child sharpness at the far end,
  // which averages the sharpness round that end's vertex (a one-ring vertex), so every edge at a
  // one-ring vertex must be kept with its true sharpness. (Points of the second ring may be
  // wrong; no kept face of the next level uses them.)
  const int rings = refined.crease_method == CreaseMethod::Chaikin ? 2 : 1;
  std::vector<char> vertexIn(refined.points.size(), 0), faceIn(refined.faceCount(), 0);
  std::vector<int> faces{face};
  faceIn[face] = 1;
  for (int ring = 0; ring < rings; ++ring) {
    for (int g : faces)
      for (int c = 0; c < refined.face_sizes[g]; ++c) vertexIn[refined.corner(g, c)] = 1;
    for (int f = 0; f < refined.faceCount(); ++f) {
      if (faceIn[f]) continue;
      for (int c = 0; c < refined.face_sizes[f]; ++c)
        if (vertexIn[refined.corner(f, c)]) {
          faceIn[f] = 1;
          faces.push_back(f);
          break;
        }
    }
  }
  mesh_ = extract(refined, faces, start);
  face_ = 0;
  // Re-centre on the irregular vertex and rescale by a power of two (exact) to unit extent.
  const glm::dvec3 centre = mesh_.points[mesh_.corner(0, 0)];
  double extent = 0;
  for (auto& p : mesh_.points) {
    p -= centre;
    extent = std::max({extent, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
  }
  origin_ += scale_ * centre;
  if (extent > 0) {
    int e;
    std::frexp(extent, &e);
    for (auto& p : mesh_.points) p = glm::dvec3(std::ldexp(p.x, -e), std::ldexp(p.y, -e), std::ldexp(p.z, -e));
    scale_ = std::ldexp(scale_, e);
  }
}

void LocalNet::step(std::array<Grid, 3>* world, std::array<Grid, 3>* tangent, int only) {
  const MeshTopology t = MeshTopology::build(mesh_);
  RefinedMesh r = catmullClarkStep(mesh_, t);
  // Children of face_ are 4 face_ + c (every face is a quad); child c sits at corner c. Sub-patch
  // k is the child at corner k, whose grid origin (the frame's lower left of its cell) is its
  // corner 4 - k: the edge point before corner 1, the face point, the edge point after corner 3.
  if (world)
    for (int k = 1; k <= 3; ++k) {
      if (only != 0 && k != only) continue;
      const Grid local = gridOf(r.mesh, 4 * face_ + k, 4 - k);
      (*world)[k - 1] = toWorld(local);
      if (tangent) (*tangent)[k - 1] = local;
    }
  keepOneRing(r.mesh, 4 * face_);
}

LocalNet::Grid LocalNet::gridOf(const PolyMesh& mesh, int f, int start) {
  const MeshTopology t = MeshTopology::build(mesh);
  std::array<int, 16> grid;
  grid.fill(-1);
  auto at = [](glm::ivec2 q) { return (q.y + 1) * 4 + (q.x + 1); };
  std::vector<char> placed(mesh.faceCount(), 0);
  std::vector<std::array<glm::ivec2, 4>> pos(mesh.faceCount());
  std::vector<int> queue;
  // Face g with corner d at a and corner d + 1 at b; counter-clockwise, so the others are b and a
  // moved a quarter turn left of a -> b.
  auto place = [&](int g, int d, glm::ivec2 a, glm::ivec2 b) {
    const glm::ivec2 left(-(b - a).y, (b - a).x);
    const glm::ivec2 q[4] = {a, b, b + left, a + left};
    glm::ivec2 lo = glm::min(glm::min(q[0], q[1]), glm::min(q[2], q[3]));
    if (lo.x < -1 || lo.x > 1 || lo.y < -1 || lo.y > 1) return;  // outside the 3 x 3 cells
    placed[g] = 1;
    for (int i = 0; i < 4; ++i) {
      pos[g][(d + i) % 4] = q[i];
      int& slot = grid[at(q[i])];
      if (slot >= 0 && slot != mesh.corner(g, (d + i) % 4))
        throw std::logic_error("LocalNet: the cells round a regular face do not form a grid");
      slot = mesh.corner(g, (d + i) % 4);
    }
    queue.push_back(g);
  };
  place(f, start, {0, 0}, {1, 0});
  while (!queue.empty()) {
    const int g = queue.back();
    queue.pop_back();
    for (int e = 0; e < 4; ++e) {
      const auto s = t.twin[mesh.face_offsets[g] + e];
      // An infinitely sharp edge is a boundary for the faces on each side: beyond it, phantoms.
      if (s.face < 0 || placed[s.face] || isSharp(mesh.edgeSharp(mesh.face_offsets[g] + e))) continue;
      place(s.face, s.corner, pos[g][(e + 1) % 4], pos[g][e]);
    }
  }
  std::array<glm::dvec3, 16> out;
  std::array<char, 16> have{};
  for (int i = 0; i < 16; ++i)
    if (grid[i] >= 0) out[i] = mesh.points[grid[i]], have[i] = 1;
  // Phantom points beyond a boundary: reflected across it, columns first, then rows (which fills
  // the corner cell beyond a corner with 4 P00 - 2 P10 - 2 P01 + P11).
  for (int pass = 0; pass < 2; ++pass)
    for (int y = -1; y <= 2; ++y)
      for (int x = -1; x <= 2; ++x) {
        const glm::ivec2 q(x, y);
        if (have[at(q)]) continue;
        const glm::ivec2 dir = pass == 0 ? glm::ivec2(1, 0) : glm::ivec2(0, 1);
        const int c = pass == 0 ? x : y;
        if (c != -1 && c != 2) continue;
        const glm::ivec2 in = c == -1 ? q + dir : q - dir, in2 = c == -1 ? q + 2 * dir : q - 2 * dir;
        if (!have[at(in)] || !have[at(in2)]) continue;
        out[at(q)] = 2.0 * out[at(in)] - out[at(in2)];
        have[at(q)] = 1;
      }
  for (char h : have)
    if (!h) throw std::logic_error("LocalNet: a regular face's grid has a hole");
  return out;
}

}  // namespace sortlast
