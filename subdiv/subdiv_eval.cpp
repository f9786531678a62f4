#include "subdiv/subdiv_eval.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace sortlast {

void bsplinePatch(const std::array<glm::dvec3, 16>& p, double s, double t, glm::dvec3& position,
                  glm::dvec3& ds, glm::dvec3& dt) {
  double bs[4], dbs[4], bt[4], dbt[4];
  bsplineBasis(s, bs, dbs);
  bsplineBasis(t, bt, dbt);
  position = ds = dt = glm::dvec3(0.0);
  for (int b = 0; b < 4; ++b)
    for (int a = 0; a < 4; ++a) {
      const glm::dvec3& q = p[b * 4 + a];
      position += bs[a] * bt[b] * q;
      ds += dbs[a] * bt[b] * q;
      dt += bs[a] * dbt[b] * q;
    }
}

namespace {

// The 2N + 8 points of the patch on control face `face` whose corner 0 has valence n, in
// ValenceBasis's labels, found by walking the directed edges (see subdiv_basis.h for the layout).
std::vector<int> gatherPatch(const PolyMesh& m, const MeshTopology& t, int face, int n) {
  auto at = [&](int f, int c) { return m.corner(f, c % 4); };
  auto across = [&](int f, int c) { return t.twin[m.face_offsets[f] + c % 4]; };
  std::vector<int> label(2 * n + 8, -1);
  label[0] = at(face, 0);
  int g = face, c = 0;
  for (int i = 1; i <= n; ++i) {  // the fan round the extraordinary vertex, counter-clockwise
    label[2 * i - 1] = at(g, c + 1);
    label[2 * i] = at(g, c + 2);
    if (i == n) break;
    const auto next = across(g, c + 3);
    g = next.face;
    c = next.corner;
  }
  if (at(g, c + 3) != label[1]) throw std::logic_error("gatherPatch: the fan does not close");
  auto L = [n](int i, int j) { return ValenceBasis::label(n, i, j); };
  const auto h = across(g, c + 2);        // cell (1,-1)-(2,0), entered at e_1
  const auto jc = across(face, 1);        // cell (1,0)-(2,1), entered at f_1
  const auto lc = across(face, 2);        // cell (0,1)-(1,2), entered at e_2
  const auto mc = across(jc.face, jc.corner + 3);  // cell (1,1)-(2,2), entered at f_1
  const auto pc = across(lc.face, lc.corner + 3);  // cell (-1,1)-(0,2), entered at e_2
  label[L(2, -1)] = at(h.face, h.corner + 2);
  label[L(2, 0)] = at(h.face, h.corner + 3);
  label[L(2, 1)] = at(jc.face, jc.corner + 3);
  label[L(2, 2)] = at(mc.face, mc.corner + 2);
  label[L(1, 2)] = at(lc.face, lc.corner + 2);
  label[L(0, 2)] = at(lc.face, lc.corner + 3);
  label[L(-1, 2)] = at(pc.face, pc.corner + 2);
  // The cells must fit together as the grid says; a mismatch is a bug, not bad input.
  if (at(jc.face, jc.corner + 2) != label[L(2, 0)] || at(mc.face, mc.corner + 3) != label[L(1, 2)] ||
      at(pc.face, pc.corner + 3) != label[L(-1, 1)])
    throw std::logic_error("gatherPatch: cells round the patch do not match");
  return label;
}

}  // namespace

SubdivSurface::SubdivSurface(const PolyMesh& input) : control_(buildControlMesh(input)) {
  const PolyMesh& m = control_.mesh;
  const MeshTopology& t = control_.topology;
  patches_.resize(m.faceCount());
  for (int f = 0; f < m.faceCount(); ++f) {
    Patch& p = patches_[f];
    bool tagged = false;
    for (int c = 0; c < 4; ++c) tagged |= faceCornerKind(m, t, f, c) != CornerKind::Smooth;
    if (tagged) {
      // Tags or a boundary at some corner: explicit local subdivision with their rules, down to
      // where every semi-sharp value has decayed (buildNode). A face that is one B-spline patch
      // straight away keeps its grid as a regular patch.
      const LocalNet net(m, t, f);
      if (net.kind() == LocalNet::Kind::Regular) {
        LocalNet::Grid world, local;
        net.grid(world, local);
        p.kind = Kind::Regular;
        p.points.resize(16, 3);
        for (int i = 0; i < 16; ++i) p.points.row(i) << world[i].x, world[i].y, world[i].z;
      } else {
        p.kind = Kind::Tree;
        p.root = buildNode(net, 0);
      }
      continue;
    }
    p.valence = t.valence[m.corner(f, 0)];  // the only corner that may be extraordinary
    const std::vector<int> label = gatherPatch(m, t, f, p.valence);
    if (p.valence == 4) {
      p.kind = Kind::Regular;
      p.points.resize(16, 3);
      for (int b = 0; b < 4; ++b)
        for (int a = 0; a < 4; ++a) {
          const glm::dvec3& q = m.points[label[ValenceBasis::label(4, a - 1, b - 1)]];
          p.points.row(b * 4 + a) << q.x, q.y, q.z;
        }
      continue;
    }
    p.kind = Kind::Stam;
    auto& basis = bases_[p.valence];
    if (!basis) basis = std::make_unique<ValenceBasis>(p.valence);
    Eigen::MatrixXd c0(label.size(), 3);
    for (size_t i = 0; i < label.size(); ++i) c0.row(i) << m.points[label[i]].x, m.points[label[i]].y, m.points[label[i]].z;
    p.points = basis->Vinv * c0;
  }
}

bool SubdivSurface::twoSided() const {
  if (control_.topology.open()) return true;
  for (int f = 0; f < control_.mesh.faceCount(); ++f)
    if (hole(f)) return true;
  return false;
}

int SubdivSurface::buildNode(const LocalNet& net, int depth) {
  const int index = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  fillNode(index, net, depth);
  return index;
}

void SubdivSurface::fillNode(int index, const LocalNet& net, int depth) {
  const LocalNet::Kind kind = net.kind();
  if (kind == LocalNet::Kind::Regular) {
    nodes_[index].type = NodeType::Regular;
    net.grid(nodes_[index].grid, nodes_[index].tangent);
    return;
  }
  if (kind == LocalNet::Kind::Irregular) {
    nodes_[index].type = NodeType::Irregular;
    nodes_[index].net = std::make_shared<LocalNet>(net);
    return;
  }
  // Semi-sharp: every value decays by at least 1 a level under the uniform rule (Chaikin's
  // averages also end below 10 levels), so a deep tree is a bug.
  if (depth >= kMaxSemiSharpDepth) throw std::logic_error("SubdivSurface: a semi-sharp feature did not decay");
  const int first = static_cast<int>(nodes_.size());
  nodes_.resize(nodes_.size() + 4);  // the four children side by side, their subtrees after them
  nodes_[index].type = NodeType::Split;
  nodes_[index].first_child = first;
  const std::array<LocalNet, 4> children = net.split();
  for (int q = 0; q < 4; ++q) fillNode(first + q, children[q], depth + 1);
}

void SubdivSurface::nodeGrid(int node, std::array<glm::dvec3, 16>& position, std::array<glm::dvec3, 16>& tangent) const {
  position = nodes_[node].grid;
  tangent = nodes_[node].tangent;
}

void SubdivSurface::nodeSubPatches(int node, int levels, std::vector<std::array<glm::dvec3, 16>>& positions,
                                   std::vector<std::array<glm::dvec3, 16>>& tangents) const {
  positions.clear();
  tangents.clear();
  LocalNet net = *nodes_[node].net;
  for (int n = 1; n <= levels; ++n) {
    std::array<LocalNet::Grid, 3> world, local;
    net.step(&world, &local);
    positions.insert(positions.end(), world.begin(), world.end());
    tangents.insert(tangents.end(), local.begin(), local.end());
  }
}

namespace {

// Which (n, k) sub-patch of a face with its extraordinary vertex at (0, 0) holds (u, v).
SubdivSurface::Location locateIrregular(double u, double v, int maxLevel) {
  SubdivSurface::Location loc;
  // n = floor(-log2 max(u, v)) + 1: the level whose ring [2^-n, 2^(1-n)] holds max(u, v).
  const double m = std::max(u, v);
  int n = maxLevel;
  if (m > 0) {
    int e;
    const double fraction = std::frexp(m, &e);  // m = fraction * 2^e, fraction in [1/2, 1)
    n = std::min(maxLevel, fraction == 0.5 ? 2 - e : 1 - e);
  }
  n = std::max(n, 1);
  const double su = std::ldexp(u, n), sv = std::ldexp(v, n);  // in [0, 2] but at the level cap
  loc.n = n;
  if (su >= 1.0 && sv >= 1.0) loc.k = 2;
  else if (su >= 1.0) loc.k = 1;
  else if (sv >= 1.0) loc.k = 3;
  else loc.k = su >= sv ? 1 : 3;  // below 2^-maxLevel: the nearer sub-patch, slightly extrapolated
  loc.s = su - (loc.k != 3 ? 1.0 : 0.0);
  loc.t = sv - (loc.k != 1 ? 1.0 : 0.0);
  return loc;
}

}  // namespace

SubdivSurface::Location SubdivSurface::locate(int face, double u, double v, int maxLevel) const {
  if (regular(face)) {
    Location loc;
    loc.s = u, loc.t = v;
    return loc;
  }
  if (patches_[face].kind == Kind::Tree) {
    if (nodes_[patches_[face].root].type != NodeType::Irregular)
      throw std::logic_error("SubdivSurface::locate: a face split at semi-sharp tags has no single (n, k)");
    maxLevel = std::min(maxLevel, kBoundaryMaxLevel);
  }
  return locateIrregular(u, v, maxLevel);
}

std::array<glm::dvec3, 16> SubdivSurface::controlPoints(int face, int n, int k, bool tangent) const {
  const Patch& p = patches_[face];
  std::array<glm::dvec3, 16> out;
  if (p.kind == Kind::Tree) {
    if (nodes_[p.root].type != NodeType::Irregular)
      throw std::logic_error("SubdivSurface::controlPoints: a face split at semi-sharp tags");
    std::array<glm::dvec3, 16> position, tangents;
    irregularSubPatch(p.root, n, k, position, tangents);
    return tangent ? tangents : position;
  }
  if (regular(face)) {
    for (int i = 0; i < 16; ++i) out[i] = {p.points(i, 0), p.points(i, 1), p.points(i, 2)};
    return out;
  }
  const ValenceBasis& basis = *bases_.at(p.valence);
  // X_k Lambda^(n-1) C-hat: the paper's equation (8) for the 16 points of Omega_k^n.
  // Eigenvalues are sorted: lambda_0 = 1, lambda_1 = lambda_2 = the subdominant one.
  Eigen::VectorXd scale = (tangent ? basis.lambda / basis.lambda[1] : basis.lambda).array().pow(double(n - 1));
  if (tangent) scale[0] = 0.0;
  const Eigen::MatrixXd q = basis.X[k - 1] * (scale.asDiagonal() * p.points);
  for (int i = 0; i < 16; ++i) out[i] = {q(i, 0), q(i, 1), q(i, 2)};
  return out;
}

void SubdivSurface::irregularSubPatch(int node, int n, int k, std::array<glm::dvec3, 16>& position,
                                      std::array<glm::dvec3, 16>& tangent) const {
  LocalNet net = *nodes_[node].net;
  for (int level = 1; level < n; ++level) net.step();
  std::array<LocalNet::Grid, 3> world, local;
  net.step(&world, &local, k);
  position = world[k - 1];
  tangent = local[k - 1];
}

void SubdivSurface::subPatches(int face, int levels, std::vector<std::array<glm::dvec3, 16>>& positions,
                               std::vector<std::array<glm::dvec3, 16>>& tangents) const {
  positions.clear();
  tangents.clear();
  if (patches_[face].kind == Kind::Tree) {
    if (nodes_[patches_[face].root].type != NodeType::Irregular)
      throw std::logic_error("SubdivSurface::subPatches: a face split at semi-sharp tags");
    nodeSubPatches(patches_[face].root, levels, positions, tangents);
    return;
  }
  for (int n = 1; n <= levels; ++n)
    for (int k = 1; k <= 3; ++k) {
      positions.push_back(controlPoints(face, n, k));
      tangents.push_back(controlPoints(face, n, k, true));
    }
}

LimitPoint SubdivSurface::evaluate(int face, double u, double v) const {
  glm::dvec3 position, ds, dt, unused;
  const Patch& p = patches_[face];
  if (p.kind == Kind::Tree) {
    // Down the tree to the leaf whose square holds (u, v), in that leaf's own parameters.
    int node = p.root;
    while (nodes_[node].type == NodeType::Split) {
      const int a = u >= 0.5 ? 1 : 0, b = v >= 0.5 ? 1 : 0;
      u = 2.0 * u - a;
      v = 2.0 * v - b;
      node = nodes_[node].first_child + (b == 0 ? a : 3 - a);
    }
    std::array<glm::dvec3, 16> points, tangents;
    double s = u, t = v;
    if (nodes_[node].type == NodeType::Regular) {
      points = nodes_[node].grid;
      tangents = nodes_[node].tangent;
    } else {
      const Location loc = locateIrregular(u, v, kBoundaryMaxLevel);
      irregularSubPatch(node, loc.n, loc.k, points, tangents);
      s = loc.s, t = loc.t;
    }
    bsplinePatch(points, s, t, position, unused, unused);
    bsplinePatch(tangents, s, t, unused, ds, dt);
    return {position, glm::normalize(glm::cross(ds, dt))};
  }
  const Location loc = locate(face, u, v);
  bsplinePatch(controlPoints(face, loc.n, loc.k), loc.s, loc.t, position, unused, unused);
  bsplinePatch(controlPoints(face, loc.n, loc.k, true), loc.s, loc.t, unused, ds, dt);
  // The 2^n scale of the sub-patch does not turn the normal, so the cross product of the
  // sub-patch's own derivatives gives the normal directly.
  return {position, glm::normalize(glm::cross(ds, dt))};
}

}  // namespace sortlast
