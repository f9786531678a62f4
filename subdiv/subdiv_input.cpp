#include "subdiv/subdiv_input.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <array>
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

// The subdivision tags of an OBJ file as OpenSubdiv's shapes write them: `t name i/f/s` then i
// integers, f floats and s strings; vertex and face indices from 0. Read here, not through
// tinyobjloader, so that every error can name its line.
struct ObjTags {
  SubdivTags tags;
  bool boundarySet = false;
  BoundaryInterpolation boundary = BoundaryInterpolation::EdgeAndCorner;
  CreaseMethod method = CreaseMethod::Uniform;
};

ObjTags readTagLines(const std::string& path) {
  ObjTags out;
  std::ifstream in(path);
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    std::istringstream words(line);
    std::string t, name, counts;
    if (!(words >> t) || t != "t") continue;
    const std::string where = "surface file '" + path + "' line " + std::to_string(number);
    auto fail = [&](const std::string& what) { throw InputError(where + ": " + what); };
    if (!(words >> name)) fail("a tag line needs a name ('t crease 2/1/0 a b sharpness')");
    int ni = -1, nf = -1, ns = -1;
    char slash1 = 0, slash2 = 0;
    std::istringstream c;
    if (words >> counts) c.str(counts);
    if (!(c >> ni >> slash1 >> nf >> slash2 >> ns) || slash1 != '/' || slash2 != '/' || ni < 0 || nf < 0 || ns < 0 ||
        !c.eof())
      fail("tag '" + name + "' needs its argument counts as ints/floats/strings (e.g. 2/1/0), not '" + counts + "'");
    std::vector<int> ints;
    std::vector<double> floats;
    std::vector<std::string> strings;
    std::string w;
    for (int i = 0; i < ni + nf + ns; ++i) {
      if (!(words >> w)) fail("tag '" + name + "' says " + counts + " arguments but has fewer");
      char* end = nullptr;
      if (i < ni) {
        const long v = std::strtol(w.c_str(), &end, 10);
        if (end != w.c_str() + w.size() || v < 0 || v > 2147483647L)
          fail("tag '" + name + "': '" + w + "' is not a vertex or face index (an integer from 0)");
        ints.push_back(int(v));
      } else if (i < ni + nf) {
        const double v = std::strtod(w.c_str(), &end);
        if (end != w.c_str() + w.size() || !std::isfinite(v)) fail("tag '" + name + "': '" + w + "' is not a finite number");
        floats.push_back(v);
      } else {
        strings.push_back(w);
      }
    }
    if (words >> w) fail("tag '" + name + "' has more arguments than its counts " + counts + " say");
    if (name == "crease") {
      if (ni < 2 || ni % 2 != 0 || (nf != 1 && nf != ni / 2) || ns != 0)
        fail("'t crease' needs vertex pairs and one sharpness, or one per pair (e.g. 't crease 2/1/0 a b 2.5')");
      for (int i = 0; i < ni / 2; ++i)
        out.tags.creases.push_back({ints[2 * i], ints[2 * i + 1], floats[nf == 1 ? 0 : i], where});
    } else if (name == "corner") {
      if (ni < 1 || (nf != 1 && nf != ni) || ns != 0)
        fail("'t corner' needs vertices and one sharpness, or one per vertex (e.g. 't corner 1/1/0 v 3')");
      for (int i = 0; i < ni; ++i) out.tags.corners.push_back({ints[i], floats[nf == 1 ? 0 : i], where});
    } else if (name == "hole") {
      if (ni < 1 || nf != 0 || ns != 0) fail("'t hole' needs face indices only (e.g. 't hole 1/0/0 f')");
      for (int f : ints) out.tags.holes.push_back({f, where});
    } else if (name == "interpolateboundary") {
      if (ni != 1 || nf != 0 || ns != 0 || ints[0] > 2)
        fail("'t interpolateboundary' needs one integer: 0 none, 1 edge and corner, 2 edge only");
      out.boundarySet = true;
      out.boundary = ints[0] == 0   ? BoundaryInterpolation::None
                     : ints[0] == 1 ? BoundaryInterpolation::EdgeAndCorner
                                    : BoundaryInterpolation::EdgeOnly;
    } else if (name == "creasemethod") {
      if (ni != 0 || nf != 0 || ns != 1 || (strings[0] != "normal" && strings[0] != "uniform" && strings[0] != "chaikin"))
        fail("'t creasemethod' needs one string: normal (uniform) or chaikin");
      out.method = strings[0] == "chaikin" ? CreaseMethod::Chaikin : CreaseMethod::Uniform;
    } else if (name == "facevaryinginterpolateboundary" || name == "facevaryingpropagatecorners") {
      // Face-varying data (texture coordinates) is not read, so its interpolation has no effect.
    } else if (name == "smoothtriangles") {
      if (ns != 1 || strings[0] != "catmark")
        fail("'t smoothtriangles' other than catmark is not supported (triangles take the Catmull-Clark rules)");
    } else {
      fail("unknown or unsupported subdivision tag '" + name +
           "' (supported: crease, corner, hole, interpolateboundary, creasemethod)");
    }
  }
  return out;
}

}  // namespace

PolyMesh readObjMesh(const std::string& path) {
  checkVertexLines(path);
  const ObjTags tags = readTagLines(path);
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
    size_t at = 0;
    for (const auto count : shape.mesh.num_face_vertices) {
      std::vector<int> corners;
      for (unsigned i = 0; i < count; ++i) corners.push_back(shape.mesh.indices[at + i].vertex_index);
      at += count;
      mesh.addFace(corners);
    }
  }
  mesh.boundary = tags.boundary;
  mesh.crease_method = tags.method;
  applyTags(mesh, tags.tags);
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

// A closed mesh slightly and irregularly deformed, so that no symmetry hides an error.
void deform(PolyMesh& m, double amount) {
  for (size_t i = 0; i < m.points.size(); ++i)
    m.points[i] += amount * glm::dvec3(std::sin(1.7 * i + 0.3), std::cos(2.3 * i + 1.1), std::sin(0.9 * i + 2.0));
}

// The edges round face f of `m` as crease tags of sharpness s.
void creaseFace(SubdivTags& tags, const PolyMesh& m, int f, double s) {
  for (int c = 0; c < m.face_sizes[f]; ++c)
    tags.creases.push_back({m.corner(f, c), m.corner(f, (c + 1) % m.face_sizes[f]), s, m.name});
}

// The cube, deformed, its top face's edge loop creased at sharpness s.
PolyMesh cubeCrease(double s, const std::string& name) {
  PolyMesh m = cube();
  m.name = name;
  deform(m, 0.06);
  SubdivTags tags;
  creaseFace(tags, m, 1, s);  // the face {4, 5, 7, 6} at z = +1
  applyTags(m, tags);
  return m;
}

// The cube, deformed, one vertex a corner of sharpness s, and one edge elsewhere infinitely
// sharp (its ends are darts).
PolyMesh cubeCorner(double s, const std::string& name) {
  PolyMesh m = cube();
  m.name = name;
  deform(m, 0.06);
  SubdivTags tags;
  tags.corners.push_back({7, s, name});
  tags.creases.push_back({0, 1, kInfinitelySharp, name});
  applyTags(m, tags);
  return m;
}

// Three semi-sharp edges of different sharpness meeting at one cube vertex, by Chaikin's method.
PolyMesh cubeChaikin() {
  PolyMesh m = cube();
  m.name = "cube_chaikin";
  deform(m, 0.06);
  m.crease_method = CreaseMethod::Chaikin;
  SubdivTags tags;
  tags.creases = {{7, 6, 0.5, m.name}, {7, 5, 1.5, m.name}, {7, 3, 2.5, m.name}};
  applyTags(m, tags);
  return m;
}

// A pawn-like lathe: a profile turned round the z axis in n segments (10 n faces), closed by
// triangle fans at both poles; the base's rim infinitely sharp, the foot's edge at sharpness 2.5,
// the collar's 1.
PolyMesh lathe(int n, const std::string& name) {
  PolyMesh m;
  m.name = name;
  const double pi = std::numbers::pi;
  const std::vector<std::array<double, 2>> profile = {{1.0, 0.0},  {1.0, 0.25}, {0.62, 0.4}, {0.42, 0.9},
                                                      {0.38, 1.2}, {0.7, 1.32}, {0.42, 1.45}, {0.55, 1.75},
                                                      {0.45, 2.0}};
  const int rings = static_cast<int>(profile.size());
  m.points.emplace_back(0.0, 0.0, 0.0);  // bottom pole
  for (int r = 0; r < rings; ++r)
    for (int i = 0; i < n; ++i) {
      const double a = 2 * pi * i / n;
      m.points.emplace_back(profile[r][0] * std::cos(a), profile[r][0] * std::sin(a), profile[r][1]);
    }
  m.points.emplace_back(0.0, 0.0, 2.1);  // top pole
  deform(m, 0.02 * std::min(1.0, 8.0 / n));  // (less with more segments: no ripples)
  auto id = [n](int r, int i) { return 1 + r * n + (i % n); };
  const int top = static_cast<int>(m.points.size()) - 1;
  for (int i = 0; i < n; ++i) m.addFace({0, id(0, i + 1), id(0, i)});
  for (int r = 0; r + 1 < rings; ++r)
    for (int i = 0; i < n; ++i) m.addFace({id(r, i), id(r, i + 1), id(r + 1, i + 1), id(r + 1, i)});
  for (int i = 0; i < n; ++i) m.addFace({top, id(rings - 1, i), id(rings - 1, i + 1)});
  SubdivTags tags;
  for (int i = 0; i < n; ++i) {
    tags.creases.push_back({id(0, i), id(0, i + 1), kInfinitelySharp, m.name});  // base rim
    tags.creases.push_back({id(1, i), id(1, i + 1), 2.5, m.name});               // foot
    tags.creases.push_back({id(5, i), id(5, i + 1), 1.0, m.name});               // collar
  }
  applyTags(m, tags);
  return m;
}

// open_grid with another boundary rule; with `none` its bottom boundary edges are tagged
// infinitely sharp, so the faces along them stay (the others at the boundary are holes).
PolyMesh openGridWith(BoundaryInterpolation b, const std::string& name) {
  PolyMesh m = openGrid();
  m.name = name;
  m.boundary = b;
  if (b == BoundaryInterpolation::None) {
    SubdivTags tags;
    for (int i = 0; i < 4; ++i) tags.creases.push_back({i, i + 1, kInfinitelySharp, name});
    applyTags(m, tags);
  }
  return m;
}

// The sharpness after `prefix` in a name ("inf" or a number from 0), or -1.
double suffixSharpness(const std::string& name, const std::string& prefix) {
  if (name.rfind(prefix, 0) != 0 || name.size() == prefix.size()) return -1;
  const std::string rest = name.substr(prefix.size());
  if (rest == "inf") return kInfinitelySharp;
  char* end = nullptr;
  const double v = std::strtod(rest.c_str(), &end);
  return end == rest.c_str() + rest.size() && v >= 0 && v <= kInfinitelySharp ? v : -1;
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
  if (const double s = suffixSharpness(name, "cube_crease"); s >= 0) return cubeCrease(s, name);
  if (const double s = suffixSharpness(name, "cube_corner"); s >= 0) return cubeCorner(s, name);
  if (name == "cube_chaikin") return cubeChaikin();
  if (name == "lathe") return lathe(8, name);
  if (const int n = suffixNumber(name, "lathe"); n >= 3 && n <= 200) return lathe(n, name);
  if (name == "open_grid_edge_only") return openGridWith(BoundaryInterpolation::EdgeOnly, name);
  if (name == "open_grid_none") return openGridWith(BoundaryInterpolation::None, name);
  throw InputError("unknown procedural surface '" + name +
                   "' (known: cube, torus, pole<N>, prism<N> for N = 3..32, octahedron, open_grid, "
                   "fan<N> for N = 1..12; tagged: cube_crease<S> and cube_corner<S> for a sharpness S "
                   "(a number up to 10, or inf), cube_chaikin, lathe (8 segments), lathe<N> for N = 3..200 (10 N faces), "
                   "open_grid_edge_only, open_grid_none)");
}

}  // namespace sortlast
