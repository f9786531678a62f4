#pragma once
// The scene's subdivision surfaces (the `surfaces` key, docs/scene.md; the surfaces themselves:
// docs/subdivision.md): which mesh, where (a transform), how coarse the rasterised mesh is and how
// it is shaded. Parsed and validated here, apart from scene.cpp, as one list-valued key. Each
// entry's mesh is read and checked while parsing, so a bad mesh is an InputError naming
// `surfaces[i]` on every rank alike, before anything is rendered.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "common/box.h"
#include "subdiv/subdiv_mesh.h"
#include "subdiv/subdiv_shading.h"

namespace YAML {
class Node;
}

namespace sortlast {

struct SurfaceSpec {
  std::string name;  // "surfaces[i]": what messages call it
  std::string file;  // an OBJ file (absolute), or empty
  std::string procedural;  // cube | torus | pole<N> | ... (subdiv/subdiv_input.h), or empty
  int level = 2;           // coarse subdivisions of the control mesh rasterised (1-3)
  SubdivShading shading;
  // The input mesh with the transform applied (faces re-ordered if it mirrors), checked.
  std::shared_ptr<const PolyMesh> mesh;
  Box3 bounds;  // of the transformed input points: holds the limit surface (convex hull property)
};

// Reads `surfaces` (a list of maps) and every entry's mesh; relative files are taken from
// `base_dir`. Throws InputError naming the key and entry.
std::vector<SurfaceSpec> parseSurfaces(const YAML::Node& list, const std::filesystem::path& base_dir);

// The union of the surfaces' bounds (lo > hi: none).
Box3 surfacesBounds(const std::vector<SurfaceSpec>& surfaces);
// The part of the scene's domain the surfaces need: their bounds grown by 1 % of their diagonal
// (a limit point on the domain's upper faces would otherwise belong to no half-open brick). The
// render session's layout and the reference both frame it. Lo > hi: none.
Box3 surfacesDomain(const std::vector<SurfaceSpec>& surfaces);

}  // namespace sortlast
