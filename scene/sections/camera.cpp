// The camera section's keys: the camera and its orbit.
#include "scene/key_rows.h"

std::vector<sortlast::SceneKey> sortlast::cameraKeys() {
  const Check kLength = lengthCheck();
  const Check kCoordinate = coordinateCheck();
  return {
    {"camera.position", "auto",
     "Eye position. `auto`: along (0.55, 0.35, 1) from `camera.look_at`, just far enough that "
     "the bounding sphere of the scene's bounds (the volume box, grown to hold the particles' "
     "domain) fits the vertical and the horizontal field of view. Must lie outside the volume.",
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
