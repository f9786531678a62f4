// The surfaces section's keys: subdivision surfaces (docs/subdivision.md).
#include "scene/key_rows.h"

std::vector<sortlast::SceneKey> sortlast::surfaceKeys() {
  return {
    {"surfaces", "[]",
     "Catmull-Clark subdivision surfaces drawn exactly (docs/subdivision.md), opaque, composited "
     "with the volume and particles: a list of maps. Each has exactly one of `file` (an OBJ "
     "file, relative to the scene file; faces of any size; manifold meshes, closed or with "
     "boundaries (OpenSubdiv's edge-and-corner boundary rules unless the file's `t "
     "interpolateboundary` says otherwise; open surfaces are two-sided), with OpenSubdiv's "
     "subdivision tags `t crease`, `t corner`, `t hole`, `t interpolateboundary`, `t creasemethod`) "
     "and `procedural` (`cube`, `torus`, `pole<N>` for N = "
     "3 ... 32, `prism<N>`, `octahedron`, open ones: `open_grid`, `fan<N>` for N = 1 ... 12, and "
     "tagged ones: `cube_crease<S>` and `cube_corner<S>` for a sharpness S (a number up to 10 or "
     "`inf`), `cube_chaikin`, `lathe`, `lathe<N>`, `open_grid_edge_only`, `open_grid_none`), "
     "and optionally: `color` [r, g, b] in "
     "[0, 1] (default [0.8, 0.8, 0.85]); `transform`, either `{scale: s | [sx, sy, sz], rotate: "
     "[x, y, z] (degrees, about x then y then z), translate: [x, y, z]}` applied scale, rotate, "
     "translate, or a 4 x 4 matrix (4 rows, last 0 0 0 1); `level` 1 ... 3 (default 2): how often "
     "the control mesh is subdivided for the rasterised coarse mesh, which decides coverage at "
     "silhouettes; `shading` `headlight` (default) or `reflection_lines` with `stripes` (default "
     "12), `stripe_width` in (0, 1) (default 0.3) and `stripe_direction` [x, y, z] (the striped "
     "light's normal, default [0, 1, 0]); `newton_steps` 0 ... 8 (default 3) per fragment onto "
     "its pixel's ray. Every mesh is read and checked when the scene is read: a bad one is an "
     "error naming `surfaces[i]`.",
     Structured{"list of surfaces"}},
  };
}
