#pragma once
// What every rank knows about a scene's layout before any sample is read, and what stays fixed for
// the life of a resident session: the brick grid (volume and particles share it), which rank owns
// which bricks, and the scene's box (cameras frame it and must stay outside it).
#include <mpi.h>

#include <vector>

#include "common/brick.h"
#include "common/brick_planes.h"
#include "common/camera.h"
#include "common/decomposition.h"
#include "scene/scene.h"

namespace sortlast {

struct SessionLayout {
  GridGeometry grid;                 // the volume's (read from the file for VTK data)
  std::vector<Brick> volume_bricks;  // empty without a volume
  BrickPlanes planes;
  Assignment assignment;
  Box3 bounds;            // the scene's box
  Box3 particle_domain;   // particle centres (of every step) grown by h (lo > hi: no particles)
  double particle_h = 0;  // the h the domain was grown by
  Box3 glow_box = noBox();  // glow.box, or the scene's bounds (lo > hi: no glow)
  std::vector<int> mine;  // this rank's brick ids
};

// `particle_centres`: the bounds of every step's particle centres (lo > hi: none). Throws
// InputError for a camera inside the box.
SessionLayout makeLayout(const Scene& scene, const Box3& particle_centres, int rank, int size);

// The camera must not be too far from the scene's box (float math), and must lie outside
// `keep_out` (default: that box): the particles', surfaces' and glow box (keepOutBox), which
// the metaball billboards, the surfaces and the glow pass need in front of the eye (orthographic:
// wholly in front of the eye plane). An eye inside the volume is fine: rays start at it, slices
// are drawn in front of the near plane. Throws InputError naming the position and the box.
void checkCameraOutside(const Camera& cam, const Box3& box, const std::string& which = "",
                        const Box3* keep_out = nullptr);
// What the eye must stay out of: the particles' (and surfaces') domain and the glow box.
Box3 keepOutBox(const SessionLayout& layout);

// Near and far planes enclosing the whole box, shared by every brick of a frame.
std::pair<double, double> depthRange(const Camera& cam, const Box3& box);

Box3 grow(const Box3& b, double by);

}  // namespace sortlast
