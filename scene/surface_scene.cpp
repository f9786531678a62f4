#include "scene/surface_scene.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <set>

#include "common/error.h"
#include "scene/scene_reader.h"
#include "subdiv/subdiv_input.h"

namespace sortlast {

namespace {

constexpr double kPi = 3.14159265358979323846;

[[noreturn]] void fail(const std::string& key, const std::string& what, const YAML::Node& n) {
  throw InputError("scene key '" + key + "': " + what + where(n));
}

std::vector<double> numbers(const YAML::Node& n, const std::string& key) {
  std::vector<double> v;
  try {
    if (n.IsScalar()) v.push_back(n.as<double>());
    else if (n.IsSequence())
      for (const auto& x : n) v.push_back(x.as<double>());
    else throw YAML::Exception(n.Mark(), "not a number or list");
  } catch (const YAML::Exception&) {
    fail(key, "expected numbers", n);
  }
  for (double x : v)
    if (!std::isfinite(x) || std::abs(x) > kMaxCoordinate) fail(key, "values must be finite, within +-1e18", n);
  return v;
}

glm::dvec3 vec3(const YAML::Node& n, const std::string& key) {
  std::vector<double> v = numbers(n, key);
  if (v.size() != 3) fail(key, "expected a list of 3 numbers", n);
  return {v[0], v[1], v[2]};
}

// `transform`: a map {scale: s | [sx, sy, sz], rotate: [x, y, z] degrees (about x, then y, then
// z), translate: [x, y, z]} applied scale, rotate, translate; or a 4 x 4 matrix (4 rows) whose
// last row is 0 0 0 1.
glm::dmat4 readTransform(const YAML::Node& n, const std::string& key) {
  if (n.IsSequence()) {
    glm::dmat4 m(1.0);
    if (n.size() != 4) fail(key, "a matrix is a list of 4 rows of 4 numbers", n);
    for (int r = 0; r < 4; ++r) {
      std::vector<double> row = numbers(n[r], key);
      if (row.size() != 4) fail(key, "a matrix is a list of 4 rows of 4 numbers", n);
      for (int c = 0; c < 4; ++c) m[c][r] = row[size_t(c)];  // glm: column major
    }
    if (m[0][3] != 0 || m[1][3] != 0 || m[2][3] != 0 || m[3][3] != 1)
      fail(key, "the matrix's last row must be 0 0 0 1 (an affine transform)", n);
    return m;
  }
  if (!n.IsMap()) fail(key, "expected {scale, rotate, translate} or a 4 x 4 matrix", n);
  static const std::set<std::string> known = {"scale", "rotate", "translate"};
  for (auto it = n.begin(); it != n.end(); ++it)
    if (!known.count(it->first.as<std::string>()))
      fail(key + "." + it->first.as<std::string>(), "unknown (a transform has scale, rotate, translate)", it->first);
  glm::dvec3 scale(1.0), rotate(0.0), translate(0.0);
  if (n["scale"]) {
    std::vector<double> s = numbers(n["scale"], key + ".scale");
    if (s.size() == 1) scale = glm::dvec3(s[0]);
    else if (s.size() == 3) scale = {s[0], s[1], s[2]};
    else fail(key + ".scale", "expected a number or a list of 3", n["scale"]);
  }
  if (n["rotate"]) rotate = vec3(n["rotate"], key + ".rotate");
  if (n["translate"]) translate = vec3(n["translate"], key + ".translate");
  glm::dmat4 m = glm::translate(glm::dmat4(1.0), translate);
  m = glm::rotate(m, rotate.z * kPi / 180.0, glm::dvec3(0, 0, 1));
  m = glm::rotate(m, rotate.y * kPi / 180.0, glm::dvec3(0, 1, 0));
  m = glm::rotate(m, rotate.x * kPi / 180.0, glm::dvec3(1, 0, 0));
  return glm::scale(m, scale);
}

// Points moved; a mirroring transform would turn the faces inside out (clockwise seen from
// outside), so their corners are reversed.
void applyTransform(PolyMesh& mesh, const glm::dmat4& m, const std::string& key) {
  const double det = glm::determinant(glm::dmat3(m));
  if (!(std::abs(det) > 1e-300) || !std::isfinite(det))
    throw InputError("scene key '" + key + "': the transform is singular (it flattens the surface)");
  for (glm::dvec3& p : mesh.points) {
    p = glm::dvec3(m * glm::dvec4(p, 1.0));
    for (int a = 0; a < 3; ++a)
      if (!(std::abs(p[a]) <= kMaxCoordinate))
        throw InputError("scene key '" + key + "': a transformed point is not finite or beyond +-1e18");
  }
  if (det < 0) mesh.reverseFaces();
}

}  // namespace

std::vector<SurfaceSpec> parseSurfaces(const YAML::Node& list, const std::filesystem::path& base_dir) {
  std::vector<SurfaceSpec> out;
  if (list.IsNull()) return out;
  if (!list.IsSequence())
    fail("surfaces", "expected a list of surfaces ({file | procedural, color, transform, level, shading, ...})", list);
  static const std::set<std::string> known = {"file",    "procedural",   "color",           "transform",
                                              "level",   "shading",      "stripes",         "stripe_width",
                                              "stripe_direction", "newton_steps"};
  for (size_t i = 0; i < list.size(); ++i) {
    const YAML::Node e = list[i];
    SurfaceSpec s;
    s.name = "surfaces[" + std::to_string(i) + "]";
    const std::string& name = s.name;
    if (!e.IsMap()) fail(name, "expected a map {file | procedural, color, transform, ...}", e);
    for (auto it = e.begin(); it != e.end(); ++it)
      if (!known.count(it->first.as<std::string>()))
        throw InputError("unknown scene key '" + name + "." + it->first.as<std::string>() + "'" + where(it->first) +
                         " (a surface has file, procedural, color, transform, level, shading, stripes, "
                         "stripe_width, stripe_direction, newton_steps)");
    auto text = [&](const char* k) {
      try {
        return e[k].as<std::string>();
      } catch (const YAML::Exception&) {
        fail(name + "." + k, "expected a string", e[k]);
      }
    };
    auto integer = [&](const char* k, int lo, int hi, int fallback) {
      if (!e[k]) return fallback;
      int v = 0;
      try {
        v = e[k].as<int>();
      } catch (const YAML::Exception&) {
        fail(name + "." + k, "expected an integer", e[k]);
      }
      if (v < lo || v > hi)
        fail(name + "." + k, "must be in " + std::to_string(lo) + " ... " + std::to_string(hi), e[k]);
      return v;
    };
    if (e["file"].IsDefined() == e["procedural"].IsDefined())
      fail(name, "give exactly one of 'file' (an OBJ file) and 'procedural' (cube, torus, pole<N>, fan<N>, ...)", e);
    PolyMesh mesh;
    const std::string source = e["file"] ? name + ".file" : name + ".procedural";
    try {
      if (e["file"]) {
        std::filesystem::path f = text("file");
        s.file = (f.is_relative() ? base_dir / f : f).string();
        if (!std::filesystem::is_regular_file(s.file))
          fail(source, "no such file: " + s.file, e["file"]);
        mesh = readObjMesh(s.file);
      } else {
        s.procedural = text("procedural");
        mesh = proceduralMesh(s.procedural);
      }
    } catch (const InputError& err) {
      const std::string what = err.what();
      if (what.rfind("scene key", 0) == 0) throw;
      throw InputError("scene key '" + source + "': " + what);
    }
    if (e["transform"]) applyTransform(mesh, readTransform(e["transform"], name + ".transform"), name + ".transform");
    // The checks (empty, NaN, indices, manifold, boundaries, valence 2) and the refinement the
    // renderers repeat: cheap for the meshes a scene holds, and every rank fails alike here.
    try {
      (void)buildControlMesh(mesh);
    } catch (const InputError& err) {
      throw InputError("scene key '" + source + "': " + err.what());
    }
    s.level = integer("level", 1, 3, 2);
    if (e["color"]) {
      s.shading.colour = vec3(e["color"], name + ".color");
      for (int c = 0; c < 3; ++c)
        if (s.shading.colour[c] < 0 || s.shading.colour[c] > 1) fail(name + ".color", "entries must be in [0, 1]", e["color"]);
    }
    if (e["shading"]) {
      s.shading.mode = text("shading");
      if (s.shading.mode != "headlight" && s.shading.mode != "reflection_lines")
        fail(name + ".shading", "expected headlight or reflection_lines, got '" + s.shading.mode + "'", e["shading"]);
    }
    s.shading.stripes = integer("stripes", 1, 1000, 12);
    if (e["stripe_width"]) {
      std::vector<double> w = numbers(e["stripe_width"], name + ".stripe_width");
      if (w.size() != 1 || !(w[0] > 0 && w[0] < 1)) fail(name + ".stripe_width", "must be a number in (0, 1)", e["stripe_width"]);
      s.shading.stripe_width = w[0];
    }
    if (e["stripe_direction"]) {
      s.shading.light_direction = vec3(e["stripe_direction"], name + ".stripe_direction");
      if (!(glm::length(s.shading.light_direction) >= kMinLength))
        fail(name + ".stripe_direction", "must not be zero", e["stripe_direction"]);
    }
    s.shading.newton_steps = integer("newton_steps", 0, 8, 3);
    mesh.name = name;
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const glm::dvec3& p : mesh.points) lo = glm::min(lo, p), hi = glm::max(hi, p);
    s.bounds = {lo, hi};
    s.mesh = std::make_shared<const PolyMesh>(std::move(mesh));
    out.push_back(std::move(s));
  }
  return out;
}

Box3 surfacesBounds(const std::vector<SurfaceSpec>& surfaces) {
  Box3 b = noBox();
  for (const SurfaceSpec& s : surfaces)
    b = isEmpty(b) ? s.bounds : unite(b, s.bounds);
  return b;
}

Box3 surfacesDomain(const std::vector<SurfaceSpec>& surfaces) {
  Box3 b = surfacesBounds(surfaces);
  if (isEmpty(b)) return b;
  const double by = 0.01 * glm::length(b.hi - b.lo);
  return {b.lo - by, b.hi + by};
}

}  // namespace sortlast
