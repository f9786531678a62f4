#include "session/session_layout.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "common/error.h"

namespace sortlast {

Box3 grow(const Box3& b, double by) { return {b.lo - by, b.hi + by}; }

SessionLayout makeLayout(const Scene& scene, const Box3& particle_centres, int rank, int size) {
  SessionLayout L;
  const int d = scene.bricks.per_axis;
  // Several fields: one grid covering them all is cut (scene/fields_scene.h fieldsGrid); each
  // field hands each brick its part (session/fields_loading.h).
  L.grid = scene.hasFields() ? fieldsGrid(scene.fields) : scene.volume.grid;
  if (scene.hasVolume()) L.volume_bricks = makeBricks(L.grid, d);
  // The domain holds every particle's field: h, or the anisotropic ellipsoids' reach.
  L.particle_h = scene.particles.enabled() ? scene.particles.reach() : 0.0;
  L.particle_domain = isEmpty(particle_centres) ? noBox()
                                                : grow(particle_centres, L.particle_h);
  // Subdivision surfaces join the particles' domain (scene/surface_scene.h: surfacesDomain).
  const Box3 surfaces = surfacesDomain(scene.surfaces);
  if (!isEmpty(surfaces))
    L.particle_domain = isEmpty(L.particle_domain) ? surfaces : unite(L.particle_domain, surfaces);
  if (scene.hasVolume()) {
    L.planes = volumeBrickPlanes(L.volume_bricks, d);
    L.bounds = L.grid.worldBox();
    if (!isEmpty(L.particle_domain)) {
      L.planes = coverBox(L.planes, L.particle_domain);
      L.bounds = unite(L.bounds, L.particle_domain);
    }
    // Glow (docs/glow.md): the outer bricks reach out to the glow box, as for the particles.
    if (scene.glow.enabled()) {
      L.glow_box = scene.glow.box.value_or(L.bounds);
      L.planes = coverBox(L.planes, L.glow_box);
      L.bounds = unite(L.bounds, L.glow_box);
    }
  } else {
    // No volume and no particle at all: an empty (transparent) frame of a unit box.
    L.bounds = isEmpty(L.particle_domain) ? Box3{glm::dvec3(-0.5), glm::dvec3(0.5)} : L.particle_domain;
    // Glow emitters (docs/glow.md): the bricks cut the glow box too (emitters alone: only it;
    // the scene refuses them without a box), as the reference's bounds hold it.
    if (scene.glow.enabled()) {
      L.glow_box = scene.glow.box.value_or(L.bounds);
      L.bounds = isEmpty(L.particle_domain) ? L.glow_box : unite(L.bounds, L.glow_box);
    }
    L.planes = uniformBrickPlanes(L.bounds, d);
  }
  L.assignment = assignBricks(d, size);
  L.mine = L.assignment.bricksOf(rank);
  return L;
}

Box3 keepOutBox(const SessionLayout& layout) {
  if (isEmpty(layout.glow_box)) return layout.particle_domain;
  return isEmpty(layout.particle_domain) ? layout.glow_box : unite(layout.particle_domain, layout.glow_box);
}

void checkCameraOutside(const Camera& cam, const Box3& scene_box, const std::string& which,
                        const Box3* keep_out) {
  const Box3& box = scene_box;
  const glm::dvec3& p = cam.position;
  char msg[512];
  const double size = glm::length(box.extent()), distance = glm::length(p - box.centre());
  if (!isEmpty(box) && size > 0.0 && distance > kMaxDistanceToExtent * size) {
    std::snprintf(msg, sizeof msg,
                  "camera.position (%g, %g, %g)%s is %g away from the scene's centre, %g times the "
                  "scene's size (%g): beyond 1e6, float math on the GPU cannot resolve the scene "
                  "from there; move the camera closer",
                  p.x, p.y, p.z, which.c_str(), distance, distance / size, size);
    throw InputError(msg);
  }
  const Box3& out = keep_out ? *keep_out : box;
  if (isEmpty(out)) return;
  if (cam.orthographic() && !out.contains(p)) {
    // Parallel rays start on the eye plane: one that starts inside a particle's field would find
    // that particle's surface in one brick and miss it in the others (a brick entered inside the
    // surface shows nothing), and the coarse mesh of a surface is cut at the near plane. So that
    // box must lie wholly in front of the plane, as it must lie around the perspective eye.
    double nearest = HUGE_VAL;
    for (int c = 0; c < 8; ++c) nearest = std::min(nearest, glm::dot(out.corner(c) - p, cam.forward()));
    if (nearest > 0.0) return;
    std::snprintf(msg, sizeof msg,
                  "camera.position (%g, %g, %g)%s: its orthographic eye plane (through it, "
                  "perpendicular to the view direction) cuts or lies beyond the box of the particles "
                  "(grown by their influence radius), surfaces and glow, [%g, %g] x [%g, %g] x [%g, %g] "
                  "(its nearest corner %g behind the plane): their renderers need it wholly in front "
                  "of the plane; move the camera back along the view direction",
                  p.x, p.y, p.z, which.c_str(), out.lo.x, out.hi.x, out.lo.y, out.hi.y, out.lo.z,
                  out.hi.z, -nearest);
    throw InputError(msg);
  }
  if (!out.contains(p)) return;
  std::snprintf(msg, sizeof msg,
                "camera.position (%g, %g, %g)%s is inside the box of the particles (grown by "
                "their influence radius), surfaces and glow, [%g, %g] x [%g, %g] x [%g, %g]: "
                "their renderers need the eye outside it (inside the volume is fine); move the "
                "camera outside it",
                p.x, p.y, p.z, which.c_str(), out.lo.x, out.hi.x, out.lo.y, out.hi.y, out.lo.z,
                out.hi.z);
  throw InputError(msg);
}

std::pair<double, double> depthRange(const Camera& cam, const Box3& box) {
  double tmin = 1e300, tmax = -1e300;
  for (int c = 0; c < 8; ++c) {
    double t = glm::dot(cam.forward(), box.corner(c) - cam.position);
    tmin = std::min(tmin, t);
    tmax = std::max(tmax, t);
  }
  double extent = glm::length(box.extent());
  double near_plane = std::max(tmin * 0.5, 1e-4 * extent);
  return {near_plane, std::max(tmax * 1.01, near_plane * 2.0)};
}

}  // namespace sortlast
