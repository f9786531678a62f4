// The camera section's keys: the camera and its orbit.
#include "scene/key_rows.h"
#include "scene/scene_reader.h"
#include <algorithm>
#include <cmath>

std::vector<sortlast::SceneKey> sortlast::cameraKeys() {
  const Check kLength = lengthCheck();
  const Check kCoordinate = coordinateCheck();
  return {
    {"camera.position", "auto",
     "Eye position. `auto`: along (0.55, 0.35, 1) from `camera.look_at`, just far enough that "
     "the bounding sphere of the scene's bounds (the volume box, grown to hold the particles' "
     "domain) fits the vertical and the horizontal field of view. May lie inside the volume (rays "
     "start at the eye; slicing draws the slices in front of the near plane), not inside the "
     "particles' domain, the surfaces' or the glow box.",
     Vector<glm::dvec3>{member<&Scene::camera, &Camera::position>, {kCoordinate}},
     AutoValue{member<&Scene::camera_auto>}},
    {"camera.look_at", "auto",
     "Point the camera looks at. `auto`: the centre of the scene's bounds (the volume box, "
     "grown to hold the particles' domain; for a volume alone, the origin).",
     Vector<glm::dvec3>{member<&Scene::camera, &Camera::look_at>, {kCoordinate}},
     AutoValue{member<&Scene::look_at_auto>}},
    {"camera.up", "[0, 1, 0]", "Up direction; also the axis of the orbit.",
     Vector<glm::dvec3>{
         member<&Scene::camera, &Camera::up>,
         {kCoordinate,
          {">= 1e-12", "must not be zero (its length must be at least 1e-12)", true}}}},
    {"camera.fov", "35", "Vertical field of view in degrees.",
     Real{member<&Scene::camera, &Camera::fov_deg>,
          {{"in (0, 180)", "must be {allowed} degrees"}}}},
    {"camera.projection", "perspective",
     "`perspective` (a pinhole at `camera.position`, `camera.fov`) or `orthographic` (parallel "
     "rays along the view direction, each from its pixel's point on the plane through "
     "`camera.position` perpendicular to it; the view is 2 x `camera.parallel_scale` high). "
     "Every renderer takes it; the box of the particles, surfaces and glow must then lie wholly in "
     "front of that plane (as it must lie around the perspective eye).",
     Choice{member<&Scene::camera, &Camera::projection>,
            std::vector<std::pair<const char*, Projection>>{
                {"perspective", Projection::kPerspective}, {"orthographic", Projection::kOrthographic}}}},
    {"camera.parallel_scale", "auto",
     "Orthographic only: half the view's height in world units (ParaView's meaning). `auto`: "
     "what the perspective view shows at `camera.look_at`, distance x tan(fov / 2) (so the "
     "automatic camera frames the scene the same way).",
     Real{member<&Scene::camera, &Camera::parallel_scale>, {{"> 0"}, kLength}},
     AutoValue{member<&Scene::parallel_scale_auto>}},
    {"camera.orbit.frames", "0",
     "0: a single view. N > 0: the paper's orbit, N frames 360/N degrees apart on a circle "
     "around `camera.look_at`, written as a numbered series (out_0000.png, ...).",
     Int{member<&Scene::orbit, &OrbitSpec::frames>, {{">= 0"}}}},
    {"camera.orbit.elevation", "0", "Tilt of the orbit circle in degrees.",
     Real{member<&Scene::orbit, &OrbitSpec::elevation>, {{"in [-90, 90]", "must be {allowed} degrees"}}}},
    {"camera.orbit.start", "0",
     "Azimuth of the orbit's first frame, degrees about `camera.up`, from the direction of "
     "`camera.position` (or of its `auto` placement): frame i is at start + 360 i / N. To begin "
     "an orbit at a chosen view without moving the camera.",
     Real{member<&Scene::orbit, &OrbitSpec::start>, {{"in [-360, 360]", "must be {allowed} degrees"}}}},
    {"camera.orbit.radius", "auto",
     "Orbit radius. `auto`: 2 x the largest extent of the scene's bounds (the volume box, "
     "grown to hold the particles' domain; the paper's R, kept for the benchmark protocol: it "
     "may crop a wide scene, which `camera.position: auto` does not).",
     OptionalReal{member<&Scene::orbit, &OrbitSpec::radius>, {{"> 0"}, kLength}}, AutoValue{}},
  };
}

namespace sortlast {

// The image size (both in one message), and a fixed camera that has a view direction and an up.
void checkCameraKeys(const Scene& s) {
  const Camera& cam = s.camera;
  const Allowed& size = sceneKeyChecks("image.width").front().allowed;
  if (!size.admits(cam.width) || !size.admits(cam.height))
    throw InputError("image size " + std::to_string(cam.width) + " x " + std::to_string(cam.height) +
                     ": image.width and image.height must be " + size.phrase());
  if (!s.camera_auto && s.orbit.frames == 0) {
    if (glm::length(cam.look_at - cam.position) == 0.0)
      throw InputError("camera.position equals camera.look_at: no view direction");
    if (glm::length(glm::cross(cam.forward(), cam.up)) < 1e-9)
      throw InputError("camera.up is parallel to the view direction");
  }
}

std::vector<Camera> Scene::frameCameras(const Box3& bounds) const {
  Camera base = camera;
  // No volume and no particles leaves an empty box; one particle, a point: any camera that looks
  // at where the (absent) data would be will do.
  const bool empty = isEmpty(bounds);
  glm::dvec3 e = bounds.extent();
  double largest = glm::max(e.x, glm::max(e.y, e.z));
  double extent = empty || !(largest > 0.0) ? 1.0 : largest;
  if (look_at_auto) base.look_at = empty ? glm::dvec3(0.0) : bounds.centre();
  if (camera_auto) {
    // Far enough that the box's bounding sphere (about the look-at point) fits in the vertical
    // and the horizontal field of view, with 2% to spare: the whole scene is in the frame
    // whatever its shape and the image's aspect. (The viewer's reset, viewer/orbit.js
    // frameBounds, frames the same way.)
    glm::dvec3 centre = empty ? glm::dvec3(0.0) : bounds.centre();
    double radius = empty || !(largest > 0.0) ? 0.5 * std::sqrt(3.0) : 0.5 * glm::length(e);
    radius += glm::length(centre - base.look_at);
    double vhalf = 0.5 * base.fov_deg * 3.14159265358979323846 / 180.0;
    double hhalf = std::atan(std::tan(vhalf) * double(base.width) / base.height);
    double dist = 1.02 * radius / std::sin(std::min(vhalf, hhalf));
    base.position = base.look_at + dist * glm::normalize(glm::dvec3(0.55, 0.35, 1.0));
  }
  // camera.parallel_scale: auto: the height the perspective view has at the look-at point.
  auto scaled = [&](Camera c) {
    if (parallel_scale_auto)
      c.parallel_scale = std::max(kMinLength, glm::length(c.look_at - c.position) *
                                                  std::tan(0.5 * c.fov_deg * 3.14159265358979323846 / 180.0));
    return c;
  };
  if (orbit.frames == 0) return {scaled(base)};
  std::vector<Camera> cams;
  double radius = orbit.radius.value_or(2.0 * extent);
  for (int i = 0; i < orbit.frames; ++i)
    cams.push_back(scaled(orbitCamera(base, base.look_at, radius, orbit.elevation, i, orbit.frames, orbit.start)));
  return cams;
}

}  // namespace sortlast
