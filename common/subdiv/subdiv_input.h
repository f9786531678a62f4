#pragma once
// Where surface meshes come from: OBJ files (read with tinyobjloader) and the procedural test
// meshes. Both return an unchecked PolyMesh; buildControlMesh (subdiv_mesh.h) checks it.
#include <string>

#include "common/subdiv/subdiv_mesh.h"

namespace sortlast {

// Reads the polygons of an OBJ file (every group and object; texture coordinates, normals and
// materials are ignored). Subdivision tags (`t crease`, `t corner`, `t hole`, ...) are refused
// with an InputError naming the tag: creases and corners are not implemented.
PolyMesh readObjMesh(const std::string& path);

// Procedural meshes, by name:
//   cube             6 quads, eight valence-3 corners
//   torus            16 x 8 quads, every vertex of valence 4 (the regular case)
//   pole<N>          an N-gon prism refined once into quads: two poles of valence N (3 <= N <= 32),
//                    2N valence-3 vertices, slightly and irregularly deformed
//   prism<N>         the N-gon prism itself (N-gon faces: refined twice before evaluation)
//   octahedron       8 triangles
//   open_grid        a 4 x 4 quad sheet with a boundary (refused: boundaries are not supported)
// Throws InputError for unknown names, listing the known ones.
PolyMesh proceduralMesh(const std::string& name);

}  // namespace sortlast
