#pragma once
// Where surface meshes come from: OBJ files (read with tinyobjloader) and the procedural test
// meshes. Both return an unchecked PolyMesh; buildControlMesh (subdiv_mesh.h) checks it.
#include <string>

#include "subdiv/subdiv_mesh.h"

namespace sortlast {

// Reads the polygons of an OBJ file (every group and object; texture coordinates, normals and
// materials are ignored) and its subdivision tags as OpenSubdiv writes them (`t crease 2/1/0 a b
// s`, `t corner 1/1/0 v s`, `t hole 1/0/0 f`, `t interpolateboundary 1/0/0 mode` with 0 none,
// 1 edge and corner, 2 edge only, `t creasemethod 0/0/1 chaikin`; indices from 0). Without an
// interpolateboundary tag boundaries are edge and corner. Unknown tags, malformed counts,
// negative sharpness and creases on non-edges are InputErrors naming the line.
PolyMesh readObjMesh(const std::string& path);

// Procedural meshes, by name:
//   cube             6 quads, eight valence-3 corners
//   torus            16 x 8 quads, every vertex of valence 4 (the regular case)
//   pole<N>          an N-gon prism refined once into quads: two poles of valence N (3 <= N <= 32),
//                    2N valence-3 vertices, slightly and irregularly deformed
//   prism<N>         the N-gon prism itself (N-gon faces: refined twice before evaluation)
//   octahedron       8 triangles
//   open_grid        a 4 x 4 quad sheet with a boundary (edge-and-corner interpolation)
// and tagged ones: cube_crease<S> (the top face's edge loop creased at S, a number or inf),
// cube_corner<S> (a vertex of sharpness S and an infinitely sharp edge with darts at its ends),
// cube_chaikin (three semi-sharp edges at one vertex, Chaikin's method), lathe and lathe<N> (a
// pawn-like lathe with creased rims, 8 or N segments, 10 N faces), open_grid_edge_only and open_grid_none (boundary rules).
// Throws InputError for unknown names, listing the known ones.
PolyMesh proceduralMesh(const std::string& name);

}  // namespace sortlast
