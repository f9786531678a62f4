// libFuzzer target: an OBJ surface mesh with subdivision tags (subdiv/subdiv_input.h,
// readObjMesh) on any text, then, for small meshes, the control mesh, the exact evaluation with
// its patch trees and the tables. Bad input must end in InputError; anything else (a logic_error
// from a broken invariant, a crash) is a bug.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <string>

#include "common/error.h"
#include "subdiv/subdiv_eval.h"
#include "subdiv/subdiv_input.h"
#include "subdiv/subdiv_tables.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace sortlast;
  // readObjMesh reads a file (tinyobjloader and the tag lines both read paths).
  static const std::string path = "/tmp/sortlast_fuzz_obj_" + std::to_string(getpid()) + ".obj";
  if (FILE* f = std::fopen(path.c_str(), "wb")) {
    std::fwrite(data, 1, size, f);
    std::fclose(f);
  } else {
    return 0;
  }
  try {
    const PolyMesh mesh = readObjMesh(path);
    // Small meshes only: the evaluation's cost grows with faces and sharpness, not its branches.
    if (mesh.faceCount() > 24 || mesh.points.size() > 48) return 0;
    for (int s : mesh.face_sizes)
      if (s > 8) return 0;
    const SubdivSurface surface(mesh);
    const SubdivTables tables = buildTables(surface);
    for (int f = 0; f < surface.patchCount(); ++f)
      if (!surface.hole(f)) {
        surface.evaluate(f, 0.3, 0.6);
        evaluateTables(tables, f, 0.01f, 0.002f);
      }
  } catch (const InputError&) {
  }
  return 0;
}
