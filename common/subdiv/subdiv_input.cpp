#include "common/subdiv/subdiv_input.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <numbers>
#include <sstream>

#include "common/error.h"

namespace sortlast {

namespace {

// tinyobjloader reads a coordinate it cannot parse ("nan", "1e999", a missing one) as 0 or
// infinity without a word; a mesh silently moved or broken is worse than an error, so every
// vertex line is checked first: at least three numbers, all finite.
void checkVertexLines(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    std::istringstream words(line);
    std::string tag;
    if (!(words >> tag) || tag != "v") continue;
    int count = 0;
    for (std::string w; words >> w; ++count) {
      char* end = nullptr;
      const double x = std::strtod(w.c_str(), &end);
      if (end != w.c_str() + w.size() || !std::isfinite(x))
        throw InputError("surface file '" + path + "' line " + std::to_string(number) + ": vertex coordinate '" + w +
                         "' is not a finite number (NaN and infinity are refused)");
    }
    if (count < 3)
      throw InputError("surface file '" + path + "' line " + std::to_string(number) +
                       ": a vertex needs three coordinates");
  }
}

}  // namespace

PolyMesh readObjMesh(const std::string& path) {
  checkVertexLines(path);
  tinyobj::ObjReaderConfig config;
  config.triangulate = false;  // the faces as written: n-gons get a Catmull-Clark step instead
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(path, config))
    throw InputError("surface file '" + path + "' could not be read: " + reader.Error());
  PolyMesh mesh;
  mesh.name = path;
  const auto& v = reader.GetAttrib().vertices;
  for (size_t i = 0; i + 2 < v.size(); i += 3) mesh.points.emplace_back(v[i], v[i + 1], v[i + 2]);
  for (const auto& shape : reader.GetShapes()) {
    for (const auto& tag : shape.mesh.tags)
      throw InputError("surface file '" + path + "' has the subdivision tag 't " + tag.name +
                       "': creases, corners and other tags are not supported (remove the 't' lines)");
    size_t at = 0;
    for (const auto count : shape.mesh.num_face_vertices) {
      std::vector<int> corners;
      for (unsigned i = 0; i < count; ++i) corners.push_back(shape.mesh.indices[at + i].vertex_index);
      at += count;
      mesh.addFace(corners);
    }
  }
  return mesh;
}

namespace {

PolyMesh cube() {
  PolyMesh m;
  m.name = "cube";
  for (int i = 0; i < 8; ++i) m.points.emplace_back(i & 1 ? 1.0 : -1.0, i & 2 ? 1.0 : -1.0, i & 4 ? 1.0 : -1.0);
  // Counter-clockwise seen from outside.
  for (const auto& f : {std::vector<int>{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}})
    m.addFace(f);
  return m;
}

PolyMesh torus() {
  PolyMesh m;
  m.name = "torus";
  const int nu = 16, nv = 8;
  const double pi = std::numbers::pi;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double a = 2 * pi * i / nu, b = 2 * pi * j / nv;
      const double r = 1.0 + 0.4 * std::cos(b);
      m.points.emplace_back(r * std::cos(a), r * std::sin(a), 0.4 * std::sin(b));
    }
  auto id = [&](int i, int j) { return ((i + nu) % nu) * nv + (j + nv) % nv; };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) m.addFace({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
  return m;
}

PolyMesh prism(int n) {
  PolyMesh m;
  m.name = "prism" + std::to_string(n);
  const double pi = std::numbers::pi;
  for (int k = 0; k < 2; ++k)
    for (int i = 0; i < n; ++i) {
      const double a = 2 * pi * i / n;
      m.points.emplace_back(std::cos(a), std::sin(a), k ? 0.8 : -0.8);
    }
  std::vector<int> bottom, top;
  for (int i = 0; i < n; ++i) {
    bottom.push_back(n - 1 - i);
    top.push_back(n + i);
    m.addFace({i, (i + 1) % n, n + (i + 1) % n, n + i});
  }
  m.addFace(bottom);
  m.addFace(top);
  return m;
}

PolyMesh pole(int n) {
  PolyMesh p = prism(n);
  RefinedMesh r = catmullClarkStep(p, checkMesh(p));
  // An irregular deformation, so that no symmetry hides an error in the evaluation.
  for (size_t i = 0; i < r.mesh.points.size(); ++i) {
    auto& q = r.mesh.points[i];
    q += 0.08 * glm::dvec3(std::sin(1.7 * i + 0.3), std::cos(2.3 * i + 1.1), std::sin(0.9 * i + 2.0));
  }
  r.mesh.name = "pole" + std::to_string(n);
  return r.mesh;
}

PolyMesh octahedron() {
  PolyMesh m;
  m.name = "octahedron";
  m.points = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (const auto& f : {std::vector<int>{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}})
    m.addFace(f);
  return m;
}

// A saddle z = (x^2 - y^2) / 6 over a 4 x 4 grid of quads: an open surface whose boundary has
// only regular vertices (valence 3) and four corners.
PolyMesh openGrid() {
  PolyMesh m;
  m.name = "open_grid";
  for (int j = 0; j <= 4; ++j)
    for (int i = 0; i <= 4; ++i) {
      const double x = i - 2.0, y = j - 2.0;
      m.points.emplace_back(x, y, (x * x - y * y) / 6.0 + 0.05 * std::sin(1.3 * i + 2.1 * j));
    }
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) m.addFace({j * 5 + i, j * 5 + i + 1, (j + 1) * 5 + i + 1, (j + 1) * 5 + i});
  return m;
}

// An open fan of two rings round a centre vertex on the boundary: N quads round the centre (a
// boundary vertex of N faces, valence N + 1: irregular unless N = 2, a corner if N = 1), 2N quads
// outside them. The inner ring's vertices between two spokes are interior of valence 3, the
// outer ring's are boundary vertices of valence 3 and corners. Curved and irregularly deformed.
PolyMesh fan(int n) {
  PolyMesh m;
  m.name = "fan" + std::to_string(n);
  const double pi = std::numbers::pi;
  const double span = 0.5 * pi * std::min(n, 3);  // 90, 180, then 270 degrees
  m.points.emplace_back(0.0, 0.0, 0.0);
  for (int ring = 1; ring <= 2; ++ring)
    for (int i = 0; i <= 2 * n; ++i) {
      const double a = span * i / (2 * n), r = ring;
      const int k = static_cast<int>(m.points.size());
      m.points.emplace_back(r * std::cos(a), r * std::sin(a),
                            0.2 * r * r * std::sin(2 * a + 0.3) + 0.06 * std::sin(1.7 * k + 0.4));
    }
  auto id = [n](int ring, int i) { return 1 + (ring - 1) * (2 * n + 1) + i; };
  for (int i = 0; i < n; ++i) m.addFace({0, id(1, 2 * i), id(1, 2 * i + 1), id(1, 2 * i + 2)});
  for (int i = 0; i < 2 * n; ++i) m.addFace({id(1, i), id(2, i), id(2, i + 1), id(1, i + 1)});
  return m;
}

// The N of "pole<N>" / "prism<N>", or 0.
int suffixNumber(const std::string& name, const std::string& prefix) {
  if (name.rfind(prefix, 0) != 0 || name.size() == prefix.size()) return 0;
  for (size_t i = prefix.size(); i < name.size(); ++i)
    if (name[i] < '0' || name[i] > '9') return 0;
  return std::stoi(name.substr(prefix.size()));
}

}  // namespace

PolyMesh proceduralMesh(const std::string& name) {
  if (name == "cube") return cube();
  if (name == "torus") return torus();
  if (name == "octahedron") return octahedron();
  if (name == "open_grid") return openGrid();
  for (const std::string prefix : {"pole", "prism"}) {
    const int n = suffixNumber(name, prefix);
    if (n >= 3 && n <= 32) return prefix == "pole" ? pole(n) : prism(n);
  }
  if (const int n = suffixNumber(name, "fan"); n >= 1 && n <= 12) return fan(n);
  throw InputError("unknown procedural surface '" + name +
                   "' (known: cube, torus, pole<N>, prism<N> for N = 3..32, octahedron, open_grid, "
                   "fan<N> for N = 1..12)");
}

}  // namespace sortlast
