#pragma once
// A pinhole (perspective) or orthographic camera. Pixel (0,0) is the top-left of the image; pixel
// centres sit at +0.5. Both the GL renderer (through viewProjection, or pixelRay's formula in a
// shader) and the CPU reference (through pixelRay) derive their rays from this one object, so they
// sample the same rays. Orthographic rays are parallel (direction forward()), each starting on the
// eye plane (through `position`, perpendicular to forward()); `parallel_scale` is half the view's
// height in world units (ParaView's meaning).
#include <optional>

#include <glm/glm.hpp>

#include "common/box.h"

namespace sortlast {

enum class Projection { kPerspective, kOrthographic };

// A ray: origin + t * direction, t >= 0, direction unit.
struct CameraRay {
  glm::dvec3 origin, direction;
};

struct Camera {
  glm::dvec3 position{0.0, 0.0, 5.0};
  glm::dvec3 look_at{0.0};
  glm::dvec3 up{0.0, 1.0, 0.0};
  double fov_deg = 35.0;  // vertical field of view
  int width = 512, height = 512;
  Projection projection = Projection::kPerspective;
  double parallel_scale = 1.0;  // orthographic only: half the view's height, world units

  bool orthographic() const { return projection == Projection::kOrthographic; }

  glm::dvec3 forward() const { return glm::normalize(look_at - position); }
  glm::dvec3 right() const { return glm::normalize(glm::cross(forward(), up)); }
  glm::dvec3 trueUp() const { return glm::cross(right(), forward()); }

  // The ray through the centre of pixel (px, py): from the eye (perspective) or from the pixel's
  // point on the eye plane (orthographic).
  CameraRay pixelRay(double px, double py) const;
  // Unit direction of that ray.
  glm::dvec3 rayDirection(double px, double py) const { return pixelRay(px, py).direction; }
  // Screen offsets of pixel (px, py)'s centre in [-1, 1] (x right, y up): the ray is
  // forward + sx * right * sr + sy * trueUp * su (perspective; sr = tan(fov/2) * aspect,
  // su = tan(fov/2)) or starts at position + sx * right * sr + sy * trueUp * su (orthographic;
  // sr = parallel_scale * aspect, su = parallel_scale). screenScale() returns (sr, su).
  glm::dvec2 screenScale() const;

  // Clip-space transform for OpenGL with window row 0 = image row 0 (top): the y axis is flipped
  // relative to the usual GL convention so read-back needs no row swap.
  glm::mat4 viewProjection(double near_plane, double far_plane) const;

  // Pixel coordinates of a world point, or nothing if it is at or behind the eye plane (the
  // orthographic rays start on it too: nothing behind it is seen).
  std::optional<glm::dvec2> project(const glm::dvec3& p) const;
};

// Frame i of an orbit of n frames: a circle of the given radius around `centre`, in the plane
// perpendicular to base.up, tilted by `elevation_deg`, starting `start_deg` on from the base
// camera's azimuth.
Camera orbitCamera(const Camera& base, const glm::dvec3& centre, double radius,
                   double elevation_deg, int i, int n, double start_deg = 0.0);

// Screen rectangle (in pixels, clamped to the image) that covers the projection of a box. A box
// wholly at or behind the eye plane covers nothing; one that straddles it (or holds the eye)
// covers the whole screen under perspective (conservative), its corners' projection under an
// orthographic camera.
struct Rect {
  int x = 0, y = 0, w = 0, h = 0;
  bool empty() const { return w <= 0 || h <= 0; }
  long long area() const { return empty() ? 0 : 1LL * w * h; }
  bool operator==(const Rect&) const = default;
};
Rect screenRectOf(const Camera& cam, const Box3& box);
// Smallest rectangle holding both (non-empty) rectangles.
Rect unite(const Rect& a, const Rect& b);

}  // namespace sortlast
